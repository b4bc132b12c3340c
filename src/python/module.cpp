// The compiled part of the Python package `asperity` (src/python/asperity/__init__.py is the
// public face): scenes, runs, sweeps and fits through the same library calls as the command
// line. The GIL is released while the engine works; a single run polls Python's signal handlers
// (RunMonitor), a sweep or a fit runs on a worker thread while the caller polls them (interruptible),
// so Ctrl-C interrupts any of them as KeyboardInterrupt within a fraction of a second. Arguments
// are checked as the command line checks its options (io/arguments.hpp), with the same message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "campaign/campaign_load.hpp"
#include "campaign/store.hpp"
#include "campaign/sweep.hpp"
#include "fit/fit_inputs.hpp"
#include "fit/fit_journal.hpp"
#include "fit/fit_load.hpp"
#include "io/arguments.hpp"
#include "io/input_error.hpp"
#include "io/provenance.hpp"
#include "io/temp_files.hpp"
#include "observe/simulate.hpp"
#include "report/fit_writer.hpp"
#include "report/run_writer.hpp"
#include "scene/load.hpp"

namespace py = pybind11;
using namespace asperity;

namespace {

// Observables as a dict, keyed and typed by the one table of fields.
py::dict summary_dict(const Observables& o) {
  py::dict d;
  for (const ObservableField& f : observable_fields()) {
    switch (f.kind) {
      case ObservableKind::real: d[f.name] = f.value(o); break;
      case ObservableKind::count: d[f.name] = static_cast<long long>(f.value(o)); break;
      case ObservableKind::flag: d[f.name] = f.value(o) != 0; break;
      case ObservableKind::label: d[f.name] = std::string(f.label(o)); break;
    }
  }
  return d;
}

py::array_t<double> column(const std::vector<Sample>& s, double Sample::*field) {
  py::array_t<double> a(static_cast<py::ssize_t>(s.size()));
  auto m = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < s.size(); ++i) m(static_cast<py::ssize_t>(i)) = s[i].*field;
  return a;
}

py::array_t<long long> count_column(const std::vector<Sample>& s, std::int64_t Sample::*field) {
  py::array_t<long long> a(static_cast<py::ssize_t>(s.size()));
  auto m = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < s.size(); ++i) m(static_cast<py::ssize_t>(i)) = s[i].*field;
  return a;
}

// Runs the scene with the GIL released; every period the monitor takes the GIL and lets Python
// run its signal handlers (a pending KeyboardInterrupt stops the run).
py::dict run_scene(const Scene& scene) {
  RunMonitor monitor;
  monitor.period_s = 0.1;
  monitor.poll = [](double, double) {
    py::gil_scoped_acquire gil;
    return PyErr_CheckSignals() == 0;
  };
  RunResult r = [&] {
    py::gil_scoped_release release;
    return simulate(scene, 0, &monitor);
  }();
  const std::vector<Sample>& s = r.recorder.series();
  py::dict series;
  series["t"] = column(s, &Sample::t);
  series["X"] = column(s, &Sample::X);
  series["V"] = column(s, &Sample::V);
  series["Q"] = column(s, &Sample::Q);
  series["A"] = column(s, &Sample::A);
  series["n_slipping"] = count_column(s, &Sample::n_slipping);
  series["n_intact"] = count_column(s, &Sample::n_intact);
  py::list peaks;
  for (const Peak& p : r.recorder.peaks()) {
    py::dict d;
    d["t_max"] = p.max.t, d["Q_max"] = p.max.Q, d["A_max"] = p.max.A;
    d["t_min"] = p.min.t, d["Q_min"] = p.min.Q, d["A_min"] = p.min.A;
    peaks.append(d);
  }
  py::dict out;
  out["summary"] = summary_dict(r.obs);
  out["series"] = series;
  out["peaks"] = peaks;
  out["summary_yaml"] = summary_yaml(scene, r.obs, r.recorder.peaks(), "python: asperity.run");
  return out;
}

