// Probe (ASPERITY_PROBES builds it): is a hierarchical (H-matrix) representation of the pinned
// junctions' compliance M = D + C a faster route than the dense one, at the accuracy the
// interacting solver needs? Issue 26, docs/interactions.md ("Routes measured").
// It assembles M for the bench's synthetic populations (the stand-in P4.00N's areas repeated,
// placed like `bench interacting` does) as an H-matrix with hmat-oss (ACA+, low-rank epsilon eps,
// leaves of `leaf` junctions, admissibility eta), factorises it (LLT), and times a two-column
// solve and product against Eigen's dense LLT, with the relative errors against it.
// Needs Debian's libhmat-oss-dev (not a dependency of asperity) and a Release build in build/:
//   cmake -S . -B build -DASPERITY_PROBES=ON && ninja -C build hmat_probe
//   OMP_NUM_THREADS=1 build/hmat_probe N eps [leaf [eta]]      (from the repository root)
#include <hmat/hmat.h>
#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include "generate/positions.hpp"
#include "physics/elastic_interaction.hpp"
using namespace asperity;
struct Data {
  std::vector<double> x, y, a, D;
  double E = 1.6e6, nu = 0.5;
};
static void entry(void* ctx, int i, int j, void* out) {
  auto* d = static_cast<Data*>(ctx);
  double v;
  if (i == j)
    v = d->D[i];
  else
    v = disc_compliance(d->x[i] - d->x[j], d->y[i] - d->y[j], d->a[i], d->a[j], d->E, d->nu);
  *static_cast<double*>(out) = v;
}
static double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
int main(int argc, char** argv) {
  const int N = std::atoi(argv[1]);
  const double eps = std::atof(argv[2]);
  const int leaf = argc > 3 ? std::atoi(argv[3]) : 64;
  const double eta = argc > 4 ? std::atof(argv[4]) : 2.0;
  std::ifstream in("data/standin/P4.00N/junctions.csv");  // run from the repository root
  if (!in) {
    std::fprintf(stderr, "run from the repository root (data/standin/P4.00N/junctions.csv)\n");
    return 2;
  }
  std::string line;
  std::getline(in, line);
  std::vector<double> A0;
  while (std::getline(in, line)) A0.push_back(std::stod(line.substr(0, line.find(','))));
  const std::size_t N0 = A0.size();
  std::vector<double> areas(N);
  for (int i = 0; i < N; ++i) areas[i] = A0[i % N0];
  const double R = 4.5e-3 * std::sqrt(double(N) / N0);
  Positions p = place_in_contact_disc(areas, R, 20200318);
  Data d;
  d.x = p.x_m;
  d.y = p.y_m;
  d.a.resize(N);
  d.D.resize(N);
  const double G = d.E / (2 * (1 + d.nu));
  for (int i = 0; i < N; ++i) {
    d.a[i] = std::sqrt(areas[i] / M_PI);
    d.D[i] = (2 - d.nu) / (8 * G * d.a[i]);
  }
  std::vector<double> coord(3 * N);
  for (int i = 0; i < N; ++i) {
    coord[3 * i] = d.x[i];
    coord[3 * i + 1] = d.y[i];
    coord[3 * i + 2] = 0;
  }
  hmat_interface_t hmat;
  hmat_settings_t settings;
  hmat_get_parameters(&settings);
  hmat_init_default_interface(&hmat, HMAT_DOUBLE_PRECISION);
  hmat_set_parameters(&settings);
  hmat.init();
  double t0 = now();
  auto* cl = hmat_create_clustering_median();
  auto* cl2 = hmat_create_clustering_max_dof(cl, leaf);
  auto* tree = hmat_create_cluster_tree(coord.data(), 3, N, cl2);
  auto* adm = hmat_create_admissibility_standard(eta);
  auto* H = hmat.create_empty_hmatrix_admissibility(tree, tree, 1, adm);
  hmat.set_low_rank_epsilon(H, eps);
  hmat_assemble_context_t ctx;
  hmat_assemble_context_init(&ctx);
  ctx.progress = nullptr;
  ctx.compression = hmat_create_compression_aca_plus(eps);
  ctx.user_context = &d;
  ctx.simple_compute = entry;
  ctx.lower_symmetric = 1;
  hmat.assemble_generic(H, &ctx);
  double t1 = now();
  hmat_info_t info;
  hmat.get_info(H, &info);
  std::printf("N %d eps %g leaf %d: assemble %.3f s, %.1f MB of %.1f MB\n", N, eps, leaf, t1 - t0,
              8e-6 * info.compressed_size, 8e-6 * info.uncompressed_size);
  // gemv with a copy before factorizing
  hmat_matrix_t* Hc = hmat.copy(H);
  std::vector<double> b(2 * N), x(2 * N);
  for (int i = 0; i < N; ++i) {
    b[i] = 1.0;
    b[N + i] = std::sin(0.37 * i);
  }
  double t2 = now();
  hmat_factorization_context_t fc;
  hmat_factorization_context_init(&fc);
  fc.progress = nullptr;
  fc.factorization = hmat_factorization_llt;
  hmat.factorize_generic(H, &fc);
  double t3 = now();
  hmat.get_info(H, &info);
  std::printf("  LLT %.3f s, %.1f MB\n", t3 - t2, 8e-6 * info.compressed_size);
  x = b;
  const int reps = 10;
  double t4 = now();
  for (int r = 0; r < reps; ++r) {
    x = b;
    hmat.solve_systems(H, x.data(), 2);
  }
  double t5 = now();
  std::vector<double> y(2 * N, 0.0);
  double one = 1, zero = 0;
  double t6 = now();
  for (int r = 0; r < reps; ++r) hmat.gemv('N', &one, Hc, x.data(), &zero, y.data(), 2);
  double t7 = now();
  std::printf("  solve(2 rhs) %.4f s, gemv(2 rhs) %.4f s\n", (t5 - t4) / reps, (t7 - t6) / reps);
  double res = 0, nb = 0;
  for (int i = 0; i < 2 * N; ++i) {
    res += (y[i] - b[i]) * (y[i] - b[i]);
    nb += b[i] * b[i];
  }
  std::printf("  ||H x - b||/||b|| (H-gemv) %.3e\n", std::sqrt(res / nb));
  if (N <= 6000) {
    Eigen::MatrixXd M(N, N);
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) entry(&d, i, j, &M(i, j));
    double t8 = now();
    Eigen::LLT<Eigen::MatrixXd> llt(M);
    double t9 = now();
    Eigen::VectorXd bb = Eigen::Map<Eigen::VectorXd>(b.data(), N);
    Eigen::VectorXd xe = llt.solve(bb);
    Eigen::VectorXd xh = Eigen::Map<Eigen::VectorXd>(x.data(), N);
    Eigen::VectorXd ye = M * xh;
    Eigen::VectorXd yh = Eigen::Map<Eigen::VectorXd>(y.data(), N);
    // The dense solver's chord pass: the explicit inverse times two vectors (here M itself, the
    // same memory traffic).
    Eigen::MatrixXd B2 = Eigen::Map<Eigen::MatrixXd>(b.data(), N, 2), Y2(N, 2);
    double t10 = now();
    for (int r = 0; r < reps; ++r) Y2.noalias() = M * B2;
    double t11 = now();
    std::printf("  dense LLT %.3f s, dense product (2 rhs) %.4f s; solve rel err %.3e; gemv rel err %.3e\n", t9 - t8,
                (t11 - t10) / reps, (xh - xe).norm() / xe.norm(), (yh - ye).norm() / ye.norm());
  }
  return 0;
}
