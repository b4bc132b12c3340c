#pragma once
// A junction's own tangential displacement u(f) and du/df while its area follows its force
// (Eq. 3 with Mindlin's Eq. 2: the universal law ψ(φ), docs/model.md §8's nonlinear junctions), for
// every junction of a population, by Newton on the universal law's table (two or three cubic
// evaluations instead of the elliptic integrals), warm-started from the junction's last ψ.
#include <cstddef>
#include <memory>
#include <vector>

#include "physics/contact_law.hpp"
#include "physics/universal_law.hpp"

namespace asperity {

class Eq3Displacement {
 public:
  Eq3Displacement() = default;  // no junction: a population without Eq. (3) junctions
  // Throws SolverError when the universal law's table cannot reach the needed accuracy.
  Eq3Displacement(const ContactLaw& law, const std::vector<double>& A0_m2);

  // u [m] and du/df [m/N] of junction i at force f [N].
  void at(std::size_t i, double f, double& u, double& du);       // and keeps the warm start
  double force_scale(std::size_t i) const { return s_[i]; }      // s [1/N]: φ = s f
  double slip_force(std::size_t i) const { return f_slip_[i]; }  // N: φ = φ_s

 private:
  const ContactLaw* law_ = nullptr;
  std::shared_ptr<const UniversalForceLaw> table_;
  std::vector<double> c_, s_;  // per junction: ψ per metre c = ℓ0 E s, and s
  std::vector<double> f_slip_;
  // Per junction, a warm start only: the last φ, ψ and dψ/dφ; the next call starts from the
  // tangent's prediction ψ + (φ_new − φ) dψ/dφ.
  std::vector<double> phi_last_, psi_last_, dpsi_last_;
};

}  // namespace asperity
