#include "fricon/mesh/gmsh_file.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/shared_random.hpp"
#include "fricon/mesh/gmsh_api.hpp"

namespace fricon::mesh {

namespace {

namespace fs = std::filesystem;
// The Gmsh API, through libgmsh loaded on first use (gmsh_api.hpp): the calls read as those of
// Gmsh's C++ API.
namespace gmsh = gmsh_api;

// Gmsh element types (Gmsh reference manual, "MSH file format": elm-type): the linear line,
// triangle and tetrahedron, and the quadratic ones (second order: the corners, then the edge
// midpoints in the order of kTriangleEdge and kTetEdge, tet_mesh.hpp; theory.md §2.12).
constexpr int kGmshLine = 1;
constexpr int kGmshTriangle = 2;
constexpr int kGmshTetrahedron = 4;
constexpr int kGmshLine3 = 8;
constexpr int kGmshTriangle6 = 9;
constexpr int kGmshTetrahedron10 = 11;
// The corners of a triangle and of a tetrahedron (the first nodes of an element of either order).
constexpr int kNodesPerTriangle = 3;
constexpr int kNodesPerTet = 4;
// The polynomial orders of the elements (TetMesh::order).
constexpr int kLinearOrder = 1;
constexpr int kQuadraticOrder = 2;

// The Gmsh element types of the tetrahedra and boundary triangles of one order, with their node
// counts.
struct OrderTypes {
  int tet = kGmshTetrahedron;
  int triangle = kGmshTriangle;
  int tet_nodes = kNodesPerTet;
  int triangle_nodes = kNodesPerTriangle;
};

OrderTypes order_types(int order) {
  if (order == kQuadraticOrder)
    return {kGmshTetrahedron10, kGmshTriangle6, kNodesPerTet + kTetEdges,
            kNodesPerTriangle + kTriangleEdges};
  return {};
}

// The nodes of a triangle of Gmsh type `type` (kGmshTriangle or kGmshTriangle6).
int triangle_nodes(int type) {
  return type == kGmshTriangle6 ? kNodesPerTriangle + kTriangleEdges : kNodesPerTriangle;
}
// A tetrahedron is degenerate when its volume is below this times its longest edge cubed (as in
// check_mesh).
constexpr Real kDegenerateVolume = 1e-12;

// @sect: the Gmsh session.

// Throws E naming `source` when libgmsh cannot be loaded (the first call loads it).
template <class E>
void require_gmsh_library(const std::string& source) {
  if (const std::string& why = gmsh_api::load_error(); !why.empty())
    throw E(fmt::format("{}: cannot use Gmsh: {}", source, why));
}

// The message of the exception in flight, whatever Gmsh threw.
std::string current_exception_message() {
  try {
    throw;
  } catch (const std::exception& e) {
    return e.what();
  } catch (const std::string& s) {
    return s;
  } catch (const char* s) {
    return s;
  } catch (...) {
    return "unknown error";
  }
}

// Gmsh's global state (one model, its options, its logger) is the process's: the lock of every
// session, held from before gmsh::initialize to after gmsh::finalize, so that sessions of
// several threads (fricon.solve from Python threads, docs/python.md) run one after another.
std::mutex& gmsh_state_mutex() {
  static std::mutex mutex;
  return mutex;
}

// Gmsh's global state for the lifetime of the object, for this thread alone: the locks taken
// (waiting for other threads' sessions and METIS calls to end), then Gmsh initialised without the
// user's configuration files and silent; finalised on destruction, then the lock released.
class GmshSession {
 public:
  explicit GmshSession(std::string source)
      : lock_(gmsh_state_mutex()), random_lock_(shared_random_mutex()), source_(std::move(source)) {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    // What an earlier session's failed .geo left in the parser (gmsh_api.hpp).
    gmsh_api::flush_geo_parser();
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::logger::start();
  }
  ~GmshSession() {
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {  // a destructor must not throw
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  // Runs `step` (calls of the Gmsh API) and turns a Gmsh failure, thrown or only logged, into an
  // exception of type E naming the source, what was done and Gmsh's message.
  template <class E = InputError>
  void run(const std::string& what, const std::function<void()>& step) {
    std::string message;
    try {
      step();
    } catch (const fricon::Error&) {
      throw;
    } catch (...) {
      message = current_exception_message();
      std::string last;
      gmsh::logger::getLastError(last);
      if (!last.empty()) message = last;
    }
    if (message.empty()) message = new_logged_error();
    if (!message.empty()) throw E(fmt::format("{}: {}: {}", source_, what, message));
  }

 private:
  // The last error Gmsh logged since the previous call, or "".
  std::string new_logged_error() {
    std::vector<std::string> log;
    gmsh::logger::get(log);
    std::string last;
    for (size_t i = n_log_seen_; i < log.size(); ++i)
      if (log[i].rfind("Error", 0) == 0) last = log[i];
    n_log_seen_ = log.size();
    return last;
  }
  // First members: taken first, released last. Gmsh's mesher seeds and draws from the C
  // library's random sequence (core/shared_random.hpp).
  std::unique_lock<std::mutex> lock_;
  std::unique_lock<std::mutex> random_lock_;
  size_t n_log_seen_ = 0;
  std::string source_;
};

// @sect: reading, the steps.

struct GmshNodes {
  std::unordered_map<std::size_t, Index> index_of;  // Gmsh node tag -> fricon node index
  std::vector<std::size_t> tag_of;                  // fricon node index -> Gmsh node tag
};

struct GmshTets {
  std::vector<std::size_t> element_tag;  // Gmsh element tag of each tetrahedron
};

std::string element_type_name(int type) {
  std::string name;
  int dim = 0, order = 0, n_nodes = 0, n_primary = 0;
  std::vector<double> local_coords;
  gmsh::model::mesh::getElementProperties(type, name, dim, order, n_nodes, local_coords, n_primary);
  return name;
}

void require_readable(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) throw InputError(fmt::format("{}: no such file", file.string()));
  if (fs::is_directory(file, ec))
    throw InputError(fmt::format("{}: is a folder, not a mesh file", file.string()));
}

bool is_geo(const fs::path& file) {
  return file.extension() == ".geo";
}

// Opens the file; a .geo file is meshed in 3D, then, when `order` is given, brought to that order
// (whatever its own Mesh.ElementOrder): Gmsh places the edge nodes of order 2 on the geometry, so
// that the edges on a curved surface are curved.
void load_model(GmshSession& gmsh_session, const fs::path& file, std::optional<Real> size_factor,
                std::optional<int> order) {
  if (size_factor) gmsh::option::setNumber("Mesh.MeshSizeFactor", *size_factor);
  gmsh_session.run("Gmsh cannot read it", [&] { gmsh::open(file.string()); });
  if (!is_geo(file)) return;
  gmsh_session.run("meshing failed", [] { gmsh::model::mesh::generate(3); });
  if (order)
    gmsh_session.run(fmt::format("meshing at order {} failed", *order),
                     [&] { gmsh::model::mesh::setOrder(*order); });
}

// All nodes of the model, numbered in the order of their Gmsh tags.
GmshNodes read_nodes(TetMesh& mesh) {
  std::vector<std::size_t> tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(tags, coords, parametric, -1, -1, false, false);
  std::vector<size_t> order(tags.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return tags[a] < tags[b]; });
  GmshNodes nodes;
  std::vector<size_t> kept;
  for (size_t i : order)
    if (nodes.index_of.emplace(tags[i], static_cast<Index>(kept.size())).second) {
      kept.push_back(i);
      nodes.tag_of.push_back(tags[i]);
    }
  mesh.nodes.resize(3, static_cast<Index>(kept.size()));
  for (size_t n = 0; n < kept.size(); ++n)
    for (int d = 0; d < 3; ++d)
      mesh.nodes(d, static_cast<Index>(n)) = coords[3 * kept[n] + static_cast<size_t>(d)];
  return nodes;
}

// Refuses an element type of dimension `dim` that is not one of `wanted`.
void require_wanted_type(const std::string& source, int dim, int type,
                         std::initializer_list<int> wanted, const std::string& how) {
  if (std::find(wanted.begin(), wanted.end(), type) == wanted.end())
    throw InputError(
        fmt::format("{}: has elements of type '{}' (Gmsh type {}) in dimension {}; fricon needs {}",
                    source, element_type_name(type), type, dim, how));
}

// The element types of dimension `dim` on the entity `entity_tag` (-1: all), each one of
// `wanted`: any other type is refused. (Gmsh gives the type of the first element of each kind
// of an entity: elements_of_entity sees the others.)
std::vector<int> require_element_types(const std::string& source, int dim, int entity_tag,
                                       std::initializer_list<int> wanted, const std::string& how) {
  std::vector<int> types;
  gmsh::model::mesh::getElementTypes(types, dim, entity_tag);
  for (int type : types)
    require_wanted_type(source, dim, type, wanted, how);
  return types;
}

// The elements of one dimension on one elementary entity, by Gmsh type.
struct EntityElements {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags;  // per type
  std::vector<std::vector<std::size_t>> node_tags;     // per type, each element's nodes in turn
};

// The elements of dimension `dim` on the elementary entity `entity`, each of a type of `wanted`
// (any other type is refused; `how` says what fricon needs). Gmsh keeps the elements of an
// entity in one list per kind (its tetrahedra, its triangles, its lines) and takes the type of
// its first element for the whole list: a list that mixes orders (4-node and 10-node
// tetrahedra) is refused too, as its elements of the other order would be left out here (and
// misread by getElementsByType, which sizes its output by the first element's type).
EntityElements elements_of_entity(const std::string& source, int dim, int entity,
                                  std::initializer_list<int> wanted, const std::string& how) {
  EntityElements elements;
  gmsh::model::mesh::getElements(elements.types, elements.element_tags, elements.node_tags, dim,
                                 entity);
  for (size_t k = 0; k < elements.types.size(); ++k) {
    const int type = elements.types[k];
    require_wanted_type(source, dim, type, wanted, how);
    std::vector<std::size_t> of_kind, unused;
    gmsh::model::mesh::preallocateElementsByType(type, /*elementTag=*/true, /*nodeTag=*/false,
                                                 of_kind, unused, entity);
    if (of_kind.size() != elements.element_tags[k].size())
      throw InputError(fmt::format(
          "{}: the elementary entity {} of dimension {} has {} elements of type '{}' (Gmsh type "
          "{}) among {} of their kind, the others of another order; fricon needs {}",
          source, entity, dim, elements.element_tags[k].size(), element_type_name(type), type,
          of_kind.size(), how));
  }
  return elements;
}

const char* const kHowToGetTets =
    "linear or quadratic tetrahedra (4-node or 10-node, all of one order): mesh with "
    "'Mesh.ElementOrder = 1;' or 'Mesh.ElementOrder = 2;' and no 'Recombine' nor "
    "'Mesh.RecombineAll'/'Mesh.Recombine3DAll' (or run 'gmsh -3 -order 1' or 'gmsh -3 -order 2')";
const char* const kHowToGetTriangles =
    "triangles on the tagged surfaces, of the tetrahedra's order (3-node with 4-node "
    "tetrahedra, 6-node with 10-node): mesh with 'Mesh.ElementOrder = 1;' or "
    "'Mesh.ElementOrder = 2;' and no 'Recombine' nor 'Mesh.RecombineAll' (or run 'gmsh -3 "
    "-order 1' or 'gmsh -3 -order 2')";
const char* const kHowToGetLines =
    "lines on the physical curves, 2-node or 3-node: mesh with 'Mesh.ElementOrder = 1;' or "
    "'Mesh.ElementOrder = 2;' (or run 'gmsh -3 -order 1' or 'gmsh -3 -order 2')";

// The names of the physical groups of dimension `dim`, in the order of their tags.
std::vector<std::pair<int, std::string>> physical_groups(int dim) {
  gmsh::vectorpair dim_tags;
  gmsh::model::getPhysicalGroups(dim_tags, dim);
  std::vector<std::pair<int, std::string>> groups;
  for (const auto& [d, tag] : dim_tags) {
    std::string name;
    gmsh::model::getPhysicalName(d, tag, name);
    groups.emplace_back(tag, name.empty() ? fmt::format("{}:{}", d, tag) : name);
  }
  return groups;
}

std::vector<int> entities_of_group(int dim, int group_tag) {
  std::vector<int> entities;
  gmsh::model::getEntitiesForPhysicalGroup(dim, group_tag, entities);
  return entities;
}

// Region index of each volume entity: its first 3D physical group, else "body" (added to
// region_names on demand). Empty without any 3D physical group.
std::map<int, int> region_of_volume(TetMesh& mesh) {
  std::map<int, int> region_of;
  const auto groups = physical_groups(3);
  if (groups.empty()) return region_of;
  for (const auto& [tag, name] : groups) {
    const int region = static_cast<int>(mesh.region_names.size());
    mesh.region_names.push_back(name);
    for (int entity : entities_of_group(3, tag))
      region_of.emplace(entity, region);
  }
  gmsh::vectorpair volumes;
  gmsh::model::getEntities(volumes, 3);
  for (const auto& [dim, entity] : volumes)
    if (!region_of.count(entity)) {
      if (mesh.find_region("body") < 0) mesh.region_names.push_back("body");
      region_of.emplace(entity, mesh.find_region("body"));
    }
  return region_of;
}

Real longest_edge(const TetMesh& mesh, Index t) {
  Real longest = 0.0;
  for (int a = 0; a < kNodesPerTet; ++a)
    for (int b = a + 1; b < kNodesPerTet; ++b)
      longest = std::max(
          longest, (mesh.nodes.col(mesh.tets(a, t)) - mesh.nodes.col(mesh.tets(b, t))).norm());
  return longest;
}

void require_valid_volume(const std::string& source, const TetMesh& mesh, Index t,
                          std::size_t element_tag) {
  const Real volume = tet_volume(mesh, t);
  if (volume < 0.0)
    throw InputError(
        fmt::format("{}: tetrahedron {} (Gmsh element {}) is inverted (signed volume {:.3e} m^3)",
                    source, t, element_tag, volume));
  const Real edge = longest_edge(mesh, t);
  if (volume <= kDegenerateVolume * edge * edge * edge)
    throw InputError(
        fmt::format("{}: tetrahedron {} (Gmsh element {}) is degenerate (volume {:.3e} m^3, "
                    "longest edge {:.3e} m)",
                    source, t, element_tag, volume, edge));
}

// The order of the tetrahedra: linear when the volume elements are 4-node tetrahedra, quadratic
// when they are 10-node ones. Any other volume element, and both kinds in one mesh, are refused.
int tet_order(const std::string& source) {
  const std::vector<int> types =
      require_element_types(source, 3, -1, {kGmshTetrahedron, kGmshTetrahedron10}, kHowToGetTets);
  if (types.size() > 1)
    throw InputError(fmt::format(
        "{}: has elements of type '{}' (Gmsh type {}) and '{}' (Gmsh type {}) in dimension 3: "
        "fricon needs {}",
        source, element_type_name(kGmshTetrahedron), kGmshTetrahedron,
        element_type_name(kGmshTetrahedron10), kGmshTetrahedron10, kHowToGetTets));
  return !types.empty() && types.front() == kGmshTetrahedron10 ? kQuadraticOrder : kLinearOrder;
}

// Refuses a tetrahedron that names one node twice among its nodes (corners and edge nodes).
void require_distinct_nodes(const std::string& source, const TetMesh& mesh, Index t,
                            std::size_t element_tag) {
  for (int a = 0; a < mesh.nodes_per_tet(); ++a)
    for (int b = a + 1; b < mesh.nodes_per_tet(); ++b)
      if (mesh.tet_node(t, a) == mesh.tet_node(t, b))
        throw InputError(fmt::format(
            "{}: tetrahedron {} (Gmsh element {}) has node {} twice (its nodes {} and {})", source,
            t, element_tag, mesh.tet_node(t, a), a, b));
}

// The tetrahedra of all volumes (4-node, or 10-node: their edge nodes in tet_extra), with their
// regions.
GmshTets read_tets(const std::string& source, const GmshNodes& nodes, TetMesh& mesh) {
  const OrderTypes types = order_types(tet_order(source));
  const std::map<int, int> region_of = region_of_volume(mesh);
  gmsh::vectorpair volumes;
  gmsh::model::getEntities(volumes, 3);
  std::vector<std::size_t> all_nodes;
  GmshTets tets;
  for (const auto& [dim, entity] : volumes) {
    // The tetrahedra of the entity, all of the type of the others (tet_order).
    const EntityElements elements =
        elements_of_entity(source, dim, entity, {types.tet}, kHowToGetTets);
    for (size_t k = 0; k < elements.types.size(); ++k) {
      const auto& element_tags = elements.element_tags[k];
      tets.element_tag.insert(tets.element_tag.end(), element_tags.begin(), element_tags.end());
      all_nodes.insert(all_nodes.end(), elements.node_tags[k].begin(), elements.node_tags[k].end());
      if (!region_of.empty())
        mesh.tet_region.insert(mesh.tet_region.end(), element_tags.size(), region_of.at(entity));
    }
  }
  if (tets.element_tag.empty())
    throw InputError(
        fmt::format("{}: the mesh has no volume element (fricon needs {})", source, kHowToGetTets));
  const auto n_tets = static_cast<Index>(tets.element_tag.size());
  mesh.tets.resize(kNodesPerTet, n_tets);
  if (types.tet_nodes > kNodesPerTet) mesh.tet_extra.resize(types.tet_nodes - kNodesPerTet, n_tets);
  for (Index t = 0; t < n_tets; ++t) {
    // Gmsh's node order is ours (tet_mesh.hpp): the corners, then the edge nodes.
    for (int v = 0; v < types.tet_nodes; ++v) {
      const Index node = nodes.index_of.at(all_nodes[static_cast<size_t>(types.tet_nodes * t + v)]);
      if (v < kNodesPerTet)
        mesh.tets(v, t) = node;
      else
        mesh.tet_extra(v - kNodesPerTet, t) = node;
    }
    require_distinct_nodes(source, mesh, t, tets.element_tag[static_cast<size_t>(t)]);
    require_valid_volume(source, mesh, t, tets.element_tag[static_cast<size_t>(t)]);
  }
  return tets;
}

// Every face of every tetrahedron, sorted by its vertex set, with its tetrahedron: to name the
// tetrahedra of a non-conforming face.
struct TetFaceRef {
  std::array<Index, 3> key;
  Index tet;
};

std::array<Index, 3> sorted_key(Index a, Index b, Index c) {
  std::array<Index, 3> k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

std::vector<TetFaceRef> tet_faces(const TetMesh& mesh) {
  std::vector<TetFaceRef> faces;
  faces.reserve(static_cast<size_t>(kNodesPerTet * mesh.n_tets()));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int opposite = 0; opposite < kNodesPerTet; ++opposite) {
      std::array<Index, 3> others{};
      int n = 0;
      for (int v = 0; v < kNodesPerTet; ++v)
        if (v != opposite) others[n++] = mesh.tets(v, t);
      faces.push_back({sorted_key(others[0], others[1], others[2]), t});
    }
  std::stable_sort(faces.begin(), faces.end(),
                   [](const TetFaceRef& a, const TetFaceRef& b) { return a.key < b.key; });
  return faces;
}

// Refuses a face shared by three or more tetrahedra, naming their Gmsh elements.
void require_conforming(const std::string& source, const std::vector<TetFaceRef>& faces,
                        const GmshTets& tets) {
  constexpr size_t kMaxTetsPerFace = 2;
  for (size_t i = 0; i + kMaxTetsPerFace < faces.size(); ++i)
    if (faces[i].key == faces[i + kMaxTetsPerFace].key)
      throw InputError(fmt::format(
          "{}: the mesh is not conforming: a triangle is a face of three or more tetrahedra "
          "(Gmsh elements {}, {}, {})",
          source, tets.element_tag[static_cast<size_t>(faces[i].tet)],
          tets.element_tag[static_cast<size_t>(faces[i + 1].tet)],
          tets.element_tag[static_cast<size_t>(faces[i + 2].tet)]));
}

// The tetrahedron of which the triangle with the sorted vertex set `key` is a face (the first
// one), or -1 when it is no face of a tetrahedron.
Index tet_of_face(const std::vector<TetFaceRef>& faces, const std::array<Index, 3>& key) {
  const auto it = std::lower_bound(
      faces.begin(), faces.end(), key,
      [](const TetFaceRef& f, const std::array<Index, 3>& k) { return f.key < k; });
  return it != faces.end() && it->key == key ? it->tet : -1;
}

// A 2D physical group none of whose triangles is a face of a tetrahedron: its triangles as in the
// file by their corners (node indices of the whole model), before its points are copied out, and
// the edge nodes of its 6-node triangles, which the rigid surface leaves out (gmsh_file.hpp).
struct RigidGroup {
  std::string name;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<Index> edge_nodes;
};

// The triangles of a 2D physical group: each distinct triangle once (MSH 2.2 repeats an element
// once per physical group it is in), with its Gmsh element type (3-node or 6-node), element and
// entity, and the edge nodes of a 6-node triangle (kTriangleEdge's order; -1 for a 3-node one).
struct GroupTriangles {
  std::vector<std::array<Index, 3>> corners;
  std::vector<std::array<Index, kTriangleEdges>> edge_nodes;
  std::vector<int> type;
  std::vector<std::size_t> element;
  std::vector<int> entity;
};

GroupTriangles triangles_of_group(const std::string& source, const GmshNodes& nodes, int group) {
  GroupTriangles triangles;
  std::set<std::array<Index, 3>> seen;
  for (int entity : entities_of_group(2, group)) {
    const EntityElements elements =
        elements_of_entity(source, 2, entity, {kGmshTriangle, kGmshTriangle6}, kHowToGetTriangles);
    for (size_t kind = 0; kind < elements.types.size(); ++kind) {
      const int type = elements.types[kind];
      const auto n_nodes = static_cast<size_t>(triangle_nodes(type));
      const auto& element_tags = elements.element_tags[kind];
      const auto& node_tags = elements.node_tags[kind];
      for (size_t e = 0; e < element_tags.size(); ++e) {
        std::array<Index, 3> triangle{};
        std::array<Index, kTriangleEdges> edges{-1, -1, -1};
        for (size_t v = 0; v < n_nodes; ++v) {
          const Index node = nodes.index_of.at(node_tags[n_nodes * e + v]);
          if (v < kNodesPerTriangle)
            triangle[v] = node;
          else
            edges[v - kNodesPerTriangle] = node;
        }
        if (!seen.insert(sorted_key(triangle[0], triangle[1], triangle[2])).second) continue;
        triangles.corners.push_back(triangle);
        triangles.edge_nodes.push_back(edges);
        triangles.type.push_back(type);
        triangles.element.push_back(element_tags[e]);
        triangles.entity.push_back(entity);
      }
    }
  }
  return triangles;
}

// Refuses triangle k of the boundary tag `name` unless it is of the tetrahedra's order, and, if
// it has edge nodes, unless they are those of the tetrahedron `t` it bounds on the same edges.
void require_triangle_of_tet(const std::string& source, const std::string& name,
                             const GroupTriangles& triangles, size_t k, const GmshNodes& nodes,
                             const TetMesh& mesh, Index t) {
  const OrderTypes types = order_types(mesh.order());
  const int tet_type = types.tet;
  if (triangles.type[k] != types.triangle)
    throw InputError(fmt::format(
        "{}: the triangle (Gmsh element {}) of physical group '{}' is of type '{}' (Gmsh type "
        "{}), the tetrahedra of type '{}' (Gmsh type {}): fricon needs {}",
        source, triangles.element[k], name, element_type_name(triangles.type[k]), triangles.type[k],
        element_type_name(tet_type), tet_type, kHowToGetTriangles));
  if (mesh.order() == kLinearOrder) return;
  const auto& corners = triangles.corners[k];
  for (int e = 0; e < kTriangleEdges; ++e) {
    const Index a = corners[static_cast<size_t>(kTriangleEdge[e][0])];
    const Index b = corners[static_cast<size_t>(kTriangleEdge[e][1])];
    Index expected = -1;
    for (int te = 0; te < kTetEdges; ++te) {
      const Index p = mesh.tets(kTetEdge[te][0], t), q = mesh.tets(kTetEdge[te][1], t);
      if ((p == a && q == b) || (p == b && q == a)) expected = mesh.tet_extra(te, t);
    }
    const Index given = triangles.edge_nodes[k][static_cast<size_t>(e)];
    if (given != expected)
      throw InputError(fmt::format(
          "{}: the triangle (Gmsh element {}) of physical group '{}' has Gmsh node {} on its "
          "edge between Gmsh nodes {} and {}, where the tetrahedron it bounds has Gmsh node {}: "
          "the surface mesh does not conform to the volume mesh",
          source, triangles.element[k], name, nodes.tag_of[static_cast<size_t>(given)],
          nodes.tag_of[static_cast<size_t>(a)], nodes.tag_of[static_cast<size_t>(b)],
          nodes.tag_of[static_cast<size_t>(expected)]));
  }
}

// The triangles of every 2D physical group, 3-node or 6-node, by their corners (the edge nodes
// of the faces are the tetrahedra's, TetMesh::face_extra, filled by orient_faces). A group whose
// triangles are all faces of the tetrahedra (or that has none) is a boundary tag: one face per
// triangle and group (not yet oriented), each triangle of the tetrahedra's order
// (require_triangle_of_tet). A group none of whose triangles is a face of a tetrahedron is a
// rigid surface, returned. A group with some triangles on the tetrahedra and some not is refused.
std::vector<RigidGroup> read_tagged_faces(const std::string& source, const GmshNodes& nodes,
                                          const std::vector<TetFaceRef>& tet_face_refs,
                                          TetMesh& mesh) {
  std::vector<RigidGroup> rigid;
  std::vector<std::array<Index, 3>> corners;
  for (const auto& [group, name] : physical_groups(2)) {
    GroupTriangles triangles = triangles_of_group(source, nodes, group);
    std::vector<Index> tet_of(triangles.corners.size());
    std::vector<bool> on_tets(triangles.corners.size());
    size_t n_on = 0;
    for (size_t k = 0; k < on_tets.size(); ++k) {
      const auto& c = triangles.corners[k];
      tet_of[k] = tet_of_face(tet_face_refs, sorted_key(c[0], c[1], c[2]));
      on_tets[k] = tet_of[k] >= 0;
      n_on += on_tets[k] ? 1 : 0;
    }
    if (n_on == 0 && !triangles.corners.empty()) {
      RigidGroup surface{name, std::move(triangles.corners), {}};
      for (const auto& edges : triangles.edge_nodes)
        for (Index node : edges)
          if (node >= 0) surface.edge_nodes.push_back(node);
      rigid.push_back(std::move(surface));
      continue;
    }
    if (n_on < on_tets.size()) {
      const size_t k =
          static_cast<size_t>(std::find(on_tets.begin(), on_tets.end(), false) - on_tets.begin());
      throw InputError(fmt::format(
          "{}: a triangle (Gmsh element {}) of physical group '{}' is no face of any tetrahedron, "
          "while {} of its {} triangles are: a physical surface is either a boundary of the "
          "tetrahedra or, none of its triangles on them, a rigid surface (a rigid obstacle's)",
          source, triangles.element[k], name, n_on, on_tets.size()));
    }
    for (size_t k = 0; k < triangles.corners.size(); ++k)
      require_triangle_of_tet(source, name, triangles, k, nodes, mesh, tet_of[k]);
    const int tag = static_cast<int>(mesh.tag_names.size());
    mesh.tag_names.push_back(name);
    corners.insert(corners.end(), triangles.corners.begin(), triangles.corners.end());
    mesh.face_tag.insert(mesh.face_tag.end(), triangles.corners.size(), tag);
    mesh.face_entity.insert(mesh.face_entity.end(), triangles.entity.begin(),
                            triangles.entity.end());
  }
  mesh.faces.resize(kNodesPerTriangle, static_cast<Index>(corners.size()));
  for (Index f = 0; f < mesh.n_faces(); ++f)
    for (int v = 0; v < kNodesPerTriangle; ++v)
      mesh.faces(v, f) = corners[static_cast<size_t>(f)][static_cast<size_t>(v)];
  return rigid;
}

// The rigid surfaces of `groups`, each with a copy of its points (the corners of its triangles,
// in the order of their Gmsh tags); then the nodes of no tetrahedron taken out of the mesh
// (tetrahedra, faces, their edge nodes and nodes.index_of renumbered; a dropped node's index
// becomes -1). A node of no tetrahedron and no rigid surface (a corner or an edge node of one of
// its triangles) is refused.
void split_off_rigid_surfaces(const std::string& source, const std::vector<RigidGroup>& groups,
                              GmshNodes& nodes, TetMesh& mesh) {
  const size_t n_nodes = static_cast<size_t>(mesh.n_nodes());
  std::vector<bool> on_tets(n_nodes, false), on_rigid(n_nodes, false);
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int v = 0; v < mesh.nodes_per_tet(); ++v)
      on_tets[static_cast<size_t>(mesh.tet_node(t, v))] = true;
  std::vector<Index> local(n_nodes, -1);
  for (const RigidGroup& group : groups) {
    for (Index node : group.edge_nodes)
      on_rigid[static_cast<size_t>(node)] = true;
    std::vector<Index> used;
    for (const auto& triangle : group.triangles)
      used.insert(used.end(), triangle.begin(), triangle.end());
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    RigidSurface surface{group.name, mesh.nodes(Eigen::all, used), {}};
    for (size_t k = 0; k < used.size(); ++k) {
      local[static_cast<size_t>(used[k])] = static_cast<Index>(k);
      on_rigid[static_cast<size_t>(used[k])] = true;
    }
    surface.triangles.resize(kNodesPerTriangle, static_cast<Index>(group.triangles.size()));
    for (size_t f = 0; f < group.triangles.size(); ++f)
      for (size_t v = 0; v < kNodesPerTriangle; ++v)
        surface.triangles(static_cast<Index>(v), static_cast<Index>(f)) =
            local[static_cast<size_t>(group.triangles[f][v])];
    mesh.rigid_surfaces.push_back(std::move(surface));
  }
  // Each node's index once the nodes of no tetrahedron are out.
  std::vector<Index> renumbered(n_nodes, -1);
  std::vector<Index> kept;
  for (size_t n = 0; n < n_nodes; ++n) {
    if (on_tets[n]) {
      renumbered[n] = static_cast<Index>(kept.size());
      kept.push_back(static_cast<Index>(n));
    } else if (!on_rigid[n]) {
      throw InputError(fmt::format(
          "{}: node {} (Gmsh node {}) belongs to no tetrahedron (remove it, or mesh the volume "
          "it lies in)",
          source, n, nodes.tag_of[n]));
    }
  }
  if (kept.size() == n_nodes) return;
  const auto renumber = [&renumbered](Index v) { return renumbered[static_cast<size_t>(v)]; };
  mesh.nodes = mesh.nodes(Eigen::all, kept).eval();
  renumber_nodes(mesh, renumber);
  std::vector<std::size_t> tag_of;
  for (Index n : kept)
    tag_of.push_back(nodes.tag_of[static_cast<size_t>(n)]);
  for (auto& [tag, index] : nodes.index_of)
    index = renumber(index);
  nodes.tag_of = std::move(tag_of);
}

// Orients every boundary face outward (each one is a face of a tetrahedron: read_tagged_faces)
// and gives it the edge nodes of its tetrahedron in a quadratic mesh (orient_faces_outward),
// after checking first that the tetrahedra agree on the edge node of every edge (fill_face_extra
// refuses them naming the file).
void orient_faces(const std::string& source, TetMesh& mesh) {
  fill_face_extra(mesh, source);
  if (const Index f = orient_faces_outward(mesh); f >= 0)
    throw Error(fmt::format("{}: boundary face {} is no face of any tetrahedron (internal error)",
                            source, f));
}

// The physical groups of dimension 1 (curves) and 0 (points), each the node set of all nodes of
// its entities and of their elements (a curve's end points included, and the midpoints of its
// 3-node lines in a quadratic mesh). A name of a 2D physical group too is refused:
// the boundary would mean two things.
void read_node_sets(const std::string& source, const GmshNodes& nodes, TetMesh& mesh) {
  for (int dim : {kCurveDimension, kPointDimension})
    for (const auto& [group, name] : physical_groups(dim)) {
      if (mesh.find_tag(name) >= 0 || mesh.find_rigid_surface(name) != nullptr)
        throw InputError(fmt::format(
            "{}: physical group '{}' of dimension {} has the name of a physical surface too; "
            "give the {} a name of its own",
            source, name, dim, node_set_kind(dim)));
      NodeSet set{name, dim, {}};
      for (int entity : entities_of_group(dim, group)) {
        std::vector<std::size_t> tags;
        std::vector<double> coords, parametric;
        gmsh::model::mesh::getNodes(tags, coords, parametric, dim, entity,
                                    /*includeBoundary=*/true, /*returnParametricCoord=*/false);
        // And the nodes of a curve's lines: a 3-node line's midpoint is a node of the curve
        // even where the file does not say on which entity it lies (MSH 2.2).
        if (dim == kCurveDimension)
          for (const auto& node_tags :
               elements_of_entity(source, dim, entity, {kGmshLine, kGmshLine3}, kHowToGetLines)
                   .node_tags)
            tags.insert(tags.end(), node_tags.begin(), node_tags.end());
        for (std::size_t tag : tags) {
          const Index index = nodes.index_of.at(tag);
          if (index < 0)
            throw InputError(fmt::format(
                "{}: physical {} '{}' has Gmsh node {}, which belongs to no tetrahedron, only to a "
                "rigid surface: a {} must lie on an elastic body",
                source, node_set_kind(dim), name, tag, node_set_kind(dim)));
          set.nodes.push_back(index);
        }
      }
      std::sort(set.nodes.begin(), set.nodes.end());
      set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
      if (set.nodes.empty())
        throw InputError(
            fmt::format("{}: physical {} '{}' has no mesh node", source, node_set_kind(dim), name));
      mesh.node_sets.push_back(std::move(set));
    }
}

// @sect: writing, the steps.

// The Gmsh surfaces to write: each groups the distinct triangles of one face entity that carry
// the same set of tags (so that each triangle is one Gmsh element, and each tag's physical group
// is a union of surfaces).
struct SurfacePlan {
  struct Surface {
    int gmsh_tag = 0;
    std::set<int> tags;
    std::vector<Index> faces;  // one representative face per triangle
  };
  std::vector<Surface> surfaces;
};

SurfacePlan plan_surfaces(const TetMesh& mesh) {
  const bool has_entities = !mesh.face_entity.empty();
  // Each distinct (triangle, entity): the tags it carries and a representative face. Faces with
  // no entity (-1) are set apart by their tag.
  using TriangleKey = std::pair<std::array<Index, 3>, std::pair<int, int>>;
  std::map<TriangleKey, std::pair<std::set<int>, Index>> triangles;
  int max_entity = 0;
  for (Index f = 0; f < mesh.n_faces(); ++f) {
    const int entity = has_entities ? mesh.face_entity[static_cast<size_t>(f)] : -1;
    const int tag = mesh.face_tag[static_cast<size_t>(f)];
    max_entity = std::max(max_entity, entity);
    const TriangleKey key{sorted_key(mesh.faces(0, f), mesh.faces(1, f), mesh.faces(2, f)),
                          {entity, entity > 0 ? -1 : tag}};
    auto [it, inserted] = triangles.try_emplace(key, std::set<int>{}, f);
    it->second.first.insert(tag);
  }
  // One surface per (entity, tag set), in the order of the faces' first appearance.
  std::map<std::pair<std::pair<int, int>, std::set<int>>, size_t> surface_of;
  std::vector<std::pair<Index, std::pair<std::pair<int, int>, std::set<int>>>> firsts;
  for (const auto& [key, value] : triangles)
    firsts.push_back({value.second, {key.second, value.first}});
  std::sort(firsts.begin(), firsts.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  SurfacePlan plan;
  std::set<int> used_gmsh_tags;
  int next_tag = max_entity + 1;
  for (const auto& [face, key] : firsts) {
    auto [it, inserted] = surface_of.try_emplace(key, plan.surfaces.size());
    if (inserted) {
      const int entity = key.first.first;
      const bool keep = entity > 0 && used_gmsh_tags.insert(entity).second;
      plan.surfaces.push_back({keep ? entity : next_tag++, key.second, {}});
    }
    plan.surfaces[it->second].faces.push_back(face);
  }
  return plan;
}

// Gmsh node tags (fricon index + 1) of the elements `columns`, node(v, c) the v-th node of c.
std::vector<std::size_t> gmsh_node_tags(const std::vector<Index>& columns, int n_per,
                                        const std::function<Index(int, Index)>& node) {
  std::vector<std::size_t> tags;
  tags.reserve(columns.size() * static_cast<size_t>(n_per));
  for (Index c : columns)
    for (int v = 0; v < n_per; ++v)
      tags.push_back(static_cast<std::size_t>(node(v, c)) + 1);
  return tags;
}

std::vector<std::size_t> consecutive_tags(std::size_t first, std::size_t count) {
  std::vector<std::size_t> tags(count);
  for (std::size_t i = 0; i < count; ++i)
    tags[i] = first + i;
  return tags;
}

// Volumes: one discrete volume and one 3D physical group per region; all nodes on the first. The
// tetrahedra are of the mesh's order (10-node ones with their edge nodes: Gmsh's order is ours).
void add_volumes(const TetMesh& mesh) {
  const OrderTypes types = order_types(mesh.order());
  const int n_regions = mesh.n_regions();
  std::vector<std::vector<Index>> tets_of(static_cast<size_t>(n_regions));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    tets_of[static_cast<size_t>(mesh.region(t))].push_back(t);
  for (int r = 0; r < n_regions; ++r)
    gmsh::model::addDiscreteEntity(3, r + 1);
  std::vector<double> coords(mesh.nodes.data(), mesh.nodes.data() + mesh.nodes.size());
  gmsh::model::mesh::addNodes(3, 1, consecutive_tags(1, static_cast<size_t>(mesh.n_nodes())),
                              coords);
  std::size_t next_element = 1;
  for (int r = 0; r < n_regions; ++r) {
    const auto& tets = tets_of[static_cast<size_t>(r)];
    gmsh::model::mesh::addElementsByType(
        r + 1, types.tet, consecutive_tags(next_element, tets.size()),
        gmsh_node_tags(tets, types.tet_nodes, [&](int v, Index t) { return mesh.tet_node(t, v); }));
    next_element += tets.size();
    const int group = gmsh::model::addPhysicalGroup(3, {r + 1}, r + 1);
    gmsh::model::setPhysicalName(
        3, group, mesh.region_names.empty() ? "body" : mesh.region_names[static_cast<size_t>(r)]);
  }
}

// The next free tags of the model being written.
struct NextTags {
  int entity = 1;           // surface entity
  std::size_t element = 1;  // element
};

// Surfaces: the planned discrete surfaces, and one 2D physical group per tag with faces (tag i is
// physical group i + 1). The triangles are of the mesh's order (6-node ones with face_extra).
NextTags add_surfaces(const TetMesh& mesh) {
  const OrderTypes types = order_types(mesh.order());
  const SurfacePlan plan = plan_surfaces(mesh);
  std::size_t next_element = static_cast<std::size_t>(mesh.n_tets()) + 1;
  std::vector<std::vector<int>> surfaces_of_tag(mesh.tag_names.size());
  int max_entity = 0;
  for (const auto& s : plan.surfaces) {
    max_entity = std::max(max_entity, s.gmsh_tag);
    gmsh::model::addDiscreteEntity(2, s.gmsh_tag);
    gmsh::model::mesh::addElementsByType(
        s.gmsh_tag, types.triangle, consecutive_tags(next_element, s.faces.size()),
        gmsh_node_tags(s.faces, types.triangle_nodes,
                       [&](int v, Index f) { return mesh.face_node(f, v); }));
    next_element += s.faces.size();
    for (int tag : s.tags)
      surfaces_of_tag[static_cast<size_t>(tag)].push_back(s.gmsh_tag);
  }
  for (size_t tag = 0; tag < mesh.tag_names.size(); ++tag) {
    if (surfaces_of_tag[tag].empty()) continue;
    const int group =
        gmsh::model::addPhysicalGroup(2, surfaces_of_tag[tag], static_cast<int>(tag) + 1);
    gmsh::model::setPhysicalName(2, group, mesh.tag_names[tag]);
  }
  return {max_entity + 1, next_element};
}

// Rigid surfaces: each one discrete surface with nodes of its own (after the mesh's nodes) and a
// 2D physical group after those of the tags, so that read_gmsh reads it back as a rigid surface.
void add_rigid_surfaces(const TetMesh& mesh, NextTags next) {
  std::size_t next_node = static_cast<std::size_t>(mesh.n_nodes()) + 1;
  int next_group = static_cast<int>(mesh.tag_names.size()) + 1;
  for (const RigidSurface& surface : mesh.rigid_surfaces) {
    const int entity = next.entity++;
    gmsh::model::addDiscreteEntity(2, entity);
    const auto n_points = static_cast<std::size_t>(surface.points.cols());
    std::vector<double> coords(surface.points.data(),
                               surface.points.data() + surface.points.size());
    gmsh::model::mesh::addNodes(2, entity, consecutive_tags(next_node, n_points), coords);
    std::vector<Index> triangles(static_cast<size_t>(surface.triangles.cols()));
    for (size_t f = 0; f < triangles.size(); ++f)
      triangles[f] = static_cast<Index>(f);
    const std::size_t first_node = next_node;
    gmsh::model::mesh::addElementsByType(
        entity, kGmshTriangle, consecutive_tags(next.element, triangles.size()),
        gmsh_node_tags(triangles, kNodesPerTriangle, [&](int v, Index f) {
          return static_cast<Index>(first_node - 1) + surface.triangles(v, f);
        }));
    next.element += triangles.size();
    next_node += n_points;
    const int group = gmsh::model::addPhysicalGroup(2, {entity}, next_group++);
    gmsh::model::setPhysicalName(2, group, surface.name);
  }
}

// Brings the mesh of a file to `order` (a .geo file's already is, load_model): a linear mesh is
// made quadratic with straight edges (add_edge_midpoints); a quadratic one is refused, as its
// edge nodes would be dropped.
void bring_to_order(const std::string& source, int order, TetMesh& mesh) {
  if (order == mesh.order()) return;
  if (order == kQuadraticOrder) {
    add_edge_midpoints(mesh);
    return;
  }
  throw InputError(fmt::format(
      "{}: the mesh has 10-node (quadratic) tetrahedra, but order {} (linear tetrahedra) was asked "
      "for: ask for order {} to solve with them ([mesh] order = {}), or save the mesh at order {} "
      "('Mesh.ElementOrder = 1;', or run 'gmsh -3 -order 1')",
      source, order, kQuadraticOrder, kQuadraticOrder, kLinearOrder));
}

// A file beside `file`, with the same extension (Gmsh chooses the format by it).
fs::path temporary_beside(const fs::path& file) {
  return file.parent_path() /
         fmt::format("{}.tmp-{}{}", file.stem().string(), getpid(), file.extension().string());
}

}  // namespace

TetMesh read_gmsh(const std::filesystem::path& file, std::optional<Real> size_factor,
                  std::optional<int> order) {
  const std::string source = file.string();
  require_readable(file);
  if (size_factor && !is_geo(file))
    throw InputError(fmt::format(
        "{}: a mesh size factor only applies to a .geo file (meshed by fricon), not to a mesh",
        source));
  if (size_factor && !(*size_factor > 0.0 && std::isfinite(*size_factor)))
    throw InputError(
        fmt::format("{}: the mesh size factor {} must be a positive number", source, *size_factor));
  if (order && *order != kLinearOrder && *order != kQuadraticOrder)
    throw InputError(
        fmt::format("{}: the element order {} is neither {} (linear tetrahedra) nor {} (quadratic)",
                    source, *order, kLinearOrder, kQuadraticOrder));
  require_gmsh_library<InputError>(source);
  TetMesh mesh;
  {
    GmshSession session(source);
    load_model(session, file, size_factor, order);
    GmshNodes nodes;
    GmshTets tets;
    session.run("reading the mesh", [&] {
      nodes = read_nodes(mesh);
      tets = read_tets(source, nodes, mesh);
      const std::vector<TetFaceRef> faces = tet_faces(mesh);
      require_conforming(source, faces, tets);
      const std::vector<RigidGroup> rigid = read_tagged_faces(source, nodes, faces, mesh);
      split_off_rigid_surfaces(source, rigid, nodes, mesh);
      orient_faces(source, mesh);
      read_node_sets(source, nodes, mesh);
    });
  }
  if (order) bring_to_order(source, *order, mesh);
  check_mesh(mesh, source);
  return mesh;
}

void write_gmsh(const std::filesystem::path& file, const TetMesh& mesh, int msh_version,
                bool binary) {
  const std::string target = file.string();
  if (msh_version != kMsh41 && msh_version != kMsh22)
    throw InputError(fmt::format("{}: MSH version {} is not one of {} (4.1) and {} (2.2)", target,
                                 msh_version, kMsh41, kMsh22));
  if (file.extension() != ".msh")
    throw InputError(fmt::format("{}: a Gmsh mesh file name must end in .msh", target));
  check_mesh(mesh, "write_gmsh");
  require_gmsh_library<Error>(target);
  std::error_code ec;
  if (!file.parent_path().empty()) fs::create_directories(file.parent_path(), ec);
  const fs::path temporary = temporary_beside(file);
  try {
    GmshSession session(target);
    session.run<Error>("writing the mesh with Gmsh failed", [&] {
      constexpr double kMshVersionScale = 10.0;
      gmsh::option::setNumber("Mesh.MshFileVersion", msh_version / kMshVersionScale);
      gmsh::option::setNumber("Mesh.Binary", binary ? 1 : 0);
      gmsh::model::add("fricon");
      add_volumes(mesh);
      add_rigid_surfaces(mesh, add_surfaces(mesh));
      gmsh::write(temporary.string());
    });
  } catch (...) {
    fs::remove(temporary, ec);
    throw;
  }
  if (!fs::exists(temporary, ec)) throw Error(fmt::format("{}: Gmsh wrote no file", target));
  fs::rename(temporary, file, ec);
  if (ec) {
    fs::remove(temporary, ec);
    throw Error(fmt::format("{}: cannot write the file: {}", target, ec.message()));
  }
}

}  // namespace fricon::mesh
