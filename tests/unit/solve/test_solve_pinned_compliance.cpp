// solve/interacting/pinned_compliance.hpp: the pinned set's G = (D + C_PP)⁻¹ and its products
// (the fast solver's chord passes) and rows, against the inverse of the same dense matrix by
// Eigen's LLT (the second method), before and after junctions leave the set (removals are kept
// aside and folded into the stored triangle eight at a time: the sizes below leave some pending),
// and every CPU form of the product kernel against the portable one, bit for bit.
#include <omp.h>
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <vector>

#include "scene/load.hpp"
#include "solve/core/junction_state.hpp"
#include "solve/core/problem.hpp"
#include "solve/interacting/interaction_matrix.hpp"
#include "solve/interacting/pinned_compliance.hpp"
#include "solve/interacting/pinned_kernels.hpp"

namespace {

using asperity::PinnedCompliance;

// max_q |y_q − exact_q| / max_q |exact_q|
double relative_error(const std::vector<double>& y, const Eigen::VectorXd& exact) {
  double e = 0;
  for (Eigen::Index q = 0; q < exact.size(); ++q) e = std::max(e, std::abs(y[q] - exact[q]));
  return e / exact.cwiseAbs().maxCoeff();
}

// The stand-in P0.98N (STAND-IN data) with interactions: its problem, D = 1/k_i, and C.
struct StandIn {
  asperity::Problem problem = asperity::make_problem(asperity::load_scene(
      std::filesystem::path(ASPERITY_SOURCE_DIR) / "scenes/paper/P0.98N.yaml", {"model.interactions=elastic"}));
  std::vector<double> D = reference(problem);
  asperity::InteractionMatrix C = asperity::interaction_matrix(problem);
  static std::vector<double> reference(const asperity::Problem& p) {
    const asperity::JunctionState J(p.A0, p.law);
    std::vector<double> D(p.size());
    for (std::size_t i = 0; i < D.size(); ++i) D[i] = 1.0 / J.k[i];
    return D;
  }
};

}  // namespace

TEST_CASE("pinned compliance: G's products equal the dense inverse's, as junctions leave the set", "[solve][pinned]") {
  // The stand-in P0.98N (STAND-IN data), every junction pinned, D = 1/k_i.
  const StandIn t;
  const std::vector<double>& D = t.D;
  const asperity::InteractionMatrix& C = t.C;
  const std::size_t N = t.problem.size();
  PinnedCompliance P(t.problem, D, true);

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::size_t> removed;
  // Even and odd set sizes (the product takes rows two at a time, an odd one alone), down to a
  // few positions.
  for (const std::size_t leave : {std::size_t{0}, std::size_t{1}, std::size_t{40}, N / 2 + 1, N - 7}) {
    while (removed.size() < leave) {
      const std::size_t q = std::uniform_int_distribution<std::size_t>(0, P.size() - 1)(rng);
      removed.push_back(P.junction(q));
      P.remove(q, 0.0);
    }
    const std::size_t n = P.size();
    CAPTURE(n);
    Eigen::MatrixXd M(n, n);
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t s = 0; s < n; ++s) M(r, s) = r == s ? D[P.junction(r)] : C(P.junction(r), P.junction(s));
    const Eigen::LLT<Eigen::MatrixXd> llt(M);
    std::vector<double> w1(n), w2(n), y1(n), y2(n);
    for (std::size_t q = 0; q < n; ++q) w1[q] = u(rng), w2[q] = u(rng);
    Eigen::VectorXd v1 = Eigen::Map<Eigen::VectorXd>(w1.data(), static_cast<Eigen::Index>(n));
    Eigen::VectorXd v2 = Eigen::Map<Eigen::VectorXd>(w2.data(), static_cast<Eigen::Index>(n));
    std::vector<std::size_t> all(n);
    for (std::size_t q = 0; q < n; ++q) all[q] = q;
    // Every column (the symmetric product over the stored triangle). Measured ≤ 1.1e-15.
    P.apply(all, w1, w2, y1, y2);
    CHECK(relative_error(y1, llt.solve(v1)) < 4e-15);
    CHECK(relative_error(y2, llt.solve(v2)) < 4e-15);
    // The same product on one and on two threads: the same bits (fixed row blocks).
    std::vector<double> z1(n), z2(n);
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    P.apply(all, w1, w2, z1, z2);
    omp_set_num_threads(2);
    P.apply(all, w1, w2, y1, y2);
    omp_set_num_threads(threads);
    CHECK(std::memcmp(z1.data(), y1.data(), n * sizeof(double)) == 0);
    CHECK(std::memcmp(z2.data(), y2.data(), n * sizeof(double)) == 0);
    // G's rows (a slip's redistribution), measured ≤ 1.1e-15.
    for (const std::size_t q : {std::size_t{0}, n / 2, n - 1}) {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
      e[static_cast<Eigen::Index>(q)] = 1.0;
      CHECK(relative_error(P.row(q), llt.solve(e)) < 4e-15);
    }
    // A few columns (the junctions never slipped, late in a run): those columns alone.
    std::vector<std::size_t> few;
    for (std::size_t q = 0; q < n; q += 23) few.push_back(q);
    std::vector<double> f1(n, 0.0), f2(n, 0.0);
    for (std::size_t q : few) f1[q] = w1[q], f2[q] = w2[q];
    P.apply(few, f1, f2, y1, y2);
    v1 = Eigen::Map<Eigen::VectorXd>(f1.data(), static_cast<Eigen::Index>(n));
    v2 = Eigen::Map<Eigen::VectorXd>(f2.data(), static_cast<Eigen::Index>(n));
    CHECK(relative_error(y1, llt.solve(v1)) < 4e-15);
    CHECK(relative_error(y2, llt.solve(v2)) < 4e-15);
  }
}

