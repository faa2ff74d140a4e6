// driver: validate() on problems built in code (src/fricon/driver/problem.hpp).

#include <array>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/fe/material.hpp"

namespace fricon::driver {
namespace {

using ::testing::HasSubstr;

constexpr Real kNan = std::numeric_limits<Real>::quiet_NaN();
constexpr Real kInf = std::numeric_limits<Real>::infinity();

/// The message of the InputError that validate throws, or "" when it does not throw.
std::string error_of(const Problem& p) {
  return test::input_error_of([&p] { validate(p); });
}

/// A valid problem with every section: clamped at x0, pulled at x1, contact on z0.
Problem base() {
  return test::clamped_problem();
}

/// The isotropic Hooke matrix of steel, as a general one.
std::array<std::array<Real, 6>, 6> steel_voigt() {
  const auto D = fe::isotropic(2e11, 0.3).D;
  std::array<std::array<Real, 6>, 6> out{};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      out[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = D(i, j);
  return out;
}

FrictionOptions table_law(std::vector<Real> t, std::vector<Real> f) {
  FrictionOptions fr;
  fr.law = contact::FrictionLawKind::Table;
  fr.t = std::move(t);
  fr.f = std::move(f);
  return fr;
}

// ------------------------------------------------------------------------------------------
// Valid problems.

TEST(Validate, DefaultsAndTheBaseAreValid) {
  EXPECT_NO_THROW(validate(Problem{}));
  EXPECT_NO_THROW(validate(base()));
}

TEST(Validate, EveryLawAndModelIsAccepted) {
  auto p = base();
  p.contact.front().friction.law = contact::FrictionLawKind::Constant;
  p.contact.front().friction.value = 0.0;
  p.contact.front().slip_bound = 0.0;
  EXPECT_NO_THROW(validate(p));
  p.contact.front().friction = table_law({0.0, 1e-5}, {0.3, 0.2});
  EXPECT_NO_THROW(validate(p));
  p.material.model = fe::MaterialModel::Anisotropic;
  p.material.voigt = steel_voigt();
  p.material.young = -1.0;  // not used by the anisotropic model
  EXPECT_NO_THROW(validate(p));
}

TEST(Validate, ParametersOfOtherLawsAreNotChecked) {
  auto p = base();
  p.contact.front().friction.law = contact::FrictionLawKind::Constant;
  p.contact.front().friction.param = -1.0;
  EXPECT_NO_THROW(validate(p));
}

TEST(Validate, PartialConstraintOnTheContactFaceIsAllowed) {
  auto p = base();
  p.dirichlet.push_back({"z0", {false, false, true}});
  p.dirichlet.push_back({"z0", {true, false, false}});
  EXPECT_NO_THROW(validate(p));
}

// ------------------------------------------------------------------------------------------
// Each bad value, named by its key.

struct BadCase {
  const char* name;
  std::function<void(Problem&)> change;
  std::string message;  ///< the whole message, or a prefix when `prefix_only`
  bool prefix_only = false;
};

std::vector<BadCase> mesh_and_material_cases() {
  using M = fe::MaterialModel;
  return {
      {"SizeZero", [](Problem& p) { p.mesh.size[1] = 0.0; },
       "<memory>: mesh.size[1]: expected a positive number [m], got 0.0"},
      {"SizeInfinite", [](Problem& p) { p.mesh.size[0] = kInf; },
       "<memory>: mesh.size[0]: expected a positive number [m], got inf (numbers must be finite)"},
      {"CellsZero", [](Problem& p) { p.mesh.cells[2] = 0; },
       "<memory>: mesh.cells[2]: expected an integer >= 1, got 0"},
      {"CellsTooMany",
       [](Problem& p) {
         p.mesh.cells = {1000, 1000, 1000};
       },
       "<memory>: mesh.cells: expected at most 100000000 cubes in all, got 1000 x 1000 x 1000 = "
       "1e+09"},
      {"MeshKindCast", [](Problem& p) { p.mesh.kind = static_cast<MeshKind>(7); },
       "<memory>: mesh.kind: expected one of \"brick\", \"gmsh\", \"arrays\", got 7 (a value "
       "outside the enum)"},
      {"YoungNegative", [](Problem& p) { p.material.young = -1.0; },
       "<memory>: material.young: expected a positive number [Pa], got -1.0"},
      {"YoungNan", [](Problem& p) { p.material.young = kNan; },
       "<memory>: material.young: expected a positive number [Pa], got nan (numbers must be "
       "finite)"},
      {"PoissonHalf", [](Problem& p) { p.material.poisson = 0.5; },
       "<memory>: material.poisson: expected a number in (-1, 0.5), got 0.5"},
      {"PoissonMinusOne", [](Problem& p) { p.material.poisson = -1.0; },
       "<memory>: material.poisson: expected a number in (-1, 0.5), got -1.0"},
      {"MaterialModelCast", [](Problem& p) { p.material.model = static_cast<M>(5); },
       "<memory>: material.model: expected one of \"isotropic\", \"anisotropic\", got 5", true},
      {"VoigtMissing", [](Problem& p) { p.material.model = M::Anisotropic; },
       "<memory>: material.voigt: expected a 6x6 Hooke matrix [Pa] (material.model = "
       "\"anisotropic\" needs one), got none"},
      {"VoigtNan",
       [](Problem& p) {
         p.material.model = M::Anisotropic;
         p.material.voigt = steel_voigt();
         (*p.material.voigt)[4][4] = kNan;
       },
       "<memory>: material.voigt[4][4]: expected a number [Pa], got nan (numbers must be finite)"},
      {"VoigtNotSymmetric",
       [](Problem& p) {
         p.material.model = M::Anisotropic;
         p.material.voigt = steel_voigt();
         (*p.material.voigt)[0][1] *= 2.0;
       },
       "<memory>: material.voigt: Hooke matrix is not symmetric: D[0][1]", true},
      {"VoigtNotElliptic",
       [](Problem& p) {
         p.material.model = M::Anisotropic;
         p.material.voigt = steel_voigt();
         (*p.material.voigt)[2][2] = -1e11;
       },
       "<memory>: material.voigt: Hooke tensor is not elliptic", true},
  };
}

std::vector<BadCase> load_and_support_cases() {
  return {
      {"VolumeForceInfinite", [](Problem& p) { p.volume_force[2] = -kInf; },
       "<memory>: volume_force[2]: expected a number [N/m^3], got -inf (numbers must be finite)"},
      {"DirichletBoundaryEmpty", [](Problem& p) { p.dirichlet[0].boundary.clear(); },
       "<memory>: dirichlet[0].boundary: expected a non-empty boundary tag, got \"\""},
      {"DirichletComponentsEmpty",
       [](Problem& p) {
         p.dirichlet.push_back({"y0", {false, false, false}});
       },
       "<memory>: dirichlet[1].components: expected a string of distinct letters from \"xyz\", "
       "got \"\""},
      {"TractionBoundaryEmpty", [](Problem& p) { p.traction[0].boundary.clear(); },
       "<memory>: traction[0].boundary: expected a non-empty boundary tag, got \"\""},
      {"TractionNan", [](Problem& p) { p.traction[0].value[1] = kNan; },
       "<memory>: traction[0].value[1]: expected a number [Pa], got nan (numbers must be finite)"},
      {"ContactOnClampedFace",
       [](Problem& p) {
         p.dirichlet.push_back({"z0", {true, true, true}});
       },
       "<memory>: contact.boundary: contact and Dirichlet on the same face \"z0\": [[dirichlet]] "
       "fixes all of x, y, z there, so no contact node would be left"},
      {"ContactOnFaceClampedInTwoEntries",
       [](Problem& p) {
         p.dirichlet.push_back({"z0", {true, true, false}});
         p.dirichlet.push_back({"z0", {false, false, true}});
       },
       "<memory>: contact.boundary: contact and Dirichlet on the same face \"z0\"", true},
  };
}

std::vector<BadCase> contact_cases() {
  using K = contact::FrictionLawKind;
  return {
      {"ContactBoundaryEmpty", [](Problem& p) { p.contact.front().boundary.clear(); },
       "<memory>: contact.boundary: expected a non-empty boundary tag, got \"\""},
      {"SlipBoundNegative", [](Problem& p) { p.contact.front().slip_bound = -2e7; },
       "<memory>: contact.slip_bound: expected a number >= 0 [Pa], got -20000000.0"},
      {"SlipBoundNan", [](Problem& p) { p.contact.front().slip_bound = kNan; },
       "<memory>: contact.slip_bound: expected a number >= 0 [Pa], got nan (numbers must be "
       "finite)"},
      {"PatchesCast",
       [](Problem& p) { p.contact.front().patches = static_cast<contact::PatchKind>(9); },
       "<memory>: contact.patches: expected one of \"chessboard\"", true},
      {"LawCast", [](Problem& p) { p.contact.front().friction.law = static_cast<K>(9); },
       "<memory>: contact.friction.law: expected one of \"paper\", \"constant\", \"table\", "
       "\"expression\", \"function\", got 9",
       true},
      {"ParamZero", [](Problem& p) { p.contact.front().friction.param = 0.0; },
       "<memory>: contact.friction.param: expected a positive number [1/m], got 0.0"},
      {"ParamInfinite", [](Problem& p) { p.contact.front().friction.param = kInf; },
       "<memory>: contact.friction.param: expected a positive number [1/m], got inf (numbers "
       "must be finite)"},
      {"ConstantNegative",
       [](Problem& p) {
         p.contact.front().friction.law = K::Constant;
         p.contact.front().friction.value = -0.1;
       },
       "<memory>: contact.friction.value: expected a number >= 0, got -0.1"},
      {"TableEmpty", [](Problem& p) { p.contact.front().friction = table_law({}, {}); },
       "<memory>: contact.friction.t: expected a non-empty array of numbers, got an empty array"},
      {"TableSlipNegative",
       [](Problem& p) { p.contact.front().friction = table_law({-1e-5}, {0.3}); },
       "<memory>: contact.friction.t[0]: expected a number >= 0 [m], got -1e-05"},
      {"TableNotIncreasing",
       [](Problem& p) {
         p.contact.front().friction = table_law({0.0, 2e-5, 1e-5}, {0.3, 0.2, 0.1});
       },
       "<memory>: contact.friction.t[2]: expected slips in strictly increasing order, got 1e-05 "
       "after 2e-05"},
      {"TableRepeated",
       [](Problem& p) {
         p.contact.front().friction = table_law({0.0, 0.0}, {0.3, 0.2});
       },
       "<memory>: contact.friction.t[1]: expected slips in strictly increasing order, got 0.0 "
       "after 0.0"},
      {"TableFEmpty", [](Problem& p) { p.contact.front().friction = table_law({0.0}, {}); },
       "<memory>: contact.friction.f: expected a non-empty array of numbers, got an empty array"},
      {"TableFNegative",
       [](Problem& p) {
         p.contact.front().friction = table_law({0.0, 1.0}, {0.3, -0.2});
       },
       "<memory>: contact.friction.f[1]: expected a number >= 0, got -0.2"},
      {"TableFNan",
       [](Problem& p) {
         p.contact.front().friction = table_law({0.0, 1.0}, {0.3, kNan});
       },
       "<memory>: contact.friction.f[1]: expected a number >= 0, got nan (numbers must be "
       "finite)"},
      {"TableLengthsDiffer",
       [](Problem& p) {
         p.contact.front().friction = table_law({0.0, 1.0}, {0.3, 0.2, 0.1});
       },
       "<memory>: contact.friction.f: expected as many values as contact.friction.t (2), got 3"},
  };
}

std::vector<BadCase> solver_and_output_cases() {
  return {
      {"OuterTolZero", [](Problem& p) { p.solver.outer.tol = 0.0; },
       "<memory>: solver.outer_tol: expected a positive number, got 0.0"},
      {"OuterTolNan", [](Problem& p) { p.solver.outer.tol = kNan; },
       "<memory>: solver.outer_tol: expected a positive number, got nan (numbers must be finite)"},
      {"OuterMaxZero", [](Problem& p) { p.solver.outer.max_iterations = 0; },
       "<memory>: solver.outer_max: expected an integer >= 1, got 0"},
      {"QpRtolZero", [](Problem& p) { p.solver.qp.rel_tolerance = 0.0; },
       "<memory>: solver.qp_rtol: expected a number in (0, 1), got 0.0"},
      {"QpRtolOne", [](Problem& p) { p.solver.qp.rel_tolerance = 1.0; },
       "<memory>: solver.qp_rtol: expected a number in (0, 1), got 1.0"},
      {"QpMaxNegative", [](Problem& p) { p.solver.qp.max_iterations = -3; },
       "<memory>: solver.qp_max: expected an integer >= 1, got -3"},
      {"AndersonDepthZero", [](Problem& p) { p.solver.outer.anderson_depth = 0; },
       "<memory>: solver.anderson_depth: expected an integer in [1, 20], got 0"},
      {"AndersonDepth21", [](Problem& p) { p.solver.outer.anderson_depth = 21; },
       "<memory>: solver.anderson_depth: expected an integer in [1, 20], got 21"},
      {"DualOperatorCast",
       [](Problem& p) { p.solver.dual_operator = static_cast<dual::DualOperatorKind>(42); },
       "<memory>: solver.dual_operator: expected one of \"auto\"", true},
      {"AccelerationCast",
       [](Problem& p) { p.solver.outer.acceleration = static_cast<outer::Acceleration>(42); },
       "<memory>: solver.acceleration: expected one of \"none\"", true},
      {"QpVariantCast", [](Problem& p) { p.solver.qp.variant = static_cast<qp::MpgpVariant>(42); },
       "<memory>: solver.qp_variant: expected one of", true},
      {"OutputDirEmpty", [](Problem& p) { p.output.dir.clear(); },
       "<memory>: output.dir: expected a non-empty folder name, got \"\""},
  };
}

std::vector<BadCase> bad_cases() {
  std::vector<BadCase> all;
  for (auto part : {mesh_and_material_cases(), load_and_support_cases(), contact_cases(),
                    solver_and_output_cases()})
    all.insert(all.end(), part.begin(), part.end());
  return all;
}

void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.name;
}

class ValidateRejects : public ::testing::TestWithParam<BadCase> {};

TEST_P(ValidateRejects, NamingTheKey) {
  const auto& c = GetParam();
  Problem p = base();
  c.change(p);
  const std::string message = error_of(p);
  if (c.prefix_only) {
    EXPECT_EQ(message.substr(0, c.message.size()), c.message) << message;
  } else {
    EXPECT_EQ(message, c.message);
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, ValidateRejects, ::testing::ValuesIn(bad_cases()),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

// ------------------------------------------------------------------------------------------
// Where: the position of the key, of its closest enclosing key, or the source.

TEST(Validate, NamesTheSourceWithoutPositions) {
  Problem p = base();
  p.source = "paper(n = 4)";
  p.material.young = 0.0;
  EXPECT_EQ(error_of(p), "paper(n = 4): material.young: expected a positive number [Pa], got 0.0");
}

TEST(Validate, NamesThePositionOfTheKeyOrOfItsTable) {
  Problem p = base();
  p.source = "f.toml";
  p.positions = {{"material", "f.toml:3:2"},
                 {"material.young", "f.toml:4:1"},
                 {"dirichlet", "f.toml:9:3"},
                 {"contact", "f.toml:20:2"},
                 {"contact.friction.t[1]", "f.toml:22:9"},
                 {"solver.qp_max", "--set solver.qp_max=0"}};
  p.material.young = -1.0;
  EXPECT_THAT(error_of(p), HasSubstr("f.toml:4:1: material.young: "));
  p.material.young = 1e9;
  p.material.poisson = 0.7;
  EXPECT_THAT(error_of(p), HasSubstr("f.toml:3:2: material.poisson: "));
  p.material.poisson = 0.3;
  p.dirichlet.push_back({"", {true, true, true}});
  EXPECT_THAT(error_of(p), HasSubstr("f.toml:9:3: dirichlet[1].boundary: "));
  p.dirichlet.pop_back();
  p.contact.front().friction = table_law({0.0, -1.0}, {0.3, 0.2});
  EXPECT_THAT(error_of(p), HasSubstr("f.toml:22:9: contact.friction.t[1]: "));
  p.contact.front().friction = table_law({0.0}, {-0.3});
  EXPECT_THAT(error_of(p), HasSubstr("f.toml:20:2: contact.friction.f[0]: "));
  p.contact.front().friction = {};
  p.dirichlet.push_back({"z0", {true, true, true}});
  EXPECT_THAT(error_of(p), HasSubstr("f.toml:20:2: contact.boundary: contact and Dirichlet"));
  p.dirichlet.pop_back();
  p.solver.qp.max_iterations = 0;
  EXPECT_EQ(error_of(p), "--set solver.qp_max=0: solver.qp_max: expected an integer >= 1, got 0");
  p.solver.qp.max_iterations = 1;
  p.output.dir.clear();
  EXPECT_THAT(error_of(p), HasSubstr("f.toml: output.dir: "));  // no position: the source
}

}  // namespace
}  // namespace fricon::driver
