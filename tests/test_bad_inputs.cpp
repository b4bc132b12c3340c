// The bad-input corpus (tests/bad_inputs/, expectations in EXPECTED.tsv): every file must be
// refused with exit status 2 and one message naming the file, the line and the key, and nothing
// may be written. Experiments are loaded through a scene, junction/measured CSVs through an
// experiment, exactly as a user's files would be; campaigns run through `asperity sweep`, fits
// through `asperity fit` (their scene paths are relative to tests/bad_inputs/).
#include <unistd.h>

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support.hpp"

namespace fs = std::filesystem;

namespace {

using asperity::testing::slurp;
std::string q(const fs::path& p) {
  std::string s(1, '\'');
  s += p.string();
  s += '\'';
  return s;
}
void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

struct Case { std::string file, line, key; };

std::vector<Case> corpus(const fs::path& dir) {
  std::vector<Case> cases;
  std::ifstream in(dir / "EXPECTED.tsv");
  std::string l;
  while (std::getline(in, l)) {
    if (l.empty() || l[0] == '#') continue;
    std::istringstream f(l);
    Case c;
    std::getline(f, c.file, '\t');
    std::getline(f, c.line, '\t');
    std::getline(f, c.key);
    cases.push_back(c);
  }
  return cases;
}

const char* kExperiment =
    "name: wrapper\nmass: 0.1\nk_L: 9200\nv: 1e-4\nE: 1.6e6\nnu: 0.5\nsigma_exp: 230000\n";

}  // namespace

TEST_CASE("bad-input corpus: each file is refused naming file, line and key, and nothing is written", "[scene][bad_inputs]") {
  const fs::path src(ASPERITY_SOURCE_DIR);
  const fs::path dir = src / "tests/bad_inputs";
  const auto cases = corpus(dir);
  // Every file of the corpus has an expectation, and every expectation a file.
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.path().filename() != "EXPECTED.tsv";
  CHECK(files == cases.size());
  CHECK(cases.size() >= 50);

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
    } else {
      FAIL("unknown kind of bad input: " << c.file);
    }
    const fs::path out = work / "out";
    fs::remove_all(out);
    const std::string cmd = q(ASPERITY_BINARY) + " " + command + " " + q(scene) + " --out " + q(out) + " >/dev/null 2>" +
                            q(work / "err.txt");
    const int rc = std::system(cmd.c_str());
    const std::string err = slurp(work / "err.txt");
    INFO("stderr: " << err);
    CHECK(WIFEXITED(rc));
    CHECK(WEXITSTATUS(rc) == 2);
    CHECK(err.find(c.file + ":" + c.line + ":") != std::string::npos);  // file and line
    CHECK(err.find(c.key) != std::string::npos);                        // key (or what is wrong)
    CHECK(std::count(err.begin(), err.end(), '\n') == 1);               // one line, no stack of noise
    CHECK_FALSE(fs::exists(out));                                       // nothing written
  }
  fs::remove_all(work);
}
