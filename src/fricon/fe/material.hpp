#pragma once
// fe: linear elastic materials as Hooke tensors in Voigt notation.
//
// Convention: stress and strain vectors are ordered (11, 22, 33, 23, 13, 12); the strain vector
// carries engineering shears (2 e23, 2 e13, 2 e12), so sigma = D * eps with D(I,J) = C_ijkl for
// I = (ij), J = (kl). The paper's conditions on C (theory.md §1) are checked on construction:
// the symmetries C_ijkl = C_jikl = C_klij and ellipticity C_ijkl e_ij e_kl >= c e_ij e_ij, c > 0.

#include <array>
#include <span>
#include <string>
#include <string_view>

#include "fricon/core/enum_names.hpp"
#include "fricon/core/types.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::fe {

/// How a material is given: isotropic (Young's modulus and Poisson's ratio) or anisotropic (a
/// 6x6 Hooke matrix in Voigt notation).
enum class MaterialModel { Isotropic, Anisotropic };

/// The keys of [material] that `model` takes ({"young", "poisson"} or {"voigt"}).
std::span<const std::string_view> material_parameters(MaterialModel model);

using Voigt6 = Eigen::Matrix<Real, 6, 6>;

struct Material {
  Voigt6 D = Voigt6::Zero();  ///< Hooke tensor in Voigt notation [Pa]
  /// Smallest eigenvalue [Pa] of the tensor as a map on symmetric strains (ellipticity constant).
  Real ellipticity = 0.0;
};

/// Isotropic material from Young's modulus E [Pa] (> 0) and Poisson's ratio nu (in (-1, 1/2)).
/// Throws InputError naming `where` (e.g. "problem.toml: material") for values out of range.
Material isotropic(Real young, Real poisson, const std::string& where = "material");

/// Lamé constants (lambda, mu) [Pa] of an isotropic material.
std::array<Real, 2> lame(Real young, Real poisson);

/// Anisotropic material from a 6x6 Voigt matrix [Pa]. Throws InputError if D is not symmetric
/// (to 1e-12 relative) or not positive definite on symmetric strains.
Material anisotropic(const Voigt6& D, const std::string& where = "material");

/// Material from the full tensor C_ijkl [Pa], C[i][j][k][l]. Checks both minor symmetries and the
/// major symmetry (1e-12 relative), then ellipticity as in anisotropic().
using HookeTensor = std::array<std::array<std::array<std::array<Real, 3>, 3>, 3>, 3>;
Material from_tensor(const HookeTensor& C, const std::string& where = "material");

/// The full tensor of a material (inverse of from_tensor).
HookeTensor to_tensor(const Material& m);

/// The materials of a body, one per region of its mesh (TetMesh::region): tetrahedron t is made
/// of materials[region(t)], or of materials[0] everywhere when there is only one.
using Materials = std::span<const Material>;

/// The material of tetrahedron t (see Materials).
inline const Material& material_of(Materials materials, const mesh::TetMesh& mesh, Index t) {
  return materials.size() == 1 ? materials[0] : materials[static_cast<size_t>(mesh.region(t))];
}

}  // namespace fricon::fe

FRICON_ENUM_NAMES(fricon::fe::MaterialModel, "material.model",
                  {fe::MaterialModel::Isotropic, "isotropic"},
                  {fe::MaterialModel::Anisotropic, "anisotropic"});
