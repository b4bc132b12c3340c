#include "studies/interaction_report.hpp"
#include "studies/study_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <ostream>
#include <sstream>

#include "campaign/store.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/numbers.hpp"
#include "report/gnuplot.hpp"
#include "report/units.hpp"
#include "studies/recovery_matrix.hpp"
#include "studies/topography_comparison.hpp"

namespace asperity::interaction_detail {
namespace fs = std::filesystem;

namespace {

// Count, mean, sample standard deviation and range of a set of values.
struct Stats {
  std::size_t n = 0;
  double mean = NAN, sd = NAN, lo = NAN, hi = NAN;
};
Stats stats(const std::vector<double>& v) {
  Stats s;
  s.n = v.size();
  if (v.empty()) return s;
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  double q = 0;
  for (double x : v) q += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(q / static_cast<double>(v.size() - 1)) : 0.0;
  s.lo = *std::min_element(v.begin(), v.end());
  s.hi = *std::max_element(v.begin(), v.end());
  return s;
}

// The sweep store's rows, by column name (StoreReader: the journal of an unfinished store too);
// empty when there is no store.
std::vector<std::map<std::string, std::string>> sweep_rows(const fs::path& store) {
  std::vector<std::map<std::string, std::string>> rows;
  if (!fs::exists(store / "points.csv") && !fs::exists(store / "journal.csv")) return rows;
  const StoreReader reader(store);
  const auto header = io::csv_split(reader.header());
  for (const StoredRow& sr : reader.rows()) {
    const auto f = io::csv_split(reader.row(sr));
    std::map<std::string, std::string> r;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) r[header[i]] = f[i];
    rows.push_back(std::move(r));
  }
  return rows;
}

// A store row's number in column k; NaN when empty, absent or not a number.
double num(const std::map<std::string, std::string>& r, const std::string& k) {
  const auto it = r.find(k);
  if (it == r.end() || it->second.empty()) return NAN;
  try {
    return std::stod(it->second);
  } catch (...) {
    return NAN;
  }
}

// The gnuplot script of force_spread.png: histograms of f/(σA) at half the peak's time among the
// junctions of equal area, crowded vs sparse, and the independent model's band.
std::string force_spread_plot(const Spread& sp) {
  std::vector<std::vector<double>> crowded, sparse, indep;
  for (std::size_t i = 0; i < sp.A0.size(); ++i) {
    if (!sp.equal[i]) continue;
    (sp.crowding[i] >= sp.crowding_median ? crowded : sparse).push_back({sp.half_inter[i]});
    indep.push_back({sp.half_indep[i]});
  }
  double lo = NAN, hi = NAN;  // the independent model's range (one bin wide or less)
  for (const auto& v : indep)
    if (std::isfinite(v[0]))
      lo = std::isnan(lo) ? v[0] : std::min(lo, v[0]), hi = std::isnan(hi) ? v[0] : std::max(hi, v[0]);
  // y tics: at most four intervals up to the tallest bar (the panel is squat at a column's width).
  constexpr double kBin = 0.02;  // the histograms' bin width (bin(x) below)
  int tallest = 1;
  for (const auto* group : {&crowded, &sparse}) {
    std::map<long, int> bars;
    for (const auto& v : *group)
      if (std::isfinite(v[0])) tallest = std::max(tallest, ++bars[std::lround(std::floor(v[0] / kBin))]);
  }
  const double raw = tallest / 4.0, decade = std::pow(10.0, std::floor(std::log10(raw))), m = raw / decade;
  const double y_step = std::max(1.0, (m <= 1 ? 1 : (m <= 2 ? 2 : (m <= 5 ? 5 : 10))) * decade);
  const FigureUnit area = figure_unit("A0");  // areas as every figure shows them (mm²)
  std::ostringstream gp;
  gp << gnuplot_block("crowded", crowded) << gnuplot_block("sparse", sparse) << gnuplot_block("indep", indep)
     << stand_in_mark(is_stand_in(sp.inter.experiment)) << "set title " << gnuplot_text(sp.experiment) << " . "
     << gnuplot_quote(": f/(σA) at half the time of the first peak")
     << " . \"\\n\" . "  // short lines and key entries: one column wide in a PDF
     << gnuplot_quote("junctions of equal area (" + io::format_cell("%.3g", sp.area_lo * area.scale) + "–" +
                      io::format_cell("%.3g", sp.area_hi * area.scale) + " " + unit_markup(area.unit) + ")")
     << " . \"\\n\" . " << gnuplot_quote("crowded: k_i Σ_j C_{ij} ≥ median") << "\nset xlabel "
     << gnuplot_quote("f_i / (σ A_i) [1]") << "\nset ylabel " << gnuplot_quote("junctions [1]")
     << "\nbin(x) = " << io::format_double(kBin) << "*floor(x/" << io::format_double(kBin) << ") + "
     << io::format_double(kBin / 2) << "\nset style fill transparent solid 0.5\nset boxwidth "
     << io::format_double(kBin)
     << "\nset key top "
        "right\nset ytics "
     << io::format_double(y_step)
     << "\n"
     // The independent model gives the junctions of equal area one f/(σA) (a range narrower
     // than a bin): a band and a line across the plot, not a bar as tall as all the junctions
     // (which squashed the histograms); the y range is the histograms'.
     << "set yrange [0:*]\nset offsets 0, 0, graph 0.1, 0\n"
     << (std::isfinite(lo) ? "set object 1 rect from first " + io::format_cell("%.10g", lo) + ", graph 0 to first " +
                                 io::format_cell("%.10g", hi) +
                                 ", graph 1 behind fc rgb '#56b4e9' fs solid 0.35 noborder\nset arrow 1 from first " +
                                 io::format_cell("%.10g", 0.5 * (lo + hi)) + ", graph 0 to first " +
                                 io::format_cell("%.10g", 0.5 * (lo + hi)) + ", graph 1 nohead lw 3 lc rgb '#56b4e9'\n"
                           : std::string())
     << "plot $crowded using (bin($1)):(1) smooth frequency with boxes title " << gnuplot_quote("interacting, crowded")
     << ", $sparse using (bin($1)):(1) smooth frequency "
     << "with boxes title " << gnuplot_quote("interacting, sparse") << ", NaN with lines lw 3 lc rgb '#56b4e9' title "
     << gnuplot_quote("independent model") << "\n";
  return gp.str();
}

// REPORT.md's title, provenance and verdict.
void write_verdict_md(std::ostream& md, const InteractionStudyOptions& opt, const Tally& t, const std::string& verdict,
                      const std::string& joint, const std::string& recovery) {
  const std::string of = " of " + std::to_string(t.ran) + " loads";
  md << "# Elastic interactions between junctions: does A(Q) turn quadratic?\n\n"
     << "**STAND-IN DATA.** Every number here comes from the stand-in experiments of `data/standin/` (areas, "
        "positions and \"measured\" curves generated, not measured): it tests the model on made-up data of the right "
        "size, not the real experiments.\n\n"
     << "Written by `" << study_command(opt.study_file) << "` from the runs of that command (calibrations read from `"
     << opt.fit_independent.generic_string() << "` and `" << opt.fit_interacting.generic_string()
     << "`, the joint calibrations from `"
     << (opt.joint_independent.empty() ? fs::path() : opt.joint_independent.front()).generic_string() << "` and `"
     << (opt.joint_interacting.empty() ? fs::path() : opt.joint_interacting.front()).generic_string()
     << "` (and the further files the section names), the sweep from `" << opt.sweep_store.generic_string()
     << "/points.csv`, the recovery matrix from `" << opt.recovery_matrix.generic_string() << "`).\n\n"
     << "## What the joint calibration can tell apart: the recovery matrix\n\n"
     << "**SYNTHETIC DATA** (read from `" << opt.recovery_matrix.generic_string()
     << "`, written by a recovery study, `study: recovery`): experiments made by each model at a known truth, each "
        "fitted by "
        "each model at equal budgets. Only where the model that made the data wins its row can a joint fit between "
        "the models decide anything.\n\n"
     << recovery << "## Verdict on the stand-ins\n\n**" << verdict << ".** ";
  if (t.ran > 0)
    md << "The independent model is within the noise at " << t.indep_quadratic << of << ". Against the measured curve, "
       << "the interacting model is closer than the independent one at " << t.closer << of << ", farther at "
       << t.farther << ", and the difference is within its spread (no evidence either way) at " << t.undecided << ". ";
  if (t.dn_count > 0)
    md << "Interactions change the shape exponent n by " << io::format_cell("%+.3f", t.dn_sum / t.dn_count)
       << " on average (interacting − independent, each at its own calibrated α_b); the stand-in \"measured\" "
          "curves are parabolas plus noise by construction, and their own n spreads by ±0.1 or more over that noise "
          "(table), so n alone decides nothing.";
  md << "\n\nRule: the rms residual of a model's A(Q) at the measured points (linear space, only the points its "
        "loading branch reaches) is compared with the rms the noise alone leaves about the measured curve's own "
        "parabola: within its 95th percentile over a residual bootstrap of the measured points (1,000 seeded "
        "resamples) counts as reproducing the measured shape. Two models differ when their residuals differ by more "
        "than twice the sum of their bootstrap sds.\n\n"
     << joint << " Per load: section \"Joint calibration\" below.\n\n";
}

// REPORT.md: the per-load table, each model at its own calibrated α_b.
void write_loads_md(std::ostream& md, const std::vector<StudyRow>& rows) {
  md << "## Per load, each model at its own calibrated α_b (the paper's method: α of A = A0 − αQ² matches the "
        "measured one)\n\n"
     << "| experiment | model | α_b [1e-15] | n | n measured | area decay | decay measured | incipient slope "
        "[mm²/N] | slope measured | Q_s [N] | t_peak [s] | stick-slip cycles | wall [s] |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    for (const auto* s : {&r.indep, &r.inter}) {
      const char* model = s == &r.indep ? "independent" : "interacting";
      if (!s->ran) {
        md << "| " << r.name << " | " << model << " | no calibration: no evidence | | | | | | | | | | |\n";
        continue;
      }
      md << "| " << r.name << " | " << model << " | " << io::format_cell("%.4f", s->alpha_b * 1e15) << " | "
         << io::format_cell("%.3f", s->obs.shape_exponent) << " | " << io::format_cell("%.3f", s->areas.n_measured)
         << " | " << io::format_cell("%.3f", s->areas.decay_model) << " | "
         << io::format_cell("%.3f", s->areas.decay_measured) << " | "
         << io::format_cell("%.3f", s->areas.slope_model * 1e6) << " | "
         << io::format_cell("%.3f", s->areas.slope_measured * 1e6) << " | " << io::format_cell("%.4f", s->obs.Q_s)
         << " | " << io::format_cell("%.3f", s->obs.t_peak) << " | " << s->obs.ss_cycles << " | "
         << io::format_cell("%.1f", s->wall_s) << " |\n";
    }
  md << "\n(n: exponent of A0 − A = c Qⁿ on the loading branch; area decay 1 − A_s/A0; incipient slope: least-squares "
        "dA/dQ over Q ≤ 0.3 Q_max; runs to five stick-slip cycles or 12 s, 20 s with interactions.)\n\n";
}

