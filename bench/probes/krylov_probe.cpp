// Probe (ASPERITY_PROBES builds it): how many coupling products a matrix-free solve of the
// pinned system (D + C) y = b needs. Preconditioned CG with the product of
// solve/interacting/fft_coupling.hpp, preconditioned by Jacobi or by the sparse Cholesky of
// D + C_near (C's exact entries within R_p, Eigen's SimplicialLDLT, AMD ordering), on `bench
// interacting`'s populations (stand-in P4.00N areas), D_i = 1/k_i (Mindlin, the initial areas).
// Also two-level: deflation by bilinear hats on a coarse grid of H spacings (the collective modes)
// around that sparse Cholesky as the smoother (the local ones).
// Right-hand sides: b = 1 (a0 = G 1), b = C e_j for a junction j near the centre (a slip's
// redistribution), and e_j itself (the column an exact slip position needs; from zero and from
// the dense solve on its patch of 12 spacings, to 1e-8 and 1e-10). Prints iterations to a relative residual of 1e-10, times, and the error against
// a dense LLT (N ≤ 5,000). With DECAY set, also (to stderr) the dense solution y = M⁻¹ C e_j by
// distance from j: how far a slip's redistribution reaches (results/bench/slip_response_decay.csv). Build against a Release build in build/ and run from the repository root:
//   cmake -S . -B build -DASPERITY_PROBES=ON && ninja -C build krylov_probe
//   NEAR=4 OMP_NUM_THREADS=1 build/krylov_probe 1200 5000 20000   (NEAR: the two-level smoother's exact radius, spacings)
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <vector>

#include "physics/elastic_interaction.hpp"
#include "probe_population.hpp"
#include "solve/interacting/fft_coupling.hpp"
using namespace asperity;
using Vector = Eigen::VectorXd;
using Map = std::function<Vector(const Vector&)>;

// Preconditioned CG on op x = b to a residual of tol |b|, from x if it has b's size (else from
// zero); returns the iterations.
int pcg(const Map& op, const Map& precondition, const Vector& b, Vector& x, double tol = 1e-10) {
  if (x.size() != b.size()) x = Vector::Zero(b.size());
  Vector r = x.isZero() ? b : Vector(b - op(x)), z = precondition(r), d = z;
  double rz = r.dot(z);
  int it = 0;
  for (const double stop = tol * b.norm(); it < 1000 && r.norm() > stop; ++it) {
    const Vector q = op(d);
    const double alpha = rz / d.dot(q);
    x += alpha * d;
    r -= alpha * q;
    z = precondition(r);
    const double rz2 = r.dot(z);
    d = z + (rz2 / rz) * d;
    rz = rz2;
  }
  return it;
}

// D + C over the pairs closer than `spacings` mean spacings (D alone at 0).
Eigen::SparseMatrix<double> near_field(const ProbePopulation& p, const std::vector<double>& D, double spacings) {
  const std::size_t N = D.size();
  const double R = spacings * std::sqrt(M_PI * p.disc_radius_m * p.disc_radius_m / N);
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t i = 0; i < N; ++i) {
    trip.emplace_back(i, i, D[i]);
    for (std::size_t j = 0; j < i && spacings > 0; ++j) {
      const double dx = p.x_m[i] - p.x_m[j], dy = p.y_m[i] - p.y_m[j];
      if (std::hypot(dx, dy) >= R) continue;
      const double c = disc_compliance(dx, dy, p.radius_m[i], p.radius_m[j], p.E_pa, p.nu);
      trip.emplace_back(i, j, c), trip.emplace_back(j, i, c);
    }
  }
  Eigen::SparseMatrix<double> P(N, N);
  P.setFromTriplets(trip.begin(), trip.end());
  return P;
}

