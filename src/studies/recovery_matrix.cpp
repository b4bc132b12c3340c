#include "studies/recovery_matrix.hpp"
#include "studies/study_file.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>

#include "fit/fit.hpp"
#include "fit/fit_load.hpp"
#include "generate/synthetic.hpp"
#include "generate/synthetic_recipe.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"
#include "scene/scene_keys.hpp"

namespace asperity {
namespace fs = std::filesystem;

const char* row_decision_name(RowDecision d) {
  switch (d) {
    case RowDecision::diagonal_wins:
      return "diagonal wins";
    case RowDecision::off_diagonal_wins:
      return "off-diagonal wins";
    case RowDecision::undecided:
      return "undecided";
    case RowDecision::no_evidence:
      return "no evidence";
  }
  return "?";
}

RowDecision decide_row(const RecoveryCell& diagonal, const RecoveryCell& off_diagonal) {
  if (!diagonal.certified() || !off_diagonal.certified() || diagonal.residuals <= 0 ||
      !std::isfinite(diagonal.objective) || !std::isfinite(off_diagonal.objective))
    return RowDecision::no_evidence;
  const double scatter = 2.0 * std::sqrt(2.0 * diagonal.residuals);
  const double gap = off_diagonal.objective - diagonal.objective;
  if (gap > scatter) return RowDecision::diagonal_wins;
  if (-gap > scatter) return RowDecision::off_diagonal_wins;
  return RowDecision::undecided;
}

std::vector<LoadVerdict> judge_loads(const std::vector<RecoveryCell>& cells) {
  std::vector<std::string> loads, models;
  for (const RecoveryCell& c : cells) {
    if (std::find(loads.begin(), loads.end(), c.load) == loads.end()) loads.push_back(c.load);
    for (const std::string* m : {&c.data_model, &c.fit_model})
      if (std::find(models.begin(), models.end(), *m) == models.end()) models.push_back(*m);
  }
  auto find = [&](const std::string& load, const std::string& data, const std::string& fit) -> const RecoveryCell* {
    for (const RecoveryCell& c : cells)
      if (c.load == load && c.data_model == data && c.fit_model == fit) return &c;
    return nullptr;
  };
  std::vector<LoadVerdict> out;
  for (const std::string& load : loads) {
    LoadVerdict v;
    v.load = load;
    bool all_diagonal = true, missing = false;
    for (const std::string& data : models) {
      const RecoveryCell* diag = find(load, data, data);
      if (diag) v.mass_kg = diag->mass_kg;
      for (const std::string& fit : models) {
        if (fit == data) continue;
        const RecoveryCell* off = find(load, data, fit);
        const RowDecision d = diag && off ? decide_row(*diag, *off) : RowDecision::no_evidence;
        v.rows.push_back(data + " data: " + row_decision_name(d));
        if (d == RowDecision::no_evidence) missing = true;
        if (d != RowDecision::diagonal_wins) all_diagonal = false;
      }
    }
    v.verdict = missing ? "no evidence" : all_diagonal ? "tells the models apart" : "cannot tell them apart";
    out.push_back(std::move(v));
  }
  return out;
}

namespace {

// The 1-based line of a top-level key in YAML text (0 when absent), for messages about it.
int line_of_key(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (line.rfind(key + ":", 0) == 0) return n;
  return 0;
}

std::string model_label(const std::vector<RecoveryModel>& models, const std::string& interactions) {
  for (const RecoveryModel& m : models)
    if (m.interactions == interactions) return m.label;
  return interactions;
}

// The budget a cell's fit spends: equal across models, or the matrix compares searches.
std::string budget_text(const FitSpec& s) {
  return s.algorithm + " " + std::to_string(s.max_evaluations) + ", polish " +
         (s.polish_algorithm.empty() ? "none" : s.polish_algorithm + " " + std::to_string(s.polish_max_evaluations)) +
         ", starts " + std::to_string(s.starts) + ", xtol_rel " + io::format_double(s.xtol_rel);
}

// The template's text with the cell's name and experiment appended (so that its own lines keep
// their numbers in any message about them).
std::string cell_fit_text(const std::string& template_text, const std::string& name, const std::string& data_rel,
                          const std::string& interactions) {
  std::string t = template_text;
  if (!t.empty() && t.back() != '\n') t += '\n';
  return t + "# Added by the recovery study: this cell's data.\nname: " + name +
         "\nexperiments:\n  - {scene: " + data_rel + "/scene.yaml, force: " + data_rel +
         "/measured_Qt.csv, set: {model.interactions: " + interactions + "}}\n";
}

RecoveryCell fit_cell(const FitSpec& spec, const SyntheticRecipe& recipe, const RecoveryMatrixOptions& opt) {
  RecoveryCell c;
  const auto t0 = std::chrono::steady_clock::now();
  FitOptions fo;
  fo.threads = opt.threads;
  fo.profile = false;
  fo.error_bars = true;  // the Hessian's intervals (the templates have no error-bar refits)
  const FitResult r = run_fit(spec, fo);
  const Optimization& o = r.fits.at(0);
  c.status = o.ok() ? "ok" : "failed: " + o.failure;
  c.objective = o.objective;
  c.converged = converged_name(o.converged);
  c.in_best_basin = o.in_best_basin;
  c.starts = static_cast<int>(o.starts.size());
  c.evaluations = o.evaluations;
  c.free_parameters = static_cast<int>(o.variables.size());
  if (!o.best_runs.empty()) c.residuals = o.best_runs[0].terms.count();
  for (std::size_t i = 0; i < o.variables.size(); ++i) {
    RecoveryParameter p;
    p.key = spec.parameters[o.variables[i].parameter].key;
    p.value = o.best[i];
    if (o.uncertainty.computed && i < o.uncertainty.sigma.size()) p.sigma = o.uncertainty.sigma[i];
    p.truth = scene_value(recipe.scene, p.key);
    c.parameters.push_back(p);
  }
  c.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return c;
}

// J at the truth: the same spec, one evaluation started at the generating values.
double objective_at_truth(FitSpec spec, const SyntheticRecipe& recipe, int threads) {
  for (FitParameter& p : spec.parameters) p.start = scene_value(recipe.scene, p.key);
  // One evaluation of a local algorithm is the objective at its start (fit.cpp); a global one,
  // the template's DIRECT, would evaluate the box's centre instead.
  spec.algorithm = "LN_NELDERMEAD";
  spec.max_evaluations = 1;
  spec.polish_algorithm.clear();
  spec.starts = 1;
  spec.intervals = false;
  FitOptions fo;
  fo.threads = threads;
  fo.profile = false;
  fo.error_bars = false;
  const FitResult r = run_fit(spec, fo);
  return r.fits.at(0).objective;
}

const char* kColumns =
    "load,mass_kg,junctions,data_model,fit_model,status,objective,objective_at_truth,residuals,free_parameters,"
    "reduced_chi2,converged,in_best_basin,starts,evaluations,wall_s";
const char* kParameterKeys[] = {"model.alpha_b", "model.epsilon", "model.eta", "model.position_scale"};

void write_matrix_csv(const fs::path& file, const std::vector<RecoveryCell>& cells, const std::string& command) {
  std::ostringstream t;
  t << "# SYNTHETIC experiments (examples/recovery/), each fitted by each model: `" << command << "`\n" << kColumns;
  for (const char* k : kParameterKeys) {
    const std::string leaf = std::string(k).substr(6);
    t << ',' << leaf << ',' << leaf << "_sigma," << leaf << "_truth";
  }
  t << '\n';
  for (const RecoveryCell& c : cells) {
    t << c.load << ',' << io::csv_number(c.mass_kg) << ',' << c.junctions << ',' << c.data_model << ',' << c.fit_model
      << ',' << io::csv_field(c.status) << ',' << io::csv_number(c.objective) << ','
      << io::csv_number(c.objective_at_truth) << ',' << c.residuals << ',' << c.free_parameters << ','
      << io::csv_number(c.reduced_chi2()) << ',' << c.converged << ',' << c.in_best_basin << ',' << c.starts << ','
      << c.evaluations << ',' << io::csv_number(c.wall_s);
    for (const char* k : kParameterKeys) {
      RecoveryParameter p;
      for (const RecoveryParameter& q : c.parameters)
        if (q.key == k) p = q;
      t << ',' << io::csv_number(p.value) << ',' << io::csv_number(p.sigma) << ',' << io::csv_number(p.truth);
    }
    t << '\n';
  }
  io::write_text_file(file, t.str());
}

// Diagonal cells: J ≤ J at truth (1 + 1e-3) and every parameter within 2σ of its truth.
std::string recovered_text(const RecoveryCell& c) {
  if (c.data_model != c.fit_model) return "–";
  if (!c.certified() || !std::isfinite(c.objective_at_truth)) return "no evidence";
  if (c.objective > c.objective_at_truth * (1 + 1e-3)) return "no (J above J at truth)";
  for (const RecoveryParameter& p : c.parameters) {
    if (!std::isfinite(p.sigma)) return "no evidence (no σ)";
    if (std::abs(p.value - p.truth) > 2 * p.sigma) return "no (" + p.key + " beyond 2σ)";
  }
  return "yes";
}

}  // namespace

std::vector<RecoveryCell> run_recovery_matrix(const RecoveryMatrixOptions& opt) {
  // Templates first (a bad one fails before any run), with equal budgets.
  std::vector<std::string> templates;
  for (const RecoveryModel& m : opt.models)
    templates.push_back(io::read_input_file(m.fit_template, m.fit_template.generic_string(), io::kMaxYamlBytes));
  fs::create_directories(opt.out / "data");
  fs::create_directories(opt.out / "fits");
  std::vector<RecoveryCell> cells;
  std::string first_budget;
  for (const fs::path& recipe_file : opt.recipes) {
    const SyntheticRecipe recipe = load_synthetic_recipe(recipe_file);
    const std::string load = recipe.scene.experiment.name;
    const std::string data_model =
        model_label(opt.models, recipe.scene.model.interactions == Interactions::elastic ? "elastic" : "none");
    const std::string data_dir = load + "_" + data_model;
    if (opt.log)
      *opt.log << "generating " << data_dir << " from " << recipe_file.generic_string() << "\n" << std::flush;
    const SyntheticExperiment x = build_synthetic(recipe);
    write_synthetic_experiment(recipe, x, opt.out / "data" / data_dir);
    // Every model's spec first: budgets that differ stop the study before any fit runs.
    std::vector<FitSpec> specs;
    for (std::size_t m = 0; m < opt.models.size(); ++m) {
      const RecoveryModel& model = opt.models[m];
      const std::string name = data_dir + "_by_" + model.label;
      const fs::path fit_file = opt.out / "fits" / (name + ".yaml");
      io::write_text_file(fit_file, cell_fit_text(templates[m], name, "../data/" + data_dir, model.interactions));
      specs.push_back(load_fit(fit_file));
      const std::string budget = budget_text(specs.back());
      if (first_budget.empty()) first_budget = budget;
      if (budget != first_budget)
        throw io::InputError(model.fit_template.generic_string(), line_of_key(templates[m], "optimizer"), "optimizer",
                             "budget " + budget + " differs from " + first_budget +
                                 " (the first template's): the matrix compares models at equal budgets");
    }
    for (std::size_t m = 0; m < opt.models.size(); ++m) {
      const RecoveryModel& model = opt.models[m];
      const FitSpec& spec = specs[m];
      if (opt.log) *opt.log << "fitting " << spec.name << " (" << first_budget << ")\n" << std::flush;
      RecoveryCell c = fit_cell(spec, recipe, opt);
      c.load = load;
      c.mass_kg = recipe.scene.experiment.mass_kg;
      c.junctions = static_cast<int>(recipe.scene.experiment.junctions.area_m2.size());
      c.data_model = data_model;
      c.fit_model = model.label;
      if (model.label == data_model) c.objective_at_truth = objective_at_truth(spec, recipe, opt.threads);
      if (opt.log)
        *opt.log << "  J = " << io::format_short(c.objective) << ", reduced chi2 " << io::format_short(c.reduced_chi2())
                 << ", converged " << c.converged << " (" << c.in_best_basin << " of " << c.starts << "), "
                 << io::format_cell("%.1f", c.wall_s) << " s\n"
                 << std::flush;
      cells.push_back(std::move(c));
      write_matrix_csv(opt.out / "matrix.csv", cells,
                       study_command(opt.study_file));  // after every cell: a killed study keeps what it fitted
    }
  }
  std::ostringstream md;
  md << "# The recovery matrix\n\n**SYNTHETIC DATA.** Each experiment here was made by one of the models at a known "
        "truth, with the noise its recipe states (the recipes: examples/recovery/ by default), then fitted by each "
        "model. It shows what the "
        "joint calibration can tell apart, not what the real experiments say.\n\n"
     << "Written by `" << study_command(opt.study_file) << "`; the budget of every fit: " << first_budget
     << ". Each cell's fit file is in `fits/`, its data in `data/`.\n\n";
  write_recovery_matrix_md(md, cells);
  io::write_text_file(opt.out / "REPORT.md", md.str());
  return cells;
}

void write_recovery_matrix_md(std::ostream& md, const std::vector<RecoveryCell>& cells) {
  if (cells.empty()) {
    md << "No recovery matrix: **no evidence** of what the joint method can tell apart.\n\n";
    return;
  }
  md << "Rule: a row (one synthetic data set) is won by the model that made it when its certified fit's J is lower "
        "than the other model's certified J by more than 2·sqrt(2N), twice the scatter a chi-square of its N "
        "residuals has from the noise alone; a fit that is not certified (fewer than two starts in its best basin) or "
        "failed leaves its row without evidence. The method tells the models apart at a load only where the diagonal "
        "wins on every row.\n\n";
  md << "| load | M [kg] | junctions | verdict | rows |\n|---|---|---|---|---|\n";
  for (const LoadVerdict& v : judge_loads(cells)) {
    int junctions = 0;
    for (const RecoveryCell& c : cells)
      if (c.load == v.load) junctions = c.junctions;
    md << "| " << v.load << " | " << io::format_short(v.mass_kg) << " | " << junctions << " | **" << v.verdict
       << "** | ";
    for (std::size_t i = 0; i < v.rows.size(); ++i) md << (i ? "; " : "") << v.rows[i];
    md << " |\n";
  }
  md << "\n| load | data by | fitted by | J | J at truth | N | reduced χ² | converged | α_b [1e-15] (truth) | ε "
        "(truth) | "
        "η [1/s] (truth) | position scale (truth) | recovered | status "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto param = [](const RecoveryCell& c, const char* key, double unit, const char* format) -> std::string {
    for (const RecoveryParameter& p : c.parameters)
      if (p.key == key) {
        std::string s = io::format_cell(format, p.value / unit);
        if (std::isfinite(p.sigma)) s += " ± " + io::format_cell(format, p.sigma / unit);
        return s + " (" + io::format_cell(format, p.truth / unit) + ")";
      }
    return "–";
  };
  for (const RecoveryCell& c : cells)
    md << "| " << c.load << " | " << c.data_model << " | " << c.fit_model << " | "
       << io::format_cell("%.6g", c.objective) << " | " << io::format_cell("%.6g", c.objective_at_truth) << " | "
       << c.residuals << " | " << io::format_cell("%.4g", c.reduced_chi2()) << " | " << c.converged << " ("
       << c.in_best_basin << " of " << c.starts << ") | " << param(c, "model.alpha_b", 1e-15, "%.4f") << " | "
       << param(c, "model.epsilon", 1, "%.4f") << " | " << param(c, "model.eta", 1, "%.2f") << " | "
       << param(c, "model.position_scale", 1, "%.4f") << " | " << recovered_text(c) << " | " << c.status << " |\n";
  md << "\n(± the Hessian's standard deviation where the fit gave one; J at truth: the generating model's objective at "
        "the generating values, on the diagonal only. A recovery holds where J ≤ J at truth (1 + 1e-3) and the truth "
        "lies within 2σ.)\n\n";
}

std::vector<RecoveryCell> read_recovery_matrix(const fs::path& file) {
  // A matrix is a few dozen cells; a wrong file stops at this many rows.
  const io::TextTable t = io::read_text_table(file, file.generic_string(), 10000);
  std::vector<RecoveryCell> cells;
  for (std::size_t r = 0; r < t.size(); ++r) {
    auto text = [&](const std::string& name) { return t.text(r, name); };
    // Quantities are written as measured (nan where a fit gave none); counts as whole numbers.
    auto number = [&](const std::string& name) { return t.measured(r, name); };
    auto count = [&](const std::string& name) {
      return static_cast<int>(std::min<std::int64_t>(t.count(r, name), 1 << 30));
    };
    RecoveryCell c;
    c.load = text("load");
    c.mass_kg = number("mass_kg");
    c.junctions = count("junctions");
    c.data_model = text("data_model");
    c.fit_model = text("fit_model");
    c.status = text("status");
    c.objective = number("objective");
    c.objective_at_truth = number("objective_at_truth");
    c.residuals = count("residuals");
    c.free_parameters = count("free_parameters");
    c.converged = text("converged");
    c.in_best_basin = count("in_best_basin");
    c.starts = count("starts");
    c.evaluations = count("evaluations");
    c.wall_s = number("wall_s");
    for (const char* k : kParameterKeys) {
      const std::string leaf = std::string(k).substr(6);
      RecoveryParameter p;
      p.key = k;
      p.value = number(leaf);
      p.sigma = number(leaf + "_sigma");
      p.truth = number(leaf + "_truth");
      if (std::isfinite(p.value)) c.parameters.push_back(p);
    }
    cells.push_back(std::move(c));
  }
  return cells;
}

}  // namespace asperity
