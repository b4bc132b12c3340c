// The bad-input corpus (tests/bad_inputs/, expectations in EXPECTED.tsv): every file must be
// refused with exit status 2 and exactly one line on stderr that starts with the file, the line
// (and CSV column), the key and the start of the message, and nothing anywhere may change: the
// working folder and the corpus are listed (paths, sizes, modification times) before and after
// each case. Experiments are loaded through a scene, junction/measured CSVs through an
// experiment, exactly as a user's files would be; campaigns run through `asperity sweep`, fits
// through `asperity fit` (their scene paths are relative to tests/bad_inputs/), topography
// recipes through `asperity generate --recipe`, and height maps (heights_*.csv, float64 headers
// heights_*.yaml) through a topography recipe that names them. Inputs that cannot be committed
// (a FIFO, a file over the size cap) are made here.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support_files.hpp"

namespace fs = std::filesystem;

namespace {

using asperity::testing::slurp;
std::string q(const fs::path& p) { return asperity::testing::shell_quoted(p); }
void write(const fs::path& p, const std::string& text) { asperity::testing::write_text(p, text); }

struct Case {
  std::string file, location, key, message;  // location: LINE or LINE:COLUMN
};

std::vector<Case> corpus(const fs::path& dir) {
  std::vector<Case> cases;
  std::ifstream in(dir / "EXPECTED.tsv");
  std::string l;
  while (std::getline(in, l)) {
    if (l.empty() || l[0] == '#') continue;
    std::istringstream f(l);
    Case c;
    std::getline(f, c.file, '\t');
    std::getline(f, c.location, '\t');
    std::getline(f, c.key, '\t');
    std::getline(f, c.message);
    cases.push_back(c);
  }
  return cases;
}

// "<file>:<location>: <key>: <message start>" (key and location left out when empty).
std::string expected_prefix(const fs::path& file, const std::string& location, const std::string& key,
                            const std::string& message) {
  std::string s = file.lexically_normal().string();
  if (!location.empty()) s += ":" + location;
  s += ": ";
  if (!key.empty()) s += key + ": ";
  return s + message;
}

// Every entry under each root: path, type, size and modification time (ns), sorted.
std::string snapshot(const std::vector<fs::path>& roots) {
  std::vector<std::string> lines;
  for (const fs::path& root : roots) {
    for (const auto& e : fs::recursive_directory_iterator(root)) {
      struct stat st {};
      ::lstat(e.path().c_str(), &st);
      std::ostringstream l;
      l << e.path().string() << ' ' << (st.st_mode & S_IFMT) << ' ' << st.st_size << ' ' << st.st_mtim.tv_sec << '.'
        << st.st_mtim.tv_nsec;
      lines.push_back(l.str());
    }
  }
  std::sort(lines.begin(), lines.end());
  std::string s;
  for (const auto& l : lines) s += l + '\n';
  return s;
}

struct Outcome {
  int status = -1;
  std::string err;
  double wall_s = 0;
};

// Runs `asperity COMMAND SCENE --out out` in `work` (so that a default output folder would
// land there too).
Outcome run_asperity(const fs::path& work, const std::string& command, const fs::path& scene) {
  const fs::path err_file = fs::path(asperity::testing::temp_path("asperity_test_bad_inputs_err"));
  const std::string cmd = "cd " + q(work) + " && " + q(ASPERITY_BINARY) + " " + command + " " + q(scene) +
                          " --out out >/dev/null 2>" + q(err_file);
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  Outcome o;
  o.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  o.err = slurp(err_file);
  fs::remove(err_file);
  return o;
}

// Exit 2, one line that starts with `prefix`, nothing changed in `watched`.
void check_refused(const fs::path& work, const std::vector<fs::path>& watched, const std::string& command,
                   const fs::path& scene, const std::string& prefix) {
  const std::string before = snapshot(watched);
  const Outcome o = run_asperity(work, command, scene);
  INFO("stderr: " << o.err);
  INFO("expected prefix: " << prefix);
  CHECK(o.status == 2);
  CHECK(o.err.rfind(prefix, 0) == 0);                        // file:line: key: message, at the start
  CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);  // one line, no stack of noise
  CHECK(o.err.back() == '\n');
  CHECK(snapshot(watched) == before);  // nothing written, moved or touched
  CHECK(o.wall_s < 10.0);              // refused at load, not after a run
}

const char* kExperiment = "name: wrapper\nmass: 0.1\nk_L: 9200\nv: 1e-4\nE: 1.6e6\nnu: 0.5\nsigma_exp: 230000\n";

}  // namespace

