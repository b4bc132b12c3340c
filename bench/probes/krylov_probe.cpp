// Probe (not part of the build; issue 26): how many coupling products a matrix-free solve of the
// pinned system (D + C) y = b needs. Preconditioned CG with the product of
// solve/interacting/fft_coupling.hpp, preconditioned by Jacobi or by the sparse Cholesky of
// D + C_near (C's exact entries within R_p, Eigen's SimplicialLDLT, AMD ordering), on `bench
// interacting`'s populations (stand-in P4.00N areas), D_i = 1/k_i (Mindlin, the initial areas).
// Also two-level: deflation by bilinear hats on a coarse grid of H spacings (the collective modes)
// around that sparse Cholesky as the smoother (the local ones).
// Right-hand sides: b = 1 (a0 = G 1) and b = C e_j for a junction j near the centre (a slip's
// redistribution). Prints iterations to a relative residual of 1e-10, times, and the error against
// a dense LLT (N ≤ 5,000). With DECAY set, also (to stderr) the dense solution y = M⁻¹ C e_j by
// distance from j: how far a slip's redistribution reaches (results/bench/slip_response_decay.csv). Build against a Release build in build/ and run from the repository root:
//   B=build; g++ -O2 -std=c++20 -Isrc -I/usr/include/eigen3 bench/probes/krylov_probe.cpp -o build/krylov_probe \
//     -Wl,--start-group $B/libasperity_solve.a $B/libasperity_scene.a $B/libasperity_surface.a \
//     $B/libasperity_physics.a $B/libasperity_io.a $B/libasperity_generate.a -Wl,--end-group \
//     -lyaml-cpp -lcrypto -ltbb -lfftw3_threads -lfftw3 -fopenmp
//   NEAR=4 OMP_NUM_THREADS=1 build/krylov_probe 1200 5000 20000   (NEAR: the two-level smoother's exact radius, spacings)
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "generate/positions.hpp"
#include "physics/contact_law.hpp"
#include "physics/elastic_interaction.hpp"
#include "scene/load.hpp"
#include "solve/interacting/fft_coupling.hpp"
using namespace asperity;
using Clock = std::chrono::steady_clock;
static double seconds(Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); }

