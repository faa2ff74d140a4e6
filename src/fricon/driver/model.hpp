#pragma once
// driver: the discrete elastic model of a problem, built phase by phase in data-flow order:
// mesh (and its connected bodies) -> dofs (Dirichlet elimination) -> K and f (assembly) -> Cholesky
// factor of K. Everything later (contact, the dual QP, the outer loop) reads this model and never
// changes it.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fricon/contact/discretization.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/dual/dual_operator.hpp"
#include "fricon/fe/assembly.hpp"
#include "fricon/fe/dof_map.hpp"
#include "fricon/fe/floating.hpp"
#include "fricon/fe/material.hpp"
#include "fricon/linalg/cholesky.hpp"
#include "fricon/mesh/bodies.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::driver {

struct Model {
  mesh::TetMesh mesh;
  /// The connected bodies of the mesh (mesh::find_bodies), each held by its own Dirichlet
  /// conditions or by contact (a floating body, check_model checks that it has a contact
  /// surface). Empty in a part of a model (driver::model_part).
  mesh::Bodies bodies;
  /// The bodies whose Dirichlet conditions leave rigid motions free, and those motions R over
  /// the free dofs (theory.md §2.10); empty when every body is held.
  fe::FloatingBodies floating;
  /// The material of each region of the mesh (fe::Materials), or one for the whole body.
  std::vector<fe::Material> materials;
  fe::DofMap dofs{0};
  /// The prescribed displacement [m] at every node (3 x n_nodes): the [[dirichlet]] values at
  /// fixed components, zero elsewhere. The displacement of a solve is dofs.to_nodal(u) + this.
  fe::NodalField prescribed;
  /// Stiffness over the free dofs [N/m]; empty in a distributed run (backend "petsc"), where
  /// each rank assembles only its own elements' part and MUMPS holds the sum.
  SparseMatrix K;
  /// Load vector over the free dofs [N]: the applied loads minus K_free,fixed times the prescribed
  /// displacements.
  VectorXd f;
  /// Cholesky factor of K (CHOLMOD; empty if distributed); with floating bodies of the
  /// regularized K, so that its solves are a generalized inverse K^+ (fe/floating.hpp).
  linalg::CholeskyFactor factor;
};

/// K w [N] for w over the free dofs: with K when it was assembled, else element by element
/// (the same sum, for a distributed run whose K exists only in pieces).
VectorXd stiffness_times(const Model& model, const VectorXd& w);

/// Builds the mesh the problem describes and checks it. Throws InputError on bad input.
mesh::TetMesh make_mesh(const Problem& problem);

/// The dofs left free by the problem's Dirichlet conditions on `mesh`, whose connected bodies are
/// `bodies` (mesh::find_bodies(mesh)). Throws InputError when a boundary tag does not exist on the
/// mesh, nothing is left free, or, in a problem without [contact], the conditions leave a rigid
/// motion of a body free (K would be singular; with contact such a body floats, and check_model
/// refuses it only if it has no contact surface): the message names the problem's [[dirichlet]]
/// position, the number of free rigid motions and, for a mesh of several bodies, the first body not
/// held (its index, regions and bounding box, mesh::describe_body) and the [[dirichlet]] entries
/// that touch it.
fe::DofMap make_dofs(const Problem& problem, const mesh::TetMesh& mesh, const mesh::Bodies& bodies);

/// make_dofs with the bodies found on `mesh`.
fe::DofMap make_dofs(const Problem& problem, const mesh::TetMesh& mesh);

/// The prescribed displacements of the problem's [[dirichlet]] values (see Model::prescribed).
/// Throws InputError when two entries give one component of a node different values. With
/// `owners`, also which entry sets each component (3 a + c for node a, component c): the last of
/// those that cover it, -1 for a free one.
fe::NodalField make_prescribed(const Problem& problem, const mesh::TetMesh& mesh,
                               std::vector<int>* owners = nullptr);

/// The material of each region of the mesh: [material] everywhere, or [[material]] by region.
/// Throws InputError (with the key's position) when a region of the mesh has no material or a
/// [[material]] names a region the mesh does not have.
std::vector<fe::Material> make_materials(const Problem& problem, const mesh::TetMesh& mesh);

/// Called with each phase's name ("mesh", "assembly", "factorize", ...) as it starts.
using PhaseCallback = std::function<void(const std::string& phase)>;

/// The model without K: mesh, bodies, materials, dofs, prescribed displacements and f (phases
/// "mesh", "assembly"). Throws as assemble_model.
Model assemble_loads(const Problem& problem, PhaseTimes& times,
                     const PhaseCallback& on_phase_start = {});

