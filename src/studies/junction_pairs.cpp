#include "studies/junction_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/numbers.hpp"
#include "report/gnuplot.hpp"
#include "report/units.hpp"
#include "solve/integrate.hpp"
#include "solve/interacting/interacting_event_stepper.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

// Samples the tracked junctions at equally spaced times, and notes each one's first slip
// (population changes come after the slips are applied, so the state tells who slipped).
class TraceObserver {
 public:
  TraceObserver(InteractingEventStepper& stepper, std::vector<JunctionTrace>& traces, double t_end, int n)
      : stepper_(stepper), traces_(traces), t_end_(t_end), n_(n) {}
  void sample(const Sample& s) {
    InteractingJunctions& J = stepper_.junctions();
    const std::vector<double> f = J.forces(s.X);
    const std::vector<double> A = J.areas(f);
    for (JunctionTrace& tr : traces_) {
      tr.t_s.push_back(s.t);
      tr.X_m.push_back(s.X);
      tr.f_N.push_back(f[tr.junction]);
      tr.A_m2.push_back(A[tr.junction]);
    }
    ++k_;
  }
  void extremum(const Extremum&) {}
  void population(const PopulationChange& c) {
    const auto& pinned = stepper_.junctions().state().pinned;
    for (JunctionTrace& tr : traces_)
      if (std::isnan(tr.first_slip_s) && !pinned[tr.junction]) tr.first_slip_s = c.t;
  }
  bool done() const { return false; }
  double next_sample_time() const { return k_ <= n_ ? t_end_ * k_ / n_ : HUGE_VAL; }

 private:
  InteractingEventStepper& stepper_;
  std::vector<JunctionTrace>& traces_;
  double t_end_;
  int n_, k_ = 0;
};

// The data block of pair k, model m (0: interacting), neighbourhood sp (1: sparse).
std::string block_name(std::size_t k, int m, int sp) {
  std::string name = "p";
  name += std::to_string(k);
  name += m == 0 ? 'i' : 'n';
  name += sp ? 's' : 'c';
  return name;
}

// Linear interpolation of a trace's values at time t (NaN outside the record).
double at(const std::vector<double>& t, const std::vector<double>& v, double x) {
  if (t.empty() || !(x >= t.front()) || !(x <= t.back())) return NAN;
  const auto it = std::lower_bound(t.begin(), t.end(), x);
  const std::size_t j = static_cast<std::size_t>(it - t.begin());
  if (j == 0) return v[0];
  const double w = (x - t[j - 1]) / (t[j] - t[j - 1]);
  return v[j - 1] + w * (v[j] - v[j - 1]);
}

}  // namespace

std::vector<JunctionTrace> trace_junctions(const Scene& scene, const std::vector<std::size_t>& junctions,
                                           double t_end_s, int n_samples) {
  Scene s = scene;
  s.stop.at_first_peak = false;
  s.stop.cycles = 0;
  s.stop.time = t_end_s;
  s.output.series.clear();
  const Problem p = make_problem(s);
  std::vector<JunctionTrace> traces(junctions.size());
  for (std::size_t k = 0; k < junctions.size(); ++k) traces[k].junction = junctions[k];
  InteractingEventStepper stepper(p);
  TraceObserver obs(stepper, traces, t_end_s, n_samples);
  integrate(stepper, p, obs);
  return traces;
}

std::vector<JunctionPair> crowded_sparse_pairs(std::vector<std::size_t> candidates, const std::vector<double>& crowding,
                                               std::size_t n_pairs) {
  std::sort(candidates.begin(), candidates.end(), [&](std::size_t a, std::size_t b) {
    return crowding[a] > crowding[b] || (crowding[a] == crowding[b] && a < b);
  });
  std::vector<JunctionPair> pairs;
  for (std::size_t k = 0; k < n_pairs && 2 * k + 1 < candidates.size(); ++k)
    pairs.push_back({candidates[k], candidates[candidates.size() - 1 - k]});
  return pairs;
}