// REPORT.md: each model's A(Q) against the measured curve, at its noise.
void write_shape_md(std::ostream& md, const std::vector<StudyRow>& rows) {
  md << "## Shape against the measured curve, at its noise\n\n"
     << "| experiment | model | residual rms [mm²] | ± sd | noise rms [mm²] | noise 95 % [mm²] | within noise | "
        "α [mm²/N²] | α measured ± sd | n measured ± sd | points |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    for (const auto* s : {&r.indep, &r.inter}) {
      if (!s->ran || !std::isfinite(s->shape.residual_rms)) continue;
      const ShapeComparison& c = s->shape;
      md << "| " << r.name << " | " << (s == &r.indep ? "independent" : "interacting") << " | "
         << io::format_cell("%.4f", c.residual_rms * 1e6) << " | " << io::format_cell("%.4f", c.residual_rms_sd * 1e6)
         << " | " << io::format_cell("%.4f", c.noise_rms * 1e6) << " | "
         << io::format_cell("%.4f", c.noise_rms_p95 * 1e6) << " | " << (c.residual_exceeds_noise() ? "no" : "yes")
         << " | " << io::format_cell("%.4f", c.alpha_model * 1e6) << " | "
         << io::format_cell("%.4f", c.alpha_measured * 1e6) << " ± "
         << io::format_cell("%.4f", c.alpha_measured_sd * 1e6) << " | " << io::format_cell("%.3f", c.n_measured)
         << " ± " << io::format_cell("%.3f", c.n_measured_sd) << " | " << c.points_used << " |\n";
    }
  md << "\n(Residual: rms of A_model − A_measured at the measured Q the model's loading branch reaches; noise: rms of "
        "the measured points about their own parabola A0 − αQ², and its 95th percentile over the bootstrap. α: "
        "A = A0 − αQ² with A0 fixed, which the calibration matches by construction.)\n\n";
}

