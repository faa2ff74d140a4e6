// io: the TOML problem-file reader (src/fricon/io/problem_file.hpp).

#include "fricon/io/problem_file.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "common/fixtures.hpp"
#include "fricon/core/error.hpp"
#include "fricon/fe/material.hpp"

namespace fricon::io {
namespace {

using ::testing::HasSubstr;

const std::string kExamples = test::source_path("examples/").string();

/// The message of the InputError that parsing throws, or "" when it does not throw.
std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return test::input_error_of([&] { (void)parse_problem(text, "t.toml", overrides); });
}

/// The message of the InputError that reading `file` throws, or "" when it does not throw.
std::string read_error(const std::string& file, const std::vector<std::string>& overrides = {}) {
  return test::input_error_of([&] { (void)read_problem(file, overrides); });
}

// ------------------------------------------------------------------------------------------
// Valid input.

TEST(ProblemFile, PaperBrickExample) {
  const auto p = read_problem(kExamples + "paper-brick.toml");
  EXPECT_EQ(p.source, kExamples + "paper-brick.toml");
  EXPECT_EQ(enum_name(p.mesh.kind), "brick");
  EXPECT_EQ(p.mesh.size, (std::array<Real, 3>{3.0, 1.0, 1.0}));
  EXPECT_EQ(p.mesh.cells, (std::array<Index, 3>{12, 4, 4}));
  EXPECT_EQ(enum_name(p.material.model), "isotropic");
  EXPECT_DOUBLE_EQ(p.material.young, 21.19e10);
  EXPECT_DOUBLE_EQ(p.material.poisson, 0.277);
  EXPECT_FALSE(p.material.voigt.has_value());
  ASSERT_EQ(p.dirichlet.size(), 1u);
  EXPECT_EQ(p.dirichlet[0].boundary, "x0");
  EXPECT_EQ(p.dirichlet[0].components, (std::array<bool, 3>{true, true, true}));
  ASSERT_EQ(p.traction.size(), 2u);
  EXPECT_EQ(p.traction[0].boundary, "x1");
  EXPECT_EQ(p.traction[0].value, Vec3(1.0e7, 0.0, 2.0e7));
  EXPECT_EQ(p.traction[1].boundary, "z1");
  EXPECT_EQ(p.traction[1].value, Vec3(0.0, 0.0, -3.0e7));
  EXPECT_EQ(p.volume_force, Vec3::Zero());
  ASSERT_EQ(p.contact.size(), 1u);
  EXPECT_EQ(p.contact.front().boundary, "z0");
  EXPECT_DOUBLE_EQ(p.contact.front().slip_bound, 2.0e7);
  EXPECT_EQ(enum_name(p.contact.front().patches), "chessboard");
  EXPECT_EQ(enum_name(p.contact.front().friction.law), "paper");
  EXPECT_DOUBLE_EQ(p.contact.front().friction.param, 6.0e4);
  EXPECT_DOUBLE_EQ(p.solver.outer.tol, 1.0e-4);
  EXPECT_EQ(p.solver.outer.max_iterations, 50);
  EXPECT_DOUBLE_EQ(p.solver.qp.rel_tolerance, 1.0e-6);
  EXPECT_EQ(p.output.dir, "results/paper-brick");
}

TEST(ProblemFile, ElasticBrickExampleHasNoContact) {
  const auto p = read_problem(kExamples + "elastic-brick.toml");
  EXPECT_TRUE(p.contact.empty());
  EXPECT_EQ(p.traction.size(), 2u);
  EXPECT_EQ(p.output.dir, "results/elastic-brick");
}

TEST(ProblemFile, IssueExampleParses) {
  // The file of the foundation issue, verbatim apart from the comments.
  const auto p = parse_problem(R"([mesh]
kind = "brick"
size = [3.0, 1.0, 1.0]
cells = [12, 4, 4]
[material]
young = 21.19e10
poisson = 0.277
[[dirichlet]]
boundary = "x0"
[[traction]]
boundary = "x1"
value = [1.0e7, 0.0, 2.0e7]
[[traction]]
boundary = "z1"
value = [0.0, 0.0, -3.0e7]
[output]
dir = "results/paper-brick"
)",
                               "issue.toml");
  EXPECT_EQ(p.traction.size(), 2u);
  EXPECT_TRUE(p.contact.empty());
}

TEST(ProblemFile, DefaultsApply) {
  const auto p = parse_problem("[mesh]\n[material]\n", "min.toml");
  const driver::Problem d;
  EXPECT_EQ(p.source, "min.toml");
  EXPECT_EQ(p.title, d.title);
  EXPECT_EQ(p.mesh.kind, d.mesh.kind);
  EXPECT_EQ(p.mesh.size, d.mesh.size);
  EXPECT_EQ(p.mesh.cells, d.mesh.cells);
  EXPECT_EQ(p.material.model, d.material.model);
  EXPECT_EQ(p.material.young, d.material.young);
  EXPECT_EQ(p.material.poisson, d.material.poisson);
  EXPECT_TRUE(p.dirichlet.empty());
  EXPECT_TRUE(p.traction.empty());
  EXPECT_TRUE(p.contact.empty());
  EXPECT_EQ(p.solver.outer.tol, d.solver.outer.tol);
  EXPECT_EQ(p.solver.outer.max_iterations, d.solver.outer.max_iterations);
  EXPECT_EQ(p.solver.qp.rel_tolerance, d.solver.qp.rel_tolerance);
  EXPECT_EQ(p.solver.qp.max_iterations, d.solver.qp.max_iterations);
  EXPECT_EQ(p.solver.warm_start, d.solver.warm_start);
  EXPECT_EQ(p.solver.dual_operator, d.solver.dual_operator);
  EXPECT_EQ(p.output.dir, d.output.dir);

  // An empty [contact] enables contact with every default, the paper's law included.
  const auto c = parse_problem("[mesh]\n[material]\n[contact]\n", "min.toml");
  ASSERT_EQ(c.contact.size(), 1u);
  const driver::ContactOptions dc;
  EXPECT_EQ(c.contact.front().boundary, dc.boundary);
  EXPECT_EQ(c.contact.front().slip_bound, dc.slip_bound);
  EXPECT_EQ(c.contact.front().friction.law, dc.friction.law);
  EXPECT_EQ(c.contact.front().friction.param, dc.friction.param);
}

