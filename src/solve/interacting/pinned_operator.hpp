#pragma once
// What the chord iteration (ChordSolver) needs of the pinned set's linear algebra (docs/model.md
// §8): the inverse G = (D + C_PP)⁻¹ applied to two vectors in one pass, its load vectors a0 = G 1
// and b0 = −G h, and the changes of the set (a slip removes a position, a repin adds the slipping
// junctions back, a new reference compliance D takes effect at a rebuild). PinnedCompliance (the
// dense G, with its single-precision copy) is the first model; another operator (an approximate,
// faster product) meets the same concept and is tested against it.
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solve/core/problem.hpp"

namespace asperity {

template <class Op>
concept PinnedOperator = std::constructible_from < Op,
        const Problem&, std::vector<double>,
bool, std::size_t > &&requires(Op op, const Op& c, std::size_t q, double x, const std::vector<std::size_t>& columns,
                               const std::vector<double>& w, std::vector<double>& y,
                               const typename Op::PassBudget& budget, const std::vector<double>& anchors) {
  // The pinned set: positions q = 0 .. size() − 1, the junction at each, the Eq. (3) ones.
  { c.size() } -> std::same_as<std::size_t>;
  { c.junction(q) } -> std::same_as<std::size_t>;
  { c.position(q) } -> std::same_as<std::size_t>;  // of a junction; npos: slipping
  { c.nonlinear(q) } -> std::same_as<bool>;
  { c.n_nonlinear() } -> std::same_as<std::size_t>;
  // f = X a0 + b0 − G Δ: the load vectors [N/m, N], the reference compliance D [m/N], C_ij [m/N].
  { c.a0(q) } -> std::same_as<double>;
  { c.b0(q) } -> std::same_as<double>;
  { c.reference(q) } -> std::same_as<double>;
  { c.coupling(q, q) } -> std::same_as<double>;
  { op.row(q) } -> std::same_as<std::vector<double>>;  // G's row q
  // y1 = G w1, y2 = G w2 over the columns given: exact, or within a budget of errors.
  op.apply(columns, w, w, y, y);
  op.apply(columns, w, w, y, y, budget);
  { c.single_kept() } -> std::same_as<bool>;  // whether a budgeted pass may be inexact
  // Changes of the set.
  op.remove(q, x);                                   // a slip at force x [N]
  { op.add(q, true) } -> std::same_as<std::size_t>;  // a repin; returns its position
  op.set_anchors(anchors);                           // after the adds
  op.set_reference(q, x);                            // D_q, at the next rebuild
  op.rebuild();
  // Work done, for benchmarks.
  { c.rebuilds() } -> std::same_as<std::int64_t>;
  { c.rank_one_updates() } -> std::same_as<std::int64_t>;
};

}  // namespace asperity
