#pragma once
// The Python module _fricon (python/fricon/__init__.py wraps it): the library's problem reader,
// meshes from arrays, the run and its results, with nothing re-implemented. Each part binds
// itself into the module.

#include <memory>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "fricon/contact/friction_law.hpp"
#include "fricon/driver/problem.hpp"
#include "fricon/mesh/tet_mesh.hpp"

namespace fricon::python {

namespace py = pybind11;

/// A Mesh object of the module: a checked mesh, shared with the problems that use it.
struct PyMesh {
  std::shared_ptr<const mesh::TetMesh> mesh;
};

/// A validated problem (what the reader returns) and the edits it was read with, for the report.
struct PyProblem {
  std::shared_ptr<const driver::Problem> problem;
  std::vector<std::string> edits;  ///< the overrides, "KEY=VALUE"
};

/// A Python callable as the library's FrictionFunction: called with the GIL taken, on a 1-D
/// float64 array of slips [m]; its result (a sequence of as many numbers, or one number) is
/// copied out. The callable is held so that copies of the function need no GIL.
contact::FrictionFunction friction_function(py::function F);

/// JSON (nlohmann) as Python objects (dict, list, float, ...).
py::object to_python(const std::string& json_text);

/// A read-only numpy view of a column-major Eigen matrix (Rows x n) as a row-major (n x Rows)
/// array, without a copy; `owner` (the Python object holding the matrix) is kept alive by it.
template <typename Scalar, int Rows>
py::array rows_view(const Eigen::Matrix<Scalar, Rows, Eigen::Dynamic>& m, py::handle owner) {
  py::array a(py::dtype::of<Scalar>(), {m.cols(), static_cast<Index>(m.rows())},
              {static_cast<Index>(sizeof(Scalar) * m.rows()), static_cast<Index>(sizeof(Scalar))},
              m.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

/// As rows_view, for a vector (a 1-D array).
inline py::array vector_view(const VectorXd& v, py::handle owner) {
  py::array a(py::dtype::of<Real>(), {v.size()}, {static_cast<Index>(sizeof(Real))}, v.data(),
              owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

/// The tetrahedra of `mesh` as an (m, nodes per tetrahedron) array: every node, the corners then
/// the edge nodes of a quadratic mesh (TetMesh::tet_node; theory.md §2.12). Read-only: a view
/// of mesh.tets kept alive by `owner` for a linear mesh, a copy for a quadratic one.
py::array tet_rows(const mesh::TetMesh& mesh, py::handle owner);

void bind_mesh(py::module_& m);
void bind_solve(py::module_& m);

}  // namespace fricon::python
