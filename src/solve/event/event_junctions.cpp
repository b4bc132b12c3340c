#include "solve/event/event_junctions.hpp"

#include <algorithm>
#include <cstdio>

#include "physics/interface_law.hpp"

namespace asperity {

EventJunctions::EventJunctions(const Problem& problem)
    : law_(problem.law),
      area_law_(problem.law.alpha_b > 0 ? problem.area_law : AreaLaw::until_first_slip),
      nonlinear_(problem.law.alpha_b > 0),
      J_(problem.A0, problem.law) {
  const std::size_t N = J_.size();
  const bool always = area_law_ == AreaLaw::always;
  w_.resize(N);
  c_.resize(N);
  d_s_.resize(N);
  if (always) {
    f_sl_.resize(N);
    contact_sl_.resize(N);
  }
  nl_pos_.assign(N, npos);
  double psi_hi = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const double A0 = J_.A0[i];
    w_[i] = initial_diameter(A0) * law_.E;
    if (nonlinear_) {
      c_[i] = w_[i] * law_.force_scale(A0);
      const double psi_s = universal_psi(law_.slip_phi(A0), law_.nu, law_.shape);
      d_s_[i] = psi_s / c_[i];
      psi_hi = std::max(psi_hi, psi_s);
      if (always) {
        f_sl_[i] = slipping_force(law_, area_law_, A0, J_.f_s[i]);
        contact_sl_[i] = contact_at_force(law_, A0, f_sl_[i]);
      }
    } else {
      d_s_[i] = slip_position(0.0, J_.f_s[i], J_.k[i]);  // linear junction: f = k0 X reaches σ A0
    }
  }
  if (nonlinear_) {
    // Shipped scenes have ψ_s ~ 1; the table covers at least ψ ≤ 1e-3 (universal_law.hpp).
    table_ = universal_force_law(law_.nu, law_.shape, 1.1 * psi_hi);
    if (!(table_->max_rel_error() <= 1e-11)) {
      char msg[200];
      std::snprintf(msg, sizeof msg,
                    "event solver: the universal force law's table is only accurate to %.3g (psi up to %.3g): "
                    "junctions outside the contact law's range",
                    table_->max_rel_error(), 1.1 * psi_hi);
      throw SolverError(msg);
    }
    if (!always && N >= kBinnedMin) {
      binned_.emplace(*table_, w_, c_, J_.A0, binned_rel_width(problem.solver.tolerance, psi_hi));
      std::fill(nl_pos_.begin(), nl_pos_.end(), 0);  // "in the nonlinear set"; storage is binned_
    } else {
      for (std::size_t i = 0; i < N; ++i) nl_insert(i, 0.0);
    }
  } else {
    for (std::size_t i = 0; i < N; ++i) lin_insert(i, 0.0);
    for (double a : J_.A0) A_fixed_ += a;  // linear junctions keep their area
  }
  for (std::size_t i = 0; i < N; ++i) heap_.push({d_s_[i], static_cast<std::uint32_t>(i)});
  n_intact_ = static_cast<std::int64_t>(N);
}

double EventJunctions::area(double X) const {
  double A = A_fixed_;
  if (binned_) return A + binned_->area(X);
  for (std::size_t j = 0; j < nl_w_.size(); ++j) {
    const double d = X - nl_x_[j];
    const double psi = nl_c_[j] * d;
    const double phi = psi * table_->g(psi);
    A += sheared_area_phi(nl_A0_[j], phi);
  }
  return A;
}

std::int64_t EventJunctions::slip_crossed(double X) {
  std::int64_t n = 0;
  while (!heap_.empty() && heap_.top().first <= X) {
    const std::uint32_t i = heap_.top().second;
    heap_.pop();
    start_slip(i);
    ++n;
  }
  slips_ += n;
  return n;
}

