#include "fricon/mesh/gmsh_api.hpp"

#include <dlfcn.h>

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <fmt/format.h>
extern "C" {
#include <gmshc.h>
}

#include "fricon/core/error.hpp"

#ifndef FRICON_GMSH_SONAME
#error \
    "FRICON_GMSH_SONAME, the file name of libgmsh to load, is defined by cmake/dependencies.cmake"
#endif

namespace fricon::mesh::gmsh_api {

namespace {

// @sect: the library and its C functions.

// Every C function of gmshc.h that is called below, by name.
#define FRICON_GMSH_C_FUNCTIONS(X)          \
  X(gmshFree)                               \
  X(gmshInitialize)                         \
  X(gmshFinalize)                           \
  X(gmshOpen)                               \
  X(gmshWrite)                              \
  X(gmshOptionSetNumber)                    \
  X(gmshLoggerStart)                        \
  X(gmshLoggerStop)                         \
  X(gmshLoggerGet)                          \
  X(gmshLoggerGetLastError)                 \
  X(gmshModelAdd)                           \
  X(gmshModelAddDiscreteEntity)             \
  X(gmshModelAddPhysicalGroup)              \
  X(gmshModelGetEntities)                   \
  X(gmshModelGetEntitiesForPhysicalGroup)   \
  X(gmshModelGetPhysicalGroups)             \
  X(gmshModelGetPhysicalName)               \
  X(gmshModelSetPhysicalName)               \
  X(gmshModelMeshGenerate)                  \
  X(gmshModelMeshSetOrder)                  \
  X(gmshModelMeshGetNodes)                  \
  X(gmshModelMeshAddNodes)                  \
  X(gmshModelMeshGetElementTypes)           \
  X(gmshModelMeshGetElementProperties)      \
  X(gmshModelMeshGetElements)               \
  X(gmshModelMeshGetElementsByType)         \
  X(gmshModelMeshPreallocateElementsByType) \
  X(gmshModelMeshAddElementsByType)

// One pointer per C function, named as the function and of the type gmshc.h declares for it.
struct Functions {
#define FRICON_GMSH_POINTER(name) decltype(&::name) name = nullptr;
  FRICON_GMSH_C_FUNCTIONS(FRICON_GMSH_POINTER)
#undef FRICON_GMSH_POINTER
};

// Gmsh's internal function that empties the buffer of its .geo lexer (Gmsh.l: gmsh_yyflush), by
// its mangled name (g++'s ABI); not part of the API, so a library without it is still used.
constexpr const char* kGeoLexerFlushSymbol = "_Z12gmsh_yyflushv";

struct Library {
  Functions functions;
  void (*flush_geo_lexer)() = nullptr;  // kGeoLexerFlushSymbol, or null when absent
  std::string error;                    // why it could not be loaded; "" when it is
};

std::string dl_message() {
  const char* message = dlerror();
  return message ? message : "unknown dynamic loader error";
}

// The Debian package of a library libNAME.so.VERSION: libNAMEVERSION (libgmsh4.8).
std::string debian_package(const std::string& soname) {
  const std::string so = ".so.";
  const auto at = soname.find(so);
  if (at == std::string::npos) return "libgmsh";
  return soname.substr(0, at) + soname.substr(at + so.size());
}

template <class F>
bool resolve(void* handle, const char* name, F& pointer) {
  void* symbol = dlsym(handle, name);
  pointer = reinterpret_cast<F>(symbol);
  return symbol != nullptr;
}

// Opens `file` with dlopen (all symbols bound now, none made visible to later loads) and
// resolves every function; on failure closes it again and says why.
Library load(const std::string& file) {
  Library library;
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    library.error = fmt::format(
        "{}, Gmsh's library, could not be loaded (it is in the Debian package {}, which "
        "libgmsh-dev brings): {}",
        file, debian_package(file), dl_message());
    return library;
  }
  const char* missing = nullptr;
  std::string why;
#define FRICON_GMSH_RESOLVE(name)                                    \
  if (!missing && !resolve(handle, #name, library.functions.name)) { \
    missing = #name;                                                 \
    why = dl_message();                                              \
  }
  FRICON_GMSH_C_FUNCTIONS(FRICON_GMSH_RESOLVE)
#undef FRICON_GMSH_RESOLVE
  if (!missing) resolve(handle, kGeoLexerFlushSymbol, library.flush_geo_lexer);
  if (missing) {
    library.functions = {};
    library.error = fmt::format("{} is not Gmsh's library of API {}: it has no function {} ({})",
                                file, GMSH_API_VERSION, missing, why);
    dlclose(handle);
  }
  return library;
}

// The library all calls use, loaded on the first call and kept until the process exits, as a
// linked library would be.
const Library& shared_library() {
  static const Library library = load(FRICON_GMSH_SONAME);
  return library;
}

const Functions& api() {
  const Library& library = shared_library();
  if (!library.error.empty()) throw Error(library.error);
  return library.functions;
}

// @sect: calling a C function.

// An array (or string) Gmsh allocated for an output, released with gmshFree.
template <class T>
struct GmshArray {
  T* data = nullptr;
  std::size_t size = 0;

