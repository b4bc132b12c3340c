#pragma once
// What a stepper reports while it integrates, and the observer that receives it: samples at
// the instants the observer asks for, extrema of Q, changes of the junction population.
// observe/Recorder is the observer of every run; tests may plug in their own.
#include <concepts>
#include <cstdint>

namespace asperity {

// State of the interface at one instant, in SI units. Q = k_L (v t − X), A = Σ A_i.
struct Sample {
  double t = 0, X = 0, V = 0, Q = 0, A = 0;
  std::int64_t n_slipping = 0;  // junctions currently slipping
  std::int64_t n_intact = 0;    // junctions that have never slipped
};

// A local extremum of Q (the slider velocity crosses v: Q' = k_L (v − V) = 0).
struct Extremum {
  double t = 0, Q = 0, A = 0;
  bool is_max = true;
};

// A change of the junction population at time t: `new_slips` junctions started to slip, and/or
// (`stick`) every slipping junction repinned because the slider nearly stopped (|Ẋ| < c_min v).
// n_intact: junctions that have never slipped, after the change.
struct PopulationChange {
  double t = 0;
  std::int64_t new_slips = 0;
  bool stick = false;
  std::int64_t n_intact = 0;
};

// An observer takes every sample due at or before the time it names next, in order, and may
// end the run early (done()).
template <class O>
concept Observer = requires(O& o, const O& co, const Sample& s, const Extremum& e, const PopulationChange& c) {
  o.sample(s);
  o.extremum(e);
  o.population(c);
  { co.done() } -> std::convertible_to<bool>;
  { co.next_sample_time() } -> std::convertible_to<double>;
};

// The observer as the steppers see it: one compiled stepper serves every observer type
// (integrate() wraps the caller's observer); a virtual call per report or step is negligible
// next to a step's force evaluations.
class RunObserver {
 public:
  virtual void sample(const Sample& s) = 0;
  virtual void extremum(const Extremum& e) = 0;
  virtual void population(const PopulationChange& c) = 0;
  virtual bool done() const = 0;
  virtual double next_sample_time() const = 0;

 protected:
  ~RunObserver() = default;
};

template <Observer O>
class ObserverAdapter final : public RunObserver {
 public:
  explicit ObserverAdapter(O& o) : o_(o) {}
  void sample(const Sample& s) override { o_.sample(s); }
  void extremum(const Extremum& e) override { o_.extremum(e); }
  void population(const PopulationChange& c) override { o_.population(c); }
  bool done() const override { return o_.done(); }
  double next_sample_time() const override { return o_.next_sample_time(); }

 private:
  O& o_;
};

}  // namespace asperity