TEST_CASE("bad-input corpus: each file is refused naming file, line and key, and nothing changes",
          "[scene][bad_inputs]") {
  const fs::path src(ASPERITY_SOURCE_DIR);
  const fs::path dir = src / "tests/bad_inputs";
  const auto cases = corpus(dir);
  // Every file of the corpus has an expectation, and every expectation a file (the folder also
  // holds EXPECTED.tsv and this test).
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir))
    files += e.path().filename() != "EXPECTED.tsv" && e.path().filename() != "test_bad_inputs.cpp";
  CHECK(files == cases.size());
  CHECK(cases.size() >= 100);

  const fs::path work = asperity::testing::temp_path("asperity_test_bad_inputs");
  fs::remove_all(work);
  fs::create_directories(work);
  const fs::path junctions = src / "data/standin/P0.98N/junctions.csv";
  for (const Case& c : cases) {
    INFO("case " << c.file);
    const fs::path file = dir / c.file;
    REQUIRE(fs::exists(file));
    fs::path scene;
    std::string command = "run";
    if (c.file.rfind("campaign_", 0) == 0) {
      scene = file;
      command = "sweep";
    } else if (c.file.rfind("fit_", 0) == 0) {
      scene = file;
      command = "fit";
    } else if (c.file.rfind("study_", 0) == 0) {
      scene = file;
      command = "study";
    } else if (c.file.rfind("scene_", 0) == 0) {
      scene = file;
    } else if (c.file.rfind("experiment_", 0) == 0) {
      scene = work / "scene.yaml";
      write(scene, "experiment: " + q(file) + "\n");
    } else if (c.file.rfind("junctions_", 0) == 0 || c.file.rfind("measured_", 0) == 0) {
      const bool jun = c.file.rfind("junctions_", 0) == 0;
      std::ostringstream e;
      e << kExperiment << "junctions: " << q(jun ? file : junctions) << "\n";
      if (!jun) e << "measured: " << q(file) << "\n";
      write(work / "experiment.yaml", e.str());
      scene = work / "scene.yaml";
      write(scene, "experiment: experiment.yaml\n");
    } else if (c.file.rfind("force_", 0) == 0) {  // a Q(t) CSV named by a fit
      scene = work / "fit.yaml";
      write(scene, "objective: area_and_force\nexperiments:\n  - {scene: " + q(src / "scenes/paper/P0.98N.yaml") +
                       ", force: " + q(file) +
                       "}\nparameters:\n  model.alpha_b: {lo: 1e-16, hi: 3e-15, start: 7.25e-16}\n");
      command = "fit";
    } else if (c.file.rfind("topography_", 0) == 0) {
      scene = file;
      command = "generate --recipe";
    } else if (c.file.rfind("heights_", 0) == 0) {
      scene = work / "recipe.yaml";
      const bool csv = file.extension() == ".csv";  // a float64 header gives its own pixel size
      write(scene, "topography:\n  file: " + q(file) + (csv ? "\n  pixel_m: 1e-6" : "") +
                       "\nsphere_radius_m: 0.01\nE: 1.6e6\nnu: 0.5\nload_N: 1\n");
      command = "generate --recipe";
    } else {
      FAIL("unknown kind of bad input: " << c.file);
    }
    // The message start is part of the expectation, so a key found elsewhere in the text
    // (or a refusal for another reason) does not pass.
    REQUIRE_FALSE(c.message.empty());
    check_refused(work, {work, dir}, command, scene, expected_prefix(file, c.location, c.key, c.message));
  }
  fs::remove_all(work);
}