// REPORT.md: the force spread at the first peak (the paper's Figure 2 argument) and the pairs.
void write_spread_md(std::ostream& md, const InteractionStudyOptions& opt, const Spread& sp,
                     const std::string& fig_note, const std::string& pairs_md) {
  md << "## Force spread at the first peak (" << opt.spread_experiment << ")\n\n";
  if (!sp.ran) {
    md << "No evidence: the interacting calibration of " << opt.spread_experiment << " or its runs are missing.\n\n";
  } else {
    auto split = [&](const std::vector<double>& inter, const std::vector<double>& indep) {
      std::vector<double> c, s, ind;
      for (std::size_t i = 0; i < sp.A0.size(); ++i) {
        if (!sp.equal[i]) continue;
        (sp.crowding[i] >= sp.crowding_median ? c : s).push_back(inter[i]);
        ind.push_back(indep[i]);
      }
      return std::array<Stats, 3>{stats(c), stats(s), stats(ind)};
    };
    md << "The paper's Figure 2 argument: two junctions of similar area carry very different forces, presumably "
          "because crowded neighbourhoods evolve differently. Junctions of equal area ("
       << io::format_cell("%.3g", sp.area_lo) << "–" << io::format_cell("%.3g", sp.area_hi)
       << " m², the stand-ins' cluster) at the first peak, "
       << "split at the median of their crowding k_i Σ_j C_ij (" << io::format_cell("%.3f", sp.crowding_median)
       << ", the compliance the neighbours add relative to the junction's own), at half the time of the first peak "
          "and at the peak:\n\n"
       << "| when | set | junctions | mean f/(σA) | sd | min | max |\n|---|---|---|---|---|---|---|\n";
    for (int w = 0; w < 2; ++w) {
      const auto st = w == 0 ? split(sp.half_inter, sp.half_indep) : split(sp.ratio_inter, sp.ratio_indep);
      const char* names[3] = {"interacting, crowded", "interacting, sparse", "independent (same junctions)"};
      for (int k = 0; k < 3; ++k)
        md << "| " << (w == 0 ? "half t_peak" : "t_peak") << " | " << names[k] << " | " << st[k].n << " | "
           << io::format_cell("%.4f", st[k].mean) << " | " << io::format_cell("%.4f", st[k].sd) << " | "
           << io::format_cell("%.4f", st[k].lo) << " | " << io::format_cell("%.4f", st[k].hi) << " |\n";
    }
    md << "\n"
       << "![force spread](force_spread.png)\n\n"
       << (fig_note.empty() ? "" : fig_note + "\n\n")
       << "Every junction's ratio, crowding and position: `forces_at_peak.csv` (1 = at its threshold; ε = 0.9: "
          "slipping).\n\n"
       << pairs_md;
  }
}

