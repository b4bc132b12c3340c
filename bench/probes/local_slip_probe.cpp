// Probe (ASPERITY_PROBES builds it): how far the local-slip design of docs/interactions.md
// moves the loading branch when each slip's redistribution is applied only on the slipping
// junction's patch and the rest waits for a global refresh every K slips.
// A linear quasi-static model of `bench interacting`'s populations (STAND-IN P4.00N areas): every
// junction linear (D_i = 1/k_i, Mindlin circle), pinned until f_i reaches σA0_i, then slipping at
// ε σA0_i; X grows quasi-statically, f = X a + b on the pinned set. Exact: a removal updates a and
// b with the column g = G e_q of the pinned set's inverse (the Schur identity) and G by the
// rank-one removal. Local: g is replaced by the solve of the pinned junctions within R spacings
// of q (zero outside); every K slips a and b are reset exactly (G of the local run's own pinned
// set, kept aside). Prints the peak force, its position and every junction's slip position against the
// exact run (in units of the exact run's last slip position), and how many slips came in another order.
// Build against a Release build in build/ and run from the repository root:
//   cmake -S . -B build -DASPERITY_PROBES=ON && ninja -C build local_slip_probe
//   OMP_NUM_THREADS=1 build/local_slip_probe N
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "physics/elastic_interaction.hpp"
#include "probe_population.hpp"
using namespace asperity;

struct Run {
  std::vector<double> x_slip;  // by junction
  std::vector<std::size_t> order;
  double F_peak = 0, X_peak = 0;
  long local_solves = 0;
};