TEST_CASE("inputs that are not regular files, or too large, are refused before reading", "[scene][bad_inputs]") {
  const fs::path src(ASPERITY_SOURCE_DIR);
  const fs::path work = asperity::testing::temp_path("asperity_test_bad_files");
  fs::remove_all(work);
  fs::create_directories(work);
  const fs::path experiment = src / "data/standin/P0.98N/experiment.yaml";

  // A FIFO as the scene and as the experiment: never opened (opening one would block).
  const fs::path fifo = work / "fifo.yaml";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  check_refused(work, {work}, "run", fifo, fifo.string() + ": is a FIFO (named pipe), not a regular file");
  write(work / "scene.yaml", "experiment: fifo.yaml\n");
  check_refused(
      work, {work}, "run", work / "scene.yaml",
      (work / "scene.yaml").string() + ":1: experiment: experiment file is a FIFO (named pipe), not a regular file");
  // A directory as the scene.
  fs::create_directories(work / "folder.yaml");
  check_refused(work, {work}, "run", work / "folder.yaml",
                (work / "folder.yaml").string() + ": is a directory, not a file");
  // Files over the caps (sparse: no disk or time spent): 16 MiB of YAML, 256 MiB of CSV.
  {
    const fs::path big = work / "big.yaml";
    std::ofstream(big) << "experiment: " << experiment.string() << "\n";
    fs::resize_file(big, (std::uintmax_t{16} << 20) + 1);
    check_refused(work, {work}, "run", big,
                  big.string() + ": is 16.8 MB, more than the 16 MiB an input file of this kind may have");
    fs::remove(big);
  }
  {
    const fs::path csv = work / "big.csv";
    std::ofstream(csv) << "area_m2\n1e-8\n";
    fs::resize_file(csv, (std::uintmax_t{256} << 20) + 1);
    write(work / "experiment.yaml", std::string(kExperiment) + "junctions: big.csv\n");
    write(work / "scene.yaml", "experiment: experiment.yaml\n");
    check_refused(
        work, {work}, "run", work / "scene.yaml",
        (work / "experiment.yaml").string() +
            ":8: junctions: junctions CSV is 268 MB, more than the 256 MiB an input file of this kind may have");
    fs::remove(csv);
  }
  // A --set value whose aliases nest (a "billion laughs" of a few hundred bytes): refused at
  // load, before anything would re-emit it expanded.
  {
    std::string bomb = "output.series=[&a [Q,Q,Q,Q,Q,Q,Q,Q,Q,Q]";
    for (char c = 'b'; c <= 'i'; ++c) {
      bomb += std::string(", &") + c + " [";
      for (int k = 0; k < 10; ++k) bomb += std::string(k ? "," : "") + "*" + static_cast<char>(c - 1);
      bomb += "]";
    }
    bomb += "]";
    const fs::path scene = src / "scenes/paper/P0.98N.yaml";
    check_refused(work, {work}, "run --set '" + bomb + "'", scene,
                  "--set " + bomb + ": output.series: aliases (*name) expand this YAML to more than 1000000 nodes");
  }
  // A shard of 2e10 points: refused before the store is made (no per-point allocation), naming
  // --shard and how many shards would do.
  {
    write(work / "huge.yaml", "scene: " + q(src / "scenes/paper/P0.98N.yaml") +
                                  "\naxes:\n  model.eta: {linspace: [0, 100, 200000]}\n"
                                  "  model.epsilon: {linspace: [0.5, 0.9, 100000]}\n");
    check_refused(work, {work}, "sweep --shard 3/7", work / "huge.yaml",
                  "--shard: this shard has 2857142857 of the campaign's 20000000000 points, more than the 100000000");
    CHECK_FALSE(fs::exists(work / "out"));
    fs::remove(work / "huge.yaml");
  }
  fs::remove_all(work);
}

TEST_CASE("errors found once a scene is whole name the --set, or the file and line, that gave the value",
          "[scene][bad_inputs]") {
  const fs::path work = asperity::testing::temp_path("asperity_test_bad_later");
  fs::remove_all(work);
  fs::create_directories(work);
  // The contact at the map's edge because a --set raised the load: the --set is named.
  write(work / "topo.yaml",
        "# a smooth sphere whose contact fits the map at 1 N\ntopography:\n  smooth: {n: 32, size_m: 5e-3}\n"
        "  sphere_radius_m: 0.01\n  E: 1.6e6\n  nu: 0.5\n  load_N: 1\nstop: {time: 0.1}\n");
  check_refused(work, {work}, "run --set topography.load_N=1e6", work / "topo.yaml",
                "--set topography.load_N=1e6: topography: the contact reaches the edge of the 32 x 32 map");
  // Overlapping junctions given inline in a scene: the scene's line of experiment.junctions.
  write(work / "inline.yaml",
        "experiment:\n  name: x\n  mass: 0.1\n  k_L: 9200\n  v: 1e-4\n  E: 1.6e6\n  nu: 0.5\n  sigma_exp: 230000\n"
        "  junctions: {area_m2: [1e-8, 1e-8], x_m: [0, 1e-5], y_m: [0, 0]}\nmodel: {interactions: elastic}\n");
  check_refused(
      work, {work}, "run", work / "inline.yaml",
      (work / "inline.yaml").string() + ":9: experiment.junctions: junctions 1 and 2 overlap (centres 1e-05 m apart");
  // ... and in a junctions CSV: the file and the line of the second junction's row.
  write(work / "overlap.csv",
        "# two junctions 10 um apart, radii 56 um\narea_m2,x_m,y_m\n1e-8,0,0\n# the second\n1e-8,1e-5,0\n");
  write(work / "experiment.yaml", std::string(kExperiment) + "junctions: overlap.csv\n");
  write(work / "csv.yaml", "experiment: experiment.yaml\nmodel: {interactions: elastic}\n");
  check_refused(work, {work}, "run", work / "csv.yaml",
                (work / "overlap.csv").string() + ":5: x_m: junctions 1 and 2 overlap (centres 1e-05 m apart");
  fs::remove_all(work);
}
