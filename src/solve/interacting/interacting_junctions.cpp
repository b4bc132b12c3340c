#include "solve/interacting/interacting_junctions.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "physics/interface_law.hpp"
#include "solve/interacting/anderson.hpp"
#include "solve/core/run_info.hpp"

// LAPACK (Debian liblapack-dev, or any optimised implementation behind the same symbols):
// Cholesky factorisation and inverse of a symmetric positive definite matrix, in place.
extern "C" {
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
void dpotri_(const char* uplo, const int* n, double* a, const int* lda, int* info);
}

namespace asperity {

struct InteractingJunctions::Node {
  double X = 0, F = 0, dF = 0, A = 0, dA = 0;
  std::vector<double> f, a;  // per position of P: force [N] and df/dX [N/m]
};

namespace {

// Work below which a loop over G stays on one thread (thread start-up costs more).
constexpr std::size_t kParallelWork = 200000;

[[noreturn]] void fail(const std::string& what, double X) {
  char msg[300];
  std::snprintf(msg, sizeof msg, "interacting event solver: %s at X = %.6g m", what.c_str(), X);
  throw SolverError(msg);
}

// Cubic Hermite on [x0, x1] from values and slopes at both ends, at X (also outside, continued);
// its slope there in *slope when asked.
double hermite(double x0, double x1, double v0, double d0, double v1, double d1, double X, double* slope = nullptr) {
  const double h = x1 - x0;
  const double t = (X - x0) / h;
  const double c2 = 3 * (v1 - v0) - h * (2 * d0 + d1);
  const double c3 = 2 * (v0 - v1) + h * (d0 + d1);
  if (slope) *slope = d0 + t * (2 * c2 + 3 * t * c3) / h;
  return v0 + t * (h * d0 + t * (c2 + t * c3));
}

}  // namespace

InteractingJunctions::InteractingJunctions(const Problem& problem)
    : p_(problem),
      law_(problem.law),
      area_law_(problem.law.alpha_b > 0 ? problem.area_law : AreaLaw::until_first_slip),
      nonlinear_law_(problem.law.alpha_b > 0),
      N_(problem.size()),
      C_(interaction_matrix(problem)),
      G_(problem.size() * problem.size(), 0.0),
      J_(problem.A0, problem.law),
      tol_(0.1 * problem.solver.tolerance) {
  c_.assign(N_, 0.0);
  s_.assign(N_, 0.0);
  f_slip_nl_.assign(N_, 0.0);
  psi_guess_.assign(N_, 0.0);
  double psi_hi = 0;
  if (nonlinear_law_) {
    for (std::size_t i = 0; i < N_; ++i) {
      const double A0 = J_.A0[i];
      s_[i] = law_.force_scale(A0);
      c_[i] = initial_diameter(A0) * law_.E * s_[i];
      psi_hi = std::max(psi_hi, universal_psi(law_.slip_phi(A0), law_.nu, law_.shape));
      f_slip_nl_[i] = law_.slip_phi(A0) / s_[i];
    }
    table_ = universal_force_law(law_.nu, law_.shape, 1.1 * psi_hi);
    if (!(table_->max_rel_error() <= 1e-11)) fail("the universal force law's table is not accurate enough", 0.0);
  }
  idx_.resize(N_);
  pos_.resize(N_);
  D_.resize(N_);
  h_.assign(N_, 0.0);
  a0_.assign(N_, 0.0);
  b0_.assign(N_, 0.0);
  nl_.assign(N_, nonlinear_law_ ? 1 : 0);
  for (std::size_t i = 0; i < N_; ++i) {
    idx_[i] = static_cast<std::uint32_t>(i);
    pos_[i] = i;
    D_[i] = 1.0 / J_.k[i];  // u'(0) = 1/k0 for both kinds
    if (!nonlinear_law_) A_fixed_ += J_.A0[i];
  }
  nP_ = N_;
  n_nl_ = nonlinear_law_ ? N_ : 0;
  n_intact_ = static_cast<std::int64_t>(N_);
  last_f_.assign(N_, 0.0);
  last_a_.assign(N_, 0.0);
  rebuild();
  after_change(0.0);
}

InteractingJunctions::~InteractingJunctions() = default;

bool InteractingJunctions::has_threshold() const { return std::isfinite(x_up_); }
bool InteractingJunctions::has_threshold_below() const { return std::isfinite(x_down_); }

double InteractingJunctions::threshold(std::size_t q) const {
  const std::size_t i = idx_[q];
  // Eq. (3) junctions slip at f = σ A(f), φ = φ_s; the others at σ times their frozen area.
  return nl_[q] ? f_slip_nl_[i] : J_.f_s[i];
}

void InteractingJunctions::own(std::size_t q, double f, double& u, double& du) const {
  const std::size_t i = idx_[q];
  if (!nl_[q]) {
    u = f / J_.k[i];
    du = 1.0 / J_.k[i];
    return;
  }
  // Universal law: φ = s f = ψ g(ψ) (the tabulated inverse of ψ = φ/κ(1 − φ²)), u = ψ/c, so
  // ψ by Newton on the table from the junction's last ψ (two or three cubic evaluations
  // instead of the elliptic integrals); dψ/dφ = 1/(g + ψ g').
  const double lim = 1.0 - 1e-12;
  const double phi = std::clamp(s_[i] * f, -lim, lim);
  double psi = psi_guess_[i];
  double d[4];
  double dpsi = 0;
  bool ok = false;
  for (int it = 0; it < 8; ++it) {
    if (!table_->g_derivatives(psi, d)) break;
    dpsi = 1.0 / (d[0] + psi * d[1]);
    const double step = (psi * d[0] - phi) * dpsi;
    psi -= step;
    if (std::abs(step) <= 1e-15 * std::abs(psi)) {
      ok = table_->g_derivatives(psi, d);
      if (ok) dpsi = 1.0 / (d[0] + psi * d[1]);
      break;
    }
  }
  if (!ok) {  // beyond the table (far past the slip force): the exact law
    psi = universal_psi(phi, law_.nu, law_.shape);
    const double h = 1e-6;
    const double p1 = std::min(phi + h, lim), p0 = std::max(phi - h, -lim);
    dpsi = (universal_psi(p1, law_.nu, law_.shape) - universal_psi(p0, law_.nu, law_.shape)) / (p1 - p0);
  }
  psi_guess_[i] = psi;
  u = psi / c_[i];
  du = dpsi * s_[i] / c_[i];
}

// ---- exact solves -------------------------------------------------------------------------

void InteractingJunctions::warm_start(double X, std::vector<double>& f, std::vector<double>& a) const {
  const std::size_t n = nP_;
  // Per junction, f and df/dX are smooth between events: the cubic Hermite of the two nodes
  // around X (or of the two nearest on one side, extrapolated no farther than their spacing
  // twice over) starts the iteration within O(h^4) of the solution instead of the first-order
  // prediction's O(h^2); fewer passes over G for the same fixed point (the stopping rule is
  // unchanged). Without two nodes: the nearest node's first-order prediction, then the seed a
  // slip left at this X (the old solution plus the redistribution of the slipped junction's
  // force), then the last solution.
  const std::size_t m = nodes_.size();
  if (m >= 2) {
    auto it = std::lower_bound(nodes_.begin(), nodes_.end(), X, [](const Node& k, double x) { return k.X < x; });
    std::size_t hi = static_cast<std::size_t>(it - nodes_.begin());
    hi = std::clamp<std::size_t>(hi, 1, m - 1);
    const Node& n0 = nodes_[hi - 1];
    const Node& n1 = nodes_[hi];
    const double h = n1.X - n0.X;
    const double t = (X - n0.X) / h;
    if (h > 0 && t >= -2.0 && t <= 3.0) {
      for (std::size_t q = 0; q < n; ++q)
        f[q] = hermite(n0.X, n1.X, n0.f[q], n0.a[q], n1.f[q], n1.a[q], X, &a[q]);
      return;
    }
  }
  if (m >= 1) {
    const Node* near = &nodes_[0];
    for (const Node& k : nodes_)
      if (std::abs(k.X - X) < std::abs(near->X - X)) near = &k;
    for (std::size_t q = 0; q < n; ++q) {
      f[q] = near->f[q] + near->a[q] * (X - near->X);
      a[q] = near->a[q];
    }
    return;
  }
  if (seed_valid_ && seed_X_ == X && seed_f_.size() == n) {
    f = seed_f_;
    a = seed_a_;
    return;
  }
  for (std::size_t q = 0; q < n; ++q) {
    f[q] = last_f_[idx_[q]];
    a[q] = last_a_[idx_[q]];
  }
}

InteractingJunctions::Node InteractingJunctions::solve(double X) const {
  const std::size_t n = nP_, N = N_;
  Node node;
  node.X = X;
  node.f.resize(n);
  node.a.resize(n);
  if (n_nl_ == 0) {
    for (std::size_t q = 0; q < n; ++q) {
      node.f[q] = X * a0_[q] + b0_[q];
      node.a[q] = a0_[q];
    }
  } else {
    warm_start(X, node.f, node.a);
    std::vector<double> dl(n, 0.0), da(n, 0.0), y1(n), y2(n);
    std::vector<std::size_t> active;
    active.reserve(n_nl_);
    for (std::size_t q = 0; q < n; ++q)
      if (nl_[q]) active.push_back(q);
    // Anderson acceleration of the chord map on the active positions' forces and slopes, scaled
    // to O(1) (f by the slip force, df/dX by the mean |a0|). The chord map contracts linearly at
    // the drift of u' from D, almost the same linear map from one iteration to the next, so the
    // last few residuals predict most of the remaining error: fewer passes over G for the same
    // fixed point (the stopping rule is unchanged).
    const std::size_t nA = active.size();
    double a_scale = 0;
    for (std::size_t q : active) a_scale += std::abs(a0_[q]);
    a_scale = nA > 0 && a_scale > 0 ? a_scale / static_cast<double>(nA) : 1.0;
    Anderson aa(2 * nA);
    std::vector<double> z(2 * nA), g(2 * nA);
    double previous = HUGE_VAL;
    int iter = 0, refreshes = 0;
    for (;;) {
      ++iter;
      for (std::size_t q : active) {
        double u, du;
        own(q, node.f[q], u, du);
        dl[q] = u - D_[q] * node.f[q];
        da[q] = (du - D_[q]) * node.a[q];
      }
      // y = G [Δ, Δ'a]: the rows of the nonlinear positions (G symmetric), split by output range.
      std::fill(y1.begin(), y1.end(), 0.0);
      std::fill(y2.begin(), y2.end(), 0.0);
      const double* G = G_.data();
#pragma omp parallel if (n * active.size() > kParallelWork)
      {
        const std::size_t T = static_cast<std::size_t>(omp_get_num_threads());
        const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
        const std::size_t lo = n * t / T, hi = n * (t + 1) / T;
        double* o1 = y1.data();
        double* o2 = y2.data();
        for (std::size_t q : active) {
          const double w1 = dl[q], w2 = da[q];
          const double* gq = G + q * N;
          for (std::size_t r = lo; r < hi; ++r) {
            o1[r] += w1 * gq[r];
            o2[r] += w2 * gq[r];
          }
        }
      }
      // The chord map's image g and the current iterate z, scaled, on the active positions.
      for (std::size_t k = 0; k < nA; ++k) {
        const std::size_t q = active[k];
        const double thr = threshold(q);
        z[k] = node.f[q] / thr;
        g[k] = (X * a0_[q] + b0_[q] - y1[q]) / thr;
        z[nA + k] = node.a[q] / a_scale;
        g[nA + k] = (a0_[q] - y2[q]) / a_scale;
      }
      // Damped: no nonlinear junction's φ = s f moves by more than 0.1 in one iteration (far
      // from the solution, e.g. a poor warm start, the full step can overshoot into φ → 1).
      // The accelerated step is taken only where the plain one needs no damping and stays
      // within the same bound itself.
      double step_phi = 0;
      for (std::size_t k = 0; k < nA; ++k) {
        const std::size_t q = active[k];
        step_phi = std::max(step_phi, s_[idx_[q]] * threshold(q) * std::abs(g[k] - z[k]));
      }
      const double damp = step_phi > 0.1 ? 0.1 / step_phi : 1.0;
      bool accelerated = false;
      if (damp == 1.0) {
        accelerated = aa.step(z, g);  // g becomes the accelerated iterate when true
        if (accelerated) {
          double jump = 0;
          for (std::size_t k = 0; k < nA; ++k) {
            const std::size_t q = active[k];
            jump = std::max(jump, s_[idx_[q]] * threshold(q) * std::abs(g[k] - z[k]));
          }
          if (!(jump <= 0.1)) {  // an extrapolation too far: back to the plain step
            aa.clear();
            accelerated = false;
            for (std::size_t k = 0; k < nA; ++k) {
              const std::size_t q = active[k];
              g[k] = (X * a0_[q] + b0_[q] - y1[q]) / threshold(q);
              g[nA + k] = (a0_[q] - y2[q]) / a_scale;
            }
          }
        }
      } else {
        aa.clear();
      }
      double change = 0;
      for (std::size_t q = 0; q < n; ++q) {
        if (nl_[q]) continue;
        const double f = node.f[q] + damp * (X * a0_[q] + b0_[q] - y1[q] - node.f[q]);
        change = std::max(change, std::abs(f - node.f[q]) / threshold(q));
        node.f[q] = f;
        node.a[q] = a0_[q] - y2[q];
      }
      for (std::size_t k = 0; k < nA; ++k) {
        const std::size_t q = active[k];
        const double thr = threshold(q);
        const double f = thr * (z[k] + damp * (g[k] - z[k]));
        change = std::max(change, std::abs(f - node.f[q]) / thr);
        node.f[q] = f;
        node.a[q] = a_scale * g[nA + k];
      }
      if (change <= 1e-13) break;
      // Slow contraction: the reference compliances drifted from the junctions' own. Take them
      // at the current forces and rebuild G (a Newton step's Jacobian): the solution is the
      // same, the iteration fast again.
      if (iter >= 3 && change > 0.2 * previous && change > 1e-11 && refreshes < 5) {
        ++refreshes;
        for (std::size_t q : active) {
          double u, du;
          own(q, node.f[q], u, du);
          D_[q] = du;
        }
        rebuild();
        aa.clear();
        previous = HUGE_VAL;
        continue;
      }
      // Stalled at rounding: the change stops shrinking once it is of the order of the
      // rounding of the sums.
      if (iter >= 3 && change < 1e-12 && change > 0.5 * previous) break;
      if (iter >= 200) fail("the chord iteration did not converge in 200 iterations", X);
      previous = change;
    }
    work_.iterations += iter;
    last_iterations_ = iter;
  }
  // Totals and their X-derivatives.
  double F = F_slip_, dF = 0, A = A_fixed_, dA = 0;
  for (std::size_t q = 0; q < n; ++q) {
    F += node.f[q];
    dF += node.a[q];
    if (nl_[q]) {
      const std::size_t i = idx_[q];
      const double phi = s_[i] * node.f[q];
      A += sheared_area_phi(J_.A0[i], phi);
      dA += sheared_area_phi_slope(J_.A0[i], phi) * s_[i] * node.a[q];
    }
  }
  node.F = F;
  node.dF = dF;
  node.A = A;
  node.dA = dA;
  for (std::size_t q = 0; q < n; ++q) {
    last_f_[idx_[q]] = node.f[q];
    last_a_[idx_[q]] = node.a[q];
  }
  ++work_.solves;
  return node;
}

const InteractingJunctions::Node& InteractingJunctions::node_at(double X) const {
  auto it = std::lower_bound(nodes_.begin(), nodes_.end(), X, [](const Node& m, double x) { return m.X < x; });
  if (it != nodes_.end() && it->X == X) return *it;
  Node fresh = solve(X);
  it = std::lower_bound(nodes_.begin(), nodes_.end(), X, [](const Node& m, double x) { return m.X < x; });
  return *nodes_.insert(it, std::move(fresh));
}

// ---- the cache of nodes: piecewise cubic Hermite F(X), A(X) -------------------------------

bool InteractingJunctions::segment_ok(std::size_t s) const {
  const Node& a = nodes_[s];
  const Node& b = nodes_[s + 1];
  const double h = b.X - a.X;
  if (h <= 1e-13 * std::max(std::abs(a.X), std::abs(b.X))) return true;  // at the resolution of X
  // The Hermite piece's error is h^4 F''''/384; with F'''' ~ F'''/L (L = |F/F'|, the scale of X
  // on which F varies, smooth between events) and the cubic term c3 ~ h^3 F'''/6, it is about
  // c3 h/(64 L).
  const double L = (std::abs(a.F) + std::abs(b.F)) / (std::abs(a.dF) + std::abs(b.dF) + 1e-300);
  const double shrink = L > 0 ? std::min(1.0, h / (64 * L)) : 1.0;
  const double c3F = 2 * (a.F - b.F) + h * (a.dF + b.dF);
  const double c3A = 2 * (a.A - b.A) + h * (a.dA + b.dA);
  const double sF = std::max(std::abs(a.F), std::abs(b.F)) + 1e-300;
  const double sA = std::max(std::abs(a.A), std::abs(b.A)) + 1e-300;
  return std::abs(c3F) * shrink <= tol_ * sF && std::abs(c3A) * shrink <= tol_ * sA;
}

void InteractingJunctions::refine_all() const {
  for (std::size_t s = 0; s + 1 < nodes_.size();) {
    if (segment_ok(s)) {
      ++s;
      continue;
    }
    const double mid = 0.5 * (nodes_[s].X + nodes_[s + 1].X);
    Node m = solve(mid);
    nodes_.insert(nodes_.begin() + static_cast<std::ptrdiff_t>(s + 1), std::move(m));
  }
}

std::size_t InteractingJunctions::continuation_node(double X) const {
  // Past the next slip position (an integrator stage beyond the event, which the event then cuts
  // off) the set has changed, so the current set's F(X) there is only a smooth continuation for
  // the step's stages: the cubic Hermite from a node at least as far behind the last node as X
  // is ahead of it, continued (value and slope continuous at the slip position; no solve).
  // Farther out, or with too short a cache, nothing (a solve): a cubic continued well beyond its
  // interval drifts off, and a step taken on it would wander.
  const std::size_t m = nodes_.size();
  if (m < 2 || !(X > nodes_.back().X) || !(nodes_.back().X >= x_up_)) return npos;
  const double d = X - nodes_.back().X;
  for (std::size_t a = m - 1; a-- > 0;)
    if (nodes_.back().X - nodes_[a].X >= d) return a;
  return npos;
}

std::size_t InteractingJunctions::covering_segment(double X) const {
  if (X < nodes_.front().X || X > nodes_.back().X) {
    // Extend past X by the cache's width (a slider oscillation comes back), within the slip
    // positions: beyond them the set changes.
    const double lo = nodes_.front().X, hi = nodes_.back().X;
    const double w = hi - lo;
    double target;
    if (X < lo) {
      target = X - std::max(w, lo - X);
      if (std::isfinite(x_down_) && X >= x_down_) target = std::max(target, x_down_);
    } else {
      target = X + std::max(w, X - hi);
      if (std::isfinite(x_up_) && X <= x_up_) target = std::min(target, x_up_);
    }
    // Past a slip position (an integrator stage beyond the event): twice as far as asked, so
    // a step's stages there need few nodes, and never deep into the range beyond (where the
    // set would have changed and Eq. (3) junctions approach their force limit).
    if (X > x_up_) target = X + 2 * (X - hi);
    if (X < x_down_) target = X - 2 * (lo - X);
    node_at(target);
    refine_all();
  }
  if (nodes_.size() == 1) return 0;
  auto it = std::upper_bound(nodes_.begin(), nodes_.end(), X, [](double x, const Node& m) { return x < m.X; });
  std::size_t s = static_cast<std::size_t>(it - nodes_.begin());
  s = s == 0 ? 0 : s - 1;
  return std::min(s, nodes_.size() - 2);
}


double InteractingJunctions::cached(double X, double Node::*value, double Node::*slope) const {
  if (const std::size_t c = continuation_node(X); c != npos) {
    const Node& a = nodes_[c];
    const Node& b = nodes_.back();
    return hermite(a.X, b.X, a.*value, a.*slope, b.*value, b.*slope, X);
  }
  const std::size_t s = covering_segment(X);
  if (nodes_.size() == 1) return nodes_[0].*value + nodes_[0].*slope * (X - nodes_[0].X);
  const Node& a = nodes_[s];
  const Node& b = nodes_[s + 1];
  return hermite(a.X, b.X, a.*value, a.*slope, b.*value, b.*slope, X);
}

double InteractingJunctions::force(double X) const {
  ++force_evals_;
  if (n_nl_ == 0) return X * sum_a0_ + sum_b0_ + F_slip_;
  return cached(X, &Node::F, &Node::dF);
}

double InteractingJunctions::area(double X) const {
  if (n_nl_ == 0) return A_fixed_;
  return cached(X, &Node::A, &Node::dA);
}

std::vector<double> InteractingJunctions::forces(double X) const {
  std::vector<double> f(J_.force);
  const Node n = solve(X);
  for (std::size_t q = 0; q < nP_; ++q) f[idx_[q]] = n.f[q];
  return f;
}

std::vector<double> InteractingJunctions::areas(const std::vector<double>& f) const {
  std::vector<double> A(N_);
  for (std::size_t i = 0; i < N_; ++i) {
    const bool follows = pos_[i] != npos && nl_[pos_[i]];
    A[i] = follows ? law_.area(J_.A0[i], f[i]) : J_.area[i];
  }
  return A;
}

std::vector<double> InteractingJunctions::load_ratios(double X) const {
  const std::vector<double> f = forces(X);
  const std::vector<double> A = areas(f);
  std::vector<double> r(N_);
  for (std::size_t i = 0; i < N_; ++i) r[i] = f[i] / (law_.sigma * A[i]);
  return r;
}

// ---- events -------------------------------------------------------------------------------

void InteractingJunctions::find_thresholds(double X) {
  x_up_ = HUGE_VAL;
  x_down_ = -HUGE_VAL;
  k_up_ = k_down_ = npos;
  const std::size_t n = nP_;
  if (n == 0) return;
  if (n_nl_ == 0) {  // linear: f_q = X a0_q + b0_q exactly
    for (std::size_t q = 0; q < n; ++q) {
      const double xq = (threshold(q) - b0_[q]) / a0_[q];
      if (a0_[q] > 0 && xq < x_up_) x_up_ = xq, k_up_ = idx_[q];
      if (a0_[q] < 0 && xq > x_down_) x_down_ = xq, k_down_ = idx_[q];
    }
    return;
  }
  for (int dir : {1, -1}) {
    const Node& base = node_at(X);
    // The earliest crossing by the first-order prediction from X.
    std::size_t k = npos;
    double best = HUGE_VAL;
    for (std::size_t q = 0; q < n; ++q) {
      const double a = base.a[q];
      if (dir * a <= 0) continue;
      const double d = (threshold(q) - base.f[q]) / a;  // signed distance in X
      if (dir * d >= 0 && std::abs(d) < best) best = std::abs(d), k = q;
    }
    if (k == npos) continue;
    if (dir < 0) {
      // A junction whose force grows as X decreases (shielded by its neighbours) is rare and its
      // crossing usually far behind: the first-order prediction is the event, and reaching it
      // slips the junction only if it is over its threshold there (slip_crossed re-checks and
      // predicts again), so no solve is spent deep behind X where the slider never goes.
      x_down_ = X - best;
      k_down_ = idx_[k];
      continue;
    }
    double lo = X, hi = dir * HUGE_VAL;  // bracket: below threshold at lo, over at hi
    double Xt = X + dir * best;
    for (int round = 0;; ++round) {
      if (round > 50) fail("no slip position found", X);
      // Newton in X on f_k(X) = threshold, kept inside the bracket.
      for (int it = 0;; ++it) {
        if (it > 100) fail("Newton on a slip position did not converge", Xt);
        const Node& m = node_at(Xt);
        const std::size_t qk = k;  // positions do not move while no junction changes state
        const double thr = threshold(qk);
        const double r = m.f[qk] - thr;
        if (r < 0) lo = Xt; else hi = Xt;
        if (std::abs(r) <= 1e-12 * thr) break;
        double next = Xt - r / m.a[qk];
        const bool inside = dir > 0 ? (next > lo && next < hi) : (next < lo && next > hi);
        if (!inside && std::isfinite(hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - Xt) <= 4e-16 * std::abs(Xt)) break;
        Xt = next;
      }
      // Has another junction crossed before? Take the earliest by linear back-extrapolation.
      const Node& m = node_at(Xt);
      std::size_t other = npos;
      double earliest = Xt;
      for (std::size_t q = 0; q < n; ++q) {
        const double thr = threshold(q);
        if (q == k || m.f[q] - thr <= 1e-13 * thr) continue;
        const double back = m.a[q] != 0 ? Xt - (m.f[q] - thr) / m.a[q] : lo;
        const double xb = dir > 0 ? std::clamp(back, std::min(lo, X), Xt) : std::clamp(back, Xt, std::max(lo, X));
        if (other == npos || dir * xb < dir * earliest) other = q, earliest = xb;
      }
      if (other == npos) break;
      k = other;
      hi = Xt;
      lo = X;
      Xt = earliest;
      if (Xt == X || Xt == hi) Xt = 0.5 * (lo + hi);
    }
    if (dir > 0) x_up_ = Xt, k_up_ = idx_[k];
    else x_down_ = Xt, k_down_ = idx_[k];
  }
}

void InteractingJunctions::after_change(double X) {
  // Nodes left in the cache belong to the current set (every change of state clears it).
  sum_a0_ = sum_b0_ = 0;
  for (std::size_t q = 0; q < nP_; ++q) sum_a0_ += a0_[q], sum_b0_ += b0_[q];
  if (n_nl_ > 0) {
    node_at(X);
  }
  find_thresholds(X);
  if (n_nl_ > 0) refine_all();
}

std::int64_t InteractingJunctions::slip_crossed(double X) {
  // The slip position above X is exact (Newton): its junction slips. The one below X is a
  // prediction: whoever is at or over the threshold at X slips (possibly nobody; then the
  // prediction is renewed from X).
  return settle(X, X >= x_up_ ? k_up_ : npos);
}

std::int64_t InteractingJunctions::settle(double X, std::size_t k) {
  std::int64_t n = 0;
  for (;;) {
    if (k != npos) {
      start_slip(k, X);
      ++n;
    }
    if (nP_ == 0) {
      after_change(X);
      break;
    }
    // Who is at or over the threshold at this X with the new set? The most overloaded first.
    k = npos;
    if (n_nl_ == 0) {
      double worst = 1.0;
      for (std::size_t q = 0; q < nP_; ++q) {
        const double r = (X * a0_[q] + b0_[q]) / threshold(q);
        if (r >= worst) worst = r, k = idx_[q];
      }
    } else {
      const Node& m = node_at(X);
      double worst = 1.0;
      for (std::size_t q = 0; q < nP_; ++q) {
        const double r = m.f[q] / threshold(q);
        if (r >= worst) worst = r, k = idx_[q];
      }
    }
    if (k != npos) continue;
    after_change(X);
    // A slip position at X itself (rounding): that junction slips now.
    if (x_up_ <= X) k = k_up_;
    else if (x_down_ >= X) k = k_down_;
    if (k == npos) break;
  }
  slips_ += n;
  return n;
}

void InteractingJunctions::start_slip(std::size_t i, double X) {
  const std::size_t q = pos_[i];
  const bool always = area_law_ == AreaLaw::always;
  double f_sl;
  if (nl_[q]) {
    if (always) {
      f_sl = law_.slipping_force_always(J_.A0[i]);
      J_.set_contact(i, contact_at_force(law_, J_.A0[i], f_sl));
    } else {
      J_.set_contact(i, contact_at_first_slip(law_, J_.A0[i]));
      f_sl = slipping_force(law_, area_law_, J_.A0[i], J_.f_s[i]);
    }
    A_fixed_ += J_.area[i];
    --n_nl_;
  } else {
    f_sl = slipping_force(law_, area_law_, J_.A0[i], J_.f_s[i]);
  }
  if (J_.intact[i]) J_.intact[i] = 0, --n_intact_;
  J_.pinned[i] = 0;
  J_.force[i] = f_sl;
  F_slip_ += f_sl;
  // The old set's solution nearest X (the slip position's node: X is its event, located to the
  // integrator's resolution), from which the new set's seed at X is predicted (below).
  const Node* near = nullptr;
  for (const Node& m : nodes_)
    if (!near || std::abs(m.X - X) < std::abs(near->X - X)) near = &m;
  remove_pinned(q, f_sl, near, X);
  nodes_.clear();
}

void InteractingJunctions::remove_pinned(std::size_t q, double f_sl, const Node* at_X, double X) {
  const std::size_t n = nP_, N = N_, i = idx_[q];
  std::vector<double> g(G_.begin() + static_cast<std::ptrdiff_t>(q * N),
                        G_.begin() + static_cast<std::ptrdiff_t>(q * N + n));
  const double gqq = g[q];
  // The new set's solution at X, to first order: the others take up the slipped junction's
  // force change through column q of G (exact for linear junctions, where Δ = 0; for Eq. (3)
  // junctions off only by the drift of u' from D over the redistribution), from the old
  // solution at X (first order from the node at_X): the seed of the next solve there. Its
  // slopes likewise, the slipping force being constant.
  seed_valid_ = at_X != nullptr;
  if (seed_valid_) {
    seed_X_ = X;
    seed_f_.resize(n);
    seed_a_.resize(n);
    const double dX = X - at_X->X;
    const double df = f_sl - (at_X->f[q] + at_X->a[q] * dX), da = -at_X->a[q];
    for (std::size_t r = 0; r < n; ++r) {
      seed_f_[r] = at_X->f[r] + at_X->a[r] * dX + g[r] / gqq * df;
      seed_a_[r] = at_X->a[r] + g[r] / gqq * da;
    }
    if (q != n - 1) seed_f_[q] = seed_f_[n - 1], seed_a_[q] = seed_a_[n - 1];
    seed_f_.pop_back();
    seed_a_.pop_back();
  }
  double* G = G_.data();
  // G' = G − g gᵀ/g_qq (the inverse of M without row and column q); rows q, col q become 0.
#pragma omp parallel for schedule(static) if (n * n > kParallelWork)
  for (std::size_t r = 0; r < n; ++r) {
    const double w = g[r] / gqq;
    double* row = G + r * N;
    for (std::size_t s = 0; s < n; ++s) row[s] -= w * g[s];
  }
  // a0' = G'1, b0' = −G'h' with h' = h + C_{·i} f_sl; G'C_{·i} = −g/g_qq (from G M = I).
  const double a0q = a0_[q], b0q = b0_[q];
  for (std::size_t r = 0; r < n; ++r) {
    a0_[r] -= g[r] * a0q / gqq;
    b0_[r] += g[r] * (f_sl - b0q) / gqq;
    h_[r] += C_(idx_[r], i) * f_sl;
  }
  // The last position moves into q.
  const std::size_t last = n - 1;
  if (q != last) {
    for (std::size_t s = 0; s < n; ++s) G[q * N + s] = G[last * N + s];
    for (std::size_t r = 0; r < n; ++r) G[r * N + q] = G[r * N + last];
    idx_[q] = idx_[last];
    D_[q] = D_[last];
    h_[q] = h_[last];
    a0_[q] = a0_[last];
    b0_[q] = b0_[last];
    nl_[q] = nl_[last];
    pos_[idx_[q]] = q;
  }
  pos_[i] = npos;
  nP_ = last;
  ++work_.rank_one;
  // Rank-one updates accumulate rounding: start afresh after about N of them.
  if (++updates_since_rebuild_ > static_cast<std::int64_t>(std::max<std::size_t>(N_, 64)) && nP_ > 0) rebuild();
}

void InteractingJunctions::rebuild() const {
  const std::size_t n = nP_, N = N_;
  if (n == 0) return;
  double* G = G_.data();
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = idx_[r];
    for (std::size_t s = 0; s < n; ++s) G[r * N + s] = C_(i, idx_[s]);
    G[r * N + r] = D_[r];
  }
  // Column-major LAPACK on the row-major buffer sees the same symmetric matrix; 'L' there is
  // our upper triangle.
  const int ni = static_cast<int>(n), lda = static_cast<int>(N);
  int info = 0;
  dpotrf_("L", &ni, G, &lda, &info);
  if (info != 0) fail("the pinned junctions' compliance matrix is not positive definite", 0.0);
  dpotri_("L", &ni, G, &lda, &info);
  if (info != 0) fail("the pinned junctions' compliance matrix is singular", 0.0);
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t s = 0; s < r; ++s) G[r * N + s] = G[s * N + r];
  // a0 = G 1, b0 = −G h.
