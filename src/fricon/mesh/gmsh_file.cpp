#include "fricon/mesh/gmsh_file.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
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

// Gmsh element types (Gmsh reference manual, "MSH file format": elm-type).
constexpr int kGmshTriangle = 2;
constexpr int kGmshTetrahedron = 4;
constexpr int kNodesPerTriangle = 3;
constexpr int kNodesPerTet = 4;
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

void load_model(GmshSession& gmsh_session, const fs::path& file, std::optional<Real> size_factor) {
  if (size_factor) gmsh::option::setNumber("Mesh.MeshSizeFactor", *size_factor);
  gmsh_session.run("Gmsh cannot read it", [&] { gmsh::open(file.string()); });
  if (is_geo(file)) gmsh_session.run("meshing failed", [] { gmsh::model::mesh::generate(3); });
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

// Refuses any element of dimension `dim` on the entity `entity_tag` (-1: all) that is not of
// type `wanted`.
void require_element_type(const std::string& source, int dim, int entity_tag, int wanted,
                          const std::string& how) {
  std::vector<int> types;
  gmsh::model::mesh::getElementTypes(types, dim, entity_tag);
  for (int type : types)
    if (type != wanted)
      throw InputError(fmt::format(
          "{}: has elements of type '{}' (Gmsh type {}) in dimension {}; fricon needs {}", source,
          element_type_name(type), type, dim, how));
}

const char* const kHowToGetLinearTets =
    "linear tetrahedra: mesh with 'Mesh.ElementOrder = 1;' and no 'Recombine' nor "
    "'Mesh.RecombineAll'/'Mesh.Recombine3DAll' (or run 'gmsh -3 -order 1')";
const char* const kHowToGetLinearTriangles =
    "3-node triangles on the tagged surfaces: mesh with 'Mesh.ElementOrder = 1;' and no "
    "'Recombine' nor 'Mesh.RecombineAll' (or run 'gmsh -3 -order 1')";

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

// The 4-node tetrahedra of all volumes, with their regions.
GmshTets read_tets(const std::string& source, const GmshNodes& nodes, TetMesh& mesh) {
  require_element_type(source, 3, -1, kGmshTetrahedron, kHowToGetLinearTets);
  const std::map<int, int> region_of = region_of_volume(mesh);
  gmsh::vectorpair volumes;
  gmsh::model::getEntities(volumes, 3);
  std::vector<std::size_t> all_nodes;
  GmshTets tets;
  for (const auto& [dim, entity] : volumes) {
    std::vector<std::size_t> element_tags, node_tags;
    gmsh::model::mesh::getElementsByType(kGmshTetrahedron, element_tags, node_tags, entity);
    tets.element_tag.insert(tets.element_tag.end(), element_tags.begin(), element_tags.end());
    all_nodes.insert(all_nodes.end(), node_tags.begin(), node_tags.end());
    if (!region_of.empty())
      mesh.tet_region.insert(mesh.tet_region.end(), element_tags.size(), region_of.at(entity));
  }
  if (tets.element_tag.empty())
    throw InputError(fmt::format("{}: the mesh has no volume element (fricon needs {})", source,
                                 kHowToGetLinearTets));
  mesh.tets.resize(kNodesPerTet, static_cast<Index>(tets.element_tag.size()));
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    for (int v = 0; v < kNodesPerTet; ++v)
      mesh.tets(v, t) = nodes.index_of.at(all_nodes[static_cast<size_t>(kNodesPerTet * t + v)]);
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

// Whether the triangle with the sorted vertex set `key` is a face of a tetrahedron.
bool is_tet_face(const std::vector<TetFaceRef>& faces, const std::array<Index, 3>& key) {
  const auto it = std::lower_bound(
      faces.begin(), faces.end(), key,
      [](const TetFaceRef& f, const std::array<Index, 3>& k) { return f.key < k; });
  return it != faces.end() && it->key == key;
}

// A 2D physical group none of whose triangles is a face of a tetrahedron: its triangles as in the
// file (node indices of the whole model), before its points are copied out.
struct RigidGroup {
  std::string name;
  std::vector<std::array<Index, 3>> triangles;
};

// The triangles of a 2D physical group: each distinct triangle once (MSH 2.2 repeats an element
// once per physical group it is in), with its Gmsh element and entity.
struct GroupTriangles {
  std::vector<std::array<Index, 3>> corners;
  std::vector<std::size_t> element;
  std::vector<int> entity;
};

GroupTriangles triangles_of_group(const std::string& source, const GmshNodes& nodes, int group) {
  GroupTriangles triangles;
  std::set<std::array<Index, 3>> seen;
  for (int entity : entities_of_group(2, group)) {
    require_element_type(source, 2, entity, kGmshTriangle, kHowToGetLinearTriangles);
    std::vector<std::size_t> element_tags, node_tags;
    gmsh::model::mesh::getElementsByType(kGmshTriangle, element_tags, node_tags, entity);
    for (size_t e = 0; e < element_tags.size(); ++e) {
      std::array<Index, 3> triangle{};
      for (size_t v = 0; v < kNodesPerTriangle; ++v)
        triangle[v] = nodes.index_of.at(node_tags[kNodesPerTriangle * e + v]);
      if (!seen.insert(sorted_key(triangle[0], triangle[1], triangle[2])).second) continue;
      triangles.corners.push_back(triangle);
      triangles.element.push_back(element_tags[e]);
      triangles.entity.push_back(entity);
    }
  }
  return triangles;
}

// The 3-node triangles of every 2D physical group. A group whose triangles are all faces of the
// tetrahedra (or that has none) is a boundary tag: one face per triangle and group (not yet
// oriented). A group none of whose triangles is a face of a tetrahedron is a rigid surface,
// returned. A group with some triangles on the tetrahedra and some not is refused.
std::vector<RigidGroup> read_tagged_faces(const std::string& source, const GmshNodes& nodes,
                                          const std::vector<TetFaceRef>& tet_face_refs,
                                          TetMesh& mesh) {
  std::vector<RigidGroup> rigid;
  std::vector<std::array<Index, 3>> corners;
  for (const auto& [group, name] : physical_groups(2)) {
    GroupTriangles triangles = triangles_of_group(source, nodes, group);
    std::vector<bool> on_tets(triangles.corners.size());
    size_t n_on = 0;
    for (size_t k = 0; k < on_tets.size(); ++k) {
      const auto& c = triangles.corners[k];
      on_tets[k] = is_tet_face(tet_face_refs, sorted_key(c[0], c[1], c[2]));
      n_on += on_tets[k] ? 1 : 0;
    }
    if (n_on == 0 && !triangles.corners.empty()) {
      rigid.push_back({name, std::move(triangles.corners)});
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

// The rigid surfaces of `groups`, each with a copy of its points (in the order of their Gmsh
// tags); then the nodes of no tetrahedron taken out of the mesh (tetrahedra, faces and
// nodes.index_of renumbered; a dropped node's index becomes -1). A node of no tetrahedron and no
// rigid surface is refused.
void split_off_rigid_surfaces(const std::string& source, const std::vector<RigidGroup>& groups,
                              GmshNodes& nodes, TetMesh& mesh) {
  const size_t n_nodes = static_cast<size_t>(mesh.n_nodes());
  std::vector<bool> on_tets(n_nodes, false), on_rigid(n_nodes, false);
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int v = 0; v < kNodesPerTet; ++v)
      on_tets[static_cast<size_t>(mesh.tets(v, t))] = true;
  std::vector<Index> local(n_nodes, -1);
  for (const RigidGroup& group : groups) {
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
  mesh.tets = mesh.tets.unaryExpr(renumber).eval();
  mesh.faces = mesh.faces.unaryExpr(renumber).eval();
  std::vector<std::size_t> tag_of;
  for (Index n : kept)
    tag_of.push_back(nodes.tag_of[static_cast<size_t>(n)]);
  for (auto& [tag, index] : nodes.index_of)
    index = renumber(index);
  nodes.tag_of = std::move(tag_of);
}

// Orients every boundary face outward (each one is a face of a tetrahedron: read_tagged_faces).
void orient_faces(const std::string& source, TetMesh& mesh) {
  if (const Index f = orient_faces_outward(mesh); f >= 0)
    throw Error(fmt::format("{}: boundary face {} is no face of any tetrahedron (internal error)",
                            source, f));
}

// The physical groups of dimension 1 (curves) and 0 (points), each the node set of all nodes of
// its entities (a curve's end points included). A name of a 2D physical group too is refused:
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

// Volumes: one discrete volume and one 3D physical group per region; all nodes on the first.
void add_volumes(const TetMesh& mesh) {
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
        r + 1, kGmshTetrahedron, consecutive_tags(next_element, tets.size()),
        gmsh_node_tags(tets, kNodesPerTet, [&](int v, Index t) { return mesh.tets(v, t); }));
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
// physical group i + 1).
NextTags add_surfaces(const TetMesh& mesh) {
  const SurfacePlan plan = plan_surfaces(mesh);
  std::size_t next_element = static_cast<std::size_t>(mesh.n_tets()) + 1;
  std::vector<std::vector<int>> surfaces_of_tag(mesh.tag_names.size());
  int max_entity = 0;
  for (const auto& s : plan.surfaces) {
    max_entity = std::max(max_entity, s.gmsh_tag);
    gmsh::model::addDiscreteEntity(2, s.gmsh_tag);
    gmsh::model::mesh::addElementsByType(
        s.gmsh_tag, kGmshTriangle, consecutive_tags(next_element, s.faces.size()),
        gmsh_node_tags(s.faces, kNodesPerTriangle,
                       [&](int v, Index f) { return mesh.faces(v, f); }));
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

// A file beside `file`, with the same extension (Gmsh chooses the format by it).
fs::path temporary_beside(const fs::path& file) {
  return file.parent_path() /
         fmt::format("{}.tmp-{}{}", file.stem().string(), getpid(), file.extension().string());
}

}  // namespace

TetMesh read_gmsh(const std::filesystem::path& file, std::optional<Real> size_factor) {
  const std::string source = file.string();
  require_readable(file);
  if (size_factor && !is_geo(file))
    throw InputError(fmt::format(
        "{}: a mesh size factor only applies to a .geo file (meshed by fricon), not to a mesh",
        source));
  if (size_factor && !(*size_factor > 0.0 && std::isfinite(*size_factor)))
    throw InputError(
        fmt::format("{}: the mesh size factor {} must be a positive number", source, *size_factor));
  require_gmsh_library<InputError>(source);
  GmshSession session(source);
  load_model(session, file, size_factor);
  TetMesh mesh;
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
