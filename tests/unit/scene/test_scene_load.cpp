// src/scene: YAML scene/experiment files and CSVs → validated structs, and back.
#include <unistd.h>

#include <atomic>
#include <bit>
#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "scene/load.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using Catch::Matchers::Contains;

namespace {

const fs::path kData = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "scene";

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

using asperity::testing::write_text;

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) names.insert(e.path().string());
  return names;
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same_bits(a[i], b[i])) return false;
  return true;
}

// The fixture experiment as text, one key per line (line numbers below are relied upon):
// 1 name, 2 description, 3 mass, 4 k_L, 5 v, 6 E, 7 nu, 8 sigma_exp, 9 junctions, 10 measured.
std::string experiment_text(const std::map<std::string, std::string>& replace = {}) {
  const std::vector<std::pair<std::string, std::string>> lines{{"name", "small"},
                                                               {"description", "\"fixture\""},
                                                               {"mass", "0.1"},
                                                               {"k_L", "9200"},
                                                               {"v", "1.0e-4"},
                                                               {"E", "1.6e6"},
                                                               {"nu", "0.5"},
                                                               {"sigma_exp", "0.23e6"},
                                                               {"junctions", "junctions.csv"},
                                                               {"measured", "measured.csv"}};
  std::string s;
  for (const auto& [k, v] : lines) {
    auto it = replace.find(k);
    if (it == replace.end())
      s += k + ": " + v + "\n";
    else if (!it->second.empty())
      s += it->second + "\n";  // whole line replaced ("" drops it)
  }
  return s;
}

