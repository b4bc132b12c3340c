#include "report/claims.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "observe/quadratic_fit.hpp"
#include "observe/simulate.hpp"

namespace asperity {

std::vector<ClaimVariant> paper_claim_variants() {
  std::vector<ClaimVariant> v;
  for (double eta : {0.0, 50.0, 150.0, 180.0, 200.0, 250.0}) {
    char label[32];
    std::snprintf(label, sizeof label, "eta=%g", eta);
    v.push_back({label, [eta](Scene& s) { s.model.eta = eta; }});
  }
  v.push_back({"c_min=1e-5", [](Scene& s) { s.model.c_min = 1e-5; }});
  v.push_back({"equal_areas", [](Scene& s) {
                 auto& a = s.experiment.junctions.area_m2;
                 double sum = 0;
                 for (double x : a) sum += x;
                 a.assign(a.size(), sum / static_cast<double>(a.size()));
                 s.experiment.junctions.x_m.clear();
                 s.experiment.junctions.y_m.clear();
                 s.experiment.measured.reset();
                 s.stop.at_first_peak = true;
               }});
  v.push_back({"circular", [](Scene& s) { s.model.junction_shape = JunctionShape::circular; }});
  v.push_back({"area_law=always", [](Scene& s) { s.model.area_law = AreaLaw::always; }});
  // Claim 7 needs the explicit solver, which measures f/(σA) at every junction and step; at
  // C_t = 100 it costs about a minute per simulated second here, so a window of the loading.
  v.push_back({"reference Ct=100, 0.25 s",
               [](Scene& s) {
                 s.solver.method = SolverMethod::reference;
                 s.solver.Ct = 100;
                 s.stop.time = 0.25;  // the first slips start near 0.19 s on the smallest stand-in
                 s.stop.cycles = -1;
                 s.output.series.clear();
               },
               false});
  return v;
}

std::vector<VariantRun> run_variants(const std::vector<Scene>& base, const std::vector<ClaimVariant>& variants,
                                     int threads) {
  struct Job { std::size_t scene, variant; };
  std::vector<Job> jobs;
  for (std::size_t v = 0; v < variants.size(); ++v)
    for (std::size_t s = 0; s < base.size(); ++s)
      if (variants[v].all_experiments || s == 0) jobs.push_back({s, v});
  // Longest first: the reference window dominates.
  std::stable_sort(jobs.begin(), jobs.end(), [&](const Job& a, const Job& b) {
    return !variants[a.variant].all_experiments && variants[b.variant].all_experiments;
  });
  std::vector<VariantRun> out(jobs.size());
  tbb::task_arena arena(std::max(1, threads));
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, jobs.size(), [&](std::size_t j) {
      Scene s = base[jobs[j].scene];
      const ClaimVariant& v = variants[jobs[j].variant];
      v.apply(s);
      s.output.series.clear();  // only observables are needed
      out[j].experiment = s.experiment.name;
      out[j].label = v.label;
      try {
        out[j].obs = simulate(s).obs;
      } catch (const std::exception& e) {
        out[j].error = e.what();
      }
    }, tbb::simple_partitioner());
  });
  return out;
}

namespace {

std::string fmt(const char* f, double x) {
  char b[64];
  std::snprintf(b, sizeof b, f, x);
  return b;
}
double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

const VariantRun* find(const std::vector<VariantRun>& v, const std::string& exp, const std::string& label) {
  for (const auto& r : v)
    if (r.experiment == exp && r.label == label && r.error.empty()) return &r;
  return nullptr;
}

// Least-squares slope dA/dQ [m²/N] over Q ∈ [0, frac·Q_max] (incipient loading).
double initial_slope(std::span<const double> Q, std::span<const double> A, double frac) {
  double qmax = 0;
  for (double q : Q) qmax = std::max(qmax, q);
  double sq = 0, sa = 0, sqq = 0, sqa = 0;
  int n = 0;
  for (std::size_t i = 0; i < Q.size(); ++i) {
    if (!(Q[i] <= frac * qmax)) continue;
    sq += Q[i]; sa += A[i]; sqq += Q[i] * Q[i]; sqa += Q[i] * A[i]; ++n;
  }
  if (n < 3) return std::nan("");
  return (n * sqa - sq * sa) / (n * sqq - sq * sq);
}

}  // namespace

