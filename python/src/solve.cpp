// fricon.solve's engine: the run on a worker thread while the interpreter's thread waits without
// the GIL, calls the progress callback with each outer iteration and checks for Ctrl-C; and the
// Result with its arrays as numpy views of the run's own memory. Several solves may run at once
// from several Python threads: what the library keeps per process (Gmsh's state, the BLAS thread
// count) is guarded there (gmsh_file.hpp, linalg::RunThreads); docs/python.md, "Threads".

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/io/results.hpp"
#include "fricon/linalg/blas.hpp"
#include "fricon/solve.hpp"

namespace fricon::python {

namespace {

/// How often the waiting thread looks for Ctrl-C and progress [ms].
constexpr auto kPollInterval = std::chrono::milliseconds(20);

struct PyResult {
  std::shared_ptr<const driver::Problem> problem;
  std::shared_ptr<const driver::RunResult> run;
  io::RunContext context;
  /// Along a loading path: the files of the steps that [output] step_files_every / step_files
  /// choose, kept in memory for write() (io::step_files_wanted).
  std::shared_ptr<const std::vector<io::StepFiles>> step_files;
};

/// A table of the results as {column: numpy array} (text columns as arrays of str).
py::dict table_dict(const io::Table& table) {
  py::dict out;
  for (const auto& c : table.columns) {
    if (c.text.empty())
      out[py::str(c.name)] = py::array_t<Real>(c.values.size(), c.values.data());
    else
      out[py::str(c.name)] = py::module_::import("numpy").attr("array")(py::cast(c.text));
  }
  return out;
}

/// What the worker thread hands to the interpreter's thread, and back.
struct Exchange {
  std::mutex mutex;
  std::condition_variable changed;  ///< the worker -> the interpreter: reports, or done
  std::condition_variable handled;  ///< the interpreter -> the worker: steps handled, or gone
  std::deque<driver::IterationReport> iterations;
  std::deque<driver::StepReport> steps;
  std::size_t steps_handed = 0;   ///< steps the worker has handed over
  std::size_t steps_handled = 0;  ///< steps the interpreter has handled (on_step returned)
  bool interpreter_gone = false;  ///< the interpreter no longer handles steps: do not wait
  bool done = false;
};

/// The worker's side of on_step: hands the step over and, when the user watches the steps,
/// waits until the interpreter has called on_step with it (or will not), so that the callback
/// sees step k before step k + 1 starts and a stop it asks for ends the path at step k.
void hand_over_step(Exchange& exchange, const driver::StepReport& step, bool wait) {
  std::unique_lock lock(exchange.mutex);
  exchange.steps.push_back(step);
  const std::size_t mine = ++exchange.steps_handed;
  exchange.changed.notify_one();
  if (wait)
    exchange.handled.wait(
        lock, [&] { return exchange.steps_handled >= mine || exchange.interpreter_gone; });
}

/// The worker thread of a solve, joined however the interpreter's side ends (also by an
/// exception): it is asked to stop and released from any wait first.
class Worker {
 public:
  Worker(Exchange& exchange, std::atomic<bool>& stop) : exchange_(exchange), stop_(stop) {}
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;
  ~Worker() { join(); }

  template <typename F>
  void start(F&& body) {
    const py::gil_scoped_release release;
    thread_ = std::thread(std::forward<F>(body));
  }

  /// Waits (without the GIL) for the run to end; after an early exit of the interpreter's
  /// loop, stops it first.
  void join() {
    if (!thread_.joinable()) return;
    {
      const std::lock_guard lock(exchange_.mutex);
      if (!exchange_.done) stop_ = true;
      exchange_.interpreter_gone = true;
      exchange_.handled.notify_all();
    }
    if (PyGILState_Check() != 0) {
      const py::gil_scoped_release release;
      thread_.join();
    } else {
      thread_.join();
    }
  }

