#include "generate/standin.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>

#include "generate/positions.hpp"
#include "io/atomic_file.hpp"
#include "io/numbers.hpp"
#include "observe/simulate.hpp"
#include "scene/csv.hpp"
#include "scene/load.hpp"
#include "solve/integrate.hpp"

namespace asperity {

namespace {

// Apparent contact radius at load P: Hertz, a ∝ P^(1/3).
double contact_radius(const StandinRecipe& r, double P) {
  return r.contact_radius_m * std::cbrt(P / r.contact_reference_load_N);
}

const auto fmt = io::format_printf;

std::string g6(double x) { return fmt("%.6g", x); }

std::string u64(std::uint64_t x) { return std::to_string(x); }

std::string solver_text(const SolverSettings& s) {
  if (s.method == SolverMethod::reference) return "reference solver, Ct = " + g6(s.Ct);
  return "event solver, tolerance = " + g6(s.tolerance);
}

double drop_target(const StandinRecipe& r, double P) {
  const double P_lo = r.masses_kg.front() * r.gravity, P_hi = r.masses_kg.back() * r.gravity;
  if (r.masses_kg.size() < 2) return r.drop_smallest;
  return r.drop_smallest + (r.drop_largest - r.drop_smallest) * (P - P_lo) / (P_hi - P_lo);
}

std::filesystem::path abs_norm(const std::filesystem::path& p) {
  return std::filesystem::absolute(p).lexically_normal();
}

}  // namespace

std::string standin_name(double P) { return fmt("P%.2fN", P); }

Scene generation_scene(const StandinRecipe& r, const Experiment& e) {
  Scene s;
  s.experiment = e;
  s.model = ModelSettings{};  // the paper's parameters
  s.model.alpha_b = r.alpha_b;
  s.solver = r.solver;
  s.stop.time = r.run_stop_time;
  s.stop.at_first_peak = true;
  s.stop.cycles = -1;
  s.output.every = r.run_every;
  s.output.series.clear();  // the loading branch is kept anyway
  s.output.peak_min_drop = r.run_peak_min_drop;
  return s;
}

MeasuredCurve standin_measured_curve(double A0, double Q_s, double alpha_exp, int points, double noise_relative,
                                     std::uint64_t seed) {
  if (points < 2) throw std::invalid_argument("standin_measured_curve: need at least 2 points");
  Uniform01 u(seed);
  MeasuredCurve c;
  c.Q_N.reserve(static_cast<std::size_t>(points));
  c.A_m2.reserve(static_cast<std::size_t>(points));
  for (int j = 0; j < points; ++j) {
    // Q_j = Q_s j/(points−1), exactly Q_s at the last point.
    const double Q = j + 1 == points ? Q_s : Q_s * static_cast<double>(j) / static_cast<double>(points - 1);
    const double z = normal_quantile(u());
    c.Q_N.push_back(Q);
    c.A_m2.push_back(A0 - alpha_exp * Q * Q + A0 * noise_relative * z);
  }
  return c;
}

MeasuredForce standin_measured_force(const std::vector<Sample>& series, double t_end, double Q_s, double noise_relative,
                                     std::uint64_t seed) {
  Uniform01 u(seed);
  MeasuredForce f;
  for (const Sample& s : series) {
    if (s.t > t_end) break;
    if (!f.t_s.empty() && !(s.t > f.t_s.back())) continue;  // one value per instant
    f.t_s.push_back(s.t);
    f.Q_N.push_back(s.Q + Q_s * noise_relative * normal_quantile(u()));
  }
  return f;
}

StandinExperiment build_standin(const StandinRecipe& r, std::size_t i) {
  StandinExperiment x;
  const double M = r.masses_kg.at(i);
  x.P = M * r.gravity;
  const auto N = static_cast<std::size_t>(std::llround(r.junctions_per_newton * x.P));
  if (N == 0) throw std::invalid_argument("stand-in " + standin_name(x.P) + ": no junctions (N = 0)");
  x.area_seed = experiment_seed(r, i);
  x.noise_seed = noise_seed(x.area_seed);

  Experiment& e = x.experiment;
  e.name = standin_name(x.P);
  e.mass_kg = M;
  e.k_L = r.k_L;
  e.v = r.v;
  e.E = r.E;
  e.nu = r.nu;
  e.sigma_exp = r.sigma_exp;
  e.junctions = draw_population(r.distribution, N, x.area_seed, r.square_side_m);
  if (r.contact_radius_m > 0) {  // a stream of its own: areas and noise do not change
    const Positions p = place_in_contact_disc(e.junctions.area_m2, contact_radius(r, x.P), positions_seed(x.area_seed));
    e.junctions.x_m = p.x_m;
    e.junctions.y_m = p.y_m;
  }

  const Scene scene = generation_scene(r, e);
  {
    Scene s = scene;
    s.solver.Ct = 1e4;
    x.dt_Ct1e4 = initial_info(s).dt;
  }
  const RunResult run = simulate(scene);
  x.model = run.obs;
  const double A0 = x.model.A0, Q_s = x.model.Q_s;
  if (!(Q_s > 0.0) || !std::isfinite(Q_s))
    throw std::runtime_error("stand-in " + e.name + ": the model run gave no positive Q_s");
  x.area_drop_target = drop_target(r, x.P);
  x.alpha_exp = x.area_drop_target * A0 / (Q_s * Q_s);
  e.measured = standin_measured_curve(A0, Q_s, x.alpha_exp, r.points, r.noise_relative, x.noise_seed);
  if (r.force_every > 0) {  // the model's own Q(t) through the peak and the stick-slip after it
    Scene s = scene;
    x.force_t_end = x.model.t_peak * (1.0 + r.force_after_peak);
    s.stop.at_first_peak = false;
    s.stop.time = x.force_t_end;
    s.output.every = r.force_every;
    s.output.series = {"t", "Q"};
    const RunResult qrun = simulate(s);
    x.force_seed = force_seed(x.area_seed);
    x.force = standin_measured_force(qrun.recorder.series(), x.force_t_end, Q_s, r.force_noise_relative, x.force_seed);
    x.force_header = {
        "STAND-IN, NOT A MEASUREMENT: \"measured\" Q(t) of the stand-in experiment " + e.name +
            ", generated by `asperity generate` from " + r.file.filename().string() + " (experiment " +
            std::to_string(i) + ").",
        "Model: the paper's parameters (eta = 100 1/s, epsilon = 0.9, c_min = 0.01, p = 1.5, elliptic, Eq. 3 until "
        "first slip), "
        "alpha_b = " +
            g6(r.alpha_b) + " m^5/N^2, " + solver_text(r.solver) + ", the run of measured.csv continued past its peak.",
        "Samples: every " + g6(r.force_every) + " s from t = 0 to t_peak * (1 + " + g6(r.force_after_peak) +
            ") = " + g6(x.force_t_end) + " s (model t_peak = " + g6(x.model.t_peak) + " s, Q_s = " + g6(Q_s) + " N); " +
            std::to_string(x.force.t_s.size()) + " rows.",
        "Noise: Q = Q_model(t) + Q_s * " + g6(r.force_noise_relative) +
            " * z, z Gaussian (normal quantile of uniforms from "
            "std::mt19937_64(force seed)), force seed = splitmix64(area seed XOR 0x666f726365) = " +
            u64(x.force_seed) + ".",
        "Columns: t_s [s], Q_N [N]. Regenerate, never edit: asperity generate --recipe data/standin/" +
            r.file.filename().string() + " --out data/standin --scenes scenes/paper"};
  }

  const std::string recipe_name = r.file.filename().string();
  e.description =
      "STAND-IN, NOT A MEASUREMENT: generated by `asperity generate` from " + recipe_name + " (experiment " +
      std::to_string(i) + "). Junctions: " + std::to_string(N) + " areas drawn from " + r.distribution.describe() +
      " (area seed " + u64(x.area_seed) + ")" +
      (r.square_side_m > 0 ? ", positions uniform in a square of side L = " + g6(r.square_side_m) + " m" : "") +
      (r.contact_radius_m > 0
           ? ", centres without overlap in a contact disc of radius " + g6(contact_radius(r, x.P)) +
                 " m with Hertz density sqrt(1 - r^2/R^2) (positions seed " + u64(positions_seed(x.area_seed)) + ")"
           : "") +
      ". Measured curve: A = A0 - alpha_exp Q^2 for Q from 0 to the model's Q_s = " + g6(Q_s) +
      " N (paper parameters, alpha_b = " + g6(r.alpha_b) + ", " + solver_text(r.solver) +
      (x.model.peak_found ? ", first peak" : ", highest Q, no confirmed peak") + "), alpha_exp = " + g6(x.alpha_exp) +
      " m^2/N^2 for an area drop of " + fmt("%.4g", 100 * x.area_drop_target) + " % at Q_s, plus Gaussian noise of " +
      g6(100 * r.noise_relative) + " % of A0 (noise seed " + u64(x.noise_seed) + "). See README.md.";
  return x;
}

std::string standin_scene_yaml(const StandinRecipe& r, const StandinExperiment& x, const std::string& rel) {
  auto num = [](double v) { return io::format_double(v); };
  std::string y;
  y += "# Paper parameters (docs/model.md §2) on the stand-in experiment " + x.experiment.name + ".\n";
  y += "# STAND-IN data, not a measurement (see data/standin/README.md).\n";
  y += "# Written by `asperity generate --scenes`; regenerate rather than edit.\n";
  y += "experiment: " + rel + "\n";
  y += model_solver_yaml(ModelSettings{}, SolverSettings{});
  y += "stop:\n";
  y += "  time: " + num(r.scene_stop_time) + "\n";
  y += "output:\n";
  y += "  every: " + num(r.scene_every) + "\n";
  return y;
}

std::string standin_readme(const StandinRecipe& r, const std::vector<StandinExperiment>& xs) {
  const std::string recipe_name = r.file.filename().string();
  std::string t;
  t += "# Stand-in experiments — NOT measurements\n\n";
  t += "Every experiment in this folder is a **stand-in** generated by `asperity generate` from\n";
  t += "`" + recipe_name + "`. None of it was measured: the segmented junction lists and A(Q) curves\n";
  t += "of Scheibert, Sahli & Peyrard (2020) are not public. The stand-ins follow the published\n";
  t += "constraints (docs/model.md §2 and §7) and use the same file format as real lab data\n";
  t += "(`experiment.yaml`, `junctions.csv`, `measured.csv`), which can replace them folder for folder.\n\n";
  t += "This file is written by the generator. Do not edit the generated files by hand: change\n";
  t += "`" + recipe_name + "` and regenerate. Regenerating gives the same bytes:\n\n";
  t += "    asperity generate --recipe data/standin/" + recipe_name + " --out data/standin --scenes scenes/paper\n\n";
  t += "## How they are built\n\n";
  t += "For each slider mass M of the recipe (experiment i = 0, 1, ... in recipe order):\n\n";
  t += "1. Normal load P = M g with g = " + g6(r.gravity) + " m/s²; the folder is named `P<P, 2 decimals>N`.\n";
  t += "2. N = round(" + g6(r.junctions_per_newton) +
       " · P) junctions. Areas are drawn from: " + r.distribution.describe() + ".\n";
  t += "   Each area is the inverse CDF of a uniform in (0, 1) built from the top 53 bits of\n";
  t += "   `std::mt19937_64(area seed)` (a mixture uses one uniform to pick the component and the next\n";
  t += "   one for the area); no standard-library distribution is involved.\n";
  t += "   area seed = splitmix64(" + u64(r.seed) + " + i).\n";
  if (r.square_side_m > 0)
    t += "   Positions x_m, y_m: uniform in a square of side L = " + g6(r.square_side_m) +
         " m, drawn from the same stream after all areas.\n";
  if (r.contact_radius_m > 0)
    t += "   Positions x_m, y_m: centres of non-overlapping discs (radius sqrt(A0/π)) in an apparent contact\n"
         "   disc of radius R = " +
         g6(r.contact_radius_m) + " m · (P / " + g6(r.contact_reference_load_N) +
         " N)^(1/3) (Hertz), with a density ∝ sqrt(1 − r²/R²) (the Hertz pressure: more asperities touch\n"
         "   where it is higher); random sequential addition, largest first, from\n"
         "   `std::mt19937_64(positions seed)`, positions seed = splitmix64(area seed XOR 0x706f736974696f6e).\n"
         "   ASSUMED: the paper gives no apparent contact size; R is a recipe parameter (and a study axis).\n";
  t += "3. The model is run on the experiment at the paper's parameters (eta = 100 1/s, epsilon = 0.9,\n";
  t += "   c_min = 0.01, p = 1.5, elliptic junctions, Eq. 3 until first slip) with alpha_b = " + g6(r.alpha_b) +
       " m⁵/N²,\n";
  t += "   " + solver_text(r.solver) + ", stopping at the first confirmed peak of Q (drop ≥ " +
       g6(100 * r.run_peak_min_drop) + " %) or at t = " + g6(r.run_stop_time) + " s.\n";
  t += "   Q_s is that first peak (or the highest Q seen when no peak is confirmed).\n";
  t += "4. `measured.csv`: " + std::to_string(r.points) +
       " values of Q equally spaced on [0, Q_s], A = A0 − alpha_exp Q² + noise, with A0 = Σ A0_i and\n";
  t += "   alpha_exp = drop · A0 / Q_s², the area drop at Q_s rising linearly in P from " + g6(100 * r.drop_smallest) +
       " % at the smallest load\n";
  t += "   to " + g6(100 * r.drop_largest) + " % at the largest. Noise: Gaussian, standard deviation " +
       g6(100 * r.noise_relative) + " % of A0, normal quantile of uniforms\n";
  t += "   from `std::mt19937_64(noise seed)`, noise seed = splitmix64(area seed XOR 0x6e6f697365).\n";
  if (r.force_every > 0) {
    t += "4b. `measured_Qt.csv` (a STAND-IN \"measured\" Q(t)): the run of step 3 continued past its peak to\n";
    t += "   t_end = t_peak · (1 + " + g6(r.force_after_peak) + "), Q(t) sampled every " + g6(r.force_every) +
         " s, plus Gaussian noise of standard deviation " + g6(100 * r.force_noise_relative) + " % of Q_s,\n";
    t += "   normal quantile of uniforms from `std::mt19937_64(force seed)`, force seed = splitmix64(area seed XOR "
         "0x666f726365).\n";
    t += "   Unlike measured.csv (a prescribed parabola), it is the model's own Q(t) at the paper's parameters, so a "
         "fit of\n";
    t += "   (alpha_b, epsilon, eta) to it alone would return those; its header gives them. `experiment.yaml` does not "
         "name\n";
    t += "   it (scene texts and store hashes stay as they were); a fit names it per experiment (`force:`, objective\n";
    t += "   `area_and_force`, docs/calibration.md).\n";
    if (r.force_after_peak >= 1.0)  // the recipe's comment: past the interacting model's peak
      t += "   The window reaches past the independent model's peak so that it holds the interacting model's first "
           "peak\n"
           "   too (1.7-2.0 times later, results/interactions/REPORT.md); after its own peak it therefore holds the\n"
           "   independent model's stick-slip cycles: intended, a model without them misses that part of Q(t).\n";
  }
  t += "5. `experiment.yaml`: k_L = " + g6(r.k_L) + " N/m, v = " + g6(r.v) + " m/s, E = " + g6(r.E) +
       " Pa, nu = " + g6(r.nu) + ", sigma_exp = " + g6(r.sigma_exp) + " Pa,\n";
  t += "   and a `description` saying all of the above.\n\n";
  t += "## The stand-ins\n\n";
  t += "dt is the reference step T0/C_t at C_t = 1e4 (paper parameters). \"Model\" columns come from\n";
  t += "the run of step 3; \"drop\" is 1 − A/A0 at Q_s.\n\n";
  t += "| experiment | M [kg] | P [N] | N | Σ A0 [mm²] | dt [µs] | area seed | noise seed | model Q_s [N] "
       "| model t_peak [s] | peak confirmed | model drop | measured drop | alpha_exp [m²/N²] |\n";
  t += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& x : xs) {
    t += "| " + x.experiment.name + " | " + g6(x.experiment.mass_kg) + " | " + fmt("%.4f", x.P) + " | " +
         std::to_string(x.experiment.junctions.size()) + " | " + fmt("%.4f", x.model.A0 * 1e6) + " | " +
         fmt("%.4f", x.dt_Ct1e4 * 1e6) + " | " + u64(x.area_seed) + " | " + u64(x.noise_seed) + " | " +
         fmt("%.4f", x.model.Q_s) + " | " + fmt("%.4f", x.model.t_peak) + " | " + (x.model.peak_found ? "yes" : "no") +
         " | " + fmt("%.1f %%", 100 * x.model.area_drop_fraction) + " | " + fmt("%.1f %%", 100 * x.area_drop_target) +
         " | " + fmt("%.4g", x.alpha_exp) + " |\n";
  }
  if (r.force_every > 0) {
    t += "\nStand-in Q(t) (`measured_Qt.csv`):\n\n";
    t += "| experiment | t_end [s] | samples | force seed |\n|---|---|---|---|\n";
    for (const auto& x : xs)
      t += "| " + x.experiment.name + " | " + fmt("%.4f", x.force_t_end) + " | " + std::to_string(x.force.t_s.size()) +
           " | " + u64(x.force_seed) + " |\n";
  }
  t += "\nScenes running the paper's model on these stand-ins: `scenes/paper/P*.yaml`.\n";
  return t;
}