std::string claims_report(const std::vector<PaperRun>& base, const std::vector<VariantRun>& variants,
                          const std::vector<CalibratedRun>& calibrated, const std::string& data_label) {
  std::ostringstream r;
  const bool standin = !data_label.empty();
  r << "# Reproduction report: the paper's claims (MODEL.md §6)\n\n";
  if (standin)
    r << "> **" << data_label << ".** Every number below comes from the project's stand-in experiments "
      << "(`data/standin/`), built from the paper's published constraints. They test the engine and the "
      << "method; they are not properties of the real experiments.\n\n";
  r << "Written by `asperity reproduce` (the main job, `scripts/reproduce.sh`). Base runs: the paper's "
       "parameters (MODEL.md §2), event solver at the scenes' tolerance, each through the first peak and "
       "five stick-slip cycles. Figures: `fig3_Q_A_t.png`, `fig4_A_Q.png`; numbers: `table.csv`. The "
       "quasi-linearity index is the exponent n of A0 − A = c Qⁿ fitted on the loading branch "
       "(n = 1 linear, n = 2 quadratic).\n\n";

  // 1. dt.
  r << "## 1. dt ≈ 1 µs at C_t = 1e4 for the mid loads\n\n| experiment | N | dt [µs] |\n|---|---:|---:|\n";
  bool c1 = true;
  for (std::size_t i = 0; i < base.size(); ++i) {
    const auto& o = base[i].obs;
    r << "| " << base[i].scene.experiment.name << " | " << o.N << " | " << fmt("%.3f", o.dt * 1e6) << " |\n";
    if (i > 0 && i + 1 < base.size()) c1 = c1 && o.dt > 0.7e-6 && o.dt < 1.4e-6;
  }
  r << "\n**" << (c1 ? "Reproduced" : "Not reproduced") << "** for the mid loads"
    << (standin ? " (by construction: the stand-ins were generated to satisfy it, so this is a check of the "
                  "generator, not evidence)" : "") << ".\n\n";

  // 2. Stick-slip at all loads.
  r << "## 2. Stick-slip at all six loads (ε = 0.9, η = 100)\n\n"
       "| experiment | cycles | mean drop [N] | drop / Q_s | mean period [s] |\n|---|---:|---:|---:|---:|\n";
  bool c2 = !base.empty();
  for (const auto& b : base) {
    const auto& o = b.obs;
    r << "| " << b.scene.experiment.name << " | " << o.ss_cycles << " | " << fmt("%.4g", o.ss_drop) << " | "
      << fmt("%.3f", o.ss_drop / o.Q_s) << " | " << fmt("%.4g", o.ss_period) << " |\n";
    c2 = c2 && o.ss_cycles > 0;
  }
  r << "\n**" << (c2 ? "Reproduced" : "Not reproduced") << "**: "
    << (c2 ? "every load shows stick-slip after the first peak." : "some load slides smoothly.")
    << (standin ? " The stand-in population was chosen to show it (README: stand-in search)." : "") << "\n\n";

  // 3. η.
  r << "## 3. η = 50 and 100 virtually identical; stick-slip vanishes for η ≳ 180–200\n\n";
  const std::vector<std::string> etas{"eta=0", "eta=50", "", "eta=150", "eta=180", "eta=200", "eta=250"};
  const double eta_val[] = {0, 50, 100, 150, 180, 200, 250};
  r << "Stick-slip cycles (mean drop / Q_s) per η:\n\n| experiment |";
  for (double e : eta_val) r << " η = " << e << " |";
  r << " η where it vanishes |\n|---|";
  for (std::size_t k = 0; k < etas.size(); ++k) r << "---:|";
  r << "---:|\n";
  double max_d50 = 0, max_d50_ss = 0;
  std::vector<double> vanish;
  for (const auto& b : base) {
    const std::string& name = b.scene.experiment.name;
    r << "| " << name << " |";
    double first_zero = std::nan("");
    for (std::size_t k = 0; k < etas.size(); ++k) {
      const Observables* o = etas[k].empty() ? &b.obs : nullptr;
      if (!o) if (const auto* v = find(variants, name, etas[k])) o = &v->obs;
      if (!o) { r << " – |"; continue; }
      r << " " << o->ss_cycles << " (" << fmt("%.3f", o->ss_drop / o->Q_s) << ") |";
      if (o->ss_cycles == 0 && std::isnan(first_zero)) first_zero = eta_val[k];
      if (o->ss_cycles > 0) first_zero = std::nan("");
    }
    r << " " << (std::isnan(first_zero) ? std::string("> 250") : fmt("%g", first_zero)) << " |\n";
    vanish.push_back(first_zero);
    if (const auto* v = find(variants, name, "eta=50")) {
      max_d50 = std::max({max_d50, rel(v->obs.Q_s, b.obs.Q_s), rel(v->obs.A_s, b.obs.A_s),
                          rel(v->obs.t_peak, b.obs.t_peak), rel(v->obs.alpha, b.obs.alpha)});
      max_d50_ss = std::max({max_d50_ss, rel(v->obs.ss_drop, b.obs.ss_drop), rel(v->obs.ss_period, b.obs.ss_period)});
    }
  }
  int in_range = 0;
  for (double z : vanish) in_range += (z >= 150 && z <= 250) ? 1 : 0;
  r << "\nLargest relative difference between η = 50 and η = 100, all loads: " << fmt("%.3g", max_d50)
    << " over the loading branch and first peak (Q_s, A_s, t_peak, α); " << fmt("%.3g", max_d50_ss)
    << " over the mean stick-slip drop and period. Stick-slip vanishes between η = 150 and 250 at "
    << in_range << " of " << vanish.size() << " loads.\n\n**"
    << (max_d50 >= 0.01 ? "First half not reproduced"
        : max_d50_ss < 0.05 ? "First half reproduced"
                            : "First half reproduced for the loading branch and peak, not for the stick-slip cycles")
    << "; "
    << (in_range == static_cast<int>(vanish.size()) ? "second half reproduced" : "second half partly or not reproduced")
    << "**. The η at which stick-slip stops depends on how sudden the force drop at the peak is, i.e. on the "
       "population of junction areas" << (standin ? " — here the stand-ins'" : "") << ".\n\n";

  // 4. c_min.
  double max_dc = 0;
  for (const auto& b : base)
    if (const auto* v = find(variants, b.scene.experiment.name, "c_min=1e-5"))
      max_dc = std::max({max_dc, rel(v->obs.Q_s, b.obs.Q_s), rel(v->obs.A_s, b.obs.A_s),
                         rel(v->obs.t_peak, b.obs.t_peak), rel(v->obs.ss_drop, b.obs.ss_drop),
                         rel(v->obs.ss_period, b.obs.ss_period)});
  r << "## 4. c_min = 1e-5 and 0.01 indistinguishable\n\nLargest relative difference over Q_s, A_s, t_peak, "
       "stick-slip drop and period, all loads: " << fmt("%.3g", max_dc) << ".\n\n**"
    << (max_dc < 0.01 ? "Reproduced" : "Not reproduced") << "**"
    << (max_dc < 0.01 ? "." : ": repinning threshold changes the stick-slip cycles measurably.") << "\n\n";

  // 5. Calibrated α_b: decay, incipient slope, shape.
  r << "## 5. With α_b calibrated: area decay and incipient slope match, but A(Q) is quasi-linear in the "
       "model and quadratic in the experiment\n\n";
  const bool have_cal = !calibrated.empty();
  if (have_cal) {
    r << "α_b calibrated per load with the paper's method (model quadratic α = measured α, LN_BOBYQA on "
         "log α_b; `fits/paper_alpha_b.yaml`): ";
    for (std::size_t i = 0; i < calibrated.size(); ++i)
      r << (i ? ", " : "") << calibrated[i].experiment << " " << fmt("%.4g", calibrated[i].alpha_b * 1e15) << "e-15 ("
        << calibrated[i].evaluations << " runs, " << calibrated[i].stop_reason << ")";
    r << ". The paper found 0.45e-15 at the smallest and 1.00e-15 at the largest load on the real data"
      << (standin ? "; the stand-ins were generated with one α_b = 0.725e-15 and a measured area drop rising "
                    "with load (MODEL.md §7), which is what makes the fitted α_b rise here" : "") << ".\n\n";
  }
  r << (have_cal ? ""
                 : "No calibration in this run: the model runs at the scenes' α_b.\n\n");
  r << "| experiment | α_b [1e-15] | area decay model | area decay measured | incipient slope model "
       "[mm²/N] | measured | n model | n measured |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
  int quasi_linear = 0, quad_meas = 0, decay_ok = 0, slope_ok = 0;
  for (const auto& b : base) {
    const std::string& name = b.scene.experiment.name;
    const Observables* o = &b.obs;
    const std::vector<Sample>* loading = &b.loading;
    double ab = b.scene.model.alpha_b;
    for (const auto& c : calibrated)
      if (c.experiment == name) { o = &c.obs; ab = c.alpha_b; loading = &c.loading; }
    double dm = std::nan(""), sm = std::nan(""), smod = std::nan("");
    if (const auto& m = b.scene.experiment.measured) {
      dm = 1 - m->A_m2.back() / o->A0;
      sm = initial_slope(m->Q_N, m->A_m2, 0.3);
    }
    std::vector<double> q, a;
    for (const auto& s : *loading) { q.push_back(s.Q); a.push_back(s.A); }
    smod = initial_slope(q, a, 0.3);
    r << "| " << name << " | " << fmt("%.3f", ab * 1e15) << " | " << fmt("%.3f", o->area_drop_fraction) << " | "
      << fmt("%.3f", dm) << " | " << fmt("%.3f", smod * 1e6) << " | " << fmt("%.3f", sm * 1e6) << " | "
      << fmt("%.2f", o->shape_exponent) << " | " << fmt("%.2f", o->shape_exponent_measured) << " |\n";
    quasi_linear += o->shape_exponent < 1.6 ? 1 : 0;
    quad_meas += o->shape_exponent_measured > 1.7 ? 1 : 0;
    decay_ok += rel(o->area_drop_fraction, dm) < 0.25 ? 1 : 0;
    slope_ok += rel(smod, sm) < 0.25 ? 1 : 0;
  }
  r << "\n(Area decay = 1 − A_s/A0 at the peak; incipient slope = least-squares dA/dQ over Q ≤ 0.3 Q_s.)\n\n"
    << "Model quasi-linear (n < 1.6) at " << quasi_linear << " of " << base.size()
    << " loads; measured quadratic (n > 1.7) at " << quad_meas << "; area decay within 25 % of the measured one at "
    << decay_ok << "; incipient slope within 25 % at " << slope_ok << ".\n\n";
  const int nb = static_cast<int>(base.size());
  r << "**Area decay: " << (decay_ok == nb ? "reproduced" : "not reproduced at every load") << ". Incipient slope: "
    << (slope_ok == nb ? "reproduced" : "not reproduced") << ". Shape contrast: "
    << (quasi_linear == nb && quad_meas == nb ? "reproduced" : "not fully reproduced") << ".**";
  if (standin)
    r << " The stand-in \"measured\" curves are exact parabolas plus noise (MODEL.md §7): their slope at Q = 0 "
         "is zero, so a quasi-linear model cannot match the incipient slope, and their quadratic shape is "
         "built in, so only the model side of the shape contrast is evidence.";
  r << "\n\n";

  // 6. Equal areas → quadratic.
  r << "## 6. Equal initial areas give an exactly quadratic A(Q) up to macroscopic sliding\n\n"
       "Same N and Σ A0 as each experiment, all areas equal, run to the first peak.\n\n"
       "| experiment | R² of A0 − αQ² | n | α / (α_b / (N a^p)) |\n|---|---:|---:|---:|\n";
  bool c6 = true;
  for (const auto& b : base) {
    const auto* v = find(variants, b.scene.experiment.name, "equal_areas");
    if (!v) continue;
    const double a = v->obs.A0 / static_cast<double>(v->obs.N);
    const double theory = b.scene.model.alpha_b / (static_cast<double>(v->obs.N) * std::pow(a, b.scene.model.p));
    r << "| " << v->experiment << " | " << fmt("%.6f", v->obs.alpha_R2) << " | " << fmt("%.3f", v->obs.shape_exponent)
      << " | " << fmt("%.4f", v->obs.alpha / theory) << " |\n";
    c6 = c6 && v->obs.alpha_R2 > 0.999;
  }
  r << "\n(α uses Q; the closed form holds for the junction force F = Q − M(Ẍ + ηẊ), which differs by the "
       "small viscous term.)\n\n**" << (c6 ? "Reproduced" : "Not reproduced") << "**.\n\n";

  // 7. Forces vs σ A.
  r << "## 7. Forces exceed σ_exp A transiently but stay below σ A = σ_exp A/ε\n\n";
  bool c7 = false;
  for (const auto& v : variants) {
    if (v.label.rfind("reference", 0) != 0) continue;
    if (!v.error.empty()) { r << "Reference run failed: " << v.error << "\n\n"; continue; }
    r << "Reference solver (" << v.label << ") on " << v.experiment << ": " << v.obs.slips << " slips; max over "
      << "junctions and steps of f/(σA) = " << fmt("%.6f", v.obs.max_f_over_sigmaA) << ", of f/(σ_exp A) = "
      << fmt("%.6f", v.obs.max_f_over_sigma_exp_A) << ".\n\n";
    c7 = v.obs.max_f_over_sigmaA <= 1.0 && v.obs.max_f_over_sigma_exp_A > 1.0;
  }
  r << "The event solver slips each junction exactly at f = σA (located in time), so f/(σA) ≤ 1 holds there by "
       "construction.\n\n**" << (c7 ? "Reproduced" : "Not reproduced") << "**.\n\n";

  // 8. Robustness of the shape.
  r << "## 8. Quasi-linear shape robust to circular junctions and to Eq. (3) applied always\n\n"
       "| experiment | n elliptic, until first slip | n circular | n always |\n|---|---:|---:|---:|\n";
  bool c8 = true;
  for (const auto& b : base) {
    const auto* c = find(variants, b.scene.experiment.name, "circular");
    const auto* a = find(variants, b.scene.experiment.name, "area_law=always");
    r << "| " << b.scene.experiment.name << " | " << fmt("%.2f", b.obs.shape_exponent) << " | "
      << (c ? fmt("%.2f", c->obs.shape_exponent) : "–") << " | " << (a ? fmt("%.2f", a->obs.shape_exponent) : "–") << " |\n";
    c8 = c8 && c && a && c->obs.shape_exponent < 1.6 && a->obs.shape_exponent < 1.6;
  }
  r << "\n**" << (c8 ? "Reproduced" : "Not reproduced") << "** (quasi-linear: n < 1.6).\n\n";

  int failed = 0;
  for (const auto& v : variants) failed += v.error.empty() ? 0 : 1;
  if (failed) {
    r << "## Failed runs\n\n";
    for (const auto& v : variants)
      if (!v.error.empty()) r << "- " << v.experiment << " " << v.label << ": " << v.error << "\n";
  }
  return r.str();
}

}  // namespace asperity