TEST(ProblemFile, OtherValidForms) {
  const auto p = parse_problem(R"(title = "t"
volume_force = [0, 0, -78500]
[mesh]
size = [2, 1, 1]
cells = [2, 1, 1]
[material]
young = 200000000000
[[dirichlet]]
boundary = "x0"
components = "zx"
[contact]
boundary = "z0"
slip_bound = 0
[contact.friction]
law = "table"
t = [0, 1e-5, 2e-5]
f = [0.5, 0.3, 0.2]
[solver]
outer_max = 3
qp_max = 10
warm_start = false
dual_operator = "schur"
)",
                               "t.toml");
  EXPECT_EQ(p.title, "t");
  EXPECT_EQ(p.volume_force, Vec3(0, 0, -78500));
  EXPECT_EQ(p.mesh.size, (std::array<Real, 3>{2.0, 1.0, 1.0}));  // integers accepted as reals
  EXPECT_DOUBLE_EQ(p.material.young, 2e11);
  EXPECT_EQ(p.dirichlet[0].components, (std::array<bool, 3>{true, false, true}));
  EXPECT_EQ(p.contact.front().slip_bound, 0.0);
  EXPECT_EQ(enum_name(p.contact.front().friction.law), "table");
  EXPECT_EQ(p.contact.front().friction.t, (std::vector<Real>{0, 1e-5, 2e-5}));
  EXPECT_EQ(p.contact.front().friction.f, (std::vector<Real>{0.5, 0.3, 0.2}));
  EXPECT_EQ(p.solver.outer.max_iterations, 3);
  EXPECT_EQ(p.solver.qp.max_iterations, 10);
  EXPECT_FALSE(p.solver.warm_start);
  EXPECT_EQ(enum_name(p.solver.dual_operator), "schur");

  const auto c = parse_problem(
      "[mesh]\n[material]\n[contact.friction]\nlaw = \"constant\"\nvalue = 0.25\n", "t.toml");
  EXPECT_EQ(enum_name(c.contact.front().friction.law), "constant");
  EXPECT_EQ(c.contact.front().friction.value, 0.25);
}

TEST(ProblemFile, AnisotropicMaterial) {
  // The isotropic Hooke matrix, written out as a general one.
  const auto D = fe::isotropic(2e11, 0.3).D;
  std::ostringstream text;
  text << "[mesh]\n[material]\nmodel = \"anisotropic\"\nvoigt = [\n";
  for (int i = 0; i < 6; ++i) {
    text << "  [";
    for (int j = 0; j < 6; ++j)
      text << (j ? ", " : "") << fmt::format("{:.17g}", D(i, j));
    text << "],\n";
  }
  text << "]\n";
  const auto p = parse_problem(text.str(), "aniso.toml");
  ASSERT_TRUE(p.material.voigt.has_value());
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      EXPECT_EQ((*p.material.voigt)[i][j], D(i, j));
}

// ------------------------------------------------------------------------------------------
// Overrides.

const std::string kPaper = kExamples + "paper-brick.toml";

TEST(ProblemFileOverrides, ChangeValues) {
  const auto p =
      read_problem(kPaper, {"mesh.cells=[24,8,8]", "material.young=2e11", "output.dir=\"x\"",
                            "solver.warm_start=false", "title=bare_word"});
  EXPECT_EQ(p.mesh.cells, (std::array<Index, 3>{24, 8, 8}));
  EXPECT_EQ(p.material.young, 2e11);
  EXPECT_EQ(p.output.dir, "x");
  EXPECT_FALSE(p.solver.warm_start);
  EXPECT_EQ(p.title, "bare_word");
}

TEST(ProblemFileOverrides, FrictionLawSwitchDropsTheFileParameters) {
  // The file gives param = 6e4 for the paper's law; switching the law from the command line
  // must not trip over it.
  const auto p = read_problem(kPaper, {"contact.friction.law=constant"});
  EXPECT_EQ(enum_name(p.contact.front().friction.law), "constant");
  EXPECT_EQ(p.contact.front().friction.value, driver::FrictionOptions{}.value);
  const auto q =
      read_problem(kPaper, {"contact.friction.law=\"constant\"", "contact.friction.value=0.2"});
  EXPECT_EQ(q.contact.front().friction.value, 0.2);
  const auto r = read_problem(kPaper, {"contact.friction.law=table", "contact.friction.t=[0, 1]",
                                       "contact.friction.f=[0.3, 0.1]"});
  EXPECT_EQ(r.contact.front().friction.f, (std::vector<Real>{0.3, 0.1}));
  // A parameter of another law given on the command line is still an error.
  EXPECT_THAT(read_error(kPaper, {"contact.friction.law=constant", "contact.friction.param=1"}),
              HasSubstr("--set contact.friction.param=1: contact.friction.param: not used by law "
                        "\"constant\""));
}

TEST(ProblemFileOverrides, CoulombFromTheCommandLineDropsTheFileSlipBound) {
  // The file gives slip_bound (Tresca's); --set contact.model=coulomb makes it meaningless and
  // drops it, but a slip bound given on the command line with it is an error that says why.
  const auto p = read_problem(kPaper, {"contact.model=coulomb"});
  EXPECT_EQ(p.contact.front().model, contact::FrictionModel::Coulomb);
  EXPECT_FALSE(p.contact.front().start_slip_bound.has_value());
  EXPECT_THAT(read_error(kPaper, {"contact.model=coulomb", "contact.slip_bound=1e7"}),
              HasSubstr("--set contact.slip_bound=1e7: contact.slip_bound: not used by model "
                        "\"coulomb\""));
}

TEST(ProblemFileOverrides, ArrayOfTablesByIndex) {
  const auto p = read_problem(kPaper, {"traction.1.value=[0,0,-1e7]", "traction[0].boundary=y1",
                                       "dirichlet.0.components=z"});
  EXPECT_EQ(p.traction[1].value, Vec3(0, 0, -1e7));
  EXPECT_EQ(p.traction[0].boundary, "y1");
  EXPECT_EQ(p.traction[0].value, Vec3(1e7, 0, 2e7));  // untouched
  EXPECT_EQ(p.dirichlet[0].components, (std::array<bool, 3>{false, false, true}));
  // Index == size appends an entry.
  const auto q = read_problem(kPaper, {"dirichlet.1.boundary=x1", "dirichlet.1.components=x"});
  ASSERT_EQ(q.dirichlet.size(), 2u);
  EXPECT_EQ(q.dirichlet[1].boundary, "x1");
  // An element of a plain array.
  const auto r = read_problem(kPaper, {"mesh.cells.0=6"});
  EXPECT_EQ(r.mesh.cells, (std::array<Index, 3>{6, 4, 4}));
}