  GmshArray() = default;
  GmshArray(const GmshArray&) = delete;
  GmshArray& operator=(const GmshArray&) = delete;
  ~GmshArray() {
    if (data) shared_library().functions.gmshFree(data);
  }
  std::vector<T> vector() const {
    return data ? std::vector<T>(data, data + size) : std::vector<T>{};
  }
};

std::string string_of(const GmshArray<char>& text) {
  return text.data ? std::string(text.data) : std::string();
}

// An array of strings Gmsh allocated, each string and the array released with gmshFree.
struct GmshStrings {
  char** data = nullptr;
  std::size_t size = 0;

  GmshStrings() = default;
  GmshStrings(const GmshStrings&) = delete;
  GmshStrings& operator=(const GmshStrings&) = delete;
  ~GmshStrings() {
    if (!data) return;
    const Functions& f = shared_library().functions;
    for (std::size_t i = 0; i < size; ++i)
      f.gmshFree(data[i]);
    f.gmshFree(data);
  }
  std::vector<std::string> vector() const {
    std::vector<std::string> strings;
    for (std::size_t i = 0; data && i < size; ++i)
      strings.emplace_back(data[i] ? data[i] : "");
    return strings;
  }
};

// An array of arrays Gmsh allocated (one per element type), with their sizes: each array, the
// array of them and the array of sizes released with gmshFree.
template <class T>
struct GmshArrays {
  T** data = nullptr;
  std::size_t* sizes = nullptr;
  std::size_t size = 0;

