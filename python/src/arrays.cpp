// Meshes from and to numpy arrays (the Mesh class of the module).

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "fricon/core/error.hpp"
#include "fricon/core/format.hpp"
#include "fricon/mesh/brick.hpp"
#include "fricon/mesh/from_arrays.hpp"

namespace fricon::python {

namespace {

constexpr py::ssize_t kDimension = 3;  // coordinates per point

using IndexArray = py::array_t<Index, py::array::c_style | py::array::forcecast>;
using RealArray = py::array_t<Real, py::array::c_style | py::array::forcecast>;

/// The entries of `a`, an array of shape (k, w) for a width w of `widths`, in C order (a row per
/// entity); `width` (if not null) gets w. Throws InputError naming the array and its shape.
template <typename T>
std::vector<T> flat(const py::array_t<T, py::array::c_style | py::array::forcecast>& a,
                    std::initializer_list<py::ssize_t> widths, const std::string& what,
                    Index* width = nullptr) {
  if (a.ndim() != 2 || std::find(widths.begin(), widths.end(), a.shape(1)) == widths.end()) {
    std::string shapes;
    for (const py::ssize_t w : widths)
      shapes += fmt::format("{}(k, {})", shapes.empty() ? "" : " or ", w);
    throw InputError(fmt::format(
        "fricon.Mesh: {}: expected an array of shape {}, got {} "
        "dimension(s){}",
        what, shapes, a.ndim(),
        a.ndim() == 2 ? fmt::format(" of shape ({}, {})", a.shape(0), a.shape(1)) : ""));
  }
  if (width != nullptr) *width = static_cast<Index>(a.shape(1));
  return std::vector<T>(a.data(), a.data() + a.size());
}

/// The largest magnitude a float holds every whole number up to (2^53): a float index beyond
/// it may not be the number written.
constexpr Real kLargestExactFloatIndex = 9007199254740992.0;

/// "tets[3, 1]" or "regions['a'][3]": entry k (in C order) of an array named `what`.
std::string entry_name(const py::array& a, const std::string& what, py::ssize_t k) {
  if (a.ndim() == 2 && a.shape(1) > 0)
    return fmt::format("{}[{}, {}]", what, k / a.shape(1), k % a.shape(1));
  return fmt::format("{}[{}]", what, k);
}

/// Indices as integers: an integer array as it is; a float array (np.loadtxt gives one) only
/// when every value is a whole number, since a cast would truncate 0.5 to 0 silently. Throws
/// InputError naming the array and the first value that is no index.
IndexArray indices_of(const py::array& a, const std::string& what) {
  const char kind = a.dtype().kind();
  if (kind == 'f') {
    const RealArray values = RealArray::ensure(a);
    for (py::ssize_t k = 0; k < values.size(); ++k) {
      const Real v = values.data()[k];
      if (!std::isfinite(v) || v != std::floor(v) || std::abs(v) > kLargestExactFloatIndex)
        throw InputError(fmt::format("fricon.Mesh: {}: expected an integer index, got {}",
                                     entry_name(a, what, k), format_real(v)));
    }
  } else if (kind != 'i' && kind != 'u') {
    throw InputError(
        fmt::format("fricon.Mesh: {}: expected an array of integer indices, got "
                    "dtype {}",
                    what, py::str(a.dtype()).cast<std::string>()));
  }
  return IndexArray::ensure(a);
}

std::vector<Index> flat_indices(const py::array& a, const std::string& what) {
  const IndexArray indices = indices_of(a, what);
  if (indices.ndim() != 1)
    throw InputError(
        fmt::format("fricon.Mesh: {}: expected a 1-D array of tetrahedron indices", what));
  return std::vector<Index>(indices.data(), indices.data() + indices.size());
}

PyMesh make_mesh(const RealArray& points, const py::array& tets,
                 const std::map<std::string, py::array>& boundary,
                 const std::optional<std::map<std::string, py::array>>& regions) {
  mesh::MeshArrays arrays;
  arrays.points = flat<Real>(points, {kDimension}, "points");
  // Linear or quadratic tetrahedra (theory.md §2.12); on quadratic ones triangles of 3 nodes or 6.
  arrays.tets =
      flat<Index>(indices_of(tets, "tets"), {mesh::kLinearTetNodes, mesh::kQuadraticTetNodes},
                  "tets", &arrays.nodes_per_tet);
  for (const auto& [name, triangles] : boundary) {
    const std::string what = fmt::format("boundary['{}']", name);
    mesh::TriangleArray& rows = arrays.boundary[name];
    rows.nodes =
        flat<Index>(indices_of(triangles, what),
                    {mesh::kLinearTriangleNodes, mesh::kQuadraticTriangleNodes}, what, &rows.width);
  }
  if (regions)
    for (const auto& [name, members] : *regions)
      arrays.regions[name] = flat_indices(members, fmt::format("regions['{}']", name));
  return PyMesh{
      std::make_shared<const mesh::TetMesh>(mesh::mesh_from_arrays(arrays, "fricon.Mesh"))};
}

// Each tag's triangles with all their nodes (the corners, then the edge nodes of a quadratic
// mesh: TetMesh::face_node), as Mesh() takes them.
py::dict boundary_of(const mesh::TetMesh& mesh) {
  py::dict out;
  const int width = mesh.nodes_per_face();
  for (std::size_t tag = 0; tag < mesh.tag_names.size(); ++tag) {
    const std::vector<Index> faces = mesh.faces_with_tag(mesh.tag_names[tag]);
    py::array_t<Index> tri({static_cast<py::ssize_t>(faces.size()), py::ssize_t{width}});
    auto r = tri.mutable_unchecked<2>();
    for (std::size_t k = 0; k < faces.size(); ++k)
      for (int v = 0; v < width; ++v)
        r(static_cast<py::ssize_t>(k), v) = mesh.face_node(faces[k], v);
    out[py::str(mesh.tag_names[tag])] = tri;
  }
  return out;
}

py::dict regions_of(const mesh::TetMesh& mesh) {
  py::dict out;
  std::vector<std::vector<Index>> members(static_cast<std::size_t>(mesh.n_regions()));
  for (Index t = 0; t < mesh.n_tets(); ++t)
    members[static_cast<std::size_t>(mesh.region(t))].push_back(t);
  for (int r = 0; r < mesh.n_regions(); ++r) {
    const std::string name =
        mesh.region_names.empty() ? "body" : mesh.region_names[static_cast<std::size_t>(r)];
    out[py::str(name)] =
        py::array_t<Index>(static_cast<py::ssize_t>(members[r].size()), members[r].data());
  }
  return out;
}

}  // namespace

py::array tet_rows(const mesh::TetMesh& mesh, py::handle owner) {
  if (mesh.order() == 1) return rows_view(mesh.tets, owner);
  py::array_t<Index> rows(
      {static_cast<py::ssize_t>(mesh.n_tets()), static_cast<py::ssize_t>(mesh.nodes_per_tet())});
  auto r = rows.mutable_unchecked<2>();
  for (Index t = 0; t < mesh.n_tets(); ++t)
    for (int a = 0; a < mesh.nodes_per_tet(); ++a)
      r(t, a) = mesh.tet_node(t, a);
  py::detail::array_proxy(rows.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return rows;
}

void bind_mesh(py::module_& m) {
  py::class_<PyMesh>(m, "Mesh", R"(A tetrahedral mesh from arrays, checked as a mesh file is.

Mesh(points, tets, boundary, regions=None)
  points    (n, 3) float: node coordinates [m]
  tets      (m, 4) int: 0-based node indices of linear tetrahedra, positively oriented (a
            float array only of whole numbers); or (m, 10): quadratic tetrahedra, the corners
            (positively oriented), then the nodes of the edges 01, 12, 20, 30, 32, 31 (Gmsh's
            order; meshio's "tetra10" has the last two swapped, Mesh.from_meshio swaps them back)
  boundary  {name: (k, 3) int}: tagged boundary triangles (faces of the tetrahedra, any
            orientation), the names [[dirichlet]], [[traction]] and [contact] refer to; on
            quadratic tetrahedra (k, 3) (the corners: the edge nodes are the tetrahedra's) or
            (k, 6) (the corners, then the edges 01, 12, 20; checked against the tetrahedra's)
  regions   {name: 1-D int}: the tetrahedra of each region ([[material]] region = name);
            None: one region "body"
Raises fricon.InputError for inverted or degenerate tetrahedra, indices out of range, unused
nodes, triangles that are no face of a tetrahedron, quadratic tetrahedra that do not conform
(two nodes on one edge), fractional indices, a tag without triangles, ...)")
      .def(py::init(&make_mesh), py::arg("points"), py::arg("tets"),
           py::arg("boundary") = std::map<std::string, py::array>{},
           py::arg("regions") = py::none())
      .def_static(
          "brick",
          [](std::array<Real, 3> size, std::array<Index, 3> cells) {
            mesh::BrickSpec spec;
            spec.size = Vec3(size[0], size[1], size[2]);
            spec.cells = cells;
            return PyMesh{std::make_shared<const mesh::TetMesh>(mesh::make_brick(spec))};
          },
          py::arg("size") = std::array<Real, 3>{3.0, 1.0, 1.0},
          py::arg("cells") = std::array<Index, 3>{12, 4, 4},
          "The mesh of [mesh] kind = \"brick\" (the paper's generator), as a Mesh.")
      .def_property_readonly(
          "points",
          [](py::object self) { return rows_view(self.cast<PyMesh&>().mesh->nodes, self); },
          "(n, 3) node coordinates [m] (read-only view)")
      .def_property_readonly(
          "tets", [](py::object self) { return tet_rows(*self.cast<PyMesh&>().mesh, self); },
          "(m, 4) node indices (read-only view), or (m, 10) of a quadratic mesh (corners, then "
          "edges 01, 12, 20, 30, 32, 31; a read-only copy)")
      .def_property_readonly(
          "boundary", [](const PyMesh& p) { return boundary_of(*p.mesh); },
          "{name: (k, 3) triangles}, oriented outward; (k, 6) of a quadratic mesh (corners, then "
          "edges 01, 12, 20)")
      .def_property_readonly(
          "order", [](const PyMesh& p) { return p.mesh->order(); },
          "1: linear (4-node) tetrahedra; 2: quadratic (10-node)")
      .def_property_readonly(
          "regions", [](const PyMesh& p) { return regions_of(*p.mesh); },
          "{name: tetrahedron indices}")
      .def_property_readonly("n_nodes", [](const PyMesh& p) { return p.mesh->n_nodes(); })
      .def_property_readonly("n_tets", [](const PyMesh& p) { return p.mesh->n_tets(); })
      .def("__repr__", [](const PyMesh& p) {
        return fmt::format("fricon.Mesh({} nodes, {} {}tetrahedra, boundary: {})",
                           p.mesh->n_nodes(), p.mesh->n_tets(),
                           p.mesh->order() > 1 ? "quadratic " : "", p.mesh->tag_list());
      });
}

}  // namespace fricon::python