int main(int argc, char** argv) {
  std::printf(
      "N,preconditioner,near_spacings,rhs,setup_s,iterations,solve_ms,product_ms,error_vs_dense,factor_nnz_per_row\n");
  const double near_s = std::getenv("NEAR") ? std::atof(std::getenv("NEAR")) : 0.0;
  for (int k = 1; k < argc; ++k) {
    const std::size_t N = std::atoi(argv[k]);
    const ProbePopulation p = probe_population(N);
    const std::vector<double>& a = p.radius_m;
    const double E = p.E_pa, nu = p.nu;
    std::vector<double> D(N);
    for (std::size_t i = 0; i < N; ++i) D[i] = 1.0 / circle_stiffness(2 * a[i], E, nu);
    const FftCoupling C(p.x_m, p.y_m, a, E, nu, TractionWeighting::uniform);
    const Map apply = [&](const Vector& x) {
      Vector y(N);
      C.apply(x.data(), y.data());
      return Vector(y + Eigen::Map<const Vector>(D.data(), N).cwiseProduct(x));
    };
    auto t0 = ProbeClock::now();
    for (int r = 0; r < 5; ++r) apply(Vector::Ones(N));
    const double product_ms = 1e3 * seconds_since(t0) / 5;
    // Right-hand sides: 1, and the column of C of the junction nearest the centre.
    std::size_t centre = 0;
    for (std::size_t i = 0; i < N; ++i)
      if (std::hypot(p.x_m[i], p.y_m[i]) < std::hypot(p.x_m[centre], p.y_m[centre])) centre = i;
    Vector column(N);
    for (std::size_t i = 0; i < N; ++i)
      column[i] = i == centre
                      ? 0.0
                      : disc_compliance(p.x_m[i] - p.x_m[centre], p.y_m[i] - p.y_m[centre], a[i], a[centre], E, nu);
    // The slipping junction's own column, M⁻¹ e_j (exact slip positions need it, one a slip),
    // from zero and from the solve on its patch alone (the pinned junctions within 12 spacings,
    // dense), to 1e-8 and 1e-10.
    const Vector unit = Vector::Unit(N, centre);
    Vector local = Vector::Zero(N);
    {
      const double reach = 12 * std::sqrt(M_PI * p.disc_radius_m * p.disc_radius_m / N);
      std::vector<std::size_t> patch;
      for (std::size_t i = 0; i < N; ++i)
        if (std::hypot(p.x_m[i] - p.x_m[centre], p.y_m[i] - p.y_m[centre]) < reach) patch.push_back(i);
      Eigen::MatrixXd Mp(patch.size(), patch.size());
      Vector ep = Vector::Zero(patch.size());
      for (std::size_t r = 0; r < patch.size(); ++r) {
        ep[r] = patch[r] == centre;
        for (std::size_t c = 0; c < patch.size(); ++c) {
          const std::size_t i = patch[r], j = patch[c];
          Mp(r, c) = i == j ? D[i] : disc_compliance(p.x_m[i] - p.x_m[j], p.y_m[i] - p.y_m[j], a[i], a[j], E, nu);
        }
      }
      const Vector zp = Eigen::LLT<Eigen::MatrixXd>(Mp).solve(ep);
      for (std::size_t r = 0; r < patch.size(); ++r) local[patch[r]] = zp[r];
      std::fprintf(stderr, "N %zu: patch of %zu junctions\n", N, patch.size());
    }
    const Vector rhs[3] = {Vector::Ones(N), column, unit};
    const char* rhs_name[3] = {"ones", "slip column", "unit"};
    // Dense reference.
    Vector ref[3];
    if (N <= 5000) {
      Eigen::MatrixXd M(N, N);
      for (std::size_t i = 0; i < N; ++i)
        for (std::size_t j = 0; j < N; ++j)
          M(i, j) = i == j ? D[i] : disc_compliance(p.x_m[i] - p.x_m[j], p.y_m[i] - p.y_m[j], a[i], a[j], E, nu);
      t0 = ProbeClock::now();
      Eigen::LLT<Eigen::MatrixXd> llt(M);
      const double f = seconds_since(t0);
      t0 = ProbeClock::now();
      ref[0] = llt.solve(rhs[0]), ref[1] = llt.solve(rhs[1]), ref[2] = llt.solve(rhs[2]);
      std::printf("%zu,dense LLT,all,both,%.3f,0,%.3f,0,0,%zu\n", N, f, 1e3 * seconds_since(t0) / 2, N / 2);
      if (std::getenv("DECAY")) {  // a slip's redistribution, y = M⁻¹ C e_j, by distance from j
        const double spacing = std::sqrt(M_PI * p.disc_radius_m * p.disc_radius_m / N);
        std::vector<double> ring_max(64, 0.0), ring_sum(64, 0.0);
        double total = 0;
        for (std::size_t i = 0; i < N; ++i) {
          const std::size_t b =
              std::min<std::size_t>(63, std::hypot(p.x_m[i] - p.x_m[centre], p.y_m[i] - p.y_m[centre]) / spacing);
          ring_max[b] = std::max(ring_max[b], std::abs(ref[1][i]));
          ring_sum[b] += std::abs(ref[1][i]);
          total += std::abs(ref[1][i]);
        }
        double beyond = total;
        for (std::size_t b = 0; b < 64; ++b) {
          beyond -= ring_sum[b];
          if (ring_sum[b] > 0)
            std::fprintf(stderr, "N %zu ring %zu spacings: max |y| %.3e, share of sum |y| beyond %.3e\n", N, b,
                         ring_max[b] / ref[1].cwiseAbs().maxCoeff(), beyond / total);
        }
      }
    }
    const auto report = [&](const char* name, double near, int which, double setup, int it, double ms, const Vector& x,
                            double nnz, const char* variant = "") {
      const double err =
          ref[which].size() ? (x - ref[which]).cwiseAbs().maxCoeff() / ref[which].cwiseAbs().maxCoeff() : NAN;
      std::printf("%zu,%s,%g,%s%s,%.3f,%d,%.2f,%.3f,%.2e,%.0f\n", N, name, near, rhs_name[which], variant, setup, it,
                  ms, product_ms, err, nnz);
      std::fflush(stdout);
    };
    // One level: Jacobi (0) or the near field's sparse Cholesky.
    for (double near : {0.0, 2.0, 4.0, 8.0}) {
      t0 = ProbeClock::now();
      const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(near_field(p, D, near));
      const double setup = seconds_since(t0);
      if (ldlt.info() != Eigen::Success) {
        std::printf("%zu,near Cholesky,%g,-,factorisation failed\n", N, near);
        continue;
      }
      const double nnz = double(ldlt.matrixL().nestedExpression().nonZeros()) / N;
      for (int which = 0; which < 2; ++which) {
        t0 = ProbeClock::now();
        Vector x;
        const int it = pcg(
            apply, [&](const Vector& r) { return Vector(ldlt.solve(r)); }, rhs[which], x);
        report(near == 0 ? "Jacobi" : "near Cholesky", near, which, setup, it, 1e3 * seconds_since(t0), x, nnz);
      }
      for (const double tol : {1e-8, 1e-10})
        for (const bool from_patch : {false, true}) {
          t0 = ProbeClock::now();
          Vector x = from_patch ? local : Vector();
          const int it = pcg(
              apply, [&](const Vector& r) { return Vector(ldlt.solve(r)); }, unit, x, tol);
          report(near == 0 ? "Jacobi" : "near Cholesky", near, 2, setup, it, 1e3 * seconds_since(t0), x, nnz,
                 tol == 1e-8 ? (from_patch ? " to 1e-8 from its patch" : " to 1e-8")
                             : (from_patch ? " to 1e-10 from its patch" : " to 1e-10"));
        }
    }
    // Two levels: deflation by bilinear hats on a coarse grid of H spacings (the collective modes)
    // around the near field's Cholesky of NEAR spacings as the smoother (the local ones). Deflated
    // PCG (Frank & Vuik 2001): PCG on P A x̃ = P b, P = I − A Z E⁻¹ Zᵀ, E = Zᵀ A Z (P A is
    // symmetric; A Z kept, m products to build), then x = Z E⁻¹ Zᵀ b + x̃ − Z E⁻¹ (A Z)ᵀ x̃.
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> smoother(near_field(p, D, near_s));
    for (double Hs : {3.0, 5.0, 8.0}) {
      t0 = ProbeClock::now();
      const double R = p.disc_radius_m, H = Hs * std::sqrt(M_PI * R * R / N);
      const double x0 = -R - H, y0 = -R - H;
      const int nx = static_cast<int>(2 * (R + H) / H) + 2;
      std::vector<int> node_of(nx * nx, -1);
      std::vector<Eigen::Triplet<double>> hats;
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
            hats.emplace_back(i, id, w);
          }
      }
      Eigen::SparseMatrix<double> Zs(N, m);
      Zs.setFromTriplets(hats.begin(), hats.end());
      const Eigen::MatrixXd Z(Zs);
      Eigen::MatrixXd AZ(N, m);
      for (int c = 0; c < m; ++c) AZ.col(c) = apply(Z.col(c));
      const Eigen::MatrixXd Ec = Z.transpose() * AZ;
      const Eigen::LLT<Eigen::MatrixXd> Einv(0.5 * (Ec + Ec.transpose()));
      const double setup = seconds_since(t0);
      const Map deflate = [&](const Vector& w) { return Vector(w - AZ * Einv.solve(Z.transpose() * w)); };
      char name[64];
      std::snprintf(name, sizeof name, "two-level H=%g spacings (%d hats)", Hs, m);
      for (int which = 0; which < 2; ++which) {
        t0 = ProbeClock::now();
        Vector xt;
        const int it = pcg([&](const Vector& v) { return deflate(apply(v)); },
                           [&](const Vector& r) { return Vector(smoother.solve(r)); }, deflate(rhs[which]), xt);
        const Vector x = Z * Einv.solve(Z.transpose() * rhs[which]) + xt - Z * Einv.solve(AZ.transpose() * xt);
        report(name, near_s, which, setup, it, 1e3 * seconds_since(t0), x, 0);
      }
      for (const double tol : {1e-8, 1e-10})
        for (const bool from_patch : {false, true}) {
          t0 = ProbeClock::now();
          Vector xt = from_patch ? local : Vector();
          const Vector b = deflate(unit);
          const int it =
              pcg([&](const Vector& v) { return deflate(apply(v)); },
                  [&](const Vector& r) { return Vector(smoother.solve(r)); }, b, xt, tol * unit.norm() / b.norm());
          const Vector x = Z * Einv.solve(Z.transpose() * unit) + xt - Z * Einv.solve(AZ.transpose() * xt);
          report(name, near_s, 2, setup, it, 1e3 * seconds_since(t0), x, 0,
                 tol == 1e-8 ? (from_patch ? " to 1e-8 from its patch" : " to 1e-8")
                             : (from_patch ? " to 1e-10 from its patch" : " to 1e-10"));
        }
    }
  }
}