void EventJunctions::repin_all(double X) {
  if (slipping_.empty()) return;
  ++repins_;
  for (std::uint32_t i : slipping_) {
    J_.pinned[i] = 1;
    const double anchor = repin_anchor(X, J_.force[i], J_.k[i]);
    if (area_law_ == AreaLaw::always) {
      A_fixed_ -= J_.area[i];
      nl_insert(i, anchor);
      heap_.push({anchor + d_s_[i], i});
    } else {
      lin_insert(i, anchor);
      heap_.push({slip_position(anchor, J_.f_s[i], J_.k[i]), i});
    }
  }
  slipping_.clear();
  F_sl_ = 0.0;  // exactly: no slipping junction is left
  maybe_resum();
}

void EventJunctions::nl_insert(std::size_t i, double anchor) {
  J_.anchor[i] = anchor;
  nl_pos_[i] = nl_w_.size();
  nl_idx_.push_back(static_cast<std::uint32_t>(i));
  nl_w_.push_back(w_[i]);
  nl_c_.push_back(c_[i]);
  nl_x_.push_back(anchor);
  nl_A0_.push_back(J_.A0[i]);
}

void EventJunctions::nl_remove(std::size_t i) {
  if (binned_) {
    binned_->remove(i);
    nl_pos_[i] = npos;
    return;
  }
  const std::size_t p = nl_pos_[i], last = nl_w_.size() - 1;
  if (p != last) {
    const std::uint32_t moved = nl_idx_[last];
    nl_idx_[p] = moved;
    nl_w_[p] = nl_w_[last];
    nl_c_[p] = nl_c_[last];
    nl_x_[p] = nl_x_[last];
    nl_A0_[p] = nl_A0_[last];
    nl_pos_[moved] = p;
  }
  nl_idx_.pop_back();
  nl_w_.pop_back();
  nl_c_.pop_back();
  nl_x_.pop_back();
  nl_A0_.pop_back();
  nl_pos_[i] = npos;
}

void EventJunctions::lin_insert(std::size_t i, double anchor) {
  J_.anchor[i] = anchor;
  K_p_ += J_.k[i];
  S_p_ += J_.k[i] * anchor;
  ++updates_;
}

void EventJunctions::start_slip(std::uint32_t i) {
  const bool always = area_law_ == AreaLaw::always;
  if (nl_pos_[i] != npos) {
    nl_remove(i);
    // Under until_first_slip A, k and f_s freeze at the exact slip point; under always the
    // slipping junction's area follows its constant force.
    J_.set_contact(i, always ? contact_sl_[i] : contact_at_first_slip(law_, J_.A0[i]));
    A_fixed_ += J_.area[i];
  } else {
    K_p_ -= J_.k[i];
    S_p_ -= J_.k[i] * J_.anchor[i];
    ++updates_;
  }
  if (J_.intact[i]) {
    J_.intact[i] = 0;
    --n_intact_;
  }
  J_.pinned[i] = 0;
  slipping_.push_back(i);
  // f_sl_ holds slipping_force() under always, computed once per junction.
  J_.force[i] = always ? f_sl_[i] : slipping_force(law_, area_law_, J_.A0[i], J_.f_s[i]);
  F_sl_ += J_.force[i];
}

// Aggregate sums drift by rounding over many updates: recompute them exactly now and then
// (amortised O(1) per update).
void EventJunctions::maybe_resum() {
  if (updates_ < std::max<std::int64_t>(1024, static_cast<std::int64_t>(J_.size()))) return;
  updates_ = 0;
  double K = 0, S = 0, A = 0;
  for (std::size_t i = 0; i < J_.size(); ++i) {
    if (nl_pos_[i] != npos) continue;
    if (J_.pinned[i]) {
      K += J_.k[i];
      S += J_.k[i] * J_.anchor[i];
    }
    A += J_.area[i];
  }
  K_p_ = K;
  S_p_ = S;
  A_fixed_ = A;
}

}  // namespace asperity
