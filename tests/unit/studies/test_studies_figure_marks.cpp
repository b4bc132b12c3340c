// The studies' figures drawn as SVG from evidence that says it is a stand-in and from the same
// evidence that does not: the stand-in mark exactly on the first, time in the units table's unit.
#include <catch2/catch.hpp>
#include <filesystem>

#include "studies/junction_pairs.hpp"
#include "support_figures.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;

TEST_CASE("junction pairs figure: the mark exactly from stand-ins, a key per pair", "[report][pairs][figures]") {
  if (!io::gnuplot_available()) {
    WARN("gnuplot not installed: nothing to draw");
    return;
  }
  for (const bool stand_in : {true, false}) {
    const fs::path w = fresh_dir(stand_in ? "pairs_marks_standin" : "pairs_marks_measured");
    JunctionPairsEvidence e;
    e.experiment = "P4.00N";
    e.stand_in = stand_in;
    e.sigma_Pa = 1e6;
    e.t_peak_interacting_s = e.t_peak_independent_s = 1;
    e.pairs = {{0, 1}};
    e.A0_m2 = {1e-9, 1e-9};
    e.crowding = {2, 1};
    for (std::size_t j = 0; j < 2; ++j) {
      JunctionTrace tr;
      tr.junction = j;
      tr.t_s = {0, 0.5, 1};
      tr.X_m = {0, 1e-5, 2e-5};
      tr.f_N = {0, 5e-4, 1e-3};
      tr.A_m2 = {1e-9, 0.99e-9, 0.95e-9};
      e.interacting.push_back(tr);
      e.independent.push_back(tr);
    }
    write_junction_pairs(w, e, FigureFormats{false, true, false});
    check_figure(w / "junction_pairs.svg", stand_in, {"t"});
    const auto texts = svg_texts(w / "junction_pairs.svg");
    CHECK(has_text(texts, "pair 1: #1, #2"));  // one key entry per pair, the styles once
    CHECK(has_text(texts, "interacting, sparse"));
    done_with(w);
  }
}
