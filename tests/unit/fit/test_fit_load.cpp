// Fit files: every bad input is an InputError naming the fit file, line and key.
#include <catch2/catch.hpp>
#include <string>

#include "fit/fit_load.hpp"
#include "fit_support.hpp"

using namespace asperity;
using namespace asperity::testing;

namespace {

// A fit case folder shared by these tests (built once: one model run; removed at exit).
struct SharedCase {
  FitCase c = make_fit_case("load", 0.725e-15, 1.5, 0.1, 40);
  ~SharedCase() {
    std::error_code ec;
    std::filesystem::remove_all(c.dir, ec);
  }
};

const FitCase& shared_case() {
  static const SharedCase s;
  return s.c;
}

const char* kGood =
    "objective: quadratic_alpha\n"                                         // 1
    "experiments: [scene.yaml]\n"                                          // 2
    "parameters:\n"                                                        // 3
    "  model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 7e-16, scale: log}\n"  // 4
    "optimizer: {algorithm: LN_BOBYQA}\n";                                 // 5

// The InputError of loading `text` as a fit file in the case folder.
io::InputError load_error(const std::string& text) {
  const auto f = write_text(shared_case().dir / "bad.yaml", text);
  try {
    load_fit(f);
  } catch (const io::InputError& e) {
    return e;
  }
  FAIL("no InputError for:\n" << text);
  throw;
}

std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("A valid fit file loads with its values", "[fit][load]") {
  const FitSpec s = load_fit(write_text(shared_case().dir / "good.yaml", kGood));
  CHECK(s.name == "good");
  CHECK(s.objective == FitObjective::quadratic_alpha);
  REQUIRE(s.parameters.size() == 1);
  CHECK(s.parameters[0].key == "model.alpha_b");
  CHECK(s.parameters[0].lo == 1e-16);
  CHECK(s.parameters[0].log_scale);
  REQUIRE(s.experiments.size() == 1);
  CHECK(s.experiments[0].name == "fit-load");
  // The objective's forced settings are in the scene the fit runs.
  const Scene sc = s.experiments[0].scene.build({{"model.alpha_b", 3e-16}});
  CHECK(sc.stop.at_first_peak);
  CHECK(sc.output.series.empty());
  CHECK(sc.model.alpha_b == 3e-16);
}

TEST_CASE("Building a scene variant leaves the template unchanged", "[fit][load]") {
  const SceneTemplate t = SceneTemplate::load(shared_case().dir / "scene.yaml");
  const double E0 = t.build().experiment.E;
  const double alpha0 = t.build().model.alpha_b;
  CHECK(E0 == 1.6e6);  // the experiment file's value
  CHECK(t.build({{"experiment.E", 1.7e6}, {"model.alpha_b", 3e-16}}).experiment.E == 1.7e6);
  CHECK(t.build().experiment.E == E0);
  CHECK(t.build().model.alpha_b == alpha0);
  CHECK(t.build({{"experiment.E", 1.5e6}}).experiment.E == 1.5e6);
  CHECK(t.build().experiment.E == E0);
  // Loading a fit checks its bounds and error bars by building variants: still unchanged.
  const FitSpec s =
      load_fit(write_text(shared_case().dir / "eb.yaml", std::string(kGood) + "error_bars: {experiment.E: 0.1e6}\n"));
  CHECK(s.experiments[0].scene.build().experiment.E == E0);
  CHECK(s.experiments[0].scene.build().model.alpha_b == alpha0);
}

TEST_CASE("Fit file errors name file, line and key", "[fit][load]") {
  SECTION("unknown key") {
    const io::InputError e = load_error(std::string(kGood) + "optimiser: {}\n");
    CHECK(e.line == 6);
    CHECK(e.key == "optimiser");
    CHECK(e.message.find("did you mean 'optimizer'") != std::string::npos);
  }
  SECTION("lo >= hi") {
    const io::InputError e = load_error(with(kGood, "hi: 5e-15", "hi: 1e-16"));
    CHECK(e.line == 4);
    CHECK(e.key == "parameters.model.alpha_b.hi");
  }
  SECTION("start outside the bounds") {
    const io::InputError e = load_error(with(kGood, "start: 7e-16", "start: 7e-15"));
    CHECK(e.line == 4);
    CHECK(e.key == "parameters.model.alpha_b.start");
  }
  SECTION("log scale with lo <= 0") {
    const io::InputError e = load_error(with(kGood, "lo: 1e-16", "lo: 0"));
    CHECK(e.key == "parameters.model.alpha_b.scale");
  }
  SECTION("unknown parameter key") {
    const io::InputError e = load_error(with(kGood, "model.alpha_b:", "model.alpha:"));
    CHECK(e.line == 4);
    CHECK(e.message.find("did you mean 'model.alpha_b'") != std::string::npos);
  }
  SECTION("unknown algorithm") {
    const io::InputError e = load_error(with(kGood, "LN_BOBYQA", "LN_BOBYQUA"));
    CHECK(e.line == 5);
    CHECK(e.key == "optimizer.algorithm");
    CHECK(e.message.find("did you mean 'LN_BOBYQA'") != std::string::npos);
  }
  SECTION("gradient-based algorithm") {
    const io::InputError e = load_error(with(kGood, "LN_BOBYQA", "LD_MMA"));
    CHECK(e.message.find("gradients") != std::string::npos);
  }
  SECTION("algorithm that needs two variables") {
    const io::InputError e = load_error(with(kGood, "LN_BOBYQA", "LN_NEWUOA_BOUND"));
    CHECK(e.line == 5);
    CHECK(e.message.find("1 free variable") != std::string::npos);
  }
  SECTION("a bound the scene rejects") {
    const io::InputError e = load_error(with(kGood, "model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 7e-16, scale: log}",
                                             "model.epsilon: {lo: 0.5, hi: 1.5, start: 0.9}"));
    CHECK(e.line == 4);
    CHECK(e.key == "parameters.model.epsilon.hi");
    CHECK(e.message.find("(0, 1]") != std::string::npos);
  }
  SECTION("objective needs a measured curve") {
    write_text(shared_case().dir / "nomeas.yaml",
               "name: no-measured\nmass: 0.1\nk_L: 9200\nv: 1e-4\nE: 1.6e6\nnu: 0.5\nsigma_exp: 0.23e6\njunctions: "
               "junctions.csv\n");
    write_text(shared_case().dir / "nomeas_scene.yaml", "experiment: nomeas.yaml\n");
    const io::InputError e = load_error(with(kGood, "[scene.yaml]", "[nomeas_scene.yaml]"));
    CHECK(e.line == 2);
    CHECK(e.message.find("needs a measured A(Q) curve") != std::string::npos);
  }
  SECTION("stick_slip needs targets") {
    const io::InputError e = load_error(with(kGood, "quadratic_alpha", "stick_slip"));
    CHECK(e.line == 2);
    CHECK(e.message.find("target") != std::string::npos);
  }
  SECTION("target only with stick_slip") {
    const io::InputError e =
        load_error(with(kGood, "[scene.yaml]", "[{scene: scene.yaml, target: {drop: 0.1, period: 0.1}}]"));
    CHECK(e.key == "experiments[0].target");
  }
  SECTION("missing scene file") {
    const io::InputError e = load_error(with(kGood, "[scene.yaml]", "[nothere.yaml]"));
    CHECK(e.line == 2);
    CHECK(e.message.find("not found") != std::string::npos);
  }
  SECTION("a bad value in set names the fit file") {
    const io::InputError e = load_error(with(kGood, "[scene.yaml]", "[{scene: scene.yaml, set: {model.eta: -3}}]"));
    CHECK(e.line == 2);
    CHECK(e.file.find("bad.yaml") != std::string::npos);
  }
  SECTION("error bar on a free parameter") {
    const io::InputError e = load_error(std::string(kGood) + "error_bars: {model.alpha_b: 1e-16}\n");
    CHECK(e.line == 6);
  }
  SECTION("error bar in wrong units") {
    const io::InputError e = load_error(std::string(kGood) + "error_bars: {experiment.E: 0.1 MPa}\n");
    CHECK(e.key == "error_bars.experiment.E");
    CHECK(e.message.find("Pa") != std::string::npos);
  }
  SECTION("per_experiment with separate fits") {
    const io::InputError e =
        load_error(with(std::string(kGood) + "separate: true\n", "scale: log", "per_experiment: true"));
    CHECK(e.key == "parameters.model.alpha_b.per_experiment");
  }
  SECTION("profile of a parameter that is not free") {
    const io::InputError e = load_error(std::string(kGood) + "profile: {parameter: model.p}\n");
    CHECK(e.key == "profile.parameter");
  }
}

TEST_CASE("NLopt algorithm names are checked against NLopt's own list", "[fit][load]") {
  // Names from the NLopt manual: derivative-free ones pass, the rest are refused with a reason.
  CHECK(check_fit_algorithm("LN_BOBYQA").empty());
  CHECK(check_fit_algorithm("GN_DIRECT_L").empty());
  CHECK(check_fit_algorithm("LN_BOBYQUA").find("did you mean 'LN_BOBYQA'") != std::string::npos);
  CHECK(check_fit_algorithm("LD_LBFGS").find("gradients") != std::string::npos);
  CHECK(check_fit_algorithm("LN_AUGLAG").find("subsidiary") != std::string::npos);
  // Not names at all (nlopt_algorithm_from_string answers -1, not an enum value: found by fuzz_fit).
  CHECK(check_fit_algorithm("").find("unknown") != std::string::npos);
  CHECK(check_fit_algorithm(std::string("LN_BOBYQA\0x", 11)).find("unknown") != std::string::npos);
}
