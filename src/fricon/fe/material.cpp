#include "fricon/fe/material.hpp"

#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "fricon/core/error.hpp"

namespace fricon::fe {

std::span<const std::string_view> material_parameters(MaterialModel model) {
  static constexpr std::array<std::string_view, 2> kIsotropic{"young", "poisson"};
  static constexpr std::array<std::string_view, 1> kAnisotropic{"voigt"};
  return model == MaterialModel::Isotropic ? std::span<const std::string_view>(kIsotropic)
                                           : std::span<const std::string_view>(kAnisotropic);
}

namespace {
// Voigt index of the symmetric pair (i, j).
constexpr int kVoigt[3][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}};

Real ellipticity_constant(const Voigt6& D) {
  // With engineering shears eps_v = S e_v, where e_v holds the tensor components
  // (e11, e22, e33, e23, e13, e12) and S = diag(1,1,1,2,2,2). The energy C:e:e = eps_v^T D eps_v
  // and |e|^2 = e_v^T W e_v with W = diag(1,1,1,2,2,2). The ellipticity constant is the smallest
  // generalised eigenvalue of (S D S, W), i.e. the smallest eigenvalue of W^-1/2 S D S W^-1/2.
  Eigen::Matrix<Real, 6, 1> scale;
  scale << 1, 1, 1, std::sqrt(2.0), std::sqrt(2.0), std::sqrt(2.0);
  const Voigt6 M = scale.asDiagonal() * D * scale.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Voigt6> eig(M, Eigen::EigenvaluesOnly);
  return eig.eigenvalues()(0);
}
}  // namespace

std::array<Real, 2> lame(Real young, Real poisson) {
  const Real lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  const Real mu = young / (2.0 * (1.0 + poisson));
  return {lambda, mu};
}

Material isotropic(Real young, Real poisson, const std::string& where) {
  if (!(young > 0.0) || !std::isfinite(young))
    throw InputError(fmt::format("{}: young = {} Pa must be positive and finite", where, young));
  if (!(poisson > -1.0 && poisson < 0.5))
    throw InputError(
        fmt::format("{}: poisson = {} must lie in (-1, 0.5) for a positive definite Hooke tensor",
                    where, poisson));
  const auto [lambda, mu] = lame(young, poisson);
  Voigt6 D = Voigt6::Zero();
  D.topLeftCorner<3, 3>().setConstant(lambda);
  D.topLeftCorner<3, 3>().diagonal().array() += 2.0 * mu;
  D.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  return anisotropic(D, where);
}

Material anisotropic(const Voigt6& D, const std::string& where) {
  if (!D.allFinite())
    throw InputError(fmt::format("{}: Hooke matrix has a non-finite entry", where));
  const Real scale = D.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) throw InputError(fmt::format("{}: Hooke matrix is zero", where));
  for (int I = 0; I < 6; ++I)
    for (int J = I + 1; J < 6; ++J)
      if (std::abs(D(I, J) - D(J, I)) > 1e-12 * scale)
        throw InputError(
            fmt::format("{}: Hooke matrix is not symmetric: D[{}][{}] = {} but D[{}][{}] = {} "
                        "(C_ijkl = C_klij)",
                        where, I, J, D(I, J), J, I, D(J, I)));
  Material m;
  m.D = 0.5 * (D + D.transpose());
  m.ellipticity = ellipticity_constant(m.D);
  if (!(m.ellipticity > 1e-12 * scale))
    throw InputError(fmt::format(
        "{}: Hooke tensor is not elliptic (smallest eigenvalue on symmetric strains {:.4g} Pa, "
        "largest entry {:.4g} Pa)",
        where, m.ellipticity, scale));
  return m;
}

Material from_tensor(const HookeTensor& C, const std::string& where) {
  Real scale = 0.0;
  for (const auto& a : C)
    for (const auto& b : a)
      for (const auto& c : b)
        for (Real v : c)
          scale = std::max(scale, std::abs(v));
  const Real tol = 1e-12 * scale;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) {
          const Real v = C[i][j][k][l];
          if (std::abs(v - C[j][i][k][l]) > tol || std::abs(v - C[i][j][l][k]) > tol ||
              std::abs(v - C[k][l][i][j]) > tol)
            throw InputError(fmt::format(
                "{}: Hooke tensor lacks the symmetries C_ijkl = C_jikl = C_ijlk = C_klij at "
                "(i,j,k,l) = ({},{},{},{})",
                where, i + 1, j + 1, k + 1, l + 1));
        }
  Voigt6 D;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          D(kVoigt[i][j], kVoigt[k][l]) = C[i][j][k][l];
  return anisotropic(D, where);
}

HookeTensor to_tensor(const Material& m) {
  HookeTensor C{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          C[i][j][k][l] = m.D(kVoigt[i][j], kVoigt[k][l]);
  return C;
}

}  // namespace fricon::fe