std::vector<StandinExperiment> build_standins(const StandinRecipe& r, std::ostream* log) {
  std::vector<StandinExperiment> xs;
  for (std::size_t i = 0; i < r.masses_kg.size(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    StandinExperiment x = build_standin(r, i);
    if (log) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      *log << x.experiment.name << ": N = " << x.experiment.junctions.size()
           << ", A0 = " << fmt("%.4f", x.model.A0 * 1e6) << " mm^2, dt(Ct=1e4) = " << fmt("%.4f", x.dt_Ct1e4 * 1e6)
           << " us, Q_s = " << fmt("%.4f", x.model.Q_s) << " N"
           << (x.model.peak_found ? "" : " (no confirmed peak: highest Q)") << ", model drop "
           << fmt("%.1f", 100 * x.model.area_drop_fraction) << " %, measured drop "
           << fmt("%.1f", 100 * x.area_drop_target) << " %  [" << fmt("%.2f", wall) << " s]\n";
    }
    xs.push_back(std::move(x));
  }
  return xs;
}

void write_standin_experiments(const StandinRecipe& r, const std::vector<StandinExperiment>& xs,
                               const std::filesystem::path& out_dir) {
  namespace fs = std::filesystem;
  for (const StandinExperiment& x : xs) {
    const fs::path dir = out_dir / x.experiment.name;
    fs::create_directories(dir);
    write_junctions_csv(dir / "junctions.csv", x.experiment.junctions);
    write_measured_csv(dir / "measured.csv", *x.experiment.measured);
    if (!x.force.t_s.empty()) write_force_csv(dir / "measured_Qt.csv", x.force, x.force_header);
    io::write_text_file(dir / "experiment.yaml", experiment_to_yaml(x.experiment, "junctions.csv", "measured.csv"));
  }
  io::write_text_file(out_dir / "README.md", standin_readme(r, xs));
}

void write_standin_scenes(const StandinRecipe& r, const std::vector<StandinExperiment>& xs,
                          const std::filesystem::path& scenes_dir, const std::filesystem::path& scenes_final,
                          const std::filesystem::path& experiments_final) {
  std::filesystem::create_directories(scenes_dir);
  for (const StandinExperiment& x : xs) {
    const std::string rel = abs_norm(experiments_final / x.experiment.name / "experiment.yaml")
                                .lexically_relative(abs_norm(scenes_final))
                                .generic_string();
    io::write_text_file(scenes_dir / (x.experiment.name + ".yaml"), standin_scene_yaml(r, x, rel));
  }
}

std::vector<StandinExperiment> generate_standins(const StandinRecipe& r, const GenerateOptions& opt) {
  std::vector<StandinExperiment> xs = build_standins(r, opt.log);
  write_standin_experiments(r, xs, opt.out_dir);
  if (!opt.scenes_dir.empty()) write_standin_scenes(r, xs, opt.scenes_dir, opt.scenes_dir, opt.out_dir);
  return xs;
}

}  // namespace asperity