  GmshArrays() = default;
  GmshArrays(const GmshArrays&) = delete;
  GmshArrays& operator=(const GmshArrays&) = delete;
  ~GmshArrays() {
    const Functions& f = shared_library().functions;
    for (std::size_t i = 0; data && i < size; ++i)
      f.gmshFree(data[i]);
    if (data) f.gmshFree(data);
    if (sizes) f.gmshFree(sizes);
  }
  std::vector<std::vector<T>> vectors() const {
    std::vector<std::vector<T>> arrays(size);
    for (std::size_t i = 0; data && sizes && i < size; ++i)
      if (data[i]) arrays[i].assign(data[i], data[i] + sizes[i]);
    return arrays;
  }
};

// Pairs from a flat array (dim, tag, dim, tag, ...).
vectorpair pairs_of(const GmshArray<int>& flat) {
  vectorpair pairs;
  for (std::size_t i = 0; i + 1 < flat.size; i += 2)
    pairs.emplace_back(flat.data[i], flat.data[i + 1]);
  return pairs;
}

// Throws CallError when the call `function` returned the error code `ierr`.
void check(int ierr, const char* function) {
  if (ierr == 0) return;
  std::string message;
  logger::getLastError(message);
  if (message.empty()) message = fmt::format("{} failed (error code {})", function, ierr);
  throw CallError(message);
}

// Calls `function` (named `name`) with `args` and the error code's address, then checks it.
template <class F, class... Args>
auto call(const char* name, F function, Args&&... args) {
  int ierr = 0;
  if constexpr (std::is_void_v<std::invoke_result_t<F, Args..., int*>>) {
    function(std::forward<Args>(args)..., &ierr);
    check(ierr, name);
  } else {
    const auto result = function(std::forward<Args>(args)..., &ierr);
    check(ierr, name);
    return result;
  }
}

}  // namespace

// Calls the C function `name` of the loaded library with the arguments that follow.
#define FRICON_GMSH_CALL(name, ...) call(#name, api().name __VA_OPT__(, ) __VA_ARGS__)

// @sect: the library.

const char* library_name() {
  return FRICON_GMSH_SONAME;
}

const std::string& load_error() {
  return shared_library().error;
}

std::string try_load(const std::string& file) {
  return load(file).error;
}

bool flush_geo_parser() {
  const Library& library = shared_library();
  if (!library.error.empty()) throw Error(library.error);
  if (!library.flush_geo_lexer) return false;
  library.flush_geo_lexer();
  return true;
}

// @sect: the API. Gmsh's C API takes input arrays through non-const pointers that it only reads.

void initialize(int argc, char** argv, bool readConfigFiles) {
  FRICON_GMSH_CALL(gmshInitialize, argc, argv, readConfigFiles ? 1 : 0);
}

void finalize() {
  FRICON_GMSH_CALL(gmshFinalize);
}

void open(const std::string& fileName) {
  FRICON_GMSH_CALL(gmshOpen, fileName.c_str());
}

void write(const std::string& fileName) {
  FRICON_GMSH_CALL(gmshWrite, fileName.c_str());
}

void option::setNumber(const std::string& name, double value) {
  FRICON_GMSH_CALL(gmshOptionSetNumber, name.c_str(), value);
}

void logger::start() {
  FRICON_GMSH_CALL(gmshLoggerStart);
}

void logger::stop() {
  FRICON_GMSH_CALL(gmshLoggerStop);
}

void logger::get(std::vector<std::string>& log) {
  GmshStrings lines;
  FRICON_GMSH_CALL(gmshLoggerGet, &lines.data, &lines.size);
  log = lines.vector();
}

// Not through check(): asking for the last error must not itself throw with the last error.
void logger::getLastError(std::string& error) {
  GmshArray<char> text;
  int ierr = 0;
  api().gmshLoggerGetLastError(&text.data, &ierr);
  error = ierr == 0 ? string_of(text) : std::string();
}

void model::add(const std::string& name) {
  FRICON_GMSH_CALL(gmshModelAdd, name.c_str());
}

int model::addDiscreteEntity(int dim, int tag) {
  return FRICON_GMSH_CALL(gmshModelAddDiscreteEntity, dim, tag, nullptr, std::size_t{0});
}

int model::addPhysicalGroup(int dim, const std::vector<int>& tags, int tag) {
  return FRICON_GMSH_CALL(gmshModelAddPhysicalGroup, dim, const_cast<int*>(tags.data()),
                          tags.size(), tag);
}

void model::getEntities(vectorpair& dimTags, int dim) {
  GmshArray<int> flat;
  FRICON_GMSH_CALL(gmshModelGetEntities, &flat.data, &flat.size, dim);
  dimTags = pairs_of(flat);
}

void model::getEntitiesForPhysicalGroup(int dim, int tag, std::vector<int>& tags) {
  GmshArray<int> entities;
  FRICON_GMSH_CALL(gmshModelGetEntitiesForPhysicalGroup, dim, tag, &entities.data, &entities.size);
  tags = entities.vector();
}

void model::getPhysicalGroups(vectorpair& dimTags, int dim) {
  GmshArray<int> flat;
  FRICON_GMSH_CALL(gmshModelGetPhysicalGroups, &flat.data, &flat.size, dim);
  dimTags = pairs_of(flat);
}

void model::getPhysicalName(int dim, int tag, std::string& name) {
  GmshArray<char> text;
  FRICON_GMSH_CALL(gmshModelGetPhysicalName, dim, tag, &text.data);
  name = string_of(text);
}

void model::setPhysicalName(int dim, int tag, const std::string& name) {
  FRICON_GMSH_CALL(gmshModelSetPhysicalName, dim, tag, name.c_str());
}

void model::mesh::generate(int dim) {
  FRICON_GMSH_CALL(gmshModelMeshGenerate, dim);
}

void model::mesh::setOrder(int order) {
  FRICON_GMSH_CALL(gmshModelMeshSetOrder, order);
}

void model::mesh::getNodes(std::vector<std::size_t>& nodeTags, std::vector<double>& coord,
                           std::vector<double>& parametricCoord, int dim, int tag,
                           bool includeBoundary, bool returnParametricCoord) {
  GmshArray<std::size_t> tags;
  GmshArray<double> xyz, uvw;
  FRICON_GMSH_CALL(gmshModelMeshGetNodes, &tags.data, &tags.size, &xyz.data, &xyz.size, &uvw.data,
                   &uvw.size, dim, tag, includeBoundary ? 1 : 0, returnParametricCoord ? 1 : 0);
  nodeTags = tags.vector();
  coord = xyz.vector();
  parametricCoord = uvw.vector();
}

void model::mesh::addNodes(int dim, int tag, const std::vector<std::size_t>& nodeTags,
                           const std::vector<double>& coord) {
  FRICON_GMSH_CALL(gmshModelMeshAddNodes, dim, tag, const_cast<std::size_t*>(nodeTags.data()),
                   nodeTags.size(), const_cast<double*>(coord.data()), coord.size(), nullptr,
                   std::size_t{0});
}

void model::mesh::getElementTypes(std::vector<int>& elementTypes, int dim, int tag) {
  GmshArray<int> types;
  FRICON_GMSH_CALL(gmshModelMeshGetElementTypes, &types.data, &types.size, dim, tag);
  elementTypes = types.vector();
}

void model::mesh::getElementProperties(int elementType, std::string& elementName, int& dim,
                                       int& order, int& numNodes,
                                       std::vector<double>& localNodeCoord, int& numPrimaryNodes) {
  GmshArray<char> name;
  GmshArray<double> local;
  FRICON_GMSH_CALL(gmshModelMeshGetElementProperties, elementType, &name.data, &dim, &order,
                   &numNodes, &local.data, &local.size, &numPrimaryNodes);
  elementName = string_of(name);
  localNodeCoord = local.vector();
}

void model::mesh::getElements(std::vector<int>& elementTypes,
                              std::vector<std::vector<std::size_t>>& elementTags,
                              std::vector<std::vector<std::size_t>>& nodeTags, int dim, int tag) {
  GmshArray<int> types;
  GmshArrays<std::size_t> elements, nodes;
  FRICON_GMSH_CALL(gmshModelMeshGetElements, &types.data, &types.size, &elements.data,
                   &elements.sizes, &elements.size, &nodes.data, &nodes.sizes, &nodes.size, dim,
                   tag);
  elementTypes = types.vector();
  elementTags = elements.vectors();
  nodeTags = nodes.vectors();
}

void model::mesh::preallocateElementsByType(int elementType, bool elementTag, bool nodeTag,
                                            std::vector<std::size_t>& elementTags,
                                            std::vector<std::size_t>& nodeTags, int tag) {
  GmshArray<std::size_t> elements, nodes;
  FRICON_GMSH_CALL(gmshModelMeshPreallocateElementsByType, elementType, elementTag ? 1 : 0,
                   nodeTag ? 1 : 0, &elements.data, &elements.size, &nodes.data, &nodes.size, tag);
  elementTags = elements.vector();
  nodeTags = nodes.vector();
}

void model::mesh::getElementsByType(int elementType, std::vector<std::size_t>& elementTags,
                                    std::vector<std::size_t>& nodeTags, int tag) {
  GmshArray<std::size_t> elements, nodes;
  constexpr std::size_t kTask = 0, kNumTasks = 1;  // all elements in one call
  FRICON_GMSH_CALL(gmshModelMeshGetElementsByType, elementType, &elements.data, &elements.size,
                   &nodes.data, &nodes.size, tag, kTask, kNumTasks);
  elementTags = elements.vector();
  nodeTags = nodes.vector();
}

void model::mesh::addElementsByType(int tag, int elementType,
                                    const std::vector<std::size_t>& elementTags,
                                    const std::vector<std::size_t>& nodeTags) {
  FRICON_GMSH_CALL(gmshModelMeshAddElementsByType, tag, elementType,
                   const_cast<std::size_t*>(elementTags.data()), elementTags.size(),
                   const_cast<std::size_t*>(nodeTags.data()), nodeTags.size());
}

#undef FRICON_GMSH_CALL
#undef FRICON_GMSH_C_FUNCTIONS

}  // namespace fricon::mesh::gmsh_api
