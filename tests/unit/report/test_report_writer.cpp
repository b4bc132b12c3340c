#include <yaml-cpp/yaml.h>

#include <unistd.h>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "report/run_writer.hpp"

#include "support_files.hpp"

using namespace asperity;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("asperity-test-" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d.parent_path());
  return d;
}

using asperity::testing::slurp;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

Scene small_scene() {
  Scene s;
  s.file = "scenes/test.yaml";
  s.experiment.name = "unit \"test\"";
  s.experiment.mass_kg = 0.1;
  s.experiment.k_L = 9200;
  s.experiment.v = 1e-4;
  s.experiment.E = 1.6e6;
  s.experiment.nu = 0.5;
  s.experiment.sigma_exp = 0.23e6;
  s.experiment.junctions.area_m2 = {1e-8, 2e-8, 3e-8};
  s.solver.method = SolverMethod::reference;
  return s;
}

Observables awkward_observables() {
  Observables o;
  o.N = 1203;
  o.A0 = 1.0 / 3.0 * 1e-5;
  o.K0 = 0.1 + 0.2;
  o.T0 = std::nextafter(1e-3, 1.0);
  o.dt = 1.0000000000000002e-06;
  o.Q_s = M_PI;
  o.A_s = 1e-300;
  o.t_peak = 5e-324;  // denormal
  o.peak_found = true;
  o.alpha = 2.718281828459045e-7;
  o.alpha_R2 = 0.99999999999999989;
  o.shape_exponent = 1.1;
  o.area_drop_fraction = -0.0;
  o.ss_cycles = 5;
  o.ss_drop = std::numeric_limits<double>::max();
  o.ss_period = std::numeric_limits<double>::quiet_NaN();
  o.max_f_over_sigmaA = 0.999999999999;
  o.max_f_over_sigma_exp_A = std::numeric_limits<double>::infinity();
  o.t_end = 1.0;
  o.steps = 123456789012LL;
  o.wall_s = 12.5;
  return o;
}

}  // namespace

TEST_CASE("run writer: files, header, summary round trip with identical doubles", "[report][observe]") {
  const fs::path dir = fresh_dir("run1");
  const Scene scene = small_scene();
  Recorder rec(0.01, true, 1e-3, false, -1);
  for (int i = 0; i < 5; ++i) rec.sample({0.01 * i, 1e-7 * i, 1e-5, 0.1 * i, 1e-5 - 1e-8 * i, i, 3 - i});
  rec.population({0.02, 1, false, 0});
  rec.extremum({0.035, 0.35, 9.9e-6, true});
  rec.extremum({0.045, 0.30, 9.9e-6, false});
  rec.population({0.048, 0, true, 0});
  const Observables o = awkward_observables();
  write_run(dir, scene, o, rec);

  REQUIRE(fs::is_directory(dir));
  const std::string csv = slurp(dir / "series.csv");
  CHECK(csv.rfind("t,X,V,Q,A,n_slipping,n_intact\n", 0) == 0);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 6);
  CHECK(fs::exists(dir / "scene.yaml"));
  CHECK(fs::file_size(dir / "scene.yaml") > 0);

  const YAML::Node y = YAML::LoadFile((dir / "summary.yaml").string());
  auto D = [&](const char* k) { return y[k].as<double>(); };
  CHECK(y["N"].as<std::size_t>() == o.N);
  CHECK(same_bits(D("A0"), o.A0));
  CHECK(same_bits(D("K0"), o.K0));
  CHECK(same_bits(D("T0"), o.T0));
  CHECK(same_bits(D("dt"), o.dt));
  CHECK(same_bits(D("Q_s"), o.Q_s));
  CHECK(same_bits(D("A_s"), o.A_s));
  CHECK(same_bits(D("t_peak"), o.t_peak));
  CHECK(y["peak_found"].as<bool>() == true);
  CHECK(same_bits(D("alpha"), o.alpha));
  CHECK(same_bits(D("alpha_R2"), o.alpha_R2));
  CHECK(same_bits(D("shape_exponent"), o.shape_exponent));
  CHECK(same_bits(D("area_drop_fraction"), o.area_drop_fraction));
  CHECK(y["ss_cycles"].as<int>() == 5);
  CHECK(same_bits(D("ss_drop"), o.ss_drop));
  CHECK(std::isnan(D("ss_period")));
  CHECK(std::isnan(D("shape_prefactor")));
  CHECK(same_bits(D("max_f_over_sigmaA"), o.max_f_over_sigmaA));
  CHECK(same_bits(D("max_f_over_sigma_exp_A"), o.max_f_over_sigma_exp_A));
  CHECK(same_bits(D("t_end"), o.t_end));
  CHECK(y["steps"].as<long long>() == o.steps);
  CHECK(same_bits(D("wall_s"), o.wall_s));
  CHECK(y["method"].as<std::string>() == "reference");
  CHECK(same_bits(D("Ct"), scene.solver.Ct));
  CHECK(same_bits(D("tolerance"), scene.solver.tolerance));
  CHECK(y["experiment"].as<std::string>() == "unit \"test\"");
  REQUIRE(y["peaks"].size() == 1);
  CHECK(y["peaks"][0]["Q_max"].as<double>() == 0.35);
  CHECK(y["peaks"][0]["t_min"].as<double>() == 0.045);
  fs::remove_all(dir);
}

