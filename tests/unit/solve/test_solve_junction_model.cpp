// solve/core/junction_model.hpp: both junction models meet the concept the event integrator is
// written against, and a type that lacks one of its operations (or cannot be built from a
// Problem) does not.
#include <catch2/catch.hpp>
#include <cstdint>

#include "solve/core/junction_model.hpp"
#include "solve/event/event_junctions.hpp"
#include "solve/interacting/interacting_junctions.hpp"

using namespace asperity;

namespace {

// Every operation of the concept, with a constructor from a Problem; without repin_all when
// Repin is false (a model that could never end a slip).
template <bool Repin>
struct Model {
  Model() = default;
  explicit Model(const Problem&) {}
  double force(double) const { return 0; }
  double area(double) const { return 0; }
  bool has_threshold() const { return false; }
  double next_threshold() const { return 0; }
  bool has_threshold_below() const { return false; }
  double next_threshold_below() const { return 0; }
  std::int64_t n_slipping() const { return 0; }
  std::int64_t n_intact() const { return 0; }
  std::int64_t force_evals() const { return 0; }
  std::int64_t slips() const { return 0; }
  std::int64_t repins() const { return 0; }
  std::int64_t slip_crossed(double) { return 0; }
  void repin_all(double) requires Repin {}
};
using Complete = Model<true>;
using NoRepin = Model<false>;

// Everything, but built without a Problem.
struct NoProblem : Complete {
  NoProblem() = default;  // constructors are not inherited: none from a Problem
};

}  // namespace

TEST_CASE("both junction models meet the event integrator's concept, and incomplete types do not", "[solve][concept]") {
  CHECK(JunctionModel<EventJunctions>);
  CHECK(JunctionModel<InteractingJunctions>);
  CHECK(JunctionModel<Complete>);
  CHECK_FALSE(JunctionModel<NoRepin>);
  CHECK_FALSE(JunctionModel<NoProblem>);
  CHECK_FALSE(JunctionModel<double>);
}
