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

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <mutex>
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
#include "io/numbers.hpp"
#include "io/provenance.hpp"
#include "io/temp_files.hpp"
#include "observe/simulate.hpp"
#include "python/campaign_in_store.hpp"
#include "python/scene_from_dict.hpp"
#include "python/topography_bindings.hpp"
#include "report/fit_writer.hpp"
#include "report/gnuplot.hpp"
#include "report/run_writer.hpp"
#include "report/units.hpp"
#include "scene/load.hpp"
#include "scene/scene_keys.hpp"

namespace py = pybind11;
using namespace asperity;

namespace {

// Observables as a dict, keyed and typed by the one table of fields.
py::dict summary_dict(const Observables& o) {
  py::dict d;
  for (const ObservableField& f : observable_fields()) {
    switch (f.kind) {
      case ObservableKind::real:
        d[f.name] = f.value(o);
        break;
      case ObservableKind::count:
        d[f.name] = static_cast<long long>(f.value(o));
        break;
      case ObservableKind::flag:
        d[f.name] = f.value(o) != 0;
        break;
      case ObservableKind::label:
        d[f.name] = std::string(f.label(o));
        break;
    }
  }
  return d;
}

// An optimization's profiles: one dict per profiled parameter, its points as NumPy arrays.
py::list profiles_list(const FitSpec& spec, const Optimization& o) {
  py::list out;
  for (const ParameterProfile& pp : o.profiles) {
    py::dict d;
    d["parameter"] = spec.parameters.at(pp.parameter).key;
    std::vector<double> factor, value, objective;
    for (const ProfilePoint& q : pp.points)
      factor.push_back(q.factor), value.push_back(q.value), objective.push_back(q.objective);
    d["factor"] = py::array_t<double>(static_cast<py::ssize_t>(factor.size()), factor.data());
    d["value"] = py::array_t<double>(static_cast<py::ssize_t>(value.size()), value.data());
    d["objective"] = py::array_t<double>(static_cast<py::ssize_t>(objective.size()), objective.data());
    d["interval"] = py::make_tuple(pp.lo, pp.hi);
    d["parabola_sigma"] = pp.parabola_sigma;
    out.append(d);
  }
  return out;
}

// An optimization's statistical uncertainty (fit.hpp, Uncertainty, Bootstrap): sigma per free variable.
py::dict uncertainty_dict(const Optimization& o) {
  const Uncertainty& u = o.uncertainty;
  py::dict d, sigma;
  d["computed"] = u.computed;
  d["failure"] = u.failure;
  d["residuals"] = u.residuals;
  d["reduced_chi2"] = u.reduced_chi2;
  for (std::size_t k = 0; k < o.variables.size() && k < u.sigma.size(); ++k)
    sigma[py::str(o.variables[k].label)] = u.sigma[k];
  d["sigma"] = sigma;
  py::dict boot;  // the parametric bootstrap's (FitSpec::bootstrap_draws): empty without one
  for (std::size_t k = 0; k < o.variables.size() && k < o.bootstrap.sigma.size(); ++k)
    boot[py::str(o.variables[k].label)] = o.bootstrap.sigma[k];
  d["bootstrap_sigma"] = boot;
  d["bootstrap_failure"] = o.bootstrap.failure;
  return d;
}

// The folder a spec given as a dict reads its relative paths against: `base=`, else the working directory.
std::filesystem::path base_dir(const py::object& base) {
  if (base.is_none()) return std::filesystem::current_path();
  const std::string b = py::str(base);
  io::check_no_nul(b, "base");
  return b;
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

// The sampled series as {column: NumPy array}.
py::dict series_dict(const std::vector<Sample>& s) {
  py::dict series;
  series["t"] = column(s, &Sample::t);
  series["X"] = column(s, &Sample::X);
  series["V"] = column(s, &Sample::V);
  series["Q"] = column(s, &Sample::Q);
  series["A"] = column(s, &Sample::A);
  series["n_slipping"] = count_column(s, &Sample::n_slipping);
  series["n_intact"] = count_column(s, &Sample::n_intact);
  return series;
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
  const py::dict series = series_dict(r.recorder.series());
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
    throw py::type_error(std::string(argument) + ": an int from 1 to " + std::to_string(io::kMaxThreads) +
                         " (or None)");
  return io::checked_threads(std::string(py::str(value)), argument);
}

// Runs `work` (engine only: it never touches Python) on a worker thread, the GIL released, while
// the calling thread takes the GIL every 0.1 s to run Python's signal handlers. When a handler
// raises (Ctrl-C: KeyboardInterrupt), `stop` tells the engine, which stops within a fraction of a
// second keeping what it journaled; then the handler's exception is raised (the engine's
// RunInterrupted, or a result finished meanwhile, gives way to it). Handlers run only in the
// main thread: called from another, the work runs to its end as before.
// `tick` (may be empty; called with the GIL at every poll and once at the end) draws progress; an
// exception it raises stops the work as Ctrl-C does and is raised.
template <class F>
auto interruptible(std::atomic<bool>& stop, F work, const std::function<void()>& tick = {}) -> decltype(work()) {
  std::packaged_task<decltype(work())()> task(std::move(work));
  auto result = task.get_future();
  bool interrupted = false;
  std::exception_ptr tick_error;
  {
    py::gil_scoped_release release;
    std::jthread worker(std::move(task));
    while (!interrupted && result.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
      py::gil_scoped_acquire gil;
      interrupted = PyErr_CheckSignals() != 0;  // the handler's exception stays set while we wait
      if (!interrupted && tick) try {
          tick();
        } catch (...) {
          tick_error = std::current_exception();
          interrupted = true;
        }
    }
    stop = interrupted;
  }  // joins the worker
  if (tick_error) std::rethrow_exception(tick_error);
  if (interrupted) throw py::error_already_set();
  if (tick) tick();     // the last count
  return result.get();  // the engine's exception, if any
}

// A progress tick calling Python's `progress(finished, total)` (total 0: unknown); none for None.
std::function<void()> progress_tick(const py::object& progress,
                                    const std::function<std::pair<long long, long long>()>& counts) {
  if (progress.is_none()) return {};
  return [progress, counts] {
    const auto [done, total] = counts();
    progress(done, total);
  };
}

}  // namespace

PYBIND11_MODULE(_asperity, m) {
  m.doc() = "asperity engine (compiled part; use the `asperity` package)";
  // One-line messages `file:line: key: message`, as the command line prints them.
  static py::exception<io::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<SolverError> solver_error(m, "SolverError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::InputError& e) {
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
      .def_property_readonly("stand_in", [](const Scene& s) { return is_stand_in(s.experiment); })
      .def(
          "to_yaml", [](const Scene& s) { return scene_to_yaml(s); },
          "The scene as `asperity run` writes scene.yaml (junctions inline when it has no experiment file); "
          "Scene.from_yaml of it, or asperity.load_scene of it saved, gives the same scene")
      .def_static(
          "from_dict", &python::scene_from_dict, py::arg("d"), py::arg("areas") = py::none(), py::arg("x") = py::none(),
          py::arg("y") = py::none(), py::arg("measured") = py::none(),
          "A scene from a dict shaped as a scene file, checked as one; the experiment a map of its values with "
          "junction `areas` [m²] and optional centres `x`, `y` [m] (NumPy arrays, lists, or a pandas DataFrame "
          "with columns area_m2, x_m, y_m as `areas`), optional `measured` A(Q) (a DataFrame or dict with Q_N [N], "
          "A_m2 [m²]); or the experiment a path as in a scene file")
      .def_static(
          "from_yaml",
          [](const std::string& text) -> Scene {
            const std::string where = "Scene.from_yaml";
            return scene_from_memory(io::load_yaml_document(text, where), std::filesystem::current_path(), where);
          },
          py::arg("text"), "A scene from scene-file text (paths relative to the working directory)")
      .def("__repr__", [](const Scene& s) {
        return "<asperity.Scene " + s.experiment.name + ", " + std::to_string(s.experiment.junctions.size()) +
               " junctions, from " + (s.file.empty() ? std::string("memory") : s.file.string()) + ">";
      });

  m.def("check_no_nul", &io::check_no_nul, py::arg("text"), py::arg("argument"),
        "InputError naming `argument` when `text` holds a NUL byte (which every system call would cut)");
  m.def(
      "load_scene",
      [](const std::string& path, const std::vector<std::string>& overrides) {
        io::check_no_nul(path, "path");
        for (const std::string& o : overrides) io::check_no_nul(o, "overrides");
        return load_scene(path, overrides, "overrides:");
      },
      py::arg("path"), py::arg("overrides") = std::vector<std::string>{});
  m.def("run", &run_scene, py::arg("scene"));
  asperity::python::bind_topography(m);  // generate_junctions, tangential_contact (topography_bindings.cpp)
  m.def(
      "measured",
      [](const Scene& s) -> py::object {
        if (!s.experiment.measured) return py::none();
        py::dict d;
        d["Q"] = py::array_t<double>(static_cast<py::ssize_t>(s.experiment.measured->Q_N.size()),
                                     s.experiment.measured->Q_N.data());
        d["A"] = py::array_t<double>(static_cast<py::ssize_t>(s.experiment.measured->A_m2.size()),
                                     s.experiment.measured->A_m2.data());
        return d;
      },
      py::arg("scene"));

  m.def(
      "sweep",
      [](const py::object& campaign_arg, const std::string& out, const py::object& threads, const std::string& shard,
         const py::object& progress, const py::object& base) {
        io::check_no_nul(out, "out");
        std::string campaign;  // the campaign file (a dict's: written into the store, campaign_in_store.hpp)
        if (py::isinstance<py::dict>(campaign_arg)) {
          campaign = python::campaign_into_store(python::yaml_node(campaign_arg, ""), base_dir(base), out).string();
        } else {
          if (!base.is_none())
            throw io::InputError("", 0, "base", "is for a dict campaign; a file's paths are relative to the file");
          campaign = py::str(campaign_arg);
          io::check_no_nul(campaign, "campaign");
        }
        SweepOptions o;
        o.threads = threads_argument(threads, "threads", 0);  // 0: every hardware thread
        const Campaign c = load_campaign(campaign);
        o.out = out;
        try {
          o.shard = io::parse_shard(
              shard, [](const char* n) { return std::getenv(n); }, "shard");
        } catch (const std::invalid_argument& e) {  // as the command line's --shard
          throw io::InputError("", 0, "shard", e.what());
        }
        o.quiet = true;
        o.command_line = "python: asperity.sweep(" + campaign + ")";
        std::atomic<bool> stop{false};
        o.stop = &stop;
        SweepCounters counters;
        o.counters = &counters;
        const SweepReport r = interruptible(
            stop, [&] { return run_sweep(c, o); }, progress_tick(progress, [&] {
              return std::pair<long long, long long>(counters.finished.load(), counters.total.load());
            }));
        py::dict d;
        d["store"] = r.store.string();
        d["points"] = r.points, d["skipped"] = r.skipped, d["changed"] = r.changed, d["ran"] = r.ran;
        d["ok"] = r.ok, d["failed"] = r.failed, d["wall_s"] = r.wall_s;
        return d;
      },
      py::arg("campaign"), py::arg("out") = "", py::arg("threads") = py::none(), py::arg("shard") = "0/1",
      py::arg("progress") = py::none(), py::arg("base") = py::none());

  m.def(
      "fit",
      [](const py::object& fit_spec, const std::string& out, const py::object& threads, bool profile, bool error_bars,
         const py::object& progress, const py::object& objective, bool series, const py::object& base,
         const std::string& objective_id) {
        io::check_no_nul(out, "out");
        FitOptions fo;
        fo.threads = threads_argument(threads, "threads", io::hardware_threads());
        // A Python objective: `objective(summary, series)` (series None unless asked; __init__.py
        // wraps the user's callable) gives each experiment's term; the spec's `objective` key is
        // then absent. Journaled under `objective_id` (__init__.py: a digest of the callable's source),
        // so that an edited callable does not resume a journal it did not compute.
        FitLoadOptions lo;
        if (!objective.is_none()) {
          if (!out.empty() && objective_id.empty())
            throw io::InputError("", 0, "out",
                                 "a fit with a Python objective is journaled only under an identity of the callable");
          lo.user_objective = true;
          lo.user_series = series;
          lo.user_objective_name = "the Python callable given as objective=";
        } else if (series) {
          throw io::InputError("", 0, "series", "passes the series to a Python objective; give objective= too");
        }
        std::string what;  // the spec, as the provenance's command line names it
        FitSpec spec;
        if (py::isinstance<py::dict>(fit_spec)) {
          spec = fit_from_memory(python::yaml_node(fit_spec, ""), base_dir(base), "asperity.fit", {}, lo);
          what = "dict";
        } else {
          if (!base.is_none())
            throw io::InputError("", 0, "base", "is for a dict spec; a fit file's paths are relative to the file");
          what = py::str(fit_spec);
          io::check_no_nul(what, "fit_file");
          spec = load_fit(what, {}, lo);
        }
        if (!objective.is_none()) spec.user_objective_id = objective_id;
        const std::string command_line = "python: asperity.fit(" + what + ")";
        // The user's objective is called from the fit's worker threads, each taking the GIL; its first
        // exception stops the fit as Ctrl-C does and is raised here.
        std::mutex user_mutex;
        std::exception_ptr user_error;
        std::atomic<bool> stop{false};
        if (!objective.is_none()) {
          fo.user_term = [&, series](const FitExperiment& fe, const Scene&, const RunResult& r) -> double {
            py::gil_scoped_acquire gil;
            try {
              py::dict summary = summary_dict(r.obs);
              summary["experiment"] = fe.name;
              const py::object columns = series ? py::object(series_dict(r.recorder.series())) : py::object(py::none());
              return objective(summary, columns).cast<double>();
            } catch (...) {
              {
                const std::lock_guard<std::mutex> lock(user_mutex);
                if (!user_error) user_error = std::current_exception();
              }
              stop = true;
              throw RunInterrupted("the Python objective raised");
            }
          };
        }
        // With `out`, as `asperity fit --out`: the folder is claimed first and every evaluation is
        // journaled there as it finishes, so a fit stopped by Ctrl-C (or killed) resumes when run
        // again into the same folder (by Python or by the command line: the same inputs.txt).
        FitJournal journal;
        std::unique_ptr<io::DirLock> lock;
        if (!out.empty()) {
          claim_fit_dir(out);
          lock = lock_fit_journal_dir(out, "out");
          io::remove_stale_temporaries(out);  // of a fit that died while writing
          open_fit_journal(journal, out, fit_inputs_text(spec, {}, io::code_build_id(), io::Shard{}));
          fo.journal = &journal;
        }
        fo.profile = profile;
        fo.error_bars = error_bars;
        fo.stop = &stop;
        // Every evaluation the fit makes (profiles and refits too) against the most it can make; a
        // finished optimization adds what it left unused, so the count ends at the total.
        const long long budget = fit_run_budget(spec, fo);
        std::atomic<long long> evaluations{0};
        fo.on_evaluation = [&](const FitTick& t) { evaluations += t.counted(); };
        FitResult result;
        try {
          result = interruptible(
              stop,
              [&] {
                FitResult r = run_fit(spec, fo);
                if (!out.empty()) write_fit(out, spec, r, command_line);
                return r;
              },
              progress_tick(progress, [&] { return std::pair<long long, long long>(evaluations.load(), budget); }));
        } catch (const RunInterrupted&) {
          if (user_error) std::rethrow_exception(user_error);  // the objective's own exception
          throw;
        }
        if (user_error) std::rethrow_exception(user_error);
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
          d["converged"] = converged_name(o.converged);  // fit/convergence.hpp: yes, no, unverified
          d["starts"] = o.starts.size();
          d["in_best_basin"] = o.in_best_basin;
          d["spread"] = o.spread;
          py::dict runs;
          for (const ExperimentRun& r : o.best_runs)
            runs[py::str(spec.experiments[r.experiment].name)] = summary_dict(r.obs);
          d["runs"] = runs;
          d["profiles"] = profiles_list(spec, o);
          d["uncertainty"] = uncertainty_dict(o);
          fits.append(d);
        }
        py::dict d;
        d["name"] = spec.name;
        d["fits"] = fits;
        d["wall_s"] = result.wall_s;
        d["replayed"] = result.replayed, d["computed"] = result.computed;  // evaluations from the journal, run now
        d["fit_yaml"] = fit_yaml(spec, result, command_line);
        return d;
      },
      py::arg("spec"), py::arg("out") = "", py::arg("threads") = py::none(), py::arg("profile") = true,
      py::arg("error_bars") = true, py::arg("progress") = py::none(), py::arg("objective") = py::none(),
      py::arg("series") = false, py::arg("base") = py::none(), py::arg("objective_id") = "");

  m.def(
      "store_series",
      [](const std::string& store, const std::vector<std::uint64_t>& indices) {
        io::check_no_nul(store, "path");  // asperity.read_series(path, index)
        std::map<std::uint64_t, std::string> texts;
        {
          py::gil_scoped_release release;
          texts = read_point_series(store, indices);
        }
        return texts;
      },
      py::arg("store"), py::arg("indices"));

  m.def("version", [] { return io::version_line(); });
  m.attr("__version__") = io::build_info().version;  // the number `asperity --version` prints

  // Units of every column a result holds, from the engine's tables (report/units.hpp): SI text,
  // "1" dimensionless, "" not a number (flags, names).
  m.def("units", [] {
    py::dict observables, series, keys;
    for (const ObservableField& f : observable_fields()) observables[f.name] = column_unit(f.name);
    for (const std::string& c : all_series()) series[py::str(c)] = series_unit(c);
    for (const SceneKey& k : scene_keys()) keys[k.name] = column_unit(k.name);
    py::dict d;
    d["observables"] = observables, d["series"] = series, d["scene_keys"] = keys;
    return d;
  });
  // A column's unit as the figures show it (report/units.hpp figure_unit: areas in mm²): the unit
  // text, its figure markup (gnuplot enhanced text, asperity.plot turns it into mathtext) and the
  // factor from the SI value.
  m.def("figure_unit", [](const std::string& column) {
    const FigureUnit u = figure_unit(column);
    py::dict d;
    d["unit"] = u.unit, d["markup"] = unit_markup(u.unit), d["scale"] = u.scale;
    return d;
  });
  m.attr("STAND_IN_MARK") = kStandInMark;  // the text every stand-in figure carries
}