// REPORT.md: the crowding and cut-off sweep's table, read from its store.
void write_sweep_md(std::ostream& md, const InteractionStudyOptions& opt) {
  const auto sw = sweep_rows(opt.sweep_store);
  md << "## Crowding and cut-off (`sweeps/interactions.yaml`, α_b = 0.725e-15, not recalibrated)\n\n";
  if (sw.empty()) {
    md << "No evidence: `" << opt.sweep_store.generic_string()
       << "/points.csv` is missing (run `asperity sweep "
          "sweeps/interactions.yaml`).\n\n";
  } else {
    md << "| experiment | grid | position scale | cut-off [mm] | n | area decay | Q_s [N] | t_peak [s] | stick-slip "
          "cycles "
          "| status |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& r : sw) {
      auto g = [&](const std::string& k) {
        const auto it = r.find(k);
        return it == r.end() ? std::string() : it->second;
      };
      md << "| " << g("experiment") << " | " << g("grid") << " | " << g("model.position_scale") << " | "
         << (num(r, "model.interaction_cutoff") > 0 ? io::format_cell("%.2f", num(r, "model.interaction_cutoff") * 1e3)
                                                    : "every pair")
         << " | " << io::format_cell("%.3f", num(r, "shape_exponent")) << " | "
         << io::format_cell("%.3f", num(r, "area_drop_fraction")) << " | " << io::format_cell("%.4f", num(r, "Q_s"))
         << " | " << io::format_cell("%.3f", num(r, "t_peak")) << " | " << g("ss_cycles") << " | " << g("status")
         << " |\n";
    }
    md << "\n(Position scale s: the same arrangement in an apparent contact s times as wide, 1/s² as crowded; 1000: "
          "practically independent. A cut-off drops the pairs farther apart.)\n\n";
  }
}

