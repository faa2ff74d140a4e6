// The module _fricon: exceptions, the problem reader, and the parts bound in arrays.cpp and
// solve.cpp. python/fricon/__init__.py is the user's interface on top.

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "fricon/core/error.hpp"
#include "fricon/io/problem_file.hpp"

namespace fricon::python {

py::object to_python(const std::string& json_text) {
  return py::module_::import("json").attr("loads")(json_text);
}

contact::FrictionFunction friction_function(py::function F) {
  // Copies of a py::function touch its reference count, which needs the GIL; a shared_ptr's do
  // not, and its deleter takes the GIL for the last release.
  const std::shared_ptr<py::function> held(new py::function(std::move(F)), [](py::function* f) {
    const py::gil_scoped_acquire gil;
    delete f;
  });
  return [held](std::span<const Real> t, std::span<Real> out) {
    const py::gil_scoped_acquire gil;
    const py::array_t<Real> slips(static_cast<py::ssize_t>(t.size()), t.data());
    const py::object value = (*held)(slips);
    const auto values = py::array_t<Real, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!values)
      throw InputError("contact.friction: the function law's F returned no array of numbers");
    if (values.ndim() == 0) {
      std::fill(out.begin(), out.end(), *values.data());
      return;
    }
    if (values.ndim() != 1 || static_cast<std::size_t>(values.size()) != t.size())
      throw InputError(fmt::format(
          "contact.friction: the function law's F returned {} values for {} slips (it takes a "
          "1-D array of slips t [m] and returns F(t) of the same length)",
          values.size(), t.size()));
    std::copy(values.data(), values.data() + values.size(), out.begin());
  };
}

namespace {

PyProblem parse(const std::string& text, const std::string& source,
                const std::vector<std::string>& edits, const std::string& origin,
                const std::optional<PyMesh>& mesh, const py::object& friction,
                const std::string& friction_name) {
  io::ReadOptions options;
  options.overrides = edits;
  options.override_origin = origin;
  if (mesh) options.code.mesh = mesh->mesh;
  if (!friction.is_none()) {
    options.code.friction = friction_function(friction.cast<py::function>());
    options.code.friction_name = friction_name;
  }
  return PyProblem{
      std::make_shared<const driver::Problem>(io::parse_problem(text, source, options)), edits};
}

}  // namespace

}  // namespace fricon::python

PYBIND11_MODULE(_fricon, m) {
  namespace py = pybind11;
  using namespace fricon::python;
  m.doc() = "fricon's library (the fricon package wraps it)";
  m.attr("__version__") = FRICON_VERSION;

  static py::exception<fricon::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<fricon::NumericalError> numerical_error(m, "NumericalError",
                                                               PyExc_ArithmeticError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const fricon::InputError& e) {
      input_error(e.what());
    } catch (const fricon::NumericalError& e) {
      numerical_error(e.what());
    } catch (const fricon::Interrupted& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const fricon::OutputError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });

  py::class_<PyProblem>(m, "_Problem", "A validated problem, as the library holds it.")
      .def("to_dict",
           [](const PyProblem& p) { return to_python(fricon::io::to_json(*p.problem).dump()); })
      .def("to_toml", [](const PyProblem& p) { return fricon::io::to_toml(*p.problem); })
      .def_property_readonly("source", [](const PyProblem& p) { return p.problem->source; })
      .def_property_readonly(
          "contact_key",
          [](const PyProblem& p) {
            return p.problem->contact.size() == 1 ? p.problem->contact_key(0)
                                                  : std::string("contact");
          },
          "the key path of a problem's one contact pair: \"contact\", or \"contact[0]\" when "
          "the file wrote it as [[contact]]")
      .def_property_readonly("edits", [](const PyProblem& p) { return p.edits; });

  m.def("_parse", &parse, py::arg("text"), py::arg("source"), py::arg("edits"), py::arg("origin"),
        py::arg("mesh"), py::arg("friction"), py::arg("friction_name"),
        "Reads a problem file's text with overrides \"KEY=VALUE\" (as --set), validates it.");
  m.def("_read_text", &fricon::io::read_problem_text, py::arg("path"));

  bind_mesh(m);
  bind_solve(m);
}
