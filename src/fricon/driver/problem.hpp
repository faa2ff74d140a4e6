#pragma once
// driver: the description of one problem, as the library uses it. The TOML reader (io/) fills it;
// scripts and tests may build it directly. Every field documents its unit and default; the key
// path in the problem file is given in brackets and spelled the same (docs/problem-file.md).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fricon/core/types.hpp"

namespace fricon::driver {

/// [mesh]
struct MeshOptions {
  std::string kind = "brick";               ///< [mesh.kind] "brick" (only kind so far)
  std::array<Real, 3> size{3.0, 1.0, 1.0};  ///< [mesh.size] box edge lengths [m], > 0
  std::array<Index, 3> cells{12, 4, 4};     ///< [mesh.cells] cubes per direction, >= 1
};

/// [material]
struct MaterialOptions {
  std::string model = "isotropic";  ///< [material.model] "isotropic" or "anisotropic"
  Real young = 21.19e10;            ///< [material.young] Young's modulus [Pa], > 0
  Real poisson = 0.277;             ///< [material.poisson] Poisson's ratio, in (-1, 0.5)
  /// [material.voigt] 6x6 Hooke matrix [Pa] (order 11,22,33,23,13,12, engineering shears);
  /// required for model = "anisotropic", symmetric positive definite.
  std::optional<std::array<std::array<Real, 6>, 6>> voigt;
};

/// [[dirichlet]]: zero displacement on a tagged boundary.
struct DirichletOptions {
  std::string boundary;                              ///< [dirichlet.boundary] boundary tag
  std::array<bool, 3> components{true, true, true};  ///< [dirichlet.components] subset of "xyz"
};

/// [[traction]]: constant surface traction on a tagged boundary.
struct TractionOptions {
  std::string boundary;       ///< [traction.boundary] boundary tag
  Vec3 value = Vec3::Zero();  ///< [traction.value] traction vector [Pa]
};

/// [contact.friction]: the coefficient of friction F(t), t = ||u_t|| [m].
struct FrictionOptions {
  std::string law = "paper";  ///< "paper", "constant" or "table"
  Real param = 6.0e4;         ///< [param] paper's law (method.md §2.1): slope parameter [1/m], > 0
  Real value = 0.3;           ///< [value] constant law: F, >= 0
  std::vector<Real> t;        ///< [t] table law: slips [m], strictly increasing, >= 0
  std::vector<Real> f;        ///< [f] table law: F at those slips, >= 0
};

/// [contact]: frictional contact of a tagged boundary with a rigid half-space (no initial gap).
struct ContactOptions {
  std::string boundary = "z0";  ///< [contact.boundary] tag of the contact surface (planar)
  Real slip_bound = 2.0e7;      ///< [contact.slip_bound] g [Pa], >= 0
  /// [contact.patches] partition of the contact surface for the multipliers: "chessboard"
  /// (2x2 squares of the brick's grid, the paper's T_H).
  std::string patches = "chessboard";
  FrictionOptions friction;
};

/// [solver]
struct SolverOptions {
  Real outer_tol =
      1.0e-4;              ///< [solver.outer_tol] err(k) threshold of the successive approximations
  int outer_max = 50;      ///< [solver.outer_max] maximum outer iterations, >= 1
  Real qp_rtol = 1.0e-6;   ///< [solver.qp_rtol] QP stops when ||g^P|| <= qp_rtol ||h||
  int qp_max = 100000;     ///< [solver.qp_max] maximum QP iterations per outer step
  bool warm_start = true;  ///< [solver.warm_start] start each QP from the previous multipliers
  /// [solver.dual_operator] "implicit" (each Q product = one solve with K, the paper's n_mult),
  /// "dense" (Q formed once by a block solve with n_dual right-hand sides), "schur" (K factored
  /// with the contact dofs last, Q from the factor of the Schur complement), or "auto".
  std::string dual_operator = "auto";
  /// [solver.acceleration] of the successive approximations: "none" (the paper's plain
  /// iteration phi^k = Psi(phi^(k-1))) or "anderson" (Anderson mixing of the last iterates).
  std::string acceleration = "none";
  /// [solver.qp_variant] inner QP algorithm: "bb" (MPGP with Barzilai-Borwein expansion and
  /// proportioning lengths, 5-8x fewer products with Q on the paper's problems), "paper" (the
  /// plain MPGP of the paper, which reproduces its n_mult), or "spg" (spectral projected
  /// gradient).
  std::string qp_variant = "bb";
  /// [solver.anderson_depth] number of previous iterates Anderson mixing uses, in [1, 20].
  int anderson_depth = 1;
};

/// [output]
struct OutputOptions {
  std::string dir = "results";  ///< [output.dir] results folder, relative to the working directory
};

struct Problem {
  std::string source = "<memory>";  ///< file the problem was read from (for messages)
  std::string title;                ///< [title] free text, optional
  MeshOptions mesh;
  MaterialOptions material;
  Vec3 volume_force = Vec3::Zero();  ///< [volume_force] body force [N/m^3]
  std::vector<DirichletOptions> dirichlet;
  std::vector<TractionOptions> traction;
  std::optional<ContactOptions> contact;
  SolverOptions solver;
  OutputOptions output;
};

}  // namespace fricon::driver