// A thread count as the command line's --threads: a Python int (None: `fallback`), 1 to 1024,
// else InputError naming `argument` (an int of any size: 10**30 is refused, not overflowed).
int threads_argument(const py::object& value, const char* argument, int fallback) {
  if (value.is_none()) return fallback;
  if (!PyLong_Check(value.ptr()) || PyBool_Check(value.ptr()))
    throw py::type_error(std::string(argument) + ": an int from 1 to " + std::to_string(kMaxThreads) + " (or None)");
  return checked_threads(std::string(py::str(value)), argument);
}

// Runs `work` (engine only: it never touches Python) on a worker thread, the GIL released, while
// the calling thread takes the GIL every 0.1 s to run Python's signal handlers. When a handler
// raises (Ctrl-C: KeyboardInterrupt), `stop` tells the engine, which stops within a fraction of a
// second keeping what it journaled; then the handler's exception is raised (the engine's
// RunInterrupted, or a result finished meanwhile, gives way to it). Handlers run only in the
// main thread: called from another, the work runs to its end as before.
template <class F>
auto interruptible(std::atomic<bool>& stop, F work) -> decltype(work()) {
  std::packaged_task<decltype(work())()> task(std::move(work));
  auto result = task.get_future();
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    std::jthread worker(std::move(task));
    while (!interrupted && result.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
      py::gil_scoped_acquire gil;
      interrupted = PyErr_CheckSignals() != 0;  // the handler's exception stays set while we wait
    }
    stop = interrupted;
  }  // joins the worker
  if (interrupted) throw py::error_already_set();
  return result.get();  // the engine's exception, if any
}

}  // namespace