TEST(ProblemFileOverrides, CreatesMissingTables) {
  const auto p = read_problem(kExamples + "elastic-brick.toml", {"contact.slip_bound=1e7"});
  ASSERT_EQ(p.contact.size(), 1u);
  EXPECT_EQ(p.contact.front().slip_bound, 1e7);
  EXPECT_EQ(p.contact.front().boundary, "z0");
}

TEST(ProblemFileOverrides, AreValidatedAndNamed) {
  EXPECT_THAT(error_of("[mesh]\n[material]\n", {"material.young=-1"}),
              HasSubstr("--set material.young=-1: material.young: expected a positive number "
                        "[Pa], got -1.0"));
  EXPECT_THAT(error_of("[mesh]\n[material]\n", {"mesh.cells=[24,8,0]"}),
              HasSubstr("--set mesh.cells=[24,8,0]: mesh.cells[2]: expected an integer >= 1"));
  EXPECT_THAT(error_of("[mesh]\n[material]\n", {"material.yung=2e11"}),
              HasSubstr("--set material.yung=2e11: unknown key 'material.yung' (did you mean "
                        "'material.young'?)"));
  EXPECT_THAT(error_of("[mesh]\n[material]\n", {"contact.frction.law=paper"}),
              HasSubstr("--set contact.frction.law=paper: unknown key 'contact.frction'"));
  EXPECT_THAT(error_of("[mesh]\n[material]\n", {"material.young"}),
              HasSubstr("--set material.young: expected KEY=VALUE"));
  EXPECT_THAT(error_of("[mesh]\n[material]\n", {"mesh.cells=[1,2"}),
              HasSubstr("--set mesh.cells=[1,2: invalid TOML value"));
  EXPECT_THAT(error_of("[mesh]\n[material]\n", {"mesh..cells=1"}),
              HasSubstr("--set mesh..cells=1: invalid key"));
  // An index beyond size_t threw std::out_of_range (an internal error, exit code 3).
  EXPECT_THAT(error_of("[mesh]\n[material]\n", {"dirichlet.99999999999999999999999.boundary=x0"}),
              HasSubstr("index 99999999999999999999999 out of range: 'dirichlet' has 0 entries"));
  EXPECT_THAT(error_of("[mesh]\n[material]\n", {"material.young=inf"}),
              HasSubstr("--set material.young=inf: material.young: expected a positive number "
                        "[Pa], got inf (numbers must be finite)"));
  EXPECT_THAT(error_of("[mesh]\n[material]\n[[traction]]\nboundary=\"x1\"\nvalue=[0,0,1]\n",
                       {"traction.2.value=[0,0,1]"}),
              HasSubstr("--set traction.2.value=[0,0,1]: index 2 out of range: 'traction' has 1"));
  EXPECT_THAT(error_of("[mesh]\nkind = \"brick\"\n[material]\n", {"mesh.kind.x=1"}),
              HasSubstr("--set mesh.kind.x=1: 'mesh.kind' is \"brick\", not a table"));
  // An override of a key that the file got right does not hide an error elsewhere in the file.
  EXPECT_THAT(error_of("[mesh]\n[material]\npoisson = 0.6\n", {"material.young=1"}),
              HasSubstr("t.toml:3:1: material.poisson"));
  // A later override replaces an earlier one, and the file's value.
  const auto p = parse_problem("[mesh]\n[material]\nyoung = -5\n", "t.toml",
                               {"material.young=-1", "material.young=3"});
  EXPECT_EQ(p.material.young, 3.0);
}

// ------------------------------------------------------------------------------------------
// Errors in the file: each names the file, the line and column, and the key path.

struct ErrorCase {
  const char* name;
  std::string text;
  std::vector<std::string> expected;  ///< substrings of the message
};

// Four valid lines that the cases below extend.
const std::string kBase = "[mesh]\ncells = [12, 4, 4]\n[material]\nyoung = 21.19e10\n";