 private:
  Exchange& exchange_;
  std::atomic<bool>& stop_;
  std::thread thread_;
};

PyResult solve(const PyProblem& p, const py::object& progress, std::optional<int> threads,
               const py::object& on_step) {
  Exchange exchange;
  std::atomic<bool> stop{false};
  driver::RunOptions options;
  options.stop_requested = &stop;
  options.on_outer_iteration = [&exchange](const driver::IterationReport& it) {
    const std::lock_guard lock(exchange.mutex);
    exchange.iterations.push_back(it);
    exchange.changed.notify_one();
  };
  const bool watch_steps = !on_step.is_none();
  auto step_files = std::make_shared<std::vector<io::StepFiles>>();
  options.on_step = [&exchange, watch_steps, step_files,
                     problem = p.problem](const driver::RunResult& r) {
    const int step = r.report.steps.back().step;
    if (io::step_files_wanted(problem->output, step, problem->loading.steps))
      if (std::optional<io::StepFiles> files = io::step_files(r))
        step_files->push_back(std::move(*files));
    hand_over_step(exchange, r.report.steps.back(), watch_steps);
  };
  std::optional<driver::RunResult> result;
  std::exception_ptr failure;
  const driver::Problem& problem = *p.problem;

  Worker worker(exchange, stop);
  worker.start([&] {
    try {
      // The BLAS threads are the process's: set by the first of concurrent solves, shared by
      // the others (linalg::RunThreads; docs/python.md, "Threads").
      const linalg::RunThreads blas_threads(threads.value_or(0));
      result.emplace(fricon::solve(problem, options));
    } catch (...) {
      failure = std::current_exception();
    }
    const std::lock_guard lock(exchange.mutex);
    exchange.done = true;
    exchange.changed.notify_one();
  });

  // The interpreter's side: progress, on_step, Ctrl-C (KeyboardInterrupt) and the callbacks'
  // own errors stop the run (at its next QP step, or after the step on_step was called with);
  // the first such Python error is raised once it has ended. Any Python code may raise (also
  // the conversion of a step to a dict, where a pending Ctrl-C is delivered): each is caught.
  std::optional<py::error_already_set> python_error;
  const auto python_failed = [&](py::error_already_set& e) {
    if (!python_error) python_error.emplace(std::move(e));
    stop = true;
  };
  for (bool done = false; !done;) {
    std::deque<driver::IterationReport> iterations;
    std::deque<driver::StepReport> steps;
    {
      const py::gil_scoped_release release;
      std::unique_lock lock(exchange.mutex);
      exchange.changed.wait_for(lock, kPollInterval, [&] {
        return exchange.done || !exchange.iterations.empty() || !exchange.steps.empty();
      });
      iterations.swap(exchange.iterations);
      steps.swap(exchange.steps);
      done = exchange.done;
    }
    for (const auto& it : iterations) {
      if (progress.is_none() || python_error) break;
      try {
        progress(py::cast(it));
      } catch (py::error_already_set& e) {
        python_failed(e);
      }
    }
    for (const auto& s : steps) {
      if (watch_steps && !python_error) {
        try {
          on_step(to_python(io::step_json(problem, s).dump()));
        } catch (py::error_already_set& e) {
          python_failed(e);
        }
      }
      // Step handled: the worker may start the next one (or, after an error, stop).
      const std::lock_guard lock(exchange.mutex);
      ++exchange.steps_handled;
      exchange.handled.notify_all();
    }
    if (!python_error && PyErr_CheckSignals() != 0) {
      python_error.emplace();  // fetches the KeyboardInterrupt
      stop = true;
    }
  }
  worker.join();
  if (python_error && result) {
    // What was done before the stop (along a loading path, the steps done) goes with the
    // exception: `except KeyboardInterrupt as e: e.result`.
    PyResult partial{p.problem, std::make_shared<const driver::RunResult>(std::move(*result)),
                     io::RunContext{p.edits, "python: fricon.solve"}, step_files};
    py::setattr(python_error->value(), "result", py::cast(std::move(partial)));
  }
  if (python_error) throw std::move(*python_error);
  if (failure) std::rethrow_exception(failure);
  return PyResult{p.problem, std::make_shared<const driver::RunResult>(std::move(*result)),
                  io::RunContext{p.edits, "python: fricon.solve"}, step_files};
}

/// Whether this process holds the run's result: every one but a rank other than 0 of backend
/// "petsc" under mpirun, which served rank 0's solves (its status is rank 0's).
bool holds_result(const PyResult& r) {
  return !r.run->report.parallel || r.run->report.parallel->rank == 0;
}

/// The run's result where this process holds it (holds_result); elsewhere throws Error, so that
/// nothing hollow is read or written.
const driver::RunResult& held(const PyResult& r) {
  const auto& parallel = r.run->report.parallel;
  if (!holds_result(r))
    throw Error(fmt::format(
        "this is rank {} of {} of a backend \"petsc\" run under mpirun: the ranks other than 0 "
        "serve rank 0's solves and hold no result (only `converged` and `message`); read and "
        "write it on rank 0 (docs/python.md, \"Under mpirun\")",
        parallel->rank, parallel->n_ranks));
  return *r.run;
}

std::string report_text(const PyResult& r) {
  return io::report_json(*r.problem, held(r), r.context).dump();
}

}  // namespace

void bind_solve(py::module_& m) {
  py::class_<driver::IterationReport>(m, "OuterIteration",
                                      "One outer iteration, as the progress callback receives it.")
      .def_readonly("k", &driver::IterationReport::k)
      .def_readonly("err", &driver::IterationReport::err,
                    "||phi^k - phi^(k-1)|| / ||phi^k|| (docs/theory.md §5.2)")
      .def_readonly("qp_iterations", &driver::IterationReport::qp_iterations)
      .def_readonly("qp_products", &driver::IterationReport::qp_products,
                    "products with Q in this QP")
      .def_readonly("qp_rel_gp", &driver::IterationReport::qp_rel_gp, "final ||g^P|| / ||h||")
      .def_readonly("seconds", &driver::IterationReport::seconds)
      .def("__repr__", [](const driver::IterationReport& it) {
        return fmt::format("OuterIteration(k={}, err={:.3e}, qp_iterations={}, qp_products={})",
                           it.k, it.err, it.qp_iterations, it.qp_products);
      });

  py::class_<PyResult>(m, "Result", "The outcome of fricon.solve (the files of `fricon solve`).")
      .def_property_readonly(
          "converged",
          [](const PyResult& r) { return r.run->report.status == driver::RunStatus::Converged; },
          "False when the run did not converge or its certificate failed (exit code 2)")
      .def_property_readonly(
          "message", [](const PyResult& r) { return r.run->report.message; },
          "why the run did not converge (empty when it did)")
      .def_property_readonly(
          "report", [](const PyResult& r) { return to_python(report_text(r)); },
          "the content of report.json, as a dict")
      .def_property_readonly(
          "points",
          [](py::object self) {
            return rows_view(held(self.cast<PyResult&>()).model.mesh.nodes, self);
          },
          "(n, 3) node coordinates [m]")
      .def_property_readonly(
          "tets",
          [](py::object self) { return tet_rows(held(self.cast<PyResult&>()).model.mesh, self); },
          "(m, 4) node indices, or (m, 10) of a quadratic mesh (corners, then edges 01, 12, 20, "
          "30, 32, 31)")
      .def_property_readonly(
          "displacement",
          [](py::object self) {
            return rows_view(held(self.cast<PyResult&>()).displacement, self);
          },
          "(n, 3) displacement [m]")
      .def_property_readonly(
          "stress",
          [](py::object self) { return rows_view(held(self.cast<PyResult&>()).stress, self); },
          "(m, 6) stress per tetrahedron [Pa], Voigt order 11, 22, 33, 23, 13, 12")
      .def_property_readonly(
          "von_mises",
          [](py::object self) { return vector_view(held(self.cast<PyResult&>()).von_mises, self); },
          "(m,) von Mises stress per tetrahedron [Pa]")
      .def_property_readonly(
          "subdomain",
          [](const PyResult& r) -> py::object {
            const auto& feti = held(r).report.feti;
            if (!feti) return py::none();
            return py::array_t<Index>(static_cast<py::ssize_t>(feti->subdomain_of_tet.size()),
                                      feti->subdomain_of_tet.data());
          },
          "(m,) the subdomain of each tetrahedron with backend \"tfeti\" (solution.vtu's "
          "\"subdomain\"), None with the other backends")
      .def_property_readonly(
          "contact_nodes",
          [](const PyResult& r) -> py::object {
            if (!held(r).contact) return py::none();
            return table_dict(io::contact_node_table(held(r).model.mesh, *held(r).contact));
          },
          "the columns of contact_nodes.csv as numpy arrays (None without contact)")
      .def_property_readonly(
          "patches",
          [](const PyResult& r) -> py::object {
            if (!held(r).contact) return py::none();
            return table_dict(io::patch_table(*held(r).contact));
          },
          "the columns of patches.csv as numpy arrays (None without contact)")
      .def_property_readonly(
          "steps",
          [](const PyResult& r) -> py::object {
            if (held(r).report.steps.empty()) return py::none();
            return table_dict(io::steps_table(*r.problem, held(r).report));
          },
          "the columns of steps.csv as numpy arrays: one row per step of a loading path "
          "([loading] steps > 1; None for a static run)")
      .def(
          "write",
          [](const PyResult& r, const std::string& dir) {
            // As `fricon solve`: the folder checked and cleared of an earlier run's results,
            // per-step files and figures; then the chosen steps' files and the results.
            const driver::RunResult& run = held(r);
            io::prepare_results(dir);
            std::vector<std::string> written;
            std::vector<int> steps;
            for (const io::StepFiles& files : *r.step_files) {
              for (const auto& path :
                   io::write_step_files(dir, files, r.problem->output.vtu_encoding))
                written.push_back(path.string());
              steps.push_back(files.step);
            }
            for (const auto& path : io::write_results(dir, *r.problem, run, r.context, steps))
              written.push_back(path.string());
            return written;
          },
          py::arg("dir"),
          "Writes the files of `fricon solve` into dir (atomically; marked .not-converged when "
          "the run did not converge), after removing an earlier run's results, step files and "
          "figures there; along a loading path also the files of the steps that [output] "
          "step_files_every / step_files choose (steps/). Returns their paths. Raises OSError "
          "when dir is not a writable folder (or a file cannot be written), fricon.InputError "
          "for an empty path, RuntimeError on a rank that holds no result (backend \"petsc\" "
          "under mpirun, ranks other than 0).")
      .def("__repr__", [](const PyResult& r) {
        if (!holds_result(r))
          return fmt::format(
              "fricon.Result({}, rank {} of {}: the result is rank 0's)",
              r.run->report.status == driver::RunStatus::Converged ? "converged" : "NOT converged",
              r.run->report.parallel->rank, r.run->report.parallel->n_ranks);
        return fmt::format(
            "fricon.Result({}, {} nodes{})",
            r.run->report.status == driver::RunStatus::Converged ? "converged" : "NOT converged",
            r.run->report.n_nodes,
            r.run->report.contact
                ? fmt::format(", {} outer iterations", r.run->report.contact->outer_iterations)
                : "");
      });

  m.def("_solve", &solve, py::arg("problem"), py::arg("progress") = py::none(),
        py::arg("threads") = py::none(), py::arg("on_step") = py::none());
}

}  // namespace fricon::python