// REPORT.md: both models on junctions from topography, from the topography study's own table
// (not run here: it takes minutes per surface; its REPORT.md has the protocol).
void write_topography_md(std::ostream& md, const InteractionStudyOptions& opt) {
  const std::string table = opt.topography_table.generic_string();
  md << "## Junctions from topography (SYNTHETIC surfaces)\n\n";
  const std::vector<TopographyShapeRow> rows = read_topography_table(opt.topography_table);
  if (rows.empty()) {
    md << "No evidence: `" << table << "` is missing (run `scripts/topography_study.py`).\n\n";
    return;
  }
  const TopographyTally t = tally_topography(rows);
  md << "Read from `" << table
     << "` (the topography study, `results/topography/REPORT.md`: a generated "
        "self-affine rough sphere pressed at each load, its contact clusters as junctions, α_b per load and model "
        "so that the area drop at the first peak equals the stand-in one; roughness parameters assumed). Its "
        "surfaces are synthetic and it has no measured Q(t), so no joint calibration is made there. ";
  if (t.pairs > 0)
    md << "Over the " << t.pairs << " loads (and surface realisations) where both models ran, interactions change "
       << "the shape exponent n by " << io::format_cell("%+.3f", t.mean_dn) << " on average (from "
       << io::format_cell("%+.3f", t.min_dn) << " to " << io::format_cell("%+.3f", t.max_dn) << "; lower at "
       << t.n_lower << " of " << t.pairs << ") and the endpoint residual (distance from a parabola "
       << "through the same end points, in units of the drop) by at most " << io::format_cell("%.3f", t.max_abs_dres)
       << ". ";
  md << t.within_noise << " of " << t.rows << " model curves are within the noise of a stand-in-like measured "
     << "parabola (residual at most the noise's 95th percentile).\n\n"
     << "| seed | load [N] | N | model | α_b [1e-15] | n | endpoint residual | residual [mm²] | noise 95 % [mm²] | "
        "within noise |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const TopographyShapeRow& r : rows)
    md << "| " << r.seed << " | " << io::format_cell("%.2f", r.load_N) << " | " << r.junctions << " | " << r.model
       << " | " << io::format_cell("%.4f", r.alpha_b * 1e15) << " | " << io::format_cell("%.3f", r.shape_exponent)
       << " | " << io::format_cell("%.3f", r.endpoint_residual) << " | "
       << io::format_cell("%.4f", r.residual_rms_m2 * 1e6) << " | " << io::format_cell("%.4f", r.noise_rms_p95_m2 * 1e6)
       << " | " << (r.within_noise() ? "yes" : "no") << " |\n";
  md << "\n";
}

// A parameter's 95 % interval as a table cell ("n/a" where the fit gave none).
std::string interval_cell(const JointParameter& p, double scale, const char* f) {
  if (!std::isfinite(p.lo95)) return "n/a";
  return "[" + io::format_cell(f, p.lo95 * scale) + ", " + io::format_cell(f, p.hi95 * scale) + "]";
}

// REPORT.md: the joint calibrations' values per load and model.
void write_joint_values_md(std::ostream& md, const InteractionStudyOptions& opt, const std::vector<JointRow>& rows) {
  auto files = [](const std::vector<fs::path>& v) {
    std::string s;
    for (const auto& f : v)
      s += (s.empty() ? "`" : ", `") + f.generic_string() + "`" + (fs::exists(f) ? "" : " (absent)");
    return s;
  };
  md << "## Joint calibration of (α_b, ε, η) against A(Q) and Q(t)\n\n"
     << "Calibrated values per load and model, read from " << files(opt.joint_independent) << " (independent) and "
     << files(opt.joint_interacting)
     << " (interacting): objective `area_and_force`, a chi-square over the measured "
        "A(Q) and the measured Q(t) (docs/calibration.md, \"Joint calibration\"). 95 %: the Hessian's interval (±1.96 "
        "σ, "
        "σ scaled by s²; n/a where the fit gave none: a parameter at its bound, or H not positive definite, fit.yaml's "
        "`uncertainty.failure`); profile σ: the parabola through each one-parameter profile (conditional). Neither is "
        "a "
        "statistical error bar while s² ≫ 1. (bound): the value sits at its box's bound. Position scale: the "
        "interacting fit's free junction spacing (1: the stand-ins' positions). Converged: yes where at least two of "
        "the fit's starts reached its best objective (docs/calibration.md, \"Convergence: several starts\"); "
        "intervals only then, and s² = J/(N − p) in brackets where not.\n\n"
     << "| experiment | model | α_b [1e-15] | 95 % | profile σ | ε | 95 % | profile σ | η [1/s] | 95 % | profile σ | "
        "position scale | s² | converged |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    for (const auto* s : {&r.indep, &r.inter}) {
      const char* model = s == &r.indep ? "independent" : "interacting";
      if (s->fit.label.empty() || s->fit.status != "ok") {
        md << "| " << r.name << " | " << model << " | "
           << (s->fit.label.empty() ? "no joint calibration" : "joint calibration " + s->fit.status)
           << ": no evidence | | | | | | | | | | | |\n";
        continue;
      }
      auto par = [&](const std::string& k) {
        const auto it = s->fit.parameters.find(k);
        return it == s->fit.parameters.end() ? JointParameter{} : it->second;
      };
      const JointParameter a = par("model.alpha_b"), e = par("model.epsilon"), h = par("model.eta"),
                           ps = par("model.position_scale");
      auto bound = [](const JointParameter& p) { return p.at_bound ? " (bound)" : ""; };
      // An older fit.yaml says nothing of convergence: its s² is shown as it was.
      const bool certified = s->fit.converged.empty() || s->fit.converged == "yes";
      const int dof = s->fit.n_residuals - static_cast<int>(s->fit.parameters.size());
      const double s2_value = std::isfinite(s->fit.reduced_chi2) ? s->fit.reduced_chi2
                              : dof > 0                          ? s->fit.objective / dof
                                                                 : ForceMisfit::nan;
      const std::string s2 = io::format_cell("%.1f", s2_value);
      md << "| " << r.name << " | " << model << " | " << io::format_cell("%.4f", a.value * 1e15) << bound(a) << " | "
         << interval_cell(a, 1e15, "%.4f") << " | " << io::format_cell("%.4f", a.profile_sigma * 1e15) << " | "
         << io::format_cell("%.4f", e.value) << bound(e) << " | " << interval_cell(e, 1, "%.4f") << " | "
         << io::format_cell("%.4f", e.profile_sigma) << " | " << io::format_cell("%.2f", h.value) << bound(h) << " | "
         << interval_cell(h, 1, "%.2f") << " | " << io::format_cell("%.2f", h.profile_sigma) << " | "
         << (std::isfinite(ps.value) ? io::format_cell("%.4f", ps.value) + bound(ps) : std::string("–")) << " | "
         << (certified ? s2 : "(" + s2 + ")") << " | "
         << (s->fit.converged.empty() ? std::string("–")
                                      : s->fit.converged + " (" + std::to_string(s->fit.in_best_basin) + " of " +
                                            std::to_string(s->fit.starts) + ")")
         << " |\n";
    }
}