std::vector<ErrorCase> error_cases() {
  return {
      {"SyntaxError", "[mesh]\ncells = [12, 4,\n[material]\n", {"t.toml:3:", "invalid TOML"}},
      {"DuplicateKey", kBase + "young = 1\n", {"t.toml:5:", "invalid TOML", "young"}},
      {"UnknownTopLevelKey",
       "material_young = 3\n" + kBase,
       {"t.toml:1:1: unknown key 'material_young'", "the top level takes:"}},
      {"UnknownTableHeader",
       kBase + "[slover]\nouter_tol = 1e-3\n",
       {"t.toml:5:2: unknown key 'slover' (did you mean 'solver'?)"}},
      {"UnknownKeyInMesh",
       "[mesh]\ncell = [1, 1, 1]\n[material]\n",
       {"t.toml:2:1: unknown key 'mesh.cell' (did you mean 'mesh.cells'?)"}},
      {"UnknownKeyInContact",
       kBase + "[contact]\nboundary = \"z0\"\nfrction.law = \"paper\"\n",
       {"t.toml:7:1: unknown key 'contact.frction' (did you mean 'contact.friction'?)"}},
      {"UnknownKeyInFriction",
       kBase + "[contact.friction]\nlaw = \"paper\"\nparm = 1\n",
       {"t.toml:7:1: unknown key 'contact.friction.parm' (did you mean "
        "'contact.friction.param'?)"}},
      {"UnknownKeyInDirichlet",
       kBase + "[[dirichlet]]\nboundary = \"x0\"\nfixed = \"xyz\"\n",
       {"t.toml:7:1: unknown key 'dirichlet[0].fixed'", "boundary components"}},
      {"UnknownKeyInSecondTraction",
       kBase + "[[traction]]\nboundary = \"x1\"\nvalue = [1, 0, 0]\n[[traction]]\nboundary = "
               "\"z1\"\nvalue = [0, 0, 1]\nvalu = 1\n",
       {"t.toml:11:1: unknown key 'traction[1].valu' (did you mean 'traction[1].value'?)"}},
      {"UnknownKeyInSolver",
       kBase + "[solver]\nouter_tolerance = 1e-3\n",
       {"t.toml:6:1: unknown key 'solver.outer_tolerance'"}},
      {"UnknownKeyInOutput",
       kBase + "[output]\nfolder = \"x\"\n",
       {"t.toml:6:1: unknown key 'output.folder'"}},
      {"MissingMesh", "[material]\nyoung = 1e9\n", {"t.toml: missing required key 'mesh'"}},
      {"MissingMaterial", "[mesh]\n", {"t.toml: missing required key 'material'"}},
      {"MeshNotATable",
       "mesh = 3\n[material]\n",
       {"t.toml:1:1: mesh: expected a table [mesh], got 3"}},
      {"MeshKind",
       "[mesh]\nkind = \"tetgen\"\n[material]\n",
       {"t.toml:2:1: mesh.kind: expected one of \"brick\", \"gmsh\", \"arrays\", got \"tetgen\""}},
      {"MeshKindArraysInAFile",
       "[mesh]\nkind = \"arrays\"\n[material]\n",
       {"t.toml:2:1: mesh.kind: \"arrays\" is a mesh given by code (fricon.Mesh in Python)"}},
      {"MeshSizeNegative",
       "[mesh]\nsize = [3.0, -1.0, 1.0]\n[material]\n",
       {"t.toml:2:", "mesh.size[1]: expected a positive number [m], got -1.0"}},
      {"MeshSizeLength",
       "[mesh]\nsize = [3.0, 1.0]\n[material]\n",
       {"t.toml:2:1: mesh.size: expected an array of 3 numbers, got 2 element(s)"}},
      {"MeshCellsFloat",
       "[mesh]\ncells = [12.0, 4, 4]\n[material]\n",
       {"t.toml:2:", "mesh.cells[0]: expected an integer >= 1, got 12.0 (a float"}},
      {"MeshCellsZero",
       "[mesh]\ncells = [12, 0, 4]\n[material]\n",
       {"t.toml:2:", "mesh.cells[1]: expected an integer >= 1, got 0"}},
      {"YoungNegative",
       "[mesh]\n[material]\nyoung = -1\n",
       {"t.toml:3:1: material.young: expected a positive number [Pa], got -1.0"}},
      {"YoungWrongType",
       "[mesh]\n[material]\nyoung = \"steel\"\n",
       {"t.toml:3:1: material.young: expected a positive number [Pa], got \"steel\""}},
      {"PoissonTooLarge",
       "[mesh]\n[material]\npoisson = 0.5\n",
       {"t.toml:3:1: material.poisson: expected a number in (-1, 0.5), got 0.5"}},
      {"MaterialModel",
       "[mesh]\n[material]\nmodel = \"orthotropic\"\n",
       {"t.toml:3:1: material.model: expected one of \"isotropic\", \"anisotropic\""}},
      {"AnisotropicWithoutVoigt",
       "[mesh]\n[material]\nmodel = \"anisotropic\"\n",
       {"t.toml:2:2: missing required key 'material.voigt'"}},
      {"VoigtWrongShape",
       "[mesh]\n[material]\nmodel = \"anisotropic\"\nvoigt = [[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, "
       "0]]\n",
       {"t.toml:4:1: material.voigt: expected 6 rows of 6 numbers [Pa], got 2 row(s)"}},
      {"VoigtRowWrongLength",
       "[mesh]\n[material]\nmodel = \"anisotropic\"\nvoigt = [\n[1, 0, 0, 0, 0, 0],\n[0, 1, 0, 0, "
       "0],\n[0, 0, 1, 0, 0, 0],\n[0, 0, 0, 1, 0, 0],\n[0, 0, 0, 0, 1, 0],\n[0, 0, 0, 0, 0, 1]]\n",
       {"t.toml:6:1: material.voigt[1]: expected an array of 6 numbers, got 5"}},
      {"VoigtNotSymmetric",
       "[mesh]\n[material]\nmodel = \"anisotropic\"\nvoigt = [\n[1, 0.5, 0, 0, 0, 0],\n[0, 1, 0, "
       "0, 0, 0],\n[0, 0, 1, 0, 0, 0],\n[0, 0, 0, 1, 0, 0],\n[0, 0, 0, 0, 1, 0],\n[0, 0, 0, 0, 0, "
       "1]]\n",
       {"t.toml:4:1: material.voigt: ", "not symmetric"}},
      {"VoigtNotElliptic",
       "[mesh]\n[material]\nmodel = \"anisotropic\"\nvoigt = [\n[1, 0, 0, 0, 0, 0],\n[0, 1, 0, 0, "
       "0, 0],\n[0, 0, -1, 0, 0, 0],\n[0, 0, 0, 1, 0, 0],\n[0, 0, 0, 0, 1, 0],\n[0, 0, 0, 0, 0, "
       "1]]\n",
       {"t.toml:4:1: material.voigt: ", "not elliptic"}},
      {"VoigtWithIsotropic",
       "[mesh]\n[material]\nyoung = 1e9\nvoigt = [[1, 0, 0, 0, 0, 0]]\n",
       {"t.toml:4:1: material.voigt: not used by model \"isotropic\""}},
      {"YoungWithAnisotropic",
       "[mesh]\n[material]\nmodel = \"anisotropic\"\nyoung = 1e9\n",
       {"t.toml:4:1: material.young: not used by model \"anisotropic\""}},
      {"VolumeForceNan",
       "volume_force = [0, 0, nan]\n" + kBase,
       {"t.toml:1:",
        "volume_force[2]: expected a number [N/m^3], got nan (numbers must be finite)"}},
      {"TractionInfinite",
       kBase + "[[traction]]\nboundary = \"x1\"\nvalue = [0, -inf, 0]\n",
       {"t.toml:7:", "traction[0].value[1]: expected a number [Pa], got -inf"}},
      {"TractionWithoutValue",
       kBase + "[[traction]]\nboundary = \"x1\"\n",
       {"t.toml:5:", "missing required key 'traction[0].value'"}},
      {"DirichletWithoutBoundary",
       kBase + "[[dirichlet]]\ncomponents = \"x\"\n",
       {"t.toml:5:", "missing required key 'dirichlet[0].boundary'"}},
      {"DirichletEmptyBoundary",
       kBase + "[[dirichlet]]\nboundary = \"\"\n",
       {"t.toml:6:1: dirichlet[0].boundary: expected a non-empty boundary tag, got \"\""}},
      {"DirichletComponentsRepeated",
       kBase + "[[dirichlet]]\nboundary = \"x0\"\ncomponents = \"xx\"\n",
       {"t.toml:7:1: dirichlet[0].components: expected a string of distinct letters from "
        "\"xyz\", got \"xx\""}},
      {"DirichletComponentsLetter",
       kBase + "[[dirichlet]]\nboundary = \"x0\"\ncomponents = \"xw\"\n",
       {"t.toml:7:1: dirichlet[0].components"}},
      {"DirichletAsPlainTable",
       kBase + "[dirichlet]\nboundary = \"x0\"\n",
       {"t.toml:5:", "dirichlet: expected an array of tables [[dirichlet]], got a table"}},
      {"ContactBoundaryNotString",
       kBase + "[contact]\nboundary = 0\n",
       {"t.toml:6:1: contact.boundary: expected a non-empty boundary tag, got 0"}},
      {"SlipBoundNegative",
       kBase + "[contact]\nslip_bound = -2.0e7\n",
       {"t.toml:6:1: contact.slip_bound: expected a number >= 0 [Pa], got -2"}},
      {"Patches",
       kBase + "[contact]\npatches = \"voronoi\"\n",
       {"t.toml:6:1: contact.patches: expected one of \"chessboard\", \"mesh\", \"agglomerate\", "
        "got \"voronoi\""}},
      {"FrictionLaw",
       kBase + "[contact.friction]\nlaw = \"coulomb\"\n",
       {"t.toml:6:1: contact.friction.law: expected one of \"paper\", \"constant\", \"table\""}},
      {"PaperParamZero",
       kBase + "[contact.friction]\nparam = 0\n",
       {"t.toml:6:1: contact.friction.param: expected a positive number [1/m], got 0"}},
      {"ParamWithConstantLaw",
       kBase + "[contact.friction]\nlaw = \"constant\"\nparam = 6e4\n",
       {"t.toml:7:1: contact.friction.param: not used by law \"constant\" (it takes: value)"}},
      {"TableKeysWithPaperLaw",
       kBase + "[contact.friction]\nf = [0.3]\n",
       {"t.toml:6:1: contact.friction.f: not used by law \"paper\""}},
      {"ConstantNegative",
       kBase + "[contact.friction]\nlaw = \"constant\"\nvalue = -0.1\n",
       {"t.toml:7:1: contact.friction.value: expected a number >= 0, got -0.1"}},
      {"TableMissingF",
       kBase + "[contact.friction]\nlaw = \"table\"\nt = [0, 1]\n",
       {"t.toml:5:", "missing required key 'contact.friction.f'"}},
      {"TableNotIncreasing",
       kBase + "[contact.friction]\nlaw = \"table\"\nt = [0, 1e-5, 1e-5]\nf = [0.3, 0.2, 0.1]\n",
       {"t.toml:7:", "contact.friction.t[2]: expected slips in strictly increasing order"}},
      {"TableNegativeSlip",
       kBase + "[contact.friction]\nlaw = \"table\"\nt = [-1e-5, 1e-5]\nf = [0.3, 0.2]\n",
       {"t.toml:7:", "contact.friction.t[0]: expected a number >= 0 [m], got -1e-05"}},
      {"TableLengthMismatch",
       kBase + "[contact.friction]\nlaw = \"table\"\nt = [0, 1e-5]\nf = [0.3]\n",
       {"t.toml:8:1: contact.friction.f: expected as many values as contact.friction.t (2), got "
        "1"}},
      {"TableEmpty",
       kBase + "[contact.friction]\nlaw = \"table\"\nt = []\nf = []\n",
       {"t.toml:7:1: contact.friction.t: expected a non-empty array of numbers, got an empty "
        "array"}},
      {"OuterTolZero",
       kBase + "[solver]\nouter_tol = 0.0\n",
       {"t.toml:6:1: solver.outer_tol: expected a positive number, got 0.0"}},
      {"OuterTolNan",
       kBase + "[solver]\nouter_tol = nan\n",
       {"t.toml:6:1: solver.outer_tol:", "numbers must be finite"}},
      {"OuterMaxFloat",
       kBase + "[solver]\nouter_max = 2.5\n",
       {"t.toml:6:1: solver.outer_max: expected an integer >= 1, got 2.5 (a float"}},
      {"QpMaxZero",
       kBase + "[solver]\nqp_max = 0\n",
       {"t.toml:6:1: solver.qp_max: expected an integer >= 1, got 0"}},
      {"QpRtolOne",
       kBase + "[solver]\nqp_rtol = 1\n",
       {"t.toml:6:1: solver.qp_rtol: expected a number in (0, 1), got 1"}},
      {"WarmStartString",
       kBase + "[solver]\nwarm_start = \"yes\"\n",
       {"t.toml:6:1: solver.warm_start: expected true or false, got \"yes\""}},
      {"DualOperator",
       kBase + "[solver]\ndual_operator = \"sparse\"\n",
       {"t.toml:6:1: solver.dual_operator: expected one of \"auto\", \"implicit\", \"forward\""}},
      {"OutputDirEmpty",
       kBase + "[output]\ndir = \"\"\n",
       {"t.toml:6:1: output.dir: expected a non-empty folder name"}},
      {"TitleNotString", "title = 3\n" + kBase, {"t.toml:1:1: title: expected a string, got 3"}},
      {"ContactOnClampedFace",
       kBase + "[[dirichlet]]\nboundary = \"z0\"\n[contact]\nboundary = \"z0\"\n",
       {"t.toml:8:1: contact.boundary: contact and Dirichlet on the same face \"z0\""}},
      {"ContactOnClampedFaceByDefault",
       kBase + "[[dirichlet]]\nboundary = \"z0\"\ncomponents = \"z\"\n[[dirichlet]]\nboundary = "
               "\"z0\"\ncomponents = \"xy\"\n[contact]\nslip_bound = 1\n",
       {"t.toml:11:2: contact.boundary: contact and Dirichlet on the same face \"z0\""}},
  };
}