PYBIND11_MODULE(_asperity, m) {
  m.doc() = "asperity engine (compiled part; use the `asperity` package)";
  // One-line messages `file:line: key: message`, as the command line prints them.
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<SolverError> solver_error(m, "SolverError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    } catch (const SolverError& e) {
      PyErr_SetString(solver_error.ptr(), e.what());
    } catch (const RunInterrupted&) {
      // Python's own handler raised (KeyboardInterrupt); if it did not, say what happened.
      if (!PyErr_Occurred()) PyErr_SetString(PyExc_KeyboardInterrupt, "run interrupted");
    }
  });

  py::class_<Scene>(m, "Scene", "A fully resolved scene (asperity.load_scene)")
      .def_property_readonly("file", [](const Scene& s) { return s.file.string(); })
      .def_property_readonly("experiment", [](const Scene& s) { return s.experiment.name; })
      .def_property_readonly("junctions", [](const Scene& s) { return s.experiment.junctions.size(); })
      .def_property_readonly("stand_in", [](const Scene& s) {
        std::string d = s.experiment.description;
        for (char& c : d) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return d.find("stand-in") != std::string::npos;
      })
      .def("to_yaml", [](const Scene& s) { return scene_to_yaml(s); }, "The scene as `asperity run` writes scene.yaml")
      .def("__repr__", [](const Scene& s) {
        return "<asperity.Scene " + s.experiment.name + ", " + std::to_string(s.experiment.junctions.size()) +
               " junctions, from " + s.file.string() + ">";
      });

  m.def("check_no_nul", &check_no_nul, py::arg("text"), py::arg("argument"),
        "InputError naming `argument` when `text` holds a NUL byte (which every system call would cut)");
  m.def("load_scene", [](const std::string& path, const std::vector<std::string>& overrides) {
    check_no_nul(path, "path");
    for (const std::string& o : overrides) check_no_nul(o, "overrides");
    return load_scene(path, overrides);
  }, py::arg("path"), py::arg("overrides") = std::vector<std::string>{});
  m.def("run", &run_scene, py::arg("scene"));
  m.def("measured", [](const Scene& s) -> py::object {
    if (!s.experiment.measured) return py::none();
    py::dict d;
    d["Q"] = py::array_t<double>(static_cast<py::ssize_t>(s.experiment.measured->Q_N.size()), s.experiment.measured->Q_N.data());
    d["A"] = py::array_t<double>(static_cast<py::ssize_t>(s.experiment.measured->A_m2.size()), s.experiment.measured->A_m2.data());
    return d;
  }, py::arg("scene"));

  m.def("sweep", [](const std::string& campaign, const std::string& out, const py::object& threads, const std::string& shard) {
    check_no_nul(campaign, "campaign");
    check_no_nul(out, "out");
    SweepOptions o;
    o.threads = threads_argument(threads, "threads", 0);  // 0: every hardware thread
    const Campaign c = load_campaign(campaign);
    o.out = out;
    try {
      o.shard = parse_shard(shard, [](const char* n) { return std::getenv(n); }, "shard");
    } catch (const std::invalid_argument& e) {  // as the command line's --shard
      throw InputError("", 0, "shard", e.what());
    }
    o.quiet = true;
    o.command_line = "python: asperity.sweep(" + campaign + ")";
    std::atomic<bool> stop{false};
    o.stop = &stop;
    const SweepReport r = interruptible(stop, [&] { return run_sweep(c, o); });
    py::dict d;
    d["store"] = r.store.string();
    d["points"] = r.points, d["skipped"] = r.skipped, d["changed"] = r.changed, d["ran"] = r.ran;
    d["ok"] = r.ok, d["failed"] = r.failed, d["wall_s"] = r.wall_s;
    return d;
  }, py::arg("campaign"), py::arg("out") = "", py::arg("threads") = py::none(), py::arg("shard") = "0/1");

  m.def("fit", [](const std::string& fit_file, const std::string& out, const py::object& threads, bool profile, bool error_bars) {
    check_no_nul(fit_file, "fit_file");
    check_no_nul(out, "out");
    FitOptions fo;
    fo.threads = threads_argument(threads, "threads", hardware_threads());
    const FitSpec spec = load_fit(fit_file);
    // With `out`, as `asperity fit --out`: the folder is claimed first and every evaluation is
    // journaled there as it finishes, so a fit stopped by Ctrl-C (or killed) resumes when run
    // again into the same folder (by Python or by the command line: the same inputs.txt).
    FitJournal journal;
    std::unique_ptr<DirLock> lock;
    if (!out.empty()) {
      claim_fit_dir(out);
      lock = lock_fit_journal_dir(out, "out");
      remove_stale_temporaries(out);  // of a fit that died while writing
      open_fit_journal(journal, out, fit_inputs_text(spec, {}, code_build_id(), Shard{}));
      fo.journal = &journal;
    }
    fo.profile = profile;
    fo.error_bars = error_bars;
    std::atomic<bool> stop{false};
    fo.stop = &stop;
    const FitResult result = interruptible(stop, [&] {
      FitResult r = run_fit(spec, fo);
      if (!out.empty()) write_fit(out, spec, r, "python: asperity.fit(" + fit_file + ")");
      return r;
    });
    py::list fits;
    for (const Optimization& o : result.fits) {
      py::dict d, best;
      for (std::size_t k = 0; k < o.variables.size(); ++k)
        best[py::str(o.variables[k].label)] = k < o.best.size() ? o.best[k] : std::nan("");
      d["label"] = o.label;
      d["best"] = best;
      d["objective"] = o.objective;
      d["evaluations"] = o.evaluations;
      d["stop_reason"] = o.stop_reason;
      d["failure"] = o.failure;
      py::dict runs;
      for (const ExperimentRun& r : o.best_runs) runs[py::str(spec.experiments[r.experiment].name)] = summary_dict(r.obs);
      d["runs"] = runs;
      fits.append(d);
    }
    py::dict d;
    d["name"] = spec.name;
    d["fits"] = fits;
    d["wall_s"] = result.wall_s;
    d["replayed"] = result.replayed, d["computed"] = result.computed;  // evaluations from the journal, run now
    d["fit_yaml"] = fit_yaml(spec, result, "python: asperity.fit(" + fit_file + ")");
    return d;
  }, py::arg("fit_file"), py::arg("out") = "", py::arg("threads") = py::int_(2), py::arg("profile") = true,
     py::arg("error_bars") = true);

  m.def("store_series", [](const std::string& store, const std::vector<std::uint64_t>& indices) {
    check_no_nul(store, "path");  // asperity.read_series(path, index)
    std::map<std::uint64_t, std::string> texts;
    {
      py::gil_scoped_release release;
      texts = read_point_series(store, indices);
    }
    return texts;
  }, py::arg("store"), py::arg("indices"));

  m.def("version", [] { return version_line(); });
}