// REPORT.md: each model re-run at its joint calibration against the measured Q(t) and A(Q), and
// which passes per load.
void write_joint_reruns_md(std::ostream& md, const std::vector<JointRow>& rows) {
  md << "\nEach model re-run here at its calibrated values, with the fit file's own settings (to the last measured "
        "time of the Q(t), no stop at the peak): Q(t) misfit = rms of Q_model − Q_measured at the measured samples; "
        "noise σ = 0.002 · max Q_measured (the stand-ins' noise, the fit's `noise.force`); within noise when the "
        "misfit is at most the rms that noise alone leaves in 95 % of cases (σ sqrt(χ²₀.₉₅(n)/n)). A(Q): the residual "
        "rule of the table above (bootstrap 95th percentile). χ² re-run / fit: the objective of this re-run over the "
        "one fit.yaml states (1 when the run is the fit's).\n\n"
     << "| experiment | model | t_peak [s] | Q_s [N] | Q(t) rms [mN] | ± sd | noise σ [mN] | noise 95 % [mN] | Q(t) "
        "within "
        "noise | A(Q) residual [mm²] | noise 95 % [mm²] | A(Q) within noise | χ² re-run / fit | wall [s] |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    for (const auto* s : {&r.indep, &r.inter}) {
      const char* model = s == &r.indep ? "independent" : "interacting";
      if (!s->ran) {
        md << "| " << r.name << " | " << model << " | " << s->missing << ": no evidence | | | | | | | | | | | |\n";
        continue;
      }
      const ForceMisfit& f = s->force;
      md << "| " << r.name << " | " << model << " | " << io::format_cell("%.3f", s->obs.t_peak)
         << (s->obs.peak_found ? "" : " (no peak)") << " | " << io::format_cell("%.4f", s->obs.Q_s) << " | "
         << io::format_cell("%.2f", f.rms * 1e3) << " | " << io::format_cell("%.2f", f.rms_sd * 1e3) << " | "
         << io::format_cell("%.2f", f.noise * 1e3) << " | " << io::format_cell("%.2f", f.noise_p95 * 1e3) << " | "
         << (q_within(*s) ? "yes" : "no") << " | " << io::format_cell("%.4f", s->shape.residual_rms * 1e6) << " | "
         << io::format_cell("%.4f", s->shape.noise_rms_p95 * 1e6) << " | " << (a_within(*s) ? "yes" : "no") << " | "
         << io::format_cell("%.6f", s->objective / s->fit.objective) << " | " << io::format_cell("%.1f", s->wall_s)
         << " |\n";
    }
  md << "\nPer load (from the table above: which model matches within the noise; no comparison between the "
        "models, see the verdict):\n\n"
     << "| experiment | Q(t) within noise | A(Q) within noise |\n|---|---|---|\n";
  for (const auto& r : rows)
    md << "| " << r.name << " | " << which_pass(r, q_within) << " | " << which_pass(r, a_within) << " |\n";
  md << "\n";
}

// REPORT.md: the joint calibrations, their re-runs against the measured Q(t) and A(Q), the
// per-load verdict.
void write_joint_md(std::ostream& md, const InteractionStudyOptions& opt, const std::vector<JointRow>& rows) {
  write_joint_values_md(md, opt, rows);
  write_joint_reruns_md(md, rows);
}