void PrintTo(const ErrorCase& c, std::ostream* os) {
  *os << c.name;
}

class ProblemFileError : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(ProblemFileError, NamesFileLineAndKey) {
  const auto& c = GetParam();
  const std::string message = error_of(c.text);
  ASSERT_FALSE(message.empty()) << "no InputError for:\n" << c.text;
  for (const auto& e : c.expected)
    EXPECT_THAT(message, HasSubstr(e));
}

INSTANTIATE_TEST_SUITE_P(Cases, ProblemFileError, ::testing::ValuesIn(error_cases()),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

TEST(ProblemFile, PartialConstraintOnContactFaceIsAllowed) {
  const auto p = parse_problem(kBase +
                                   "[[dirichlet]]\nboundary = \"z0\"\ncomponents = \"z\"\n"
                                   "[contact]\n",
                               "t.toml");
  EXPECT_EQ(p.contact.size(), 1u);
}

TEST(ProblemFile, MissingFile) {
  EXPECT_THAT(read_error("/nonexistent/problem.toml"),
              HasSubstr("/nonexistent/problem.toml: cannot open"));
}

// ------------------------------------------------------------------------------------------
// Positions: where each key was given, for driver::validate's messages.

const std::string kPositioned = R"(title = "t"
[mesh]
size = [3.0, 1.0, 1.0]
[material]
young = 2e11
[[dirichlet]]
boundary = "x0"
[contact]
boundary = "z0"
[contact.friction]
law = "table"
t = [0, 1e-5, 2e-5]
f = [0.3, 0.2, 0.1]
)";