TEST_CASE(
    "pinned compliance: a pass on the single-precision copy stays within its error bound, and the "
    "reference follows removals",
    "[solve][pinned]") {
  // The stand-in P0.98N (STAND-IN data) with the copy kept at any size. Truth: the dense inverse
  // of M by Eigen's LLT, whose rows' 2-norms give the bound 2⁻²⁴ ‖G_r‖₂ ‖w − ref‖₂ on row r.
  const StandIn t;
  const std::vector<double>& D = t.D;
  const asperity::InteractionMatrix& C = t.C;
  const std::size_t N = t.problem.size();
  PinnedCompliance P(t.problem, D, true, 0);
  REQUIRE(P.single_kept());
  using Pass = PinnedCompliance::Pass;

  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> w1(N), w2(N), y1(N), y2(N), e1(N), e2(N);
  for (std::size_t q = 0; q < N; ++q) w1[q] = u(rng), w2[q] = u(rng);
  const std::vector<double> ref1 = w1, ref2 = w2;
  PinnedCompliance::PassBudget loose{std::vector<double>(N, 1e300), 1e300};
  auto all = [&] {
    std::vector<std::size_t> a(P.size());
    for (std::size_t q = 0; q < a.size(); ++q) a[q] = q;
    return a;
  };
  // No pass before: exact. The same w again: exact and the copy's reference. Both equal the
  // exact product bit for bit.
  P.apply(all(), w1, w2, e1, e2);
  CHECK(P.apply(all(), w1, w2, y1, y2, loose) == Pass::exact);
  CHECK(y1 == e1);
  CHECK(P.apply(all(), w1, w2, y1, y2, loose) == Pass::refresh);
  CHECK(y1 == e1);
  CHECK(y2 == e2);

  // Moved by 1e-3 from the reference, through removals (kept aside, then folded): single passes
  // within the bound, their error of single precision's order (not the double product's).
  std::vector<std::size_t> removed;
  // Fifteen removals kept aside still leave the reference valid (a single pass at once); the
  // sixteenth folds them all.
  for (const std::size_t leave : {std::size_t{0}, std::size_t{3}, std::size_t{15}, std::size_t{19}}) {
    while (removed.size() < leave) {
      const std::size_t q = std::uniform_int_distribution<std::size_t>(0, P.size() - 1)(rng);
      removed.push_back(P.junction(q));
      // w and the reference follow the positions as remove() moves them (the last into q).
      for (auto* v : {&w1, &w2}) (*v)[q] = v->at(P.size() - 1), v->pop_back();
      P.remove(q, 0.0);
    }
    const std::size_t n = P.size();
    CAPTURE(n);
    if (leave == 19) {  // the sixteenth removal folded them into the triangle (sixteen wait for a fold
                        // from single_from on): a new reference first
      P.apply(all(), w1, w2, e1, e2);
      CHECK(P.apply(all(), w1, w2, y1, y2, loose) == Pass::refresh);
      CHECK(std::equal(e1.begin(), e1.begin() + static_cast<std::ptrdiff_t>(n), y1.begin()));
    }
    std::vector<double> v1(n), v2(n);
    for (std::size_t q = 0; q < n; ++q) v1[q] = w1[q] * (1 + 1e-3 * u(rng)), v2[q] = w2[q] * (1 + 1e-3 * u(rng));
    REQUIRE(P.apply(all(), v1, v2, y1, y2, loose) == Pass::single);
    Eigen::MatrixXd M(n, n);
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t s = 0; s < n; ++s) M(r, s) = r == s ? D[P.junction(r)] : C(P.junction(r), P.junction(s));
    const Eigen::MatrixXd inv =
        M.llt().solve(Eigen::MatrixXd::Identity(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n)));
    const Eigen::VectorXd x1 = inv * Eigen::Map<Eigen::VectorXd>(v1.data(), static_cast<Eigen::Index>(n));
    double d1 = 0;
    for (std::size_t q = 0; q < n; ++q) d1 += (v1[q] - w1[q]) * (v1[q] - w1[q]);
    d1 = std::sqrt(d1);
    double worst = 0, largest = 0;  // error / bound; error / |y|
    for (std::size_t r = 0; r < n; ++r) {
      const double bound = std::ldexp(1.0, -24) * inv.row(static_cast<Eigen::Index>(r)).norm() * d1;
      const double err = std::abs(y1[r] - x1[static_cast<Eigen::Index>(r)]);
      // The double product's own rounding is ~1e-15 of |y|: far below the bound here.
      worst = std::max(worst, err / (bound + 4e-15 * x1.cwiseAbs().maxCoeff()));
      largest = std::max(largest, err / x1.cwiseAbs().maxCoeff());
    }
    INFO("error / bound " << worst << ", error / max|y| " << largest);
    // Measured 0.15, 0.098, 0.12, 0.10 of the bound; 2.1e-11, 1.7e-11, 1.8e-11, 2.4e-11 of max |y|.
    CHECK(worst <= 1.0);
    CHECK(largest > 2e-12);  // single precision's, not the double product's ~1e-16
  }
  // A budget below the bound: an exact pass, bit for bit.
  const std::size_t n = P.size();
  std::vector<double> v1(w1.begin(), w1.begin() + static_cast<std::ptrdiff_t>(n)), v2 = v1;
  for (double& x : v1) x *= 1.5;
  PinnedCompliance::PassBudget tight{std::vector<double>(n, 1e-300), 1e-300};
  P.apply(all(), v1, v2, e1, e2);
  CHECK(P.apply(all(), v1, v2, y1, y2, tight) == Pass::exact);
  CHECK(std::equal(e1.begin(), e1.begin() + static_cast<std::ptrdiff_t>(n), y1.begin()));
  CHECK(P.single_passes() == 4);
  CHECK(P.single_refreshes() == 2);
}

