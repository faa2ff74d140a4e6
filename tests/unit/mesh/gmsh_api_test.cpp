// Tests of the loading of libgmsh at run time: not before the first use, the installed library
// found by its SONAME, and the messages when a library is missing or is not Gmsh's.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "fricon/mesh/gmsh_api.hpp"

using namespace fricon::mesh;

namespace {

// Whether a library whose path contains `name` is mapped into this process.
bool is_mapped(const std::string& name) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line))
    if (line.find(name) != std::string::npos) return true;
  return false;
}

void expect_contains(const std::string& text, const std::vector<std::string>& parts) {
  for (const auto& part : parts)
    EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

}  // namespace

// In a fresh process (the "threadsafe" death test runs this test alone in a new run of the test
// program) libgmsh is not mapped until the first use loads it.
TEST(GmshApiDeathTest, LoadsTheLibraryOnFirstUseOnly) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        const bool mapped_before = is_mapped("libgmsh");
        const bool loaded = gmsh_api::load_error().empty();
        const bool mapped_after = is_mapped("libgmsh");
        std::exit(!mapped_before && loaded && mapped_after ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(GmshApi, LoadsTheInstalledLibraryBySoname) {
  EXPECT_NE(std::string(gmsh_api::library_name()).find("libgmsh.so."), std::string::npos)
      << gmsh_api::library_name();
  EXPECT_EQ(gmsh_api::load_error(), "");
  EXPECT_EQ(gmsh_api::try_load(gmsh_api::library_name()), "");
}

TEST(GmshApi, MissingLibraryNamesItsPackageAndTheLoadersMessage) {
  const std::string why = gmsh_api::try_load("libgmsh.so.0.404");
  expect_contains(
      why, {"libgmsh.so.0.404, Gmsh's library, could not be loaded", "Debian package libgmsh0.404",
            "libgmsh-dev", "cannot open shared object file"});
}

TEST(GmshApi, LibraryWithoutTheGmshApiIsRefused) {
  const std::string why = gmsh_api::try_load("libm.so.6");
  expect_contains(why, {"libm.so.6", "no function gmshFree", "undefined symbol"});
}

// A call that Gmsh fails throws CallError with the error Gmsh logged.
TEST(GmshApi, FailedCallThrowsGmshsLastError) {
  gmsh_api::initialize(0, nullptr, /*readConfigFiles=*/false);
  gmsh_api::option::setNumber("General.Terminal", 0);
  gmsh_api::logger::start();
  try {
    gmsh_api::option::setNumber("Fricon.NoSuchOption", 1.0);
    ADD_FAILURE() << "no CallError thrown";
  } catch (const gmsh_api::CallError& e) {
    EXPECT_NE(std::string(e.what()).find("Fricon.NoSuchOption"), std::string::npos) << e.what();
  }
  std::vector<std::string> log;
  gmsh_api::logger::get(log);
  ASSERT_FALSE(log.empty());
  EXPECT_NE(log.back().find("Fricon.NoSuchOption"), std::string::npos) << log.back();
  std::string name;
  int dim = 0, order = 0, n_nodes = 0, n_primary = 0;
  std::vector<double> local_coords;
  gmsh_api::model::mesh::getElementProperties(4, name, dim, order, n_nodes, local_coords,
                                              n_primary);
  EXPECT_EQ(name, "Tetrahedron 4");
  EXPECT_EQ(n_nodes, 4);
  EXPECT_EQ(local_coords.size(), 12U);
  gmsh_api::logger::stop();
  gmsh_api::finalize();
}