/// The message of the InputError that driver::validate throws, or "" when it does not throw.
std::string validate_error(const driver::Problem& p) {
  return test::input_error_of([&p] { driver::validate(p); });
}

TEST(ProblemFilePositions, RecordsEveryKeyReadAndItsTables) {
  const auto p = parse_problem(kPositioned, "t.toml");
  const std::map<std::string, std::string, std::less<>> expected = {
      {"title", "t.toml:1:1"},
      {"mesh", "t.toml:2:2"},
      {"mesh.size", "t.toml:3:1"},
      {"mesh.size[0]", "t.toml:3:9"},
      {"mesh.size[1]", "t.toml:3:14"},
      {"mesh.size[2]", "t.toml:3:19"},
      {"material", "t.toml:4:2"},
      {"material.young", "t.toml:5:1"},
      {"dirichlet", "t.toml:6:3"},
      {"dirichlet[0]", "t.toml:6:1"},
      {"dirichlet[0].boundary", "t.toml:7:1"},
      {"contact", "t.toml:8:2"},
      {"contact.boundary", "t.toml:9:1"},
      {"contact.friction", "t.toml:10:10"},
      {"contact.friction.law", "t.toml:11:1"},
      {"contact.friction.t", "t.toml:12:1"},
      {"contact.friction.t[0]", "t.toml:12:6"},
      {"contact.friction.t[1]", "t.toml:12:9"},
      {"contact.friction.t[2]", "t.toml:12:15"},
      {"contact.friction.f", "t.toml:13:1"},
      {"contact.friction.f[0]", "t.toml:13:6"},
      {"contact.friction.f[1]", "t.toml:13:11"},
      {"contact.friction.f[2]", "t.toml:13:16"},
  };
  EXPECT_EQ(p.positions.to_map(), expected);
}

TEST(ProblemFilePositions, ProblemModifiedInCodeNamesTheFilePosition) {
  auto p = parse_problem(kPositioned, "t.toml");
  ASSERT_EQ(validate_error(p), "");
  // A key of the file: its own position.
  p.material.young = -1.0;
  EXPECT_EQ(validate_error(p),
            "t.toml:5:1: material.young: expected a positive number [Pa], got -1.0");
  p.material.young = 2e11;
  p.contact.front().friction.t[2] = 1e-6;
  EXPECT_THAT(validate_error(p), HasSubstr("t.toml:12:15: contact.friction.t[2]: expected slips "
                                           "in strictly increasing order, got 1e-06 after 1e-05"));
  p.contact.front().friction.t[2] = 2e-5;
  // A key that the file leaves out: the position of its table.
  p.material.poisson = 0.7;
  EXPECT_THAT(validate_error(p), HasSubstr("t.toml:4:2: material.poisson: "));
  p.material.poisson = 0.3;
  p.dirichlet.push_back({"", {true, true, true}});
  EXPECT_THAT(validate_error(p), HasSubstr("t.toml:6:3: dirichlet[1].boundary: "));
  p.dirichlet.back().boundary = "z0";
  EXPECT_THAT(validate_error(p), HasSubstr("t.toml:9:1: contact.boundary: contact and Dirichlet"));
  p.dirichlet.pop_back();
  // A table that the file lacks: the file.
  p.solver.qp.max_iterations = 0;
  EXPECT_EQ(validate_error(p), "t.toml: solver.qp_max: expected an integer >= 1, got 0");
}

TEST(ProblemFilePositions, SetValuesAreNamedBySet) {
  auto p = read_problem(kPaper, {"material.young=2e11", "mesh.cells=[24,8,8]",
                                 "dirichlet.1.boundary=y0", "dirichlet.1.components=z"});
  EXPECT_EQ(p.positions.at("material.young"), "--set material.young=2e11");
  EXPECT_EQ(p.positions.at("mesh.cells[1]"), "--set mesh.cells=[24,8,8]");
  EXPECT_EQ(p.positions.at("dirichlet[1]"), "--set dirichlet.1.boundary=y0");
  EXPECT_EQ(p.positions.at("dirichlet[1].components"), "--set dirichlet.1.components=z");
  EXPECT_THAT(p.positions.at("material.poisson"), HasSubstr(kPaper + ":"));  // from the file
  p.material.young = 0.0;
  EXPECT_EQ(validate_error(p),
            "--set material.young=2e11: material.young: expected a positive "
            "number [Pa], got 0.0");
  p.material.young = 2e11;
  p.mesh.cells[1] = -8;
  EXPECT_THAT(validate_error(p), HasSubstr("--set mesh.cells=[24,8,8]: mesh.cells[1]: "));
  p.mesh.cells[1] = 8;
  p.dirichlet[1].components = {false, false, false};
  EXPECT_THAT(validate_error(p),
              HasSubstr("--set dirichlet.1.components=z: dirichlet[1].components: "));
}

// One pair written as [[contact]] (issue 33): its keys are recorded as contact[0].*, and
// messages name them so, at the key's own line, or the override that gave the value.
const std::string kOneContactEntry = R"(
[mesh]
[material]
[[dirichlet]]
boundary = "z1"
[[contact]]
boundary = "z0"
slip_bound = -1.0
)";