/// Whether a model is the whole body or a part of it (a rank's tetrahedra as a model of their
/// own, driver::model_part).
enum class Extent { Whole, Part };

/// The load vector f [N] over the free dofs of `model`, from its mesh, materials, dofs and
/// prescribed displacements (not its f): the tractions and volume force minus K_free,fixed times
/// the prescribed displacements. The parts of a partition of the tetrahedra, mapped to the whole
/// model's dofs, sum to the whole model's f. Throws InputError when a traction's boundary has no
/// triangle in the Whole mesh (a Part may hold none of them).
VectorXd load_vector(const Problem& problem, const Model& model, Extent extent);

/// The model up to the factorization: mesh, bodies, material, dofs, K and f (phases "mesh",
/// "assembly"). Throws InputError when a boundary tag named by the problem does not exist on the
/// mesh or the Dirichlet conditions leave rigid motions of a body free (make_dofs).
Model assemble_model(const Problem& problem, PhaseTimes& times,
                     const PhaseCallback& on_phase_start = {});

/// Factorizes K as `request` asks (phase "factorize"; the dual operator's request, see
/// dual/dual_operator.hpp). Throws NumericalError when K is not positive definite (to working
/// precision). The model's dofs hold every body (make_dofs), so that is ill-conditioning: with
/// `problem`, the message names its [material] position and the stiffness contrast of the
/// materials when it is large.
void factorize_model(Model& model, const dual::FactorizationRequest& request, PhaseTimes& times,
                     const PhaseCallback& on_phase_start = {}, const Problem* problem = nullptr);

/// assemble_model, then factorize_model with the default ordering.
Model build_model(const Problem& problem, PhaseTimes& times,
                  const PhaseCallback& on_phase_start = {});

/// The contact discretization of the problem's [contact] section on the mesh and dofs: the one
/// function that `solve`, `check`, the benchmarks and the dual dump use to build it. Errors name
/// the positions of contact.boundary and contact.patches.
/// With `deformation` (3 x mesh nodes [m]), the gaps and normals of the curved rigid obstacles
/// are evaluated at the deformed position (a geometric update, theory.md §2.11), the obstacles
/// moved by `obstacles` (one per pair [m]) when given, else by their displacement of a static run
/// (rest along a path).
contact::ContactDiscretization discretize_contact(const Problem& problem, const mesh::TetMesh& mesh,
                                                  const fe::DofMap& dofs,
                                                  const fe::NodalField* deformation = nullptr,
                                                  const std::vector<Vec3>* obstacles = nullptr);

/// Every step's prescribed displacements (make_prescribed of at_step(problem, k), k = 1 ..
/// loading.steps; the problem itself without a path): throws InputError when two [[dirichlet]]
/// entries disagree on a node at some step, naming the step of a path.
void check_steps(const Problem& problem, const mesh::TetMesh& mesh);

/// The checks that `solve` makes on an assembled model (assemble_model, or assemble_loads) before
/// it factorizes K, and the contact discretization they end with (none without [contact]): the
/// prescribed displacements of every step (check_steps), then discretize_contact. `solve` and
/// `fricon check` both call it, so that check refuses what solve refuses. Throws InputError.
std::optional<contact::ContactDiscretization> check_model(const Problem& problem,
                                                          const Model& model);

/// Sum of all applied forces [N] (tractions and volume force), including the parts acting on
/// fixed dofs, in each direction.
Vec3 applied_force_total(const Problem& problem, const mesh::TetMesh& mesh);

/// The applied forces [N] (tractions and volume force) per node, 3 x n_nodes, including the
/// parts acting on fixed dofs; their sum over the nodes is applied_force_total.
fe::NodalField applied_forces(const Problem& problem, const mesh::TetMesh& mesh);

/// Reaction forces [N] per node for a displacement field u (3 x n_nodes): at the fixed dofs the
/// internal force minus the applied load there, zero at the free ones.
fe::NodalField reaction_forces(const Model& model, const Problem& problem, const fe::NodalField& u);

/// Reaction forces [N] at the fixed dofs for a displacement field u (3 x n_nodes): those of
/// reaction_forces, summed over the mesh.
Vec3 reaction_total(const Model& model, const Problem& problem, const fe::NodalField& u);

/// The sum over the nodes of the magnitudes |f_a| [N] of a nodal force field (3 x n_nodes): a
/// force scale that, unlike the resultant, cannot cancel.
Real force_magnitude_sum(const fe::NodalField& forces);

}  // namespace fricon::driver
