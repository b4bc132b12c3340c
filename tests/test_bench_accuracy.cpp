// Issue 3 item 2 on two stand-ins: the default tolerance against a converged run (1e-12),
// through the first peak and five stick-slip cycles. The bound is the target.
#include <catch2/catch.hpp>
#include <filesystem>

#include "bench/accuracy.hpp"
#include "bench/robust_error.hpp"
#include "observe/simulate.hpp"
#include "scene/load.hpp"

using namespace asperity;

TEST_CASE("default tolerance is within the accuracy targets on stand-ins P0.98N and P1.52N", "[bench][accuracy]") {
  for (const char* name : {"P0.98N", "P1.52N"}) {
    const std::filesystem::path path = std::filesystem::path(ASPERITY_SOURCE_DIR) / "scenes/paper" / (std::string(name) + ".yaml");
    const std::vector<std::string> o{"stop.time=8", "stop.cycles=5", "output.series=[]", "solver.method=event"};
    const Scene scene = load_scene(path, o);
    auto oc = o;
    oc.push_back("solver.tolerance=1e-12");
    const Scene conv_scene = load_scene(path, oc);
    REQUIRE(scene.solver.tolerance == 1e-9);  // the shipped default
    const RunResult run = simulate(scene), conv = simulate(conv_scene);
    REQUIRE(conv.obs.ss_cycles == 5);
    REQUIRE(run.obs.ss_cycles == 5);
    const AccuracyRow row = accuracy_row(name, scene.solver.tolerance, run.obs, conv.obs);
    for (std::size_t i = 0; i < n_robust; ++i) {
      INFO(name << " " << robust_names()[i] << ": " << row.value[i] << " vs converged " << row.converged[i]);
      CHECK(row.error[i] < robust_targets()[i]);
    }
    CHECK(row.within_targets());
  }
}