TEST(ProblemFilePositions, OneContactEntryIsNamedAsTheFileWritesIt) {
  EXPECT_EQ(error_of(kOneContactEntry),
            "t.toml:8:1: contact[0].slip_bound: expected a number >= 0 [Pa], got -1.0");
  EXPECT_EQ(error_of(kOneContactEntry, {"contact.0.slip_bound=-2"}),
            "--set contact.0.slip_bound=-2: contact[0].slip_bound: expected a number >= 0 [Pa], "
            "got -2.0");
  const auto p = parse_problem(kOneContactEntry, "t.toml", {"contact.0.slip_bound=1e7"});
  ASSERT_EQ(p.contact.size(), 1u);
  EXPECT_EQ(p.contact_key(0), "contact[0]");
  EXPECT_EQ(p.where("contact[0].boundary"), "t.toml:7:1");
  // [contact] stays "contact".
  EXPECT_EQ(read_problem(kPaper).contact_key(0), "contact");
}

// A path given by an override is the origin of each of its elements: the record holds the
// override's text once, not once per element (issue 33: a path of N steps from --set or
// Python cost O(N^2) memory, copied at each step).
TEST(ProblemFilePositions, AnOverriddenPathIsRecordedOnce) {
  constexpr int kSteps = 4000;
  std::string path = "dirichlet.1.path=[";
  for (int k = 0; k < kSteps; ++k)
    path += fmt::format("{}{}", k ? ", " : "", 0.5 * k);
  path += "]";
  const auto p = read_problem(kExamples + "loading/brick-hysteresis.toml",
                              {fmt::format("loading.steps={}", kSteps), path});
  ASSERT_EQ(p.dirichlet[1].path.size(), static_cast<std::size_t>(kSteps));
  EXPECT_EQ(p.positions.at("dirichlet[1].path[3999]"), "--set " + path);
  // Linear in the steps: a key per element ("dirichlet[1].path[3999]", 23 characters) plus the
  // override once; the old record held the override's ~40 kB text per element (160 MB).
  constexpr std::size_t kKeyChars = 32;
  EXPECT_LT(p.positions.text_size(), kKeyChars * kSteps + 2 * path.size() + 10000);
  // Copies (one per step of the path) share the record.
  const driver::Problem step = driver::at_step(p, 2);
  EXPECT_EQ(step.positions.find("dirichlet[1].path[0]"), p.positions.find("dirichlet[1].path[0]"));
}

// ------------------------------------------------------------------------------------------
// JSON.

