#include "physics/universal_law.hpp"

#include <boost/math/interpolators/cardinal_cubic_b_spline.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <list>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

namespace asperity {

double UniversalForceLaw::phi_of_psi_exact(double psi) const {
  if (psi == 0.0) return 0.0;
  const double a = std::abs(psi);
  // ψ(φ) increases from 0 to ∞ on [0, 1); ψ ≥ φ/κ(1) bounds the root from above.
  const double hi = std::min(a * stiffness_factor(1.0, nu_, shape_), 1.0 - 1e-16);
  auto fn = [&](double phi) { return psi_of_phi(phi) - a; };
  boost::math::tools::eps_tolerance<double> tol(52);
  std::uintmax_t it = 200;
  double lo = 0.0, h = hi;
  if (fn(h) < 0) {
    // ψ beyond ψ(1 − 1e-16) (~1e8): the area has vanished to double precision. Only trial
    // stages of an integrator reach this far past a slip point (e.g. at huge damping), so
    // return the saturated value rather than fail to bracket.
    return psi < 0 ? -(1.0 - 1e-16) : 1.0 - 1e-16;
  }
  const auto r = boost::math::tools::toms748_solve(fn, lo, h, -a, fn(h), tol, it);
  const double phi = 0.5 * (r.first + r.second);
  return psi < 0 ? -phi : phi;
}

double UniversalForceLaw::g_exact(double psi) const {
  if (psi == 0.0) return stiffness_factor(1.0, nu_, shape_);
  return phi_of_psi_exact(psi) / psi;
}

UniversalForceLaw::UniversalForceLaw(double nu, JunctionShape shape, double psi_max, double rel_tol)
    : nu_(nu), shape_(shape), psi_max_(psi_max) {
  if (!(psi_max > 0)) throw std::invalid_argument("UniversalForceLaw: psi_max must be > 0");
  for (std::size_t n = 64;; n *= 2) {
    const double h = psi_max / static_cast<double>(n - 1);
    std::vector<double> y(n);
    for (std::size_t i = 0; i < n; ++i) y[i] = g_exact(h * static_cast<double>(i));
    const double dl = 0.0;  // g is even: g'(0) = 0
    const double d = 1e-5 * psi_max;
    const double dr = (g_exact(psi_max + d) - g_exact(psi_max - d)) / (2 * d);
    boost::math::interpolators::cardinal_cubic_b_spline<double> spline(y.data(), n, 0.0, h, dl, dr);
    // Hermite form from the spline's values and slopes at the nodes reproduces its cubics.
    coef_.assign(n - 1, {});
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const double x0 = h * static_cast<double>(i), x1 = h * static_cast<double>(i + 1);
      const double y0 = spline(x0), y1 = spline(x1), d0 = h * spline.prime(x0), d1 = h * spline.prime(x1);
      coef_[i] = {y0, d0, 3 * (y1 - y0) - 2 * d0 - d1, 2 * (y0 - y1) + d0 + d1};
    }
    inv_h_ = 1.0 / h;
    double err = 0;
    auto check_interval = [&](std::size_t i) {
      for (double frac : {0.25, 0.5, 0.75}) {
        const double x = h * (static_cast<double>(i) + frac);
        const double ex = g_exact(x);
        err = std::max(err, std::abs(g(x) - ex) / ex);
      }
    };
    const std::size_t stride = std::max<std::size_t>(1, n / 512);
    for (std::size_t i = 0; i + 1 < n; i += stride) check_interval(i);
    check_interval(n - 2);  // the end interval, where the boundary derivative matters most
    if (err <= rel_tol || n >= (1u << 20)) {
      nodes_ = n;
      max_err_ = err;
      return;
    }
  }
}

std::shared_ptr<const UniversalForceLaw> universal_force_law(double nu, JunctionShape shape, double psi_max) {
  using Key = std::tuple<double, JunctionShape, double>;
  const Key key{nu, shape, std::max(psi_max, 1e-3)};
  // The one piece of process-wide state: a memo of a pure function. Tables are never modified
  // after construction and are keyed by exactly what determines them, so a caller cannot tell
  // whether its table was built now or before. The most recently used ones are kept up to
  // kBudget bytes (a table of the shipped scenes is 32 KiB, so a sweep cycling through a few
  // hundred ψ ranges still finds them all). Built under the lock: concurrent first callers wait
  // for one build instead of all building.
  constexpr std::size_t kBudget = std::size_t{64} << 20;
  auto bytes = [](const UniversalForceLaw& t) { return t.nodes() * sizeof(std::array<double, 4>); };
  static std::mutex mutex;
  static std::list<std::pair<Key, std::shared_ptr<const UniversalForceLaw>>> recent;  // most recent first
  static std::size_t held = 0;
  const std::lock_guard<std::mutex> lock(mutex);
  for (auto it = recent.begin(); it != recent.end(); ++it)
    if (it->first == key) {
      recent.splice(recent.begin(), recent, it);
      return recent.front().second;
    }
  recent.emplace_front(key, std::make_shared<const UniversalForceLaw>(nu, shape, std::get<2>(key)));
  held += bytes(*recent.front().second);
  while (held > kBudget && recent.size() > 1) {
    held -= bytes(*recent.back().second);
    recent.pop_back();
  }
  return recent.front().second;
}

}  // namespace asperity
