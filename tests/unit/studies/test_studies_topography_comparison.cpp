// The interaction study's reading of the topography study's table (studies/topography_comparison):
// the rows and the tally against sums worked by hand, an absent table, and bad rows refused at
// their line and column.
#include <catch2/catch.hpp>
#include <string>

#include "io/input_error.hpp"
#include "studies/topography_comparison.hpp"
#include "support_files.hpp"

using namespace asperity;
using namespace asperity::testing;
using Catch::Matchers::WithinAbs;

namespace {
const std::string kHeader =
    "seed,P_N,N,clusters,model,alpha_b,n,endpoint_residual,residual_rms_m2,noise_rms_p95_m2,peak_rule\n";
}

TEST_CASE("topography table: rows read, interacting minus independent tallied per seed and load",
          "[topography_comparison]") {
  const auto dir = fresh_dir("topography_comparison");
  const auto file =
      write_text(dir / "table.csv", kHeader +
                                        "2019,0.98,621,637,independent,2.1e-16,1.5,0.10,2e-08,3e-09,all_slipped\n"
                                        "2019,0.98,621,637,interacting,2.1e-16,1.3,0.13,3e-08,3e-09,all_slipped\n"
                                        "2019,4,917,1002,independent,8.7e-16,1.0,0.33,4e-07,1e-06,all_slipped\n"
                                        "2019,4,917,1002,interacting,8.7e-16,1.1,0.29,3e-07,1e-06,all_slipped\n"
                                        "2020,0.98,600,610,independent,2.0e-16,1.6,0.09,2e-08,3e-09,all_slipped\n");
  const auto rows = read_topography_table(file);
  REQUIRE(rows.size() == 5);
  CHECK(rows[1].model == "interacting");
  CHECK(rows[2].junctions == 917);
  CHECK(rows[3].load_N == 4.0);
  CHECK(rows[3].alpha_b == 8.7e-16);
  const TopographyTally t = tally_topography(rows);
  // Two (seed, load) pairs with both models: Δn = -0.2 and +0.1; Δ endpoint residual 0.03, -0.04.
  CHECK(t.pairs == 2);
  CHECK_THAT(t.mean_dn, WithinAbs(-0.05, 1e-15));
  CHECK_THAT(t.min_dn, WithinAbs(-0.2, 1e-15));
  CHECK_THAT(t.max_dn, WithinAbs(0.1, 1e-15));
  CHECK(t.n_lower == 1);
  CHECK_THAT(t.max_abs_dres, WithinAbs(0.04, 1e-15));
  CHECK(t.rows == 5);
  CHECK(t.within_noise == 2);  // the two rows at 4 N: residual below the noise's 95 %
}

TEST_CASE("topography table: absent means no rows, and a bad field or model is refused at its line and column",
          "[topography_comparison]") {
  const auto dir = fresh_dir("topography_comparison_bad");
  CHECK(read_topography_table(dir / "absent.csv").empty());
  const auto nan =
      write_text(dir / "nan.csv", kHeader + "2019,0.98,621,637,independent,2.1e-16,nan,0.1,2e-08,3e-09,x\n");
  try {
    read_topography_table(nan);
    FAIL("a NaN shape exponent was accepted");
  } catch (const io::InputError& e) {
    CHECK(e.line == 2);
    CHECK(e.column == 7);
    CHECK(e.key == "n");
  }
  const auto model =
      write_text(dir / "model.csv", kHeader + "2019,0.98,621,637,coupled,2.1e-16,1.2,0.1,2e-08,3e-09,x\n");
  CHECK_THROWS_AS(read_topography_table(model), io::InputError);
  const auto short_row = write_text(dir / "short.csv", kHeader + "2019,0.98,621\n");
  CHECK_THROWS_AS(read_topography_table(short_row), io::InputError);
  const auto no_column = write_text(dir / "no_column.csv", "seed,P_N,N,model\n2019,1,2,independent\n");
  CHECK_THROWS_AS(read_topography_table(no_column), io::InputError);
}