TEST(ProblemFileJson, ContainsEveryKey) {
  const auto j = to_json(read_problem(kPaper));
  for (const char* k : {"title", "mesh", "material", "volume_force", "dirichlet", "traction",
                        "contact", "solver", "output"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["mesh"]["cells"], nlohmann::json::array({12, 4, 4}));
  EXPECT_EQ(j["material"]["young"], 21.19e10);
  EXPECT_EQ(j["dirichlet"][0]["components"], "xyz");
  EXPECT_EQ(j["traction"][1]["value"], nlohmann::json::array({0.0, 0.0, -3.0e7}));
  EXPECT_EQ(j["contact"]["friction"]["law"], "paper");
  EXPECT_EQ(j["contact"]["friction"]["param"], 6.0e4);
  EXPECT_FALSE(j["contact"]["friction"].contains("value"));
  for (const char* k :
       {"outer_tol", "outer_max", "qp_rtol", "qp_max", "warm_start", "dual_operator"})
    EXPECT_TRUE(j["solver"].contains(k)) << k;  // defaults included
  EXPECT_EQ(j["output"]["dir"], "results/paper-brick");
  EXPECT_FALSE(to_json(read_problem(kExamples + "elastic-brick.toml")).contains("contact"));
}

TEST(ProblemFileJson, RoundTripThroughToml) {
  const std::vector<std::vector<std::string>> variants = {
      {},
      {"contact.friction.law=table", "contact.friction.t=[0, 1e-5]",
       "contact.friction.f=[0.3, 0.1]", "volume_force=[0, 0, -7.85e4]", "title=\"x y\""},
      {"contact.friction.law=constant", "solver.dual_operator=schur", "mesh.size=[1.5, 0.5, 2]"},
      {"contact.model=coulomb", "contact.start_slip_bound=1e7"},
      {"contact.friction.law=expression", "contact.friction.expression=\"0.1 + 0.4*exp(-t/5e-5)\"",
       "contact.friction.kinks=[1e-5, 2e-5]", "contact.friction.quadrature_rtol=1e-8"},
      {"contact.friction.law=expression", "contact.friction.expression=\"0.3\""},
  };
  for (const auto& overrides : variants) {
    const auto p = read_problem(kPaper, overrides);
    const std::string text = to_toml(p);
    const auto q = parse_problem(text, "roundtrip.toml");
    EXPECT_EQ(to_json(q), to_json(p)) << text;
  }
  // Anisotropic material.
  std::vector<std::string> voigt = {"material.model=anisotropic"};
  std::string rows = "material.voigt=[";
  for (int i = 0; i < 6; ++i) {
    rows += i ? ", [" : "[";
    for (int j = 0; j < 6; ++j)
      rows += (j ? ", " : "") + std::string(i == j ? "2e11" : "0");
    rows += "]";
  }
  voigt.push_back(rows + "]");
  const auto p = read_problem(kPaper, voigt);
  ASSERT_TRUE(p.material.voigt.has_value());
  EXPECT_EQ(to_json(parse_problem(to_toml(p), "roundtrip.toml")), to_json(p));
}

TEST(ProblemFileJson, WhatCodeGaveCannotBeWrittenToAFile) {
  auto p = read_problem(kPaper);
  p.contact.front().friction.law = contact::FrictionLawKind::Function;
  EXPECT_THROW(to_toml(p), InputError);
}

// ------------------------------------------------------------------------------------------
// The friction law "expression" (and "function", which a file cannot give).

// A problem whose [contact.friction] table is `friction` (its first line is line 6).
std::string with_friction(const std::string& friction) {
  return "[mesh]\n[material]\n[contact]\nboundary = \"z0\"\n[contact.friction]\n" + friction;
}

TEST(ProblemFileExpression, ReadsTheFormulaKinksAndTolerance) {
  const auto p = parse_problem(with_friction("law = \"expression\"\n"
                                             "expression = \"0.1 + 0.4*exp(-t/5e-5)\"\n"
                                             "kinks = [1e-5, 3e-5]\nquadrature_rtol = 1e-8\n"),
                               "t.toml");
  const auto& fr = p.contact.front().friction;
  EXPECT_EQ(fr.law, contact::FrictionLawKind::Expression);
  EXPECT_EQ(fr.expression, "0.1 + 0.4*exp(-t/5e-5)");
  EXPECT_EQ(fr.kinks, (std::vector<Real>{1e-5, 3e-5}));
  EXPECT_EQ(fr.quadrature_rtol, 1e-8);
  const auto j = to_json(p)["contact"]["friction"];
  EXPECT_EQ(j["law"], "expression");
  EXPECT_EQ(j["expression"], "0.1 + 0.4*exp(-t/5e-5)");
  EXPECT_EQ(j["kinks"], (std::vector<Real>{1e-5, 3e-5}));
  EXPECT_EQ(j["quadrature_rtol"], 1e-8);
  EXPECT_FALSE(j.contains("param"));
  // Defaults.
  const auto d =
      parse_problem(with_friction("law = \"expression\"\nexpression = \"0.3\"\n"), "t.toml");
  EXPECT_TRUE(d.contact.front().friction.kinks.empty());
  EXPECT_EQ(d.contact.front().friction.quadrature_rtol, contact::kDefaultQuadratureRtol);
}

TEST(ProblemFileExpression, SyntaxErrorsAndUnknownNamesAreNamedInsideTheFile) {
  // Line 7 is `expression = "..."`: the quote is column 14, the expression starts at column 15.
  EXPECT_EQ(error_of(with_friction("law = \"expression\"\nexpression = \"0.1 + * t\"\n")),
            "t.toml:7:21: contact.friction.expression: syntax error at column 7 of \"0.1 + * t\": "
            "Unexpected operator \"*\"");
  EXPECT_EQ(error_of(with_friction("law = \"expression\"\nexpression = \"0.1 + x\"\n")),
            "t.toml:7:21: contact.friction.expression: unknown name \"x\" at column 7 of \"0.1 + "
            "x\": the only variable is t, the slip [m] (docs/problem-file.md lists the functions)");
  // A literal string and some indentation: still the right column.
  EXPECT_THAT(error_of(with_friction("law = \"expression\"\n  expression = '0.1 + * t'\n")),
              HasSubstr("t.toml:7:23: contact.friction.expression: syntax error at column 7"));
  EXPECT_THAT(error_of(with_friction("law = \"expression\"\nexpression = \"sin(\"\n")),
              HasSubstr("t.toml:7:20: contact.friction.expression: syntax error at column 6 of "
                        "\"sin(\": Unexpected end of expression"));
  // From --set: named by the override.
  EXPECT_THAT(error_of(with_friction("law = \"expression\"\nexpression = \"t\"\n"),
                       {"contact.friction.expression=\"2 * * t\""}),
              HasSubstr("--set contact.friction.expression=\"2 * * t\": "
                        "contact.friction.expression: syntax error at column 5"));
  EXPECT_THAT(
      error_of(with_friction("law = \"expression\"\n")),
      HasSubstr("missing required key 'contact.friction.expression' (law \"expression\" needs a "
                "formula in the slip t [m])"));
  EXPECT_THAT(error_of(with_friction("law = \"expression\"\nexpression = \"\"\n")),
              HasSubstr("contact.friction.expression: syntax error"));
  EXPECT_THAT(error_of(with_friction("law = \"expression\"\nexpression = \"0.3\"\nparam = 1\n")),
              HasSubstr("not used by law \"expression\" (it takes: expression, kinks, "
                        "quadrature_rtol)"));
}

TEST(ProblemFileExpression, KinksAndToleranceAreValidated) {
  const std::string law = "law = \"expression\"\nexpression = \"0.3\"\n";
  EXPECT_THAT(error_of(with_friction(law + "kinks = [2e-5, 1e-5]\n")), HasSubstr("t.toml:8:"));
  EXPECT_THAT(error_of(with_friction(law + "kinks = [2e-5, 1e-5]\n")),
              HasSubstr("contact.friction.kinks[1]: expected slips in strictly increasing order"));
  EXPECT_THAT(error_of(with_friction(law + "kinks = [-1e-5]\n")),
              HasSubstr("contact.friction.kinks[0]: expected a number >= 0 [m], got -1e-05"));
  EXPECT_THAT(error_of(with_friction(law + "quadrature_rtol = 1.0\n")),
              HasSubstr("t.toml:8:1: contact.friction.quadrature_rtol: expected a number in (0, "
                        "1), got 1.0"));
  EXPECT_THAT(error_of(with_friction(law + "quadrature_rtol = 0\n")),
              HasSubstr("contact.friction.quadrature_rtol: expected a number in (0, 1)"));
}

TEST(ProblemFileExpression, LawFunctionIsForCodeOnly) {
  EXPECT_EQ(error_of(with_friction("law = \"function\"\n")),
            "t.toml:6:1: contact.friction.law: law \"function\" is a function given from code "
            "(fricon.FrictionLaw.function in Python); in a problem file write law = "
            "\"expression\"");
  // In code, a function law is a valid Problem; to_json names it.
  auto p = parse_problem(with_friction("law = \"expression\"\nexpression = \"0.3\"\n"), "t.toml");
  auto& fr = p.contact.front().friction;
  fr.law = contact::FrictionLawKind::Function;
  fr.function_name = "my_law";
  EXPECT_THROW(driver::validate(p), InputError);  // no function yet
  fr.function = [](std::span<const Real>, std::span<Real> out) {
    std::fill(out.begin(), out.end(), 0.3);
  };
  EXPECT_NO_THROW(driver::validate(p));
  const auto j = to_json(p)["contact"]["friction"];
  EXPECT_EQ(j["law"], "function");
  EXPECT_EQ(j["name"], "my_law");
  EXPECT_TRUE(j.contains("kinks"));
  EXPECT_EQ(j["quadrature_rtol"], contact::kDefaultQuadratureRtol);
  EXPECT_FALSE(j.contains("expression"));
}

}  // namespace
}  // namespace fricon::io