int main(int argc, char** argv) {
  const std::size_t N = argc > 1 ? std::atoi(argv[1]) : 1200;
  const ProbePopulation p = probe_population(N);
  const double sigma = 0.23e6 / 0.9, eps = 0.9;
  std::vector<double> D(N), fs(N);
  for (std::size_t i = 0; i < N; ++i)
    D[i] = 1.0 / circle_stiffness(2 * p.radius_m[i], p.E_pa, p.nu), fs[i] = sigma * p.area_m2[i];
  Eigen::MatrixXd M(N, N);
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = 0; j < N; ++j)
      M(i, j) = i == j ? D[i]
                       : disc_compliance(p.x_m[i] - p.x_m[j], p.y_m[i] - p.y_m[j], p.radius_m[i], p.radius_m[j], p.E_pa,
                                         p.nu);
  const Eigen::MatrixXd G0 = M.llt().solve(Eigen::MatrixXd::Identity(N, N));
  const double spacing = std::sqrt(M_PI * p.disc_radius_m * p.disc_radius_m / N);

  // One run: R = 0 exact; else local patches of R spacings, exact reset every K slips.
  const auto run = [&](double R, int K, bool sum_fix) {
    Run out;
    out.x_slip.assign(N, NAN);
    Eigen::MatrixXd G = G0;  // exact inverse of this run's pinned set (zero rows/columns for slipped)
    Eigen::VectorXd a = G * Eigen::VectorXd::Ones(N), b = Eigen::VectorXd::Zero(N), h = Eigen::VectorXd::Zero(N);
    std::vector<char> pinned(N, 1);
    double X = 0, F_slip = 0;
    std::vector<std::size_t> patch;
    for (std::size_t s = 0; s < N; ++s) {
      // Next slip: the most overloaded at X, else the lowest crossing above X.
      std::size_t q = N;
      double best = HUGE_VAL, over = 1.0;
      for (std::size_t i = 0; i < N; ++i) {
        if (!pinned[i]) continue;
        const double f = X * a[i] + b[i];
        if (f >= fs[i] && f / fs[i] >= over) over = f / fs[i], q = i, best = X;
      }
      if (q == N)
        for (std::size_t i = 0; i < N; ++i) {
          if (!pinned[i] || !(a[i] > 0)) continue;
          const double xi = (fs[i] - b[i]) / a[i];
          if (xi < best) best = xi, q = i;
        }
      if (q == N) break;
      X = std::max(X, best);
      double F = F_slip;
      for (std::size_t i = 0; i < N; ++i)
        if (pinned[i]) F += X * a[i] + b[i];
      if (F > out.F_peak) out.F_peak = F, out.X_peak = X;
      out.x_slip[q] = X;
      out.order.push_back(q);
      const double phi = eps * fs[q];
      // The column of the slipping junction: exact, or from its patch alone.
      Eigen::VectorXd g = G.col(q);
      if (R > 0 && (K <= 0 || (s + 1) % K != 0)) {
        patch.clear();
        for (std::size_t i = 0; i < N; ++i)
          if (pinned[i] && std::hypot(p.x_m[i] - p.x_m[q], p.y_m[i] - p.y_m[q]) < R * spacing) patch.push_back(i);
        Eigen::MatrixXd Mp(patch.size(), patch.size());
        Eigen::VectorXd e = Eigen::VectorXd::Zero(patch.size());
        for (std::size_t r = 0; r < patch.size(); ++r) {
          e[r] = patch[r] == q;
          for (std::size_t c = 0; c < patch.size(); ++c) Mp(r, c) = M(patch[r], patch[c]);
        }
        const Eigen::VectorXd gp = Mp.llt().solve(e);
        Eigen::VectorXd gl = Eigen::VectorXd::Zero(N);
        for (std::size_t r = 0; r < patch.size(); ++r) gl[patch[r]] = gp[r];
        if (sum_fix) {  // Σ g = a_q (G symmetric, G 1 = a): the missing sum on the slope field outside
          double missing = a[q] - gl.sum(), w = 0;
          std::vector<char> inside(N, 0);
          for (std::size_t i : patch) inside[i] = 1;
          for (std::size_t i = 0; i < N; ++i)
            if (pinned[i] && !inside[i]) w += a[i];
          if (w > 0)
            for (std::size_t i = 0; i < N; ++i)
              if (pinned[i] && !inside[i]) gl[i] += missing * a[i] / w;
        }
        const double aq = a[q], bq = b[q], gq = gl[q];
        a -= gl * (aq / gq);
        b -= gl * ((bq - phi) / gq);
        ++out.local_solves;
      } else {
        const double aq = a[q], bq = b[q], gq = g[q];
        a -= g * (aq / gq);
        b -= g * ((bq - phi) / gq);
      }
      // This run's exact inverse follows its own removals (for the resets).
      G.noalias() -= g * (g.transpose() / g[q]);
      G.row(q).setZero(), G.col(q).setZero();
      pinned[q] = 0, a[q] = 0, b[q] = 0;
      F_slip += phi;
      for (std::size_t i = 0; i < N; ++i) h[i] += M(i, q) * phi * (i != q);
      if (R > 0 && K > 0 && (s + 1) % K == 0) {  // the global refresh
        a = G * Eigen::VectorXd::Ones(N);
        b = -(G * h);
      }
    }
    return out;
  };

  const Run exact = run(0, 0, false);
  // Slip positions are compared in units of the exact run's last one (the loading's range).
  const double x_last = exact.x_slip[exact.order.back()];
  std::printf(
      "N,R_spacings,K,local_solves,F_peak_rel,X_peak_rel,slip_X_max_of_range,slip_X_median_of_range,order_differs\n");
  std::printf("%zu,exact,-,0,%.17g,%.17g,0,0,0\n", N, exact.F_peak, exact.X_peak);
  std::fflush(stdout);
  for (const bool fix : {false, true})
    for (double R : {4.0, 8.0, 12.0})
      for (int K : {2, 8, 32, 0}) {
        const Run r = run(R, K, fix);
        std::vector<double> d;
        for (std::size_t i = 0; i < N; ++i)
          if (std::isfinite(r.x_slip[i]) && std::isfinite(exact.x_slip[i]))
            d.push_back(std::abs(r.x_slip[i] - exact.x_slip[i]) / x_last);
        std::sort(d.begin(), d.end());
        std::size_t differ = 0;
        for (std::size_t s = 0; s < std::min(r.order.size(), exact.order.size()); ++s)
          differ += r.order[s] != exact.order[s];
        std::printf("%zu,%s%g,%d,%ld,%.3e,%.3e,%.3e,%.3e,%zu\n", N, fix ? "sum-fixed " : "", R, K, r.local_solves,
                    std::abs(r.F_peak / exact.F_peak - 1), std::abs(r.X_peak / exact.X_peak - 1),
                    d.empty() ? NAN : d.back(), d.empty() ? NAN : d[d.size() / 2], differ);
        std::fflush(stdout);
      }
}