// REPORT.md: at what noise each model would pass. The 95th percentile a noise of level σ leaves is
// proportional to σ (A(Q): the bootstrap of the residuals about the parabola; Q(t): σ sqrt(χ²₀.₉₅(n)/n)),
// while a model's misfit on the stand-ins is systematic: a model passes at k times the stand-ins'
// noise for k ≥ misfit / (95 % at their noise).
void write_noise_md(std::ostream& md, const std::vector<StudyRow>& rows, const std::vector<JointRow>& joint) {
  md << "## At what noise each model would pass\n\n"
        "A model's misfit here is systematic, while the 95th percentile that noise alone leaves grows in proportion to "
        "the noise level: the table gives k = misfit / (noise 95 %), the factor by which the stand-ins' noise would "
        "have to grow for the model to pass (k ≤ 1: it passes at their noise). A(Q) at the calibrated α_b (the "
        "first table below) and, for the joint calibrations, Q(t) and A(Q) at the jointly fitted values.\n\n"
     << "| experiment | A(Q) independent | A(Q) interacting | joint: Q(t) independent | joint: Q(t) interacting | "
        "joint: A(Q) independent | joint: A(Q) interacting |\n|---|---|---|---|---|---|---|\n";
  auto k = [](double misfit, double p95) {
    return std::isfinite(misfit) && std::isfinite(p95) && p95 > 0 ? io::format_cell("%.1f", misfit / p95)
                                                                  : std::string("no evidence");
  };
  for (const StudyRow& r : rows) {
    md << "| " << r.name << " | "
       << (r.indep.ran ? k(r.indep.shape.residual_rms, r.indep.shape.noise_rms_p95) : "no evidence") << " | "
       << (r.inter.ran ? k(r.inter.shape.residual_rms, r.inter.shape.noise_rms_p95) : "no evidence");
    const JointRow* j = nullptr;
    for (const JointRow& x : joint)
      if (x.name == r.name) j = &x;
    for (int part = 0; part < 2; ++part)
      for (int model = 0; model < 2; ++model) {
        const JointSide* s = j ? (model == 0 ? &j->indep : &j->inter) : nullptr;
        md << " | "
           << (s && s->ran ? (part == 0 ? k(s->force.rms, s->force.noise_p95)
                                        : k(s->shape.residual_rms, s->shape.noise_rms_p95))
                           : std::string("no evidence"));
      }
    md << " |\n";
  }
  md << "\n";
}

}  // namespace

void write_table_csv(const fs::path& out, const std::vector<StudyRow>& rows) {
  std::ostringstream t;
  t << "experiment,model,alpha_b,Q_s_N,t_peak_s,shape_exponent,shape_exponent_measured,area_decay,area_decay_measured,"
       "incipient_slope_m2_per_N,incipient_slope_measured_m2_per_N,ss_cycles,ss_drop,wall_s,"
       "alpha_m2_per_N2,alpha_measured_m2_per_N2,alpha_measured_sd_m2_per_N2,shape_exponent_measured_sd,"
       "residual_rms_m2,residual_rms_sd_m2,noise_rms_m2,noise_rms_p95_m2,measured_points_used\n";
  for (const auto& r : rows)
    for (const auto* s : {&r.indep, &r.inter}) {
      if (!s->ran) continue;
      t << r.name << ',' << (s == &r.indep ? "independent" : "interacting") << ',' << io::csv_number(s->alpha_b) << ','
        << io::csv_number(s->obs.Q_s) << ',' << io::csv_number(s->obs.t_peak) << ','
        << io::csv_number(s->obs.shape_exponent) << ',' << io::csv_number(s->areas.n_measured) << ','
        << io::csv_number(s->areas.decay_model) << ',' << io::csv_number(s->areas.decay_measured) << ','
        << io::csv_number(s->areas.slope_model) << ',' << io::csv_number(s->areas.slope_measured) << ','
        << s->obs.ss_cycles << ',' << io::csv_number(s->obs.ss_drop) << ',' << io::csv_number(s->wall_s) << ','
        << io::csv_number(s->shape.alpha_model) << ',' << io::csv_number(s->shape.alpha_measured) << ','
        << io::csv_number(s->shape.alpha_measured_sd) << ',' << io::csv_number(s->shape.n_measured_sd) << ','
        << io::csv_number(s->shape.residual_rms) << ',' << io::csv_number(s->shape.residual_rms_sd) << ','
        << io::csv_number(s->shape.noise_rms) << ',' << io::csv_number(s->shape.noise_rms_p95) << ','
        << s->shape.points_used << '\n';
    }
  io::write_text_file(out / "table.csv", t.str());
}