// A temporary folder holding a copy of the fixture experiment (exp/) and an empty out/ folder.
struct Sandbox {
  fs::path root;
  Sandbox() {
    static std::atomic<int> counter{0};
    root = fs::temp_directory_path() /
           ("asperity_test_scene_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(root);
    fs::create_directories(root / "out");
    for (const char* f : {"experiment.yaml", "junctions.csv", "measured.csv"})
      write_text(root / "exp" / f, read_text(kData / "exp_small" / f));
  }
  ~Sandbox() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
  fs::path scene(const std::string& text, const std::string& name = "scene.yaml") const {
    write_text(root / name, text);
    return root / name;
  }
  fs::path file(const std::string& rel, const std::string& text) const {
    write_text(root / rel, text);
    return root / rel;
  }
};

// Runs `load`, which must throw InputError; checks that what() is one line holding every
// fragment, and that nothing was written (sandbox and fixture folder unchanged, out/ empty).
std::string expect_error(const Sandbox& box, const std::function<void()>& load,
                         const std::vector<std::string>& fragments) {
  const auto before = listing(box.root);
  const auto before_data = listing(kData);
  std::string what;
  bool thrown = false;
  try {
    load();
  } catch (const io::InputError& e) {
    thrown = true;
    what = e.what();
  }
  INFO("what(): " << what);
  REQUIRE(thrown);
  CHECK(what.find('\n') == std::string::npos);
  for (const auto& f : fragments) CHECK_THAT(what, Contains(f));
  CHECK(listing(box.root) == before);
  CHECK(listing(kData) == before_data);
  CHECK(fs::is_empty(box.root / "out"));
  return what;
}

// A scene in the sandbox: line 1 names the experiment, `rest` starts at line 2.
std::string expect_scene_error(const std::string& rest, const std::vector<std::string>& fragments) {
  Sandbox box;
  const fs::path s = box.scene("experiment: exp/experiment.yaml\n" + rest);
  return expect_error(
      box, [&] { load_scene(s); }, fragments);
}

// The sandbox experiment file rewritten with some lines replaced (see experiment_text).
std::string expect_experiment_error(const std::map<std::string, std::string>& replace,
                                    const std::vector<std::string>& fragments) {
  Sandbox box;
  box.file("exp/experiment.yaml", experiment_text(replace));
  const fs::path s = box.scene("experiment: exp/experiment.yaml\n");
  return expect_error(
      box, [&] { load_scene(s); }, fragments);
}

// The sandbox junction CSV replaced by `csv`.
std::string expect_junctions_error(const std::string& csv, const std::vector<std::string>& fragments) {
  Sandbox box;
  box.file("exp/junctions.csv", csv);
  const fs::path s = box.scene("experiment: exp/experiment.yaml\n");
  return expect_error(
      box, [&] { load_scene(s); }, fragments);
}

std::string expect_measured_error(const std::string& csv, const std::vector<std::string>& fragments) {
  Sandbox box;
  box.file("exp/measured.csv", csv);
  const fs::path s = box.scene("experiment: exp/experiment.yaml\n");
  return expect_error(
      box, [&] { load_scene(s); }, fragments);
}

std::string expect_override_error(const std::vector<std::string>& sets, const std::vector<std::string>& fragments) {
  Sandbox box;
  const fs::path s = box.scene("experiment: exp/experiment.yaml\n");
  return expect_error(
      box, [&] { load_scene(s, sets); }, fragments);
}

void check_same_scene(const Scene& a, const Scene& b) {
  const Experiment &x = a.experiment, &y = b.experiment;
  CHECK(x.name == y.name);
  CHECK(x.description == y.description);
  CHECK(x.file == y.file);
  CHECK(x.junctions_file == y.junctions_file);
  CHECK(x.measured_file == y.measured_file);
  CHECK(same_bits(x.mass_kg, y.mass_kg));
  CHECK(same_bits(x.k_L, y.k_L));
  CHECK(same_bits(x.v, y.v));
  CHECK(same_bits(x.E, y.E));
  CHECK(same_bits(x.nu, y.nu));
  CHECK(same_bits(x.sigma_exp, y.sigma_exp));
  CHECK(same_bits(x.junctions.area_m2, y.junctions.area_m2));
  CHECK(same_bits(x.junctions.x_m, y.junctions.x_m));
  CHECK(same_bits(x.junctions.y_m, y.junctions.y_m));
  REQUIRE(x.measured.has_value() == y.measured.has_value());
  if (x.measured) {
    CHECK(same_bits(x.measured->Q_N, y.measured->Q_N));
    CHECK(same_bits(x.measured->A_m2, y.measured->A_m2));
  }
  CHECK(same_bits(a.model.eta, b.model.eta));
  CHECK(same_bits(a.model.epsilon, b.model.epsilon));
  CHECK(same_bits(a.model.c_min, b.model.c_min));
  CHECK(same_bits(a.model.p, b.model.p));
  CHECK(same_bits(a.model.alpha_b, b.model.alpha_b));
  CHECK(a.model.junction_shape == b.model.junction_shape);
  CHECK(a.model.area_law == b.model.area_law);
  CHECK(a.solver.method == b.solver.method);
  CHECK(same_bits(a.solver.Ct, b.solver.Ct));
  CHECK(same_bits(a.solver.tolerance, b.solver.tolerance));
  CHECK(same_bits(a.stop.time, b.stop.time));
  CHECK(a.stop.at_first_peak == b.stop.at_first_peak);
  CHECK(a.stop.cycles == b.stop.cycles);
  CHECK(same_bits(a.output.every, b.output.every));
  CHECK(a.output.series == b.output.series);
  CHECK(same_bits(a.output.peak_min_drop, b.output.peak_min_drop));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Valid input

TEST_CASE("scene: fixture scene loads with its values and the paper's defaults", "[scene]") {
  const Scene s = load_scene(kData / "small_scene.yaml");
  const Experiment& e = s.experiment;
  CHECK(e.name == "small");
  CHECK(e.description == "Test fixture: five junctions, stand-in values");
  CHECK(e.mass_kg == 0.1);
  CHECK(e.k_L == 9200);
  CHECK(e.v == 1.0e-4);
  CHECK(e.E == 1.6e6);
  CHECK(e.nu == 0.5);
  CHECK(e.sigma_exp == 0.23e6);
  // Columns in the file are y_m, area_m2, x_m: read by name, not position.
  CHECK(e.junctions.area_m2 == std::vector<double>{1e-8, 2e-8, 1.5e-8, 3e-8, 5e-9});
  CHECK(e.junctions.x_m == std::vector<double>{0.002, 0.003, 0, -0.001, 0.0001});
  CHECK(e.junctions.y_m == std::vector<double>{0.001, -0.001, 0, 0.0005, 0});
  REQUIRE(e.measured.has_value());
  CHECK(e.measured->Q_N == std::vector<double>{0, 0.01, 0.02});
  CHECK(e.measured->A_m2 == std::vector<double>{7.5e-8, 7.4e-8, 7.1e-8});
  // Paths resolved, absolute.
  CHECK(s.experiment_ref == "exp_small/experiment.yaml");
  CHECK(s.file.is_absolute());
  CHECK(e.file == fs::weakly_canonical(kData / "exp_small" / "experiment.yaml"));
  CHECK(e.junctions_file == fs::weakly_canonical(kData / "exp_small" / "junctions.csv"));
  CHECK(e.measured_file == fs::weakly_canonical(kData / "exp_small" / "measured.csv"));
  // Given values.
  CHECK(s.model.eta == 50);
  CHECK(s.model.junction_shape == JunctionShape::circular);
  CHECK(s.solver.method == SolverMethod::reference);
  CHECK(s.solver.Ct == 200);
  CHECK(s.stop.time == 0.5);
  CHECK(s.stop.at_first_peak);
  CHECK(s.output.series == std::vector<std::string>{"t", "Q", "A"});
  // Defaults (the paper's values).
  CHECK(s.model.epsilon == 0.9);
  CHECK(s.model.c_min == 0.01);
  CHECK(s.model.p == 1.5);
  CHECK(s.model.alpha_b == 0.725e-15);
  CHECK(s.model.area_law == AreaLaw::until_first_slip);
  CHECK(s.solver.tolerance == 1e-9);
  CHECK(s.stop.cycles == -1);
  CHECK(s.output.every == 1e-3);
  CHECK(s.output.peak_min_drop == 0.02);
}

TEST_CASE("scene: a scene naming only the experiment gets every struct default", "[scene]") {
  Sandbox box;
  const Scene s = load_scene(box.scene("experiment: exp/experiment.yaml\n"));
  const Scene d;
  CHECK(s.model.eta == d.model.eta);
  CHECK(s.model.epsilon == d.model.epsilon);
  CHECK(s.model.c_min == d.model.c_min);
  CHECK(s.model.p == d.model.p);
  CHECK(s.model.alpha_b == d.model.alpha_b);
  CHECK(s.model.junction_shape == d.model.junction_shape);
  CHECK(s.model.area_law == d.model.area_law);
  CHECK(s.solver.method == d.solver.method);
  CHECK(s.solver.Ct == d.solver.Ct);
  CHECK(s.solver.tolerance == d.solver.tolerance);
  CHECK(s.stop.time == d.stop.time);
  CHECK(s.stop.at_first_peak == d.stop.at_first_peak);
  CHECK(s.stop.cycles == d.stop.cycles);
  CHECK(s.output.every == d.output.every);
  CHECK(s.output.series == d.output.series);
  CHECK(s.output.peak_min_drop == d.output.peak_min_drop);
  CHECK(s.experiment.junctions.size() == 5);
  CHECK(fs::is_empty(box.root / "out"));
}

TEST_CASE("scene: experiment map overrides the experiment file's values", "[scene]") {
  Sandbox box;
  const Scene s = load_scene(box.scene(
      "experiment: {file: exp/experiment.yaml, mass: 0.2, k_L: 9400, E: 1.7e6, sigma_exp: 0.25e6, v: 2e-4, nu: 0.45,\n"
      "             name: renamed}\n"));
  CHECK(s.experiment.mass_kg == 0.2);
  CHECK(s.experiment.k_L == 9400);
  CHECK(s.experiment.E == 1.7e6);
  CHECK(s.experiment.sigma_exp == 0.25e6);
  CHECK(s.experiment.v == 2e-4);
  CHECK(s.experiment.nu == 0.45);
  CHECK(s.experiment.name == "renamed");
  CHECK(s.experiment.junctions.size() == 5);
  CHECK(s.experiment_ref == "exp/experiment.yaml");
}

TEST_CASE("scene: scene_to_yaml -> file -> load_scene is bit-identical", "[scene]") {
  Sandbox box;
  const fs::path p = box.scene(
      "experiment: {file: exp/experiment.yaml, mass: 0.30000000000000004, k_L: 9400.000000000002,\n"
      "             v: 1.0000000000000002e-4, E: 1.7e6, nu: 0.49, sigma_exp: 0.25e6}\n"
      "model: {eta: 0.30000000000000004, epsilon: 0.8999999999999999, c_min: 1e-5, p: 1.4999999999999998,\n"
      "        alpha_b: 0.725e-15, junction_shape: circular, area_law: always}\n"
      "solver: {method: reference, Ct: 12345.678, tolerance: 3e-10}\n"
      "stop: {time: 0.7000000000000001, at_first_peak: true, cycles: 3}\n"
      "output: {every: 1.1e-3, series: [Q, t], peak_min_drop: 0.0023}\n");
  const Scene a = load_scene(p);
  CHECK(same_bits(a.experiment.mass_kg, 0.1 + 0.2));
  CHECK(same_bits(a.model.eta, 0.1 + 0.2));
  CHECK(same_bits(a.model.alpha_b, 0.725e-15));

  const std::string text = scene_to_yaml(a);
  CHECK_THAT(text, Contains("alpha_b: 7.25e-16"));
  CHECK_THAT(text, Contains("file: \"" + a.experiment.file.string() + "\""));
  const fs::path q = box.file("elsewhere/deeper/resolved.yaml", text);
  const Scene b = load_scene(q);
  check_same_scene(a, b);
  CHECK(scene_to_yaml(b) == text);  // a fixed point

  SECTION("defaults round-trip too") {
    const Scene c = load_scene(box.scene("experiment: exp/experiment.yaml\n", "plain.yaml"));
    const Scene d = load_scene(box.file("elsewhere/plain.yaml", scene_to_yaml(c)));
    check_same_scene(c, d);
  }
}

TEST_CASE("scene: overrides change values", "[scene]") {
  Sandbox box;
  box.file("other/experiment.yaml", experiment_text({{"name", "name: other"},
                                                     {"mass", "mass: 0.5"},
                                                     {"junctions", "junctions: ../exp/junctions.csv"},
                                                     {"measured", ""}}));
  const fs::path p = box.scene("experiment: exp/experiment.yaml\nmodel: {eta: 100}\n");
  const Scene s = load_scene(p, {"model.eta=50", "solver.Ct=200", "solver.method=reference", "experiment.mass=0.2",
                                 "output.series=[t,Q,A]", "stop.at_first_peak=true", "model.junction_shape=circular"});
  CHECK(s.model.eta == 50);
  CHECK(s.solver.Ct == 200);
  CHECK(s.solver.method == SolverMethod::reference);
  CHECK(s.experiment.mass_kg == 0.2);
  CHECK(s.experiment.name == "small");
  CHECK(s.output.series == std::vector<std::string>{"t", "Q", "A"});
  CHECK(s.stop.at_first_peak);
  CHECK(s.model.junction_shape == JunctionShape::circular);

  const Scene o = load_scene(p, {"experiment=other/experiment.yaml"});
  CHECK(o.experiment.name == "other");
  CHECK(o.experiment.mass_kg == 0.5);
  CHECK_FALSE(o.experiment.measured.has_value());
  CHECK(o.experiment.measured_file.empty());
  CHECK(o.experiment_ref == "other/experiment.yaml");

  // Later overrides win; the scene file itself is untouched.
  CHECK(load_scene(p, {"model.eta=1", "model.eta=2"}).model.eta == 2);
  CHECK(load_scene(p).model.eta == 100);
  CHECK(fs::is_empty(box.root / "out"));
}

TEST_CASE("scene: a scene given entirely by overrides validates like a file", "[scene]") {
  Sandbox box;
  const fs::path empty = box.scene("# nothing here\n", "empty.yaml");
  const Scene s = load_scene(empty, {"experiment=exp/experiment.yaml", "model.eta=75"});
  CHECK(s.model.eta == 75);
  CHECK(s.experiment.junctions.size() == 5);

  std::string from_set, from_file;
  try {
    load_scene(empty, {"experiment=exp/experiment.yaml", "model.epsilon=1.5"});
  } catch (const io::InputError& e) {
    from_set = e.message;
    CHECK(e.file == "--set model.epsilon=1.5");
    CHECK(e.key == "model.epsilon");
    CHECK(std::string(e.what()) == "--set model.epsilon=1.5: model.epsilon: must be in (0, 1], got 1.5");
  }
  try {
    load_scene(box.scene("experiment: exp/experiment.yaml\nmodel: {epsilon: 1.5}\n", "file.yaml"));
  } catch (const io::InputError& e) {
    from_file = e.message;
    CHECK(e.line == 2);
    CHECK(e.key == "model.epsilon");
  }
  CHECK_FALSE(from_set.empty());
  CHECK(from_set == from_file);
  expect_error(box, [&] { load_scene(empty); }, {"empty.yaml:1: experiment: missing required key"});
}

TEST_CASE("scene: apply_override and scene_from_tree build variants of one tree", "[scene]") {
  Sandbox box;
  const fs::path p = box.scene("experiment: exp/experiment.yaml\nmodel:\n  eta: 100\n  epsilon: 0.9\n");
  const YAML::Node base = load_scene_tree(p);
  const YAML::Node t1 = apply_override(base, "model.eta", YAML::Node(42.5));
  const YAML::Node t2 = apply_override(t1, "experiment.mass", YAML::Node(0.1 + 0.2));
  const YAML::Node t3 = apply_override(base, "model.alpha_b", YAML::Node(0.725e-15));
  CHECK(scene_from_tree(t1, p).model.eta == 42.5);
  const Scene s2 = scene_from_tree(t2, p);
  CHECK(s2.model.eta == 42.5);
  CHECK(same_bits(s2.experiment.mass_kg, 0.1 + 0.2));  // YAML::Node(double) keeps every bit
  CHECK(same_bits(scene_from_tree(t3, p).model.alpha_b, 0.725e-15));
  // The base tree is unchanged.
  const Scene s0 = scene_from_tree(base, p);
  CHECK(s0.model.eta == 100);
  CHECK(s0.experiment.mass_kg == 0.1);

  // Errors still name the origin file and key; untouched nodes keep their lines.
  const YAML::Node bad_value = apply_override(base, "model.eta", YAML::Node(-1.0));
  expect_error(box, [&] { scene_from_tree(bad_value, p); }, {"scene.yaml", "model.eta", "must be >= 0"});
  const YAML::Node bad_other = apply_override(base, "model.epsilon", YAML::Node(2.0));
  const YAML::Node t4 = apply_override(bad_other, "solver.Ct", YAML::Node(10.0));
  const std::string w = expect_error(box, [&] { scene_from_tree(t4, p); }, {"scene.yaml", "model.epsilon"});
  const YAML::Node bad_line = apply_override(base, "solver.Ct", YAML::Node(10.0));
  YAML::Node file_bad = load_scene_tree(box.scene("experiment: exp/experiment.yaml\nmodel:\n  eta: -3\n", "bad.yaml"));
  file_bad = apply_override(file_bad, "solver.Ct", YAML::Node(10.0));
  expect_error(box, [&] { scene_from_tree(file_bad, box.root / "bad.yaml"); }, {"bad.yaml:3: model.eta: must be >= 0"});
  expect_error(box, [&] { scene_from_tree(apply_override(base, "model.etaa", YAML::Node(1.0)), p); },
               {"scene.yaml", "model.etaa", "did you mean 'eta'"});
  // Setting inside a value is an error at once.
  expect_error(box, [&] { apply_override(base, "model.eta.x", YAML::Node(1.0)); }, {"model.eta.x", "not a map"});
}

TEST_CASE("scene: CSV writers give deterministic bytes that read back bit-identical", "[scene]") {
  Sandbox box;
  JunctionPopulation j;
  j.area_m2 = {1e-8, 0.1 + 0.2, 7.25e-16, 3.0000000000000004e-9};
  j.x_m = {0, -1.5e-3, 1.0 / 3.0, 2};
  j.y_m = {1, 2, 3, -4.4e-20};
  write_junctions_csv(box.root / "j.csv", j);
  const std::string bytes = read_text(box.root / "j.csv");
  CHECK(bytes.substr(0, 16) == "area_m2,x_m,y_m\n");
  CHECK_THAT(bytes, Contains("0.30000000000000004,"));
  const JunctionPopulation r = read_junctions_csv(box.root / "j.csv");
  CHECK(same_bits(r.area_m2, j.area_m2));
  CHECK(same_bits(r.x_m, j.x_m));
  CHECK(same_bits(r.y_m, j.y_m));
  write_junctions_csv(box.root / "j2.csv", r);
  CHECK(read_text(box.root / "j2.csv") == bytes);

  JunctionPopulation areas_only;
  areas_only.area_m2 = {2e-8, 1e-9};
  write_junctions_csv(box.root / "a.csv", areas_only);
  CHECK(read_text(box.root / "a.csv") == "area_m2\n2e-08\n1e-09\n");
  CHECK(read_junctions_csv(box.root / "a.csv").x_m.empty());

  MeasuredCurve m{{0, 0.1, 1.0 / 3.0}, {1e-5, 9.9e-6, 0.1 + 0.2}};
  write_measured_csv(box.root / "m.csv", m);
  const MeasuredCurve mr = read_measured_csv(box.root / "m.csv");
  CHECK(same_bits(mr.Q_N, m.Q_N));
  CHECK(same_bits(mr.A_m2, m.A_m2));
  CHECK_FALSE(fs::exists(box.root / "m.csv.tmp"));
}

TEST_CASE("scene: experiment_to_yaml writes a file load_experiment reads back exactly", "[scene]") {
  Sandbox box;
  Experiment e = load_experiment(box.root / "exp" / "experiment.yaml");
  fs::create_directories(box.root / "gen");
  e.name = "P4.00N";
  e.description = "Stand-in data: \"not measured\"\nsecond line";
  e.mass_kg = 0.1 + 0.2;
  e.sigma_exp = 0.23e6 / 0.9;
  write_junctions_csv(box.root / "gen" / "junctions.csv", e.junctions);
  write_measured_csv(box.root / "gen" / "measured.csv", *e.measured);
  const std::string text = experiment_to_yaml(e, "junctions.csv", "measured.csv");
  box.file("gen/experiment.yaml", text);
  const Experiment r = load_experiment(box.root / "gen" / "experiment.yaml");
  CHECK(r.name == e.name);
  CHECK(r.description == e.description);
  CHECK(same_bits(r.mass_kg, e.mass_kg));
  CHECK(same_bits(r.sigma_exp, e.sigma_exp));
  CHECK(same_bits(r.k_L, e.k_L));
  CHECK(same_bits(r.junctions.area_m2, e.junctions.area_m2));
  REQUIRE(r.measured.has_value());
  CHECK(same_bits(r.measured->A_m2, e.measured->A_m2));
  CHECK(experiment_to_yaml(r, "junctions.csv", "measured.csv") == text);
  CHECK(experiment_to_yaml(r, "junctions.csv", "").find("measured:") == std::string::npos);

  // Overrides through the public entry point.
  const YAML::Node ov = YAML::Load("{mass: 0.25, nu: 0.4}");
  const Experiment o = load_experiment(box.root / "gen" / "experiment.yaml", &ov);
  CHECK(o.mass_kg == 0.25);
  CHECK(o.nu == 0.4);
}

// ---------------------------------------------------------------------------------------------
// Bad input: one test per kind; each names file, line and key, and writes nothing.

TEST_CASE("scene error: malformed YAML", "[scene]") {
  expect_scene_error("model: {eta: 1\nsolver: {}\n", {"scene.yaml:3:", "malformed YAML: end of map flow not found"});
}

TEST_CASE("scene error: malformed experiment YAML", "[scene]") {
  expect_experiment_error({{"k_L", "k_L: [9200"}},
                          {"experiment.yaml:5:", "malformed YAML: end of sequence flow not found"});
}

TEST_CASE("scene error: unknown top-level key suggests the closest", "[scene]") {
  expect_scene_error("modle:\n  eta: 50\n", {"scene.yaml:2: modle: unknown key 'modle' (did you mean 'model'?)"});
}

TEST_CASE("scene error: unknown nested key", "[scene]") {
  const std::string w =
      expect_scene_error("model:\n  eta: 50\n  etaa: 3\n", {"scene.yaml:4: model.etaa:", "did you mean 'eta'"});
  CHECK_THAT(w, Contains("valid keys here: eta, epsilon"));
  expect_scene_error("output: {zzz: 1}\n", {"scene.yaml:2: output.zzz: unknown key 'zzz'; valid keys here"});
}

TEST_CASE("scene error: unknown key in the experiment file", "[scene]") {
  expect_experiment_error({{"mass", "masss: 0.1"}}, {"experiment.yaml:3: masss:", "did you mean 'mass'"});
}

TEST_CASE("scene error: unknown key in the experiment map", "[scene]") {
  Sandbox box;
  const fs::path s = box.scene("experiment: {file: exp/experiment.yaml, junctions: x.csv}\n");
  expect_error(box, [&] { load_scene(s); },
               {"scene.yaml:1: experiment.junctions: unknown key 'junctions'; valid keys here: file, name"});
}

TEST_CASE("scene error: duplicate key", "[scene]") {
  expect_scene_error("model:\n  eta: 50\n  eta: 60\n",
                     {"scene.yaml:4: model.eta: duplicate key (first given at line 3)"});
}

TEST_CASE("scene error: wrong types", "[scene]") {
  expect_scene_error("model: 5\n", {"scene.yaml:2: model: expected a map"});
  expect_scene_error("model: {eta: [1, 2]}\n", {"scene.yaml:2: model.eta: expected a number", "got a list"});
  expect_scene_error("stop:\n  at_first_peak: maybe\n", {"scene.yaml:3: stop.at_first_peak: expected true or false"});
  expect_scene_error("stop:\n  cycles: 2.5\n", {"scene.yaml:3: stop.cycles: expected an integer"});
  expect_scene_error("output:\n  series: t\n", {"scene.yaml:3: output.series: expected a list"});
  expect_experiment_error({{"name", "name: {a: 1}"}}, {"experiment.yaml:1: name: expected text, got a map"});
  Sandbox box;
  const fs::path s = box.scene("experiment: [a, b]\n");
  expect_error(box, [&] { load_scene(s); }, {"scene.yaml:1: experiment: expected the path of an experiment file"});
}

TEST_CASE("scene error: non-numeric value", "[scene]") {
  expect_scene_error("model:\n  eta: abc\n",
                     {"scene.yaml:3: model.eta: expected a number in SI units (1/s), got 'abc'"});
}

TEST_CASE("scene error: NaN value", "[scene]") {
  expect_scene_error("model: {epsilon: .nan}\n", {"scene.yaml:2: model.epsilon: must be a finite number"});
  expect_experiment_error({{"E", "E: nan"}}, {"experiment.yaml:6: E: must be a finite number"});
}

TEST_CASE("scene error: infinite value", "[scene]") {
  expect_scene_error("solver:\n  Ct: .inf\n", {"scene.yaml:3: solver.Ct: must be a finite number"});
  expect_scene_error("stop:\n  time: 1e999\n", {"scene.yaml:3: stop.time: must be a finite number"});
}

TEST_CASE("scene error: numbers with units are rejected", "[scene]") {
  expect_experiment_error({{"E", "E: 1.6 MPa"}},
                          {"experiment.yaml:6: E: expected a plain number in SI units (Pa), got '1.6 MPa'"});
}

TEST_CASE("scene error: units in the experiment map name the scene", "[scene]") {
  Sandbox box;
  const fs::path s = box.scene("# study\nexperiment: {file: exp/experiment.yaml, mass: 100 g}\n");
  expect_error(box, [&] { load_scene(s); },
               {"scene.yaml:2: experiment.mass: expected a plain number in SI units (kg), got '100 g'"});
}

TEST_CASE("scene error: missing experiment key", "[scene]") {
  Sandbox box;
  const fs::path s = box.scene("# a scene\nmodel: {eta: 50}\n");
  expect_error(box, [&] { load_scene(s); }, {"scene.yaml:2: experiment: missing required key"});
}

TEST_CASE("scene error: missing required experiment value", "[scene]") {
  expect_experiment_error({{"k_L", ""}}, {"experiment.yaml:1: k_L: missing required key"});
  expect_experiment_error({{"junctions", ""}}, {"experiment.yaml:1: junctions: missing required key"});
  Sandbox box;
  const fs::path s = box.scene("experiment: {mass: 0.2}\n");
  expect_error(box, [&] { load_scene(s); }, {"scene.yaml:1: experiment.file: missing required key"});
}

TEST_CASE("scene error: missing value", "[scene]") {
  expect_scene_error("model:\n  eta:\n", {"scene.yaml:3: model.eta: missing value"});
}

TEST_CASE("scene error: missing experiment file", "[scene]") {
  Sandbox box;
  const fs::path s = box.scene("# x\nexperiment: nowhere/experiment.yaml\n");
  expect_error(box, [&] { load_scene(s); },
               {"scene.yaml:2: experiment: experiment file not found: 'nowhere/experiment.yaml'"});
  const fs::path m = box.scene("experiment: {file: nowhere.yaml}\n", "map.yaml");
  expect_error(box, [&] { load_scene(m); }, {"map.yaml:1: experiment.file: experiment file not found"});
}

TEST_CASE("scene error: missing junctions CSV", "[scene]") {
  expect_experiment_error({{"junctions", "junctions: gone.csv"}},
                          {"experiment.yaml:9: junctions: junctions CSV not found: 'gone.csv'"});
}

TEST_CASE("scene error: missing measured CSV", "[scene]") {
  expect_experiment_error({{"measured", "measured: gone.csv"}},
                          {"experiment.yaml:10: measured: measured CSV not found: 'gone.csv'"});
}

TEST_CASE("scene error: missing scene file", "[scene]") {
  Sandbox box;
  expect_error(box, [&] { load_scene(box.root / "absent.yaml"); }, {"absent.yaml: file not found"});
  expect_error(box, [&] { load_scene(box.root / "out"); }, {"out: is a directory, not a file"});
}

TEST_CASE("scene error: mass <= 0", "[scene]") {
  expect_experiment_error({{"mass", "mass: 0"}}, {"experiment.yaml:3: mass: must be > 0, got 0"});
}

TEST_CASE("scene error: k_L <= 0", "[scene]") {
  expect_experiment_error({{"k_L", "k_L: -9200"}}, {"experiment.yaml:4: k_L: must be > 0, got -9200"});
}

TEST_CASE("scene error: v <= 0", "[scene]") {
  expect_experiment_error({{"v", "v: 0"}}, {"experiment.yaml:5: v: must be > 0"});
}

TEST_CASE("scene error: E <= 0", "[scene]") {
  expect_experiment_error({{"E", "E: -1.6e6"}}, {"experiment.yaml:6: E: must be > 0"});
}

TEST_CASE("scene error: sigma_exp <= 0", "[scene]") {
  expect_experiment_error({{"sigma_exp", "sigma_exp: 0"}}, {"experiment.yaml:8: sigma_exp: must be > 0"});
}

TEST_CASE("scene error: experiment map value <= 0 names the scene", "[scene]") {
  Sandbox box;
  const fs::path s = box.scene("experiment:\n  file: exp/experiment.yaml\n  k_L: 0\n");
  expect_error(box, [&] { load_scene(s); }, {"scene.yaml:3: experiment.k_L: must be > 0, got 0"});
}

TEST_CASE("scene error: nu outside -1 < nu <= 0.5", "[scene]") {
  expect_experiment_error({{"nu", "nu: 0.6"}}, {"experiment.yaml:7: nu: must be in (-1, 0.5], got 0.6"});
  expect_experiment_error({{"nu", "nu: -1"}}, {"experiment.yaml:7: nu: must be in (-1, 0.5], got -1"});
}

TEST_CASE("scene error: negative junction area names the CSV line and column", "[scene]") {
  expect_junctions_error("# areas\ny_m,area_m2,x_m\n0,1e-8,0\n0,-1e-8,0\n",
                         {"junctions.csv:4:2: area_m2: junction area must be in [1e-20, 1] m^2, got -1e-08"});
  expect_junctions_error("area_m2\n1e-8\n0\n",
                         {"junctions.csv:3:1: area_m2: junction area must be in [1e-20, 1] m^2, got 0"});
}

TEST_CASE("scene error: NaN junction area", "[scene]") {
  expect_junctions_error("area_m2\n1e-8\nnan\n", {"junctions.csv:3:1: area_m2: must be a finite number, got 'nan'"});
}

TEST_CASE("scene: junction CSV with comments, CRLF and trailing blank lines loads", "[scene]") {
  Sandbox box;
  box.file("exp/junctions.csv", "# comment\r\narea_m2\r\n1e-8\r\n# inner comment\r\n 2e-8 \r\n\r\n\r\n");
  const Scene s = load_scene(box.scene("experiment: exp/experiment.yaml\n"));
  CHECK(s.experiment.junctions.area_m2 == std::vector<double>{1e-8, 2e-8});
  CHECK(s.experiment.junctions.x_m.empty());
}

TEST_CASE("scene error: empty junction list", "[scene]") {
  expect_junctions_error("# no rows\narea_m2\n\n", {"junctions.csv:2: area_m2: no data rows"});
}

TEST_CASE("scene error: junction CSV structure", "[scene]") {
  expect_junctions_error("area_m2,z_m\n1e-8,0\n", {"junctions.csv:1:2: z_m: unknown column 'z_m'", "did you mean"});
  expect_junctions_error("x_m,y_m\n0,0\n", {"junctions.csv:1: area_m2: missing required column"});
  expect_junctions_error("area_m2,x_m\n1e-8,0\n", {"junctions.csv:1: y_m: x_m and y_m must be given together"});
  expect_junctions_error("area_m2\n1e-8\n\n2e-8\n", {"junctions.csv:3:", "blank line inside the data"});
  expect_junctions_error("area_m2,x_m,y_m\n1e-8,0\n", {"junctions.csv:2:3:", "expected 3 fields"});
  expect_junctions_error("area_m2\n1e-8 m2\n", {"junctions.csv:2:1: area_m2: expected a plain number in SI units"});
  expect_junctions_error("", {"junctions.csv:1: area_m2: missing header row"});
}

TEST_CASE("scene error: epsilon outside 0 < epsilon <= 1", "[scene]") {
  expect_scene_error("model:\n  epsilon: 1.5\n", {"scene.yaml:3: model.epsilon: must be in (0, 1], got 1.5"});
  expect_scene_error("model: {epsilon: 0}\n", {"scene.yaml:2: model.epsilon: must be in (0, 1], got 0"});
}

TEST_CASE("scene error: negative eta", "[scene]") {
  expect_scene_error("model:\n  eta: -1\n", {"scene.yaml:3: model.eta: must be >= 0, got -1"});
}

TEST_CASE("scene error: c_min outside (0, 1)", "[scene]") {
  expect_scene_error("model:\n  c_min: 0\n", {"scene.yaml:3: model.c_min: must be in (0, 1), got 0"});
  expect_scene_error("model:\n  c_min: 1\n", {"scene.yaml:3: model.c_min: must be in (0, 1), got 1"});
}

TEST_CASE("scene error: negative p", "[scene]") {
  expect_scene_error("model:\n  p: -0.5\n", {"scene.yaml:3: model.p: must be in [0, 10], got -0.5"});
}

TEST_CASE("scene error: negative alpha_b", "[scene]") {
  expect_scene_error("model:\n  alpha_b: -1e-15\n", {"scene.yaml:3: model.alpha_b: must be >= 0, got -1e-15"});
}

TEST_CASE("scene error: Ct <= 0", "[scene]") {
  expect_scene_error("solver:\n  Ct: 0\n", {"scene.yaml:3: solver.Ct: must be >= 1, got 0"});
}

TEST_CASE("scene error: tolerance outside 0 < tolerance <= 0.1", "[scene]") {
  expect_scene_error("solver:\n  tolerance: 0\n", {"scene.yaml:3: solver.tolerance: must be in [1e-14, 0.1], got 0"});
  expect_scene_error("solver:\n  tolerance: 0.5\n",
                     {"scene.yaml:3: solver.tolerance: must be in [1e-14, 0.1], got 0.5"});
}

TEST_CASE("scene error: stop.time <= 0", "[scene]") {
  expect_scene_error("stop:\n  time: 0\n", {"scene.yaml:3: stop.time: must be > 0, got 0"});
}

TEST_CASE("scene error: stop.cycles 0", "[scene]") {
  expect_scene_error("stop:\n  cycles: 0\n", {"scene.yaml:3: stop.cycles: must be -1 (never) or >= 1, got 0"});
}

TEST_CASE("scene error: output.every <= 0", "[scene]") {
  expect_scene_error("output:\n  every: -1e-3\n", {"scene.yaml:3: output.every: must be > 0, got -0.001"});
}

TEST_CASE("scene error: output.peak_min_drop outside (0, 1)", "[scene]") {
  expect_scene_error("output:\n  peak_min_drop: 1\n", {"scene.yaml:3: output.peak_min_drop: must be in (0, 1), got 1"});
}

TEST_CASE("scene error: unknown series name", "[scene]") {
  expect_scene_error("output:\n  series:\n    - t\n    - F\n",
                     {"scene.yaml:5: output.series: unknown series 'F'; valid: t, X, V, Q, A, n_slipping, n_intact"});
  expect_scene_error("output: {series: [t, q]}\n",
                     {"scene.yaml:2: output.series: unknown series 'q' (did you mean 'Q'?)"});
  expect_scene_error("output: {series: [t, Q, t]}\n", {"scene.yaml:2: output.series: series 't' listed twice"});
}

TEST_CASE("scene error: unknown junction_shape", "[scene]") {
  expect_scene_error("model:\n  junction_shape: ellipse\n",
                     {"scene.yaml:3: model.junction_shape: unknown value 'ellipse'; valid: elliptic, circular"});
}

TEST_CASE("scene error: unknown area_law", "[scene]") {
  expect_scene_error("model:\n  area_law: sometimes\n",
                     {"scene.yaml:3: model.area_law: unknown value 'sometimes'; valid: until_first_slip, always"});
}

TEST_CASE("scene error: unknown solver method suggests the closest", "[scene]") {
  expect_scene_error(
      "solver:\n  method: refrence\n",
      {"scene.yaml:3: solver.method: unknown value 'refrence' (did you mean 'reference'?); valid: reference, event"});
}

TEST_CASE("scene error: measured Q_N < 0", "[scene]") {
  expect_measured_error("Q_N,A_m2\n0,7.5e-8\n-0.01,7.4e-8\n", {"measured.csv:3:1: Q_N: force must be >= 0, got -0.01"});
}

TEST_CASE("scene error: measured A_m2 <= 0", "[scene]") {
  expect_measured_error("A_m2,Q_N\n7.5e-8,0\n0,0.01\n", {"measured.csv:3:1: A_m2: area must be > 0, got 0"});
}

TEST_CASE("scene error: override with a non-numeric value", "[scene]") {
  const std::string w = expect_override_error(
      {"model.eta=abc"}, {"--set model.eta=abc: model.eta: expected a number in SI units (1/s), got 'abc'"});
  CHECK(w.rfind("--set model.eta=abc: ", 0) == 0);
}

TEST_CASE("scene error: override with an unknown key", "[scene]") {
  expect_override_error({"model.etta=5"}, {"--set model.etta=5: model.etta: unknown key 'etta' (did you mean 'eta'?)"});
  expect_override_error({"foo.bar=1"}, {"--set foo.bar=1: foo: unknown key 'foo'"});
  expect_override_error({"experiment.junctions=x.csv"},
                        {"--set experiment.junctions=x.csv: experiment.junctions: unknown key"});
}

TEST_CASE("scene error: malformed override", "[scene]") {
  expect_override_error({"model.eta"}, {"--set model.eta: expected key=value"});
  expect_override_error({"output.series=[t,Q"}, {"--set output.series=[t,Q: output.series: malformed YAML value"});
  expect_override_error({"model..eta=1"}, {"--set model..eta=1: model..eta: malformed key"});
  expect_override_error({"model.eta="}, {"--set model.eta=: model.eta: missing value"});
  expect_override_error({"model.eta.x=1"},
                        {"--set model.eta.x=1: model.eta: expected a number in SI units (1/s), got a map"});
  expect_override_error(
      {"experiment.file.x=1"},
      {"--set experiment.file.x=1: experiment.file.x: cannot set experiment.file.x: experiment.file is the value "
       "'exp/experiment.yaml', not a map"});
}

TEST_CASE("scene error: override naming a missing experiment file", "[scene]") {
  expect_override_error({"experiment=../nowhere.yaml"},
                        {"--set experiment=../nowhere.yaml: experiment: experiment file not found: '../nowhere.yaml'"});
}

TEST_CASE("scene error: a value overridden in the file keeps the file's line for other keys", "[scene]") {
  Sandbox box;
  const fs::path s = box.scene("experiment: exp/experiment.yaml\nmodel:\n  eta: 100\n  p: -2\n");
  expect_error(box, [&] { load_scene(s, {"model.eta=50"}); }, {"scene.yaml:4: model.p: must be in [0, 10], got -2"});
}

TEST_CASE("scene: experiment data inline (Scene.from_dict) load as the files and write back", "[scene]") {
  const Scene files = load_scene(kData / "small_scene.yaml");
  // The fixture's values and data written inline: the same scene, bit for bit.
  Scene memory = files;
  memory.experiment.file.clear();
  const std::string text = scene_to_yaml(memory);
  CHECK_THAT(text, Contains("  junctions: {area_m2: ["));
  CHECK_THAT(text, Contains("  measured: {Q_N: ["));
  CHECK(text.find("file:") == std::string::npos);
  Sandbox box;
  const Scene back = load_scene(box.scene(text));
  CHECK(back.experiment.file.empty());
  CHECK(same_bits(back.experiment.junctions.area_m2, files.experiment.junctions.area_m2));
  CHECK(same_bits(back.experiment.junctions.x_m, files.experiment.junctions.x_m));
  CHECK(same_bits(back.experiment.measured->A_m2, files.experiment.measured->A_m2));
  CHECK(scene_to_yaml(back) == text);
  const Scene tree = scene_from_memory(YAML::Load(text), box.root, "memory");
  CHECK(tree.file.empty());
  CHECK(scene_to_yaml(tree) == text);

  // Values checked as CSV rows are, naming the value; files and inline data not both.
  auto refused = [&](const std::string& scene_text, const std::string& fragment) {
    const fs::path p = box.scene(scene_text, "bad.yaml");
    expect_error(box, [&] { load_scene(p); }, {"bad.yaml:1: " + fragment});
  };
  const std::string head = "experiment: {name: x, mass: 0.1, k_L: 9200, v: 1e-4, E: 1.6e6, nu: 0.5, sigma_exp: 2e5, ";
  refused(head + "junctions: {area_m2: [1e-8, 2]}}\n",
          "experiment.junctions.area_m2[1]: junction area must be in [1e-20, 1] m^2, got 2");
  refused(head + "junctions: {area_m2: [1e-8], x_m: [0]}}\n",
          "experiment.junctions.y_m: x_m and y_m must be given together (or neither)");
  refused(head + "junctions: {area_m2: [1e-8], x_m: [2e9], y_m: [0]}}\n",
          "experiment.junctions.x_m[0]: junction centre must be within +-1e+09 m, got 2e+09");
  refused(head + "junctions: {area_m2: [1e-8]}, measured: {Q_N: [-1], A_m2: [1e-8]}}\n",
          "experiment.measured.Q_N[0]: force must be >= 0, got -1");
  refused("experiment: {file: exp/experiment.yaml, junctions: {area_m2: [1e-8]}}\n",
          "experiment.junctions: unknown key 'junctions'");  // the file holds the data
  refused("experiment: {name: x, junctions: {area_m2: [1e-8]}}\n", "experiment.mass: missing required key");
  refused(head + "measured: {Q_N: [0], A_m2: [1e-8]}}\n", "experiment.measured: needs the junctions inline too");
}
