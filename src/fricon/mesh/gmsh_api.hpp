#pragma once
// mesh (internal to gmsh_file.cpp): the part of the Gmsh API that the reader and writer use,
// called through Gmsh's C API (gmshc.h) in libgmsh, which is loaded with dlopen on the first use
// and never linked: a process that reads and writes no Gmsh file does not load libgmsh and the
// ~180 libraries it brings (OpenCASCADE, FLTK, ...), whose loading and initialisation were most
// of the program's start-up time.
//
// The functions have the namespaces, names and arguments of Gmsh's C++ API (gmsh.h), with
// std::vector and std::string outputs; gmsh_file.cpp calls them through the alias
// `namespace gmsh = gmsh_api`. A call that Gmsh reports as failed (its `ierr` set) throws
// CallError. Every call first loads the library if needed and throws fricon::Error (with
// load_error()'s text) if it cannot be loaded. Gmsh's global state is not thread-safe: its
// users hold the lock of gmsh_file.cpp (gmsh_file.hpp).

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fricon::mesh::gmsh_api {

/// A failed Gmsh call: what() is the last error Gmsh logged, or, when it logged none, the name of
/// the C function that failed.
class CallError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The file name of libgmsh that is loaded: its SONAME, found by CMake (FRICON_GMSH_SONAME, e.g.
/// "libgmsh.so.4.8"), searched for by dlopen on the usual library path.
const char* library_name();

/// Loads libgmsh on the first call (thread-safe; later calls return the first result) and resolves
/// every C function used below. Returns "" when it is loaded, else why not: that library_name()
/// could not be loaded (naming the Debian package that provides it) or lacks a function of the
/// Gmsh C API, with dlerror()'s text.
const std::string& load_error();

/// What load_error() does for the library `file` (a name searched for by dlopen, or a path),
/// without touching the library the other functions use: "" if it loads and has every function
/// (it then stays loaded), else why not. For tests.
std::string try_load(const std::string& file);

/// Empties the input buffer of Gmsh's .geo parser. Gmsh 4.8 keeps there the rest of a .geo file
/// whose parse failed (its API throws out of the parser before the buffer is flushed), and reads
/// it as the start of the next file it parses in the process: after `this is not Gmsh;` the next
/// file fails with "syntax error (;)". Calls Gmsh's internal gmsh_yyflush, which is not part of
/// its API: returns false, doing nothing, when the library has no such function. Throws as the
/// functions below when libgmsh cannot be loaded. Not thread-safe (gmsh_file.hpp).
bool flush_geo_parser();

using vectorpair = std::vector<std::pair<int, int>>;

void initialize(int argc, char** argv, bool readConfigFiles);
void finalize();
void open(const std::string& fileName);
void write(const std::string& fileName);

namespace option {
void setNumber(const std::string& name, double value);
}  // namespace option

namespace logger {
void start();
void stop();
void get(std::vector<std::string>& log);
void getLastError(std::string& error);
}  // namespace logger

namespace model {
void add(const std::string& name);
int addDiscreteEntity(int dim, int tag = -1);
int addPhysicalGroup(int dim, const std::vector<int>& tags, int tag = -1);
void getEntities(vectorpair& dimTags, int dim = -1);
void getEntitiesForPhysicalGroup(int dim, int tag, std::vector<int>& tags);
void getPhysicalGroups(vectorpair& dimTags, int dim = -1);
void getPhysicalName(int dim, int tag, std::string& name);
void setPhysicalName(int dim, int tag, const std::string& name);

namespace mesh {
void generate(int dim = 3);
void setOrder(int order);
void getNodes(std::vector<std::size_t>& nodeTags, std::vector<double>& coord,
              std::vector<double>& parametricCoord, int dim = -1, int tag = -1,
              bool includeBoundary = false, bool returnParametricCoord = true);
void addNodes(int dim, int tag, const std::vector<std::size_t>& nodeTags,
              const std::vector<double>& coord);
void getElementTypes(std::vector<int>& elementTypes, int dim = -1, int tag = -1);
void getElementProperties(int elementType, std::string& elementName, int& dim, int& order,
                          int& numNodes, std::vector<double>& localNodeCoord, int& numPrimaryNodes);
void getElements(std::vector<int>& elementTypes, std::vector<std::vector<std::size_t>>& elementTags,
                 std::vector<std::vector<std::size_t>>& nodeTags, int dim = -1, int tag = -1);
void getElementsByType(int elementType, std::vector<std::size_t>& elementTags,
                       std::vector<std::size_t>& nodeTags, int tag = -1);
void preallocateElementsByType(int elementType, bool elementTag, bool nodeTag,
                               std::vector<std::size_t>& elementTags,
                               std::vector<std::size_t>& nodeTags, int tag = -1);
void addElementsByType(int tag, int elementType, const std::vector<std::size_t>& elementTags,
                       const std::vector<std::size_t>& nodeTags);
}  // namespace mesh
}  // namespace model

}  // namespace fricon::mesh::gmsh_api