void write_forces_csv(const fs::path& out, const Spread& sp) {
  std::ostringstream t;
  t << "junction,A0_m2,x_m,y_m,crowding,equal_area_set,f_over_sigmaA_interacting,f_over_sigmaA_independent,"
       "f_over_sigmaA_interacting_half,f_over_sigmaA_independent_half\n";
  for (std::size_t i = 0; i < sp.A0.size(); ++i)
    t << i + 1 << ',' << io::csv_number(sp.A0[i]) << ',' << io::csv_number(sp.x[i]) << ',' << io::csv_number(sp.y[i])
      << ',' << io::csv_number(sp.crowding[i]) << ',' << int(sp.equal[i]) << ',' << io::csv_number(sp.ratio_inter[i])
      << ',' << io::csv_number(sp.ratio_indep[i]) << ',' << io::csv_number(sp.half_inter[i]) << ','
      << io::csv_number(sp.half_indep[i]) << '\n';
  io::write_text_file(out / "forces_at_peak.csv", t.str());
}

std::string draw_force_spread(const InteractionStudyOptions& opt, const Spread& sp) {
  std::string error;
  if (!render_figures(opt.out / "force_spread.png", force_spread_plot(sp), 1000, 650, opt.figures, &error))
    return "force_spread.png not drawn: " + error;
  return {};
}

void write_joint_csv(const fs::path& out, const std::vector<JointRow>& rows) {
  std::ostringstream t;
  t << "experiment,model,alpha_b,alpha_b_lo95,alpha_b_hi95,alpha_b_profile_sigma,epsilon,epsilon_lo95,epsilon_hi95,"
       "epsilon_profile_sigma,eta,eta_lo95,eta_hi95,eta_profile_sigma,reduced_chi2,objective_fit,objective_rerun,"
       "t_peak_s,peak_found,Q_s_N,force_rms_N,force_rms_sd_N,force_noise_N,force_noise_p95_N,force_samples,"
       "force_within_noise,area_residual_rms_m2,area_noise_rms_p95_m2,area_within_noise,wall_s\n";
  for (const auto& r : rows)
    for (const auto* s : {&r.indep, &r.inter}) {
      if (!s->ran) continue;
      t << r.name << ',' << (s == &r.indep ? "independent" : "interacting");
      for (const char* k : {"model.alpha_b", "model.epsilon", "model.eta"}) {
        const auto it = s->fit.parameters.find(k);
        const JointParameter p = it == s->fit.parameters.end() ? JointParameter{} : it->second;
        t << ',' << io::csv_number(p.value) << ',' << io::csv_number(p.lo95) << ',' << io::csv_number(p.hi95) << ','
          << io::csv_number(p.profile_sigma);
      }
      t << ',' << io::csv_number(s->fit.reduced_chi2) << ',' << io::csv_number(s->fit.objective) << ','
        << io::csv_number(s->objective) << ',' << io::csv_number(s->obs.t_peak) << ','
        << (s->obs.peak_found ? "true" : "false") << ',' << io::csv_number(s->obs.Q_s) << ','
        << io::csv_number(s->force.rms) << ',' << io::csv_number(s->force.rms_sd) << ','
        << io::csv_number(s->force.noise) << ',' << io::csv_number(s->force.noise_p95) << ',' << s->force.n << ','
        << (q_within(*s) ? "true" : "false") << ',' << io::csv_number(s->shape.residual_rms) << ','
        << io::csv_number(s->shape.noise_rms_p95) << ',' << (a_within(*s) ? "true" : "false") << ','
        << io::csv_number(s->wall_s) << '\n';
    }
  io::write_text_file(out / "joint.csv", t.str());
}

void write_report_md(const InteractionStudyOptions& opt, const std::vector<StudyRow>& rows, const Tally& tally,
                     const std::string& verdict, const std::vector<JointRow>& joint, const std::string& joint_text,
                     const Spread& sp, const std::string& fig_note, const std::string& pairs_md) {
  std::ostringstream md;
  std::ostringstream recovery;
  write_recovery_matrix_md(recovery, read_recovery_matrix(opt.recovery_matrix));
  write_verdict_md(md, opt, tally, verdict, joint_text, recovery.str());
  write_noise_md(md, rows, joint);
  write_loads_md(md, rows);
  write_shape_md(md, rows);
  write_joint_md(md, opt, joint);
  write_spread_md(md, opt, sp, fig_note, pairs_md);
  write_sweep_md(md, opt);
  write_topography_md(md, opt);
  io::write_text_file(opt.out / "REPORT.md", md.str());
}

}  // namespace asperity::interaction_detail
