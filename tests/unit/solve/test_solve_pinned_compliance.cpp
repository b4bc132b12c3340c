// solve/interacting/pinned_compliance.hpp: the pinned set's G = (D + C_PP)⁻¹ and its products
// (the fast solver's chord passes) and rows, against the inverse of the same dense matrix by
// Eigen's LLT (the second method), before and after junctions leave the set (removals are kept
// aside and folded into the stored triangle eight at a time: the sizes below leave some pending).
#include <catch2/catch.hpp>
#include <omp.h>

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

namespace {

using asperity::PinnedCompliance;

// max_q |y_q − exact_q| / max_q |exact_q|
double relative_error(const std::vector<double>& y, const Eigen::VectorXd& exact) {
  double e = 0;
  for (Eigen::Index q = 0; q < exact.size(); ++q) e = std::max(e, std::abs(y[q] - exact[q]));
  return e / exact.cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("pinned compliance: G's products equal the dense inverse's, as junctions leave the set", "[solve][pinned]") {
  // The stand-in P0.98N (STAND-IN data), every junction pinned, D = 1/k_i.
  const asperity::Scene scene = asperity::load_scene(std::filesystem::path(ASPERITY_SOURCE_DIR) / "scenes/paper/P0.98N.yaml",
                                                     {"model.interactions=elastic"});
  const asperity::Problem problem = asperity::make_problem(scene);
  const std::size_t N = problem.size();
  const asperity::JunctionState J(problem.A0, problem.law);
  std::vector<double> D(N);
  for (std::size_t i = 0; i < N; ++i) D[i] = 1.0 / J.k[i];
  const asperity::InteractionMatrix C = asperity::interaction_matrix(problem);
  PinnedCompliance P(problem, D, true);

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