TEST_CASE("pinned compliance: every form of the product kernel gives the same bits, within rounding of the exact sums",
          "[solve][pinned]") {
  // Each form this CPU can run (portable, AVX2, AVX-512), on random triangles of every remainder
  // of the four-row quads, from row 0 and from a block starting inside: the same bits as the
  // portable form, in double and from the single-precision copy; and the portable form within a
  // few roundings of the exact sums (long double, each entry's error in units of u Σ|terms|).
  const std::vector<asperity::ProductKernel> forms = asperity::product_kernels();
  REQUIRE(!forms.empty());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double u = std::ldexp(1.0, -53);
  double worst = 0;
  std::size_t compared = 0;
  for (std::size_t n : {1, 2, 3, 4, 5, 6, 7, 8, 9, 13, 64, 301}) {
    std::vector<double> G(n * n), Gs(n * n), w1(n), w2(n);
    std::vector<float> S(n * (n + 1) / 2);
    for (double& g : G) g = uniform(rng);
    for (std::size_t i = 0; i < n; ++i) w1[i] = uniform(rng), w2[i] = uniform(rng);
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t c = r; c < n; ++c) {
        S[asperity::packed_row(r, n) + c] = static_cast<float>(G[r * n + c]);
        Gs[r * n + c] = static_cast<double>(static_cast<float>(G[r * n + c]));
      }
    for (std::size_t r0 : {std::size_t{0}, n / 3}) {
      const auto run = [&](auto rows, const auto* A, std::vector<double>& p1, std::vector<double>& p2) {
        p1.assign(n, 0.0);
        p2.assign(n, 0.0);
        rows(A, n, n, r0, n, w1.data(), w2.data(), p1.data(), p2.data());
      };
      std::vector<double> ref1, ref2, ref1s, ref2s, p1, p2;
      run(forms[0].rows, G.data(), ref1, ref2);
      run(forms[0].rows, Gs.data(), ref1s, ref2s);
      for (const asperity::ProductKernel& k : forms) {
        INFO(k.name << ", n = " << n << ", rows from " << r0);
        run(k.rows, G.data(), p1, p2);
        CHECK(std::memcmp(p1.data(), ref1.data(), n * sizeof(double)) == 0);
        CHECK(std::memcmp(p2.data(), ref2.data(), n * sizeof(double)) == 0);
        if (k.single_rows == nullptr) continue;
        run(k.single_rows, S.data(), p1, p2);
        CHECK(std::memcmp(p1.data(), ref1s.data(), n * sizeof(double)) == 0);
        CHECK(std::memcmp(p2.data(), ref2s.data(), n * sizeof(double)) == 0);
        ++compared;
      }
      // The exact sums of the same terms, and the sums of their magnitudes.
      std::vector<long double> exact(n, 0.0L), scale(n, 0.0L);
      for (std::size_t r = r0; r < n; ++r)
        for (std::size_t c = r; c < n; ++c) {
          const long double g = G[r * n + c];
          exact[r] += g * w1[c];
          scale[r] += std::abs(g * w1[c]);
          if (c == r) continue;
          exact[c] += g * w1[r];
          scale[c] += std::abs(g * w1[r]);
        }
      for (std::size_t i = 0; i < n; ++i)
        if (scale[i] > 0) worst = std::max(worst, static_cast<double>(std::abs(ref1[i] - exact[i]) / (u * scale[i])));
    }
  }
  INFO("forms " << forms.size() << ", single-precision forms compared " << compared);
  // Measured: 1.64 roundings of Σ|terms| at worst (a rigorous bound would be n − 1 of them). A
  // mutant grouping one quad sum differently in the 16-byte form only fails 12 of the comparisons.
  CHECK(worst <= 4.0);
  CHECK(worst > 0.0);  // the sums do round: the comparison is not empty
}