#pragma omp parallel for schedule(static) if (n * n > kParallelWork)
  for (std::size_t r = 0; r < n; ++r) {
    const double* row = G + r * N;
    double a = 0, b = 0;
    for (std::size_t s = 0; s < n; ++s) a += row[s], b -= row[s] * h_[s];
    a0_[r] = a;
    b0_[r] = b;
  }
  updates_since_rebuild_ = 0;
  ++work_.rebuilds;
}

void InteractingJunctions::repin_all(double X) {
  if (nP_ == N_) return;
  ++repins_;
  const std::vector<double> f = forces(X);
  const bool always = area_law_ == AreaLaw::always;
  for (std::size_t j = 0; j < N_; ++j) {
    if (pos_[j] != npos) continue;
    // x_j = X − u_j(f_j) − Σ_l C_jl f_l: the equation holds with the forces of now.
    double uc = 0;
    const double* row = &C_.c[j * N_];
    for (std::size_t l = 0; l < N_; ++l) uc += row[l] * f[l];
    const std::size_t q = nP_++;
    idx_[q] = static_cast<std::uint32_t>(j);
    pos_[j] = q;
    nl_[q] = always && nonlinear_law_ ? 1 : 0;
    double u, du;
    own(q, f[j], u, du);
    D_[q] = du;
    J_.anchor[j] = X - u - uc;
    J_.pinned[j] = 1;
    if (nl_[q]) ++n_nl_, A_fixed_ -= J_.area[j];
  }
  for (std::size_t q = 0; q < nP_; ++q) h_[q] = J_.anchor[idx_[q]];  // nobody slips: h = x
  F_slip_ = 0.0;
  nodes_.clear();  // they belong to the old set
  seed_valid_ = false;
  rebuild();
  // Rounding of the new G may put a junction that was at its threshold a hair over it.
  settle(X, npos);
}

}  // namespace asperity