namespace {

// The trace of one junction of pair `pair`: crowded or sparse, interacting or independent.
const JunctionTrace& trace_of(const JunctionPairsEvidence& e, bool interacting, std::size_t pair, bool sparse) {
  return (interacting ? e.interacting : e.independent)[2 * pair + (sparse ? 1 : 0)];
}

// junction_pairs.csv: long format, one row per junction, model and sample.
void write_pairs_csv(const fs::path& out, const JunctionPairsEvidence& e) {
  const std::size_t P = e.pairs.size();
  std::ostringstream t;
  t << "pair,neighbourhood,junction,A0_m2,crowding,model,t_s,f_N,A_m2,f_over_sigmaA,A_over_A0\n";
  for (std::size_t k = 0; k < P; ++k)
    for (int m = 0; m < 2; ++m)
      for (int sp = 0; sp < 2; ++sp) {
        const JunctionTrace& tr = trace_of(e, m == 0, k, sp == 1);
        const double A0 = e.A0_m2[tr.junction];
        for (std::size_t j = 0; j < tr.t_s.size(); ++j)
          t << k + 1 << ',' << (sp ? "sparse" : "crowded") << ',' << tr.junction + 1 << ',' << io::csv_number(A0) << ','
            << io::csv_number(e.crowding[tr.junction]) << ',' << (m == 0 ? "interacting" : "independent") << ','
            << io::csv_number(tr.t_s[j]) << ',' << io::csv_number(tr.f_N[j]) << ',' << io::csv_number(tr.A_m2[j]) << ','
            << io::csv_number(tr.f_N[j] / (e.sigma_Pa * tr.A_m2[j])) << ',' << io::csv_number(tr.A_m2[j] / A0) << '\n';
      }
  io::write_text_file(out / "junction_pairs.csv", t.str());
}

// The plot command of one panel (column 2: f/(σA0), 3: A/A0) over every trace's data block.
// The curves carry no key entry of their own (twelve near-identical ones could not be read): the
// top panel's key names each pair by its colour, then the four line styles in black.
std::string plot_command(const JunctionPairsEvidence& e, int column) {
  const std::size_t P = e.pairs.size();
  const char* colours[] = {"#1b6ca8", "#c0392b", "#27ae60", "#8e44ad", "#d68910"};
  std::ostringstream c;
  c << "plot ";
  bool first = true;
  for (std::size_t k = 0; k < P; ++k)
    for (int m = 0; m < 2; ++m)
      for (int sp = 0; sp < 2; ++sp) {
        const std::string name = block_name(k, m, sp);
        c << (first ? "" : ", ") << "$" << name << " using 1:" << column << " with lines lw " << (m == 0 ? 2 : 1)
          << " dt " << (sp ? 2 : 1) << " lc rgb '" << colours[k % 5] << "' notitle";
        first = false;
      }
  if (column != 2) return c.str();
  for (std::size_t k = 0; k < P; ++k)
    c << ", keyentry with lines lw 4 lc rgb '" << colours[k % 5] << "' title "
      << gnuplot_text("pair " + std::to_string(k + 1) + ": #" + std::to_string(e.pairs[k].crowded + 1) + ", #" +
                      std::to_string(e.pairs[k].sparse + 1));
  for (int m = 0; m < 2; ++m)
    for (int sp = 0; sp < 2; ++sp)
      c << ", keyentry with lines lw " << (m == 0 ? 2 : 1) << " dt " << (sp ? 2 : 1) << " lc rgb 'black' title "
        << gnuplot_quote(std::string(m == 0 ? "interacting, " : "independent, ") + (sp ? "sparse" : "crowded"));
  return c.str();
}

// The figure's script: f/(σA0) and A/A0 against t of each model; crowded solid, sparse dashed;
// the independent model thin.
std::string pairs_plot(const JunctionPairsEvidence& e) {
  const std::size_t P = e.pairs.size();
  std::ostringstream gp;
  for (std::size_t k = 0; k < P; ++k)
    for (int m = 0; m < 2; ++m)
      for (int sp = 0; sp < 2; ++sp) {
        const JunctionTrace& tr = trace_of(e, m == 0, k, sp == 1);
        const double A0 = e.A0_m2[tr.junction];
        std::vector<std::vector<double>> rows;
        for (std::size_t j = 0; j < tr.t_s.size(); ++j)
          rows.push_back({tr.t_s[j], tr.f_N[j] / (e.sigma_Pa * A0), tr.A_m2[j] / A0});
        gp << gnuplot_block(block_name(k, m, sp), rows);
      }
  gp << stand_in_mark(e.stand_in) << "set multiplot layout 2,1 title "
     << gnuplot_quote(enhanced_literal(e.experiment) +
                      ": equal-area junction pairs, crowded (solid) vs sparse (dashed)")
     << " . \"\\n\" . "
     << gnuplot_quote("thick: interacting, thin: independent; dotted: the first peaks")
     // Both panels share their margins (the key sits right of the first only), so their t axes align.
     << "\nset key outside right top\nset lmargin at screen 0.08\nset rmargin at screen 0.76\nset grid\nset xlabel "
     << gnuplot_quote(axis_markup("t")) << "\n"
     << "set ylabel 'f_i / (σ A_{0,i}) [1]'\n"
     << "set arrow from " << io::csv_number(e.t_peak_interacting_s) << ", graph 0 to "
     << io::csv_number(e.t_peak_interacting_s) << ", graph 1 nohead dt 3 lc rgb 'black'\n"
     << "set arrow from " << io::csv_number(e.t_peak_independent_s) << ", graph 0 to "
     << io::csv_number(e.t_peak_independent_s) << ", graph 1 nohead dt 3 lc rgb 'gray50'\n"
     << plot_command(e, 2) << "\nset ylabel 'A_i / A_{0,i} [1]'\n"
     << plot_command(e, 3) << "\nunset multiplot\n";
  return gp.str();
}

// REPORT.md's section: each junction's first slip and its f/(σA) and A/A0 around the peaks.
std::string pairs_section(const JunctionPairsEvidence& e, const std::string& note) {
  const std::size_t P = e.pairs.size();
  std::ostringstream md;
  md << "## Junction pairs in time (" << e.experiment << ")\n\n"
     << "The same argument followed in time: " << P
     << " pairs of junctions of equal area, the k-th most crowded with "
        "the k-th least crowded (crowding k_i Σ_j C_ij), their force and area from the start of loading to past the "
        "interacting model's first peak, in both models (the independent one through the same solver, the arrangement "
        "10⁶ times wider). First slip: the time each junction first reaches its threshold (t_peak: "
     << io::format_cell("%.3f", e.t_peak_interacting_s) << " s interacting, "
     << io::format_cell("%.3f", e.t_peak_independent_s) << " s independent).\n\n"
     << "| pair | neighbourhood | junction | A0 [m²] | crowding | model | first slip [s] | first slip / t_peak | "
        "f/(σA) at ½ t_peak | f/(σA) at t_peak | A/A0 at t_peak |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t k = 0; k < P; ++k)
    for (int sp = 0; sp < 2; ++sp)
      for (int m = 0; m < 2; ++m) {
        const JunctionTrace& tr = trace_of(e, m == 0, k, sp == 1);
        const double tp = m == 0 ? e.t_peak_interacting_s : e.t_peak_independent_s;
        const double A0 = e.A0_m2[tr.junction];
        auto ratio = [&](double x) { return at(tr.t_s, tr.f_N, x) / (e.sigma_Pa * at(tr.t_s, tr.A_m2, x)); };
        md << "| " << k + 1 << " | " << (sp ? "sparse" : "crowded") << " | " << tr.junction + 1 << " | "
           << io::format_cell("%.4g", A0) << " | " << io::format_cell("%.2f", e.crowding[tr.junction]) << " | "
           << (m == 0 ? "interacting" : "independent") << " | " << io::format_cell("%.3f", tr.first_slip_s) << " | "
           << io::format_cell("%.3f", tr.first_slip_s / tp) << " | " << io::format_cell("%.3f", ratio(0.5 * tp))
           << " | " << io::format_cell("%.3f", ratio(tp)) << " | "
           << io::format_cell("%.4f", at(tr.t_s, tr.A_m2, tp) / A0) << " |\n";
      }
  md << "\n![junction pairs](junction_pairs.png)\n\n"
     << (note.empty() ? "" : note + "\n\n")
     << "Every sample of every junction above: `junction_pairs.csv` (f/(σA) = 1 at the threshold; a slipping "
        "junction carries ε times it).\n\n";
  return md.str();
}

}  // namespace

std::string write_junction_pairs(const fs::path& out, const JunctionPairsEvidence& e, const FigureFormats& formats) {
  write_pairs_csv(out, e);
  std::string error, note;
  if (!render_figures(out / "junction_pairs.png", pairs_plot(e), 1200, 1000, formats, &error))
    note = "junction_pairs.png not drawn: " + error;
  return pairs_section(e, note);
}

}  // namespace asperity
