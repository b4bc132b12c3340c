#include "studies/joint_comparison.hpp"

#include <yaml-cpp/yaml.h>
#include <boost/math/distributions/chi_squared.hpp>

#include <algorithm>

#include "fit/objective.hpp"
#include "io/input_error.hpp"
#include "io/yaml_util.hpp"

namespace asperity {
namespace fs = std::filesystem;

double noise_rms_p95(double sd, int n) {
  if (n <= 0 || !(sd >= 0)) return ForceMisfit::nan;
  const double q = boost::math::quantile(boost::math::chi_squared_distribution<double>(n), 0.95);
  return sd * std::sqrt(q / n);
}

double rms_spread(double rms, double sd, int n) {
  if (n <= 0 || !(rms > 0) || !(sd >= 0)) return ForceMisfit::nan;
  const double d2 = std::max(rms * rms - sd * sd, 0.0);
  const double var_r2 = (4 * sd * sd * d2 + 2 * sd * sd * sd * sd) / n;
  return std::sqrt(var_r2) / (2 * rms);
}

ForceMisfit force_misfit(const std::vector<Sample>& series, const MeasuredForce& measured, double noise_relative) {
  ForceMisfit m;
  if (series.empty() || measured.t_s.empty()) return m;
  const std::vector<double> Q = model_force_at(series, measured.t_s);
  double s = 0, q_max = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < Q.size(); ++k) {
    const double r = Q[k] - measured.Q_N[k];
    s += r * r;
    q_max = std::max(q_max, measured.Q_N[k]);
  }
  m.n = static_cast<int>(Q.size());
  m.rms = std::sqrt(s / m.n);
  m.noise = noise_relative * q_max;
  m.noise_p95 = noise_rms_p95(m.noise, m.n);
  m.rms_sd = rms_spread(m.rms, m.noise, m.n);
  return m;
}

namespace {

double number_or_nan(const YAML::Node& n) {
  if (!n || !n.IsScalar()) return ForceMisfit::nan;
  try {
    return n.as<double>();
  } catch (const YAML::Exception&) {  // ".nan" and the like parse; anything else: no number
    return ForceMisfit::nan;
  }
}

}  // namespace

std::map<std::string, JointFitEntry> read_joint_fits(const std::vector<fs::path>& fit_yamls) {
  std::map<std::string, JointFitEntry> out;
  for (const fs::path& file : fit_yamls) {
    if (!fs::exists(file)) continue;
    try {
      const YAML::Node root = io::load_yaml_file(file, file.string());  // the hardened reader
      const std::string fit_file = root["fit_file"].as<std::string>("");
      for (const auto& f : root["fits"]) {
        JointFitEntry e;
        e.label = f["label"].as<std::string>();
        e.status = f["status"].as<std::string>("");
        e.failure = f["failure"].as<std::string>("");
        if (const auto have = out.find(e.label); have != out.end() && (have->second.status == "ok" || e.status != "ok"))
          continue;
        e.fit_yaml = file;
        e.fit_file = fit_file;
        e.objective = number_or_nan(f["objective"]);
        e.converged = f["converged"].as<std::string>("");
        e.in_best_basin = f["in_best_basin"].as<int>(0);
        e.starts = f["starts"].as<int>(0);
        for (const auto& p : f["parameters"]) {
          JointParameter jp;
          jp.value = number_or_nan(p.second["value"]);
          jp.at_bound = p.second["at_bound"].as<bool>(false);
          e.parameters[p.first.as<std::string>()] = jp;
        }
        const YAML::Node runs = f["runs"];  // (operator[] of a missing key's node would throw)
        const YAML::Node run = runs && runs.IsMap() ? runs[e.label] : YAML::Node();
        if (run && run.IsMap() && run["chi2"]) {
          const YAML::Node c = run["chi2"];
          e.chi2_area = number_or_nan(c["area"]);
          e.chi2_force = number_or_nan(c["force"]);
          e.n_area = c["n_area"].as<int>(0);
          e.n_force = c["n_force"].as<int>(0);
          e.n_residuals = e.n_area + e.n_force + c["n_cycles"].as<int>(0) + c["n_stick_slip"].as<int>(0);
        }
        if (const YAML::Node u = f["uncertainty"]) {
          e.reduced_chi2 = number_or_nan(u["reduced_chi2"]);
          if (e.failure.empty()) e.failure = u["failure"].as<std::string>("");
          for (const auto& p : u["parameters"]) {
            auto it = e.parameters.find(p.first.as<std::string>());
            if (it == e.parameters.end()) continue;
            it->second.sigma = number_or_nan(p.second["sigma"]);
            it->second.profile_sigma = number_or_nan(p.second["profile_sigma"]);
            if (const YAML::Node iv = p.second["interval95"]; iv && iv.IsSequence() && iv.size() == 2) {
              it->second.lo95 = number_or_nan(iv[0]);
              it->second.hi95 = number_or_nan(iv[1]);
            }
          }
        }
        out[e.label] = std::move(e);
      }
    } catch (const YAML::Exception& ex) {  // not a fit.yaml of `asperity fit`
      throw io::InputError(file.string(), ex.mark.is_null() ? 0 : ex.mark.line + 1, "fits", ex.msg);
    }
  }
  return out;
}

}  // namespace asperity
