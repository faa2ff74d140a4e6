// Material checks: Lamé constants, Voigt/tensor symmetry, ellipticity, rejection of bad input.
#include <gtest/gtest.h>

#include "fricon/core/error.hpp"
#include "fricon/fe/material.hpp"

using namespace fricon;
using namespace fricon::fe;

TEST(Material, IsotropicMatchesLame) {
  const Real E = 21.19e10, nu = 0.277;
  const Material m = isotropic(E, nu);
  const Real mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  EXPECT_NEAR(m.D(0, 0), lambda + 2 * mu, 1e-6 * E);
  EXPECT_NEAR(m.D(0, 1), lambda, 1e-6 * E);
  EXPECT_NEAR(m.D(3, 3), mu, 1e-6 * E);
  // On symmetric strains the eigenvalues are 3 lambda + 2 mu (volumetric) and 2 mu (deviatoric).
  EXPECT_NEAR(m.ellipticity, 2 * mu, 1e-9 * E);
}

TEST(Material, UniaxialStressGivesYoungsModulus) {
  // Compliance: eps_11 = sigma_11 / E, eps_22 = -nu sigma_11 / E.
  const Real E = 2e11, nu = 0.3;
  const Material m = isotropic(E, nu);
  Eigen::Matrix<Real, 6, 1> sigma = Eigen::Matrix<Real, 6, 1>::Zero();
  sigma(0) = 1e8;
  const Eigen::Matrix<Real, 6, 1> eps = m.D.ldlt().solve(sigma);
  EXPECT_NEAR(eps(0), 1e8 / E, 1e-15);
  EXPECT_NEAR(eps(1), -nu * 1e8 / E, 1e-15);
}

TEST(Material, RejectsImpossibleConstants) {
  EXPECT_THROW(isotropic(-1.0, 0.3), InputError);
  EXPECT_THROW(isotropic(0.0, 0.3), InputError);
  EXPECT_THROW(isotropic(1e9, 0.5), InputError);
  EXPECT_THROW(isotropic(1e9, -1.0), InputError);
  EXPECT_THROW(isotropic(std::numeric_limits<Real>::quiet_NaN(), 0.3), InputError);
  EXPECT_NO_THROW(isotropic(1e9, -0.5));  // auxetic materials are elliptic
}

TEST(Material, TensorRoundTripAndSymmetryChecks) {
  const Material m = isotropic(1e10, 0.25);
  HookeTensor C = to_tensor(m);
  EXPECT_NEAR((from_tensor(C).D - m.D).norm(), 0.0, 1e-3);
  C[0][1][2][2] += 1e8;  // breaks C_ijkl = C_jikl
  EXPECT_THROW(from_tensor(C), InputError);
  Voigt6 D = m.D;
  D(0, 3) = 1e9;  // breaks major symmetry
  EXPECT_THROW(anisotropic(D), InputError);
  D = m.D;
  D(3, 3) = -1e9;  // not elliptic
  EXPECT_THROW(anisotropic(D), InputError);
}

TEST(Material, AnisotropicOrthotropicIsAccepted) {
  Voigt6 D = Voigt6::Zero();
  D.topLeftCorner<3, 3>() << 2e11, 5e10, 4e10, 5e10, 1e11, 3e10, 4e10, 3e10, 8e10;
  D.bottomRightCorner<3, 3>().diagonal() << 3e10, 2e10, 4e10;
  const Material m = anisotropic(D);
  EXPECT_GT(m.ellipticity, 0.0);
}