TEST_CASE("run writer replaces the files of its last run, keeps the user's and omits an empty series",
          "[report][observe]") {
  const fs::path dir = fresh_dir("run2");
  {
    Recorder rec(0.01, true, 1e-3, false, -1);
    rec.sample({0, 0, 0, 0, 6e-8, 0, 3});
    write_run(dir, small_scene(), Observables{}, rec);
  }
  REQUIRE(fs::exists(dir / "series.csv"));
  std::ofstream(dir / "notes.txt") << "mine\n";  // a file the user adds to the run folder

  Scene scene = small_scene();
  scene.output.series.clear();
  Recorder rec(0.01, false, 1e-3, false, -1);
  rec.sample({0, 0, 0, 0, 6e-8, 0, 3});
  write_run(dir.string() + "/", scene, Observables{}, rec);  // trailing slash: same directory

  CHECK(fs::exists(dir / "summary.yaml"));
  CHECK(fs::exists(dir / "scene.yaml"));
  CHECK_FALSE(fs::exists(dir / "series.csv"));  // the last run's, not made now: removed
  CHECK(slurp(dir / "notes.txt") == "mine\n");  // the user's: kept
  // No temporary or old siblings are left behind.
  for (const auto& e : fs::directory_iterator(dir.parent_path()))
    CHECK(e.path().filename().string().find(".run2.") == std::string::npos);
  const YAML::Node y = YAML::LoadFile((dir / "summary.yaml").string());
  CHECK(std::isnan(y["Q_s"].as<double>()));
  CHECK(y["peaks"].size() == 0);
  fs::remove_all(dir.parent_path());
}

TEST_CASE("run writer refuses a folder whose marker was copied or lists no files, touching nothing",
          "[report][observe]") {
  const fs::path dir = fresh_dir("copied");
  fs::create_directories(dir);
  std::ofstream(dir / "series.csv") << "my own series\n";
  std::ofstream(dir / ".asperity") << "created by asperity run\n";  // a marker without a file list
  Recorder rec(0.01, true, 1e-3, false, -1);
  CHECK_THROWS_WITH(write_run(dir, small_scene(), Observables{}, rec), Catch::Contains("does not list the files"));
  CHECK(slurp(dir / "series.csv") == "my own series\n");
  CHECK_FALSE(fs::exists(dir / "summary.yaml"));
  // A real run's marker copied beside a file of the user's with a name the run writes: refused,
  // naming that file, because its content is not what the run wrote.
  const fs::path real = fresh_dir("realrun");
  write_run(real, small_scene(), Observables{}, rec);
  fs::copy_file(real / ".asperity", dir / ".asperity", fs::copy_options::overwrite_existing);
  CHECK_THROWS_WITH(write_run(dir, small_scene(), Observables{}, rec),
                    Catch::Contains("series.csv: --out: refusing to replace it"));
  CHECK(slurp(dir / "series.csv") == "my own series\n");
  fs::remove_all(dir.parent_path());
  fs::remove_all(real.parent_path());
}

TEST_CASE("run writer refuses to replace a directory that is not a run", "[report][observe]") {
  const fs::path dir = fresh_dir("notarun");
  fs::create_directories(dir);
  std::ofstream(dir / "thesis.tex") << "precious\n";
  Recorder rec(0.01, true, 1e-3, false, -1);
  CHECK_THROWS_WITH(write_run(dir, small_scene(), Observables{}, rec), Catch::Contains("not written by asperity run"));
  CHECK(fs::exists(dir / "thesis.tex"));
  CHECK_FALSE(fs::exists(dir / "summary.yaml"));
  for (const auto& e : fs::directory_iterator(dir.parent_path()))
    CHECK(e.path().filename().string().find(".notarun.") == std::string::npos);
  fs::remove_all(dir.parent_path());
}