int main(int argc, char** argv) {
  const Scene base = load_scene("scenes/paper/P4.00N.yaml");
  const auto& areas = base.experiment.junctions.area_m2;
  const double E = base.experiment.E, nu = base.experiment.nu;
  std::printf("N,preconditioner,near_spacings,rhs,setup_s,iterations,solve_ms,product_ms,error_vs_dense,factor_nnz_per_row\n");
  for (int k = 1; k < argc; ++k) {
    const std::size_t N = std::atoi(argv[k]);
    std::vector<double> A(N), a(N), D(N);
    for (std::size_t i = 0; i < N; ++i) {
      A[i] = areas[i % areas.size()], a[i] = disc_radius(A[i]);
      D[i] = 1.0 / circle_stiffness(2 * a[i], E, nu);
    }
    const double Rdisc = 4.5e-3 * std::sqrt(double(N) / double(areas.size()));
    const Positions p = place_in_contact_disc(A, Rdisc, 20200318);
    const FftCoupling C(p.x_m, p.y_m, a, E, nu, TractionWeighting::uniform);
    const auto apply = [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
      C.apply(x.data(), y.data());
      y += Eigen::Map<const Eigen::VectorXd>(D.data(), N).cwiseProduct(x);
    };
    auto t0 = Clock::now();
    Eigen::VectorXd probe_x = Eigen::VectorXd::Ones(N), probe_y(N);
    for (int r = 0; r < 5; ++r) apply(probe_x, probe_y);
    const double product_ms = 1e3 * seconds(t0) / 5;
    // Right-hand sides.
    std::size_t centre = 0;
    for (std::size_t i = 0; i < N; ++i)
      if (std::hypot(p.x_m[i], p.y_m[i]) < std::hypot(p.x_m[centre], p.y_m[centre])) centre = i;
    Eigen::VectorXd ones = Eigen::VectorXd::Ones(N), column(N);
    for (std::size_t i = 0; i < N; ++i)
      column[i] = i == centre ? 0.0 : disc_compliance(p.x_m[i] - p.x_m[centre], p.y_m[i] - p.y_m[centre], a[i], a[centre], E, nu);
    // Dense reference.
    Eigen::VectorXd ref_ones, ref_col;
    if (N <= 5000) {
      Eigen::MatrixXd M(N, N);
      for (std::size_t i = 0; i < N; ++i)
        for (std::size_t j = 0; j < N; ++j)
          M(i, j) = i == j ? D[i] : disc_compliance(p.x_m[i] - p.x_m[j], p.y_m[i] - p.y_m[j], a[i], a[j], E, nu);
      t0 = Clock::now();
      Eigen::LLT<Eigen::MatrixXd> llt(M);
      const double f = seconds(t0);
      t0 = Clock::now();
      ref_ones = llt.solve(ones);
      ref_col = llt.solve(column);
      std::printf("%zu,dense LLT,all,both,%.3f,0,%.3f,0,0,%zu\n", N, f, 1e3 * seconds(t0) / 2, N / 2);
      if (std::getenv("DECAY")) {  // a slip's redistribution, y = M⁻¹ C e_j, by distance from j
        const double spacing = std::sqrt(M_PI * Rdisc * Rdisc / N);
        std::vector<double> ring_max(64, 0.0), ring_sum(64, 0.0);
        double total = 0;
        for (std::size_t i = 0; i < N; ++i) {
          const std::size_t b = std::min<std::size_t>(63, std::hypot(p.x_m[i] - p.x_m[centre], p.y_m[i] - p.y_m[centre]) / spacing);
          ring_max[b] = std::max(ring_max[b], std::abs(ref_col[i]));
          ring_sum[b] += std::abs(ref_col[i]);
          total += std::abs(ref_col[i]);
        }
        double beyond = total;
        for (std::size_t b = 0; b < 64; ++b) {
          beyond -= ring_sum[b];
          if (ring_sum[b] > 0) std::fprintf(stderr, "N %zu ring %zu spacings: max |y| %.3e, share of sum |y| beyond %.3e\n", N, b, ring_max[b] / ref_col.cwiseAbs().maxCoeff(), beyond / total);
        }
      }
    }
    for (double near : {0.0, 2.0, 4.0, 8.0}) {  // 0: Jacobi
      t0 = Clock::now();
      const double R = near * std::sqrt(M_PI * Rdisc * Rdisc / N);
      std::vector<Eigen::Triplet<double>> trip;
      for (std::size_t i = 0; i < N; ++i) {
        trip.emplace_back(i, i, D[i]);
        if (near == 0) continue;
        for (std::size_t j = 0; j < i; ++j) {
          const double dx = p.x_m[i] - p.x_m[j], dy = p.y_m[i] - p.y_m[j];
          if (std::hypot(dx, dy) >= R) continue;
          const double c = disc_compliance(dx, dy, a[i], a[j], E, nu);
          trip.emplace_back(i, j, c), trip.emplace_back(j, i, c);
        }
      }
      Eigen::SparseMatrix<double> P(N, N);
      P.setFromTriplets(trip.begin(), trip.end());
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(P);
      const double setup = seconds(t0);
      if (ldlt.info() != Eigen::Success) { std::printf("%zu,near Cholesky,%g,-,factorisation failed\n", N, near); continue; }
      const double nnz = double(ldlt.matrixL().nestedExpression().nonZeros()) / N;
      for (int which = 0; which < 2; ++which) {
        const Eigen::VectorXd& b = which == 0 ? ones : column;
        t0 = Clock::now();
        Eigen::VectorXd x = Eigen::VectorXd::Zero(N), r = b, z = ldlt.solve(r), d = z, q(N);
        double rz = r.dot(z);
        const double bn = b.norm();
        int it = 0;
        for (; it < 1000 && r.norm() > 1e-10 * bn; ++it) {
          apply(d, q);
          const double alpha = rz / d.dot(q);
          x += alpha * d;
          r -= alpha * q;
          z = ldlt.solve(r);
          const double rz2 = r.dot(z);
          d = z + (rz2 / rz) * d;
          rz = rz2;
        }
        const double ms = 1e3 * seconds(t0);
        const Eigen::VectorXd& ref = which == 0 ? ref_ones : ref_col;
        const double err = ref.size() ? (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff() : NAN;
        std::printf("%zu,%s,%g,%s,%.3f,%d,%.2f,%.3f,%.2e,%.0f\n", N, near == 0 ? "Jacobi" : "near Cholesky", near,
                    which == 0 ? "ones" : "slip column", setup, it, ms, product_ms, err, nnz);
        std::fflush(stdout);
      }
    }
    // Two-level: Jacobi plus a coarse space of bilinear hats on a grid of spacing H (A-DEF2, Tang
    // et al. 2009: P r = J (r − M Z E⁻¹ Zᵀ r) + Z E⁻¹ Zᵀ r, E = Zᵀ M Z; M Z kept, m products to build).
    const double near_s = std::getenv("NEAR") ? std::atof(std::getenv("NEAR")) : 0.0;
    Eigen::SparseMatrix<double> Pn(N, N);
    {
      const double R = near_s * std::sqrt(M_PI * Rdisc * Rdisc / N);
      std::vector<Eigen::Triplet<double>> trip;
      for (std::size_t i = 0; i < N; ++i) {
        trip.emplace_back(i, i, D[i]);
        if (near_s == 0) continue;
        for (std::size_t j = 0; j < i; ++j) {
          const double dx = p.x_m[i] - p.x_m[j], dy = p.y_m[i] - p.y_m[j];
          if (std::hypot(dx, dy) >= R) continue;
          const double c = disc_compliance(dx, dy, a[i], a[j], E, nu);
          trip.emplace_back(i, j, c), trip.emplace_back(j, i, c);
        }
      }
      Pn.setFromTriplets(trip.begin(), trip.end());
    }
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> smoother(Pn);
    for (double Hs : {3.0, 5.0, 8.0}) {
      t0 = Clock::now();
      const double spacing = std::sqrt(M_PI * Rdisc * Rdisc / N), H = Hs * spacing;
      const double x0 = -Rdisc - H, y0 = -Rdisc - H;
      const int nx = static_cast<int>(2 * (Rdisc + H) / H) + 2;
      std::vector<int> node_of(nx * nx, -1);
      std::vector<std::vector<std::pair<int, double>>> rows(N);  // junction → (coarse index, weight)
      int m = 0;
      for (std::size_t i = 0; i < N; ++i) {
        const double tx = (p.x_m[i] - x0) / H, ty = (p.y_m[i] - y0) / H;
        const int I = static_cast<int>(std::floor(tx)), J = static_cast<int>(std::floor(ty));
        for (int di = 0; di < 2; ++di)
          for (int dj = 0; dj < 2; ++dj) {
            const double w = (1 - std::abs(tx - (I + di))) * (1 - std::abs(ty - (J + dj)));
            if (w <= 0) continue;
            int& id = node_of[(I + di) * nx + (J + dj)];
            if (id < 0) id = m++;
            rows[i].emplace_back(id, w);
          }
      }
      Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(N, m), MZ(N, m);
      for (std::size_t i = 0; i < N; ++i)
        for (auto [c, w] : rows[i]) Z(i, c) = w;
      for (int c = 0; c < m; ++c) {
        Eigen::VectorXd zc = Z.col(c), mc(N);
        apply(zc, mc);
        MZ.col(c) = mc;
      }
      const Eigen::MatrixXd Ec = Z.transpose() * MZ;
      const Eigen::LLT<Eigen::MatrixXd> Einv(0.5 * (Ec + Ec.transpose()));
      const double setup = seconds(t0);
      const Eigen::VectorXd Dinv = Eigen::Map<const Eigen::VectorXd>(D.data(), N).cwiseInverse();
      // Deflated PCG (Frank & Vuik 2001): PCG with J on P A x̃ = P b, P = I − A Z E⁻¹ Zᵀ (P A is
      // symmetric), then x = Z E⁻¹ Zᵀ b + x̃ − Z E⁻¹ (A Z)ᵀ x̃.
      const auto deflate = [&](const Eigen::VectorXd& w) { return Eigen::VectorXd(w - MZ * Einv.solve(Z.transpose() * w)); };
      for (int which = 0; which < 2; ++which) {
        const Eigen::VectorXd& b = which == 0 ? ones : column;
        t0 = Clock::now();
        Eigen::VectorXd xt = Eigen::VectorXd::Zero(N), q(N);
        Eigen::VectorXd r = deflate(b), z = smoother.solve(r), d = z;
        double rz = r.dot(z);
        const double bn = r.norm();
        int it = 0;
        for (; it < 1000 && r.norm() > 1e-10 * bn; ++it) {
          apply(d, q);
          q = deflate(q);
          const double alpha = rz / d.dot(q);
          xt += alpha * d;
          r -= alpha * q;
          z = smoother.solve(r);
          const double rz2 = r.dot(z);
          d = z + (rz2 / rz) * d;
          rz = rz2;
        }
        const Eigen::VectorXd x = Z * Einv.solve(Z.transpose() * b) + xt - Z * Einv.solve(MZ.transpose() * xt);
        const double ms = 1e3 * seconds(t0);
        const Eigen::VectorXd& ref = which == 0 ? ref_ones : ref_col;
        const double err = ref.size() ? (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff() : NAN;
        std::printf("%zu,two-level H=%g spacings (%d hats),%g,%s,%.3f,%d,%.2f,%.3f,%.2e,0\n", N, Hs, m, near_s,
                    which == 0 ? "ones" : "slip column", setup, it, ms, product_ms, err);
        std::fflush(stdout);
      }
    }
  }
}
