#pragma once
// What the event method asks of a junction model (EventJunctions: independent junctions;
// InteractingJunctions: elastic interactions). Between events the total force F(X) and area
// A(X) are smooth functions of the slider position X alone; the model names the next slip
// positions above X (and below it: an interacting junction shielded by its neighbours may load
// as X decreases), and applies the discontinuities at an event: the slips at X (an avalanche
// included), and the repin of every slipping junction. EventIntegrator is written against this
// concept and nothing else, so a new junction model is a type that meets it.
#include <concepts>
#include <cstdint>

#include "solve/core/problem.hpp"

namespace asperity {

template <class J>
concept JunctionModel = std::constructible_from<J, const Problem&> && requires(J& j, const J& cj, double X) {
  { j.force(X) } -> std::convertible_to<double>;  // N, total junction force at X (may update caches)
  { j.area(X) } -> std::convertible_to<double>;   // m², total contact area at X
  { cj.has_threshold() } -> std::convertible_to<bool>;
  { cj.next_threshold() } -> std::convertible_to<double>;  // m: the next slip as X grows
  { cj.has_threshold_below() } -> std::convertible_to<bool>;
  { cj.next_threshold_below() } -> std::convertible_to<double>;  // m: the next slip as X falls
  { cj.n_slipping() } -> std::convertible_to<std::int64_t>;
  { cj.n_intact() } -> std::convertible_to<std::int64_t>;  // never slipped
  { cj.force_evals() } -> std::convertible_to<std::int64_t>;
  { cj.slips() } -> std::convertible_to<std::int64_t>;
  { cj.repins() } -> std::convertible_to<std::int64_t>;
  { j.slip_crossed(X) } -> std::convertible_to<std::int64_t>;  // how many slipped at X
  j.repin_all(X);
};

}  // namespace asperity
