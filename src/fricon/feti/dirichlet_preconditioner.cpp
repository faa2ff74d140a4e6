// feti: the Dirichlet preconditioner of Total FETI (docs/theory.md §8.5), on the equality
// multipliers (gluing and Dirichlet rows B_E):
//
//   M_E = (B_E B_E^T)^-1 B_E S B_E^T (B_E B_E^T)^-1,   S = diag(S_s),
//
//   S_s = K_bb - K_bi K_ii^-1 K_ib,
//
// b the dofs of subdomain s on equality rows, i the others: the stiffness of the subdomain's
// interface with its interior free to follow, where the lumped preconditioner takes K_bb alone.
// Each subdomain of this process factors K_ii once (Eigen's sparse LDL^T, minimum degree: on these
// small blocks its solves are faster than CHOLMOD's supernodal ones) and keeps of K_s only the
// entries that touch b (K_bb, K_bi, K_ib), both with 32-bit indices: as B_E^T t is zero on the
// interior dofs, a product needs no more,
//
//   w = K_s v,  z = K_ii^-1 w_i,  S_s v = (w - K_s [0; z])_b,
//
// K_ii's own entries entering only rows i, which S_s v drops. A subdomain whose equality dofs
// do not hold its rigid motions (K_ii singular: an interface on one line) keeps the lumped term
// K_bb, as does one without interior dofs.

#include <Eigen/SparseCholesky>

#include "fricon/feti/feti_operator.hpp"
#include "fricon/feti/preconditioner.hpp"

namespace fricon::feti {

namespace {

// K_ii is taken as singular when its smallest pivot is below this share of its largest: rounding
// in a rigid motion's pivot is far below, a held subdomain's pivots far above (the ratio of the
// element stiffnesses of one mesh).
constexpr double kSingularPivotShare = 1e-12;

// One subdomain's interior: its dofs off the equality rows and the factor of K_ii over them.
struct Interior {
  std::vector<Index> dofs;
  Eigen::SimplicialLDLT<LocalMatrix> K_ii;
  bool held = false;  // K_ii is positive definite; else S_s = K_bb
};

// K_ii of K over the n interior dofs (`position`: each local dof's place among them, -1 on the
// interface).
LocalMatrix interior_block(const SparseMatrix& K, const std::vector<Index>& position, Index n) {
  std::vector<Eigen::Triplet<Real>> entries;
  for (Index col = 0; col < K.outerSize(); ++col) {
    const Index c = position[static_cast<size_t>(col)];
    if (c < 0) continue;
    for (SparseMatrix::InnerIterator it(K, col); it; ++it) {
      const Index r = position[static_cast<size_t>(it.row())];
      if (r >= 0) entries.emplace_back(r, c, it.value());
    }
  }
  LocalMatrix K_ii(n, n);
  K_ii.setFromTriplets(entries.begin(), entries.end());
  return K_ii;
}

// The interior of subdomain s and its factor, and K reduced to what a product reads: the entries
// that touch the interface (those of K_bb alone where the interior is not held).
void factor_interior(const Subdomain& s, Index n_contact, SparseMatrix& K, Interior& interior) {
  const std::vector<bool> on_equality = equality_dofs(s, n_contact);
  std::vector<Index> position(static_cast<size_t>(s.n_dofs()), -1);
  for (Index d = 0; d < s.n_dofs(); ++d)
    if (!on_equality[static_cast<size_t>(d)]) {
      position[static_cast<size_t>(d)] = static_cast<Index>(interior.dofs.size());
      interior.dofs.push_back(d);
    }
  const auto n = static_cast<Index>(interior.dofs.size());
  if (n > 0) {
    interior.K_ii.compute(interior_block(K, position, n));
    if (interior.K_ii.info() == Eigen::Success) {
      const VectorXd& D = interior.K_ii.vectorD();
      interior.held = D.minCoeff() > kSingularPivotShare * D.cwiseAbs().maxCoeff();
    }
  }
  const bool held = interior.held;
  K.prune([&](Index r, Index c, Real) {
    const bool r_b = on_equality[static_cast<size_t>(r)], c_b = on_equality[static_cast<size_t>(c)];
    return held ? (r_b || c_b) : (r_b && c_b);
  });
}

class DirichletPreconditioner final : public InterfacePreconditioner {
 public:
  DirichletPreconditioner(const FetiOperator& F, const StiffnessSource& stiffness)
      : InterfacePreconditioner(F),
        interiors_(F.subdomains().size()),
        K_(reduced_stiffness(stiffness, [&](const Subdomain& s, Index i, SparseMatrix& K) {
          factor_interior(s, F.rows().n_contact, K, interiors_[static_cast<size_t>(i)]);
        })) {}

 private:
  void local(const Subdomain& s, Index i, const VectorXd& v, VectorXd& out) const override {
    const Interior& interior = interiors_[static_cast<size_t>(i)];
    const LocalMatrix& K = K_[static_cast<size_t>(i)];
    out = K * v;  // K_bb v_b on b, K_ib v_b on i
    if (interior.held) {
      VectorXd z_full = VectorXd::Zero(s.n_dofs());
      VectorXd w_i(static_cast<Index>(interior.dofs.size()));
      for (std::size_t k = 0; k < interior.dofs.size(); ++k)
        w_i(static_cast<Index>(k)) = out(interior.dofs[k]);
      const VectorXd z = interior.K_ii.solve(w_i);
      for (std::size_t k = 0; k < interior.dofs.size(); ++k)
        z_full(interior.dofs[k]) = z(static_cast<Index>(k));
      out.noalias() -= K * z_full;  // - K_bi K_ii^-1 K_ib v_b on b
    }
    for (const Index d : interior.dofs)  // S_s acts on b alone
      out(d) = 0.0;
  }

  std::vector<Interior> interiors_;  ///< per subdomain; only this process's are filled
  std::vector<LocalMatrix> K_;       ///< per subdomain: the entries of K_s that touch b
};

}  // namespace

std::unique_ptr<const Preconditioner> make_dirichlet_preconditioner(
    const FetiOperator& F, const StiffnessSource& stiffness) {
  return std::make_unique<DirichletPreconditioner>(F, stiffness);
}

}  // namespace fricon::feti
