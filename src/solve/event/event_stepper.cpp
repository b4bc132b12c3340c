// Event-driven method for independent junctions: the generic integrator (event_integrator.hpp)
// over EventJunctions (event_junctions.hpp), all controlled by solver.tolerance, the universal-law
// table kept ~1e-13 exact.
#include "solve/event/event_stepper.hpp"

#include "solve/event/event_integrator.hpp"
#include "solve/event/event_junctions.hpp"

namespace asperity {

struct EventStepper::Impl : EventIntegrator<EventJunctions> {
  using EventIntegrator<EventJunctions>::EventIntegrator;
};

EventStepper::EventStepper(const Problem& problem) : impl_(std::make_unique<Impl>(problem)) {}
EventStepper::~EventStepper() = default;

void EventStepper::start(RunObserver& out) { impl_->start(out); }
bool EventStepper::finished() const { return impl_->finished; }
std::int64_t EventStepper::slips() const { return impl_->junctions.slips(); }
void EventStepper::advance(RunObserver& out) { impl_->advance(out); }
void EventStepper::stop_early() { impl_->stop_early(); }
void EventStepper::finish(RunInfo& info) const { impl_->finish(info); }

}  // namespace asperity
