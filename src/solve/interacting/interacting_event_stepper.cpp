#include "solve/interacting/interacting_event_stepper.hpp"

#include "solve/event/event_integrator.hpp"

namespace asperity {

struct InteractingEventStepper::Impl : EventIntegrator<InteractingJunctions> {
  using EventIntegrator<InteractingJunctions>::EventIntegrator;
};

InteractingEventStepper::InteractingEventStepper(const Problem& problem, std::size_t single_from)
    : impl_(std::make_unique<Impl>(problem, single_from)) {}
InteractingEventStepper::~InteractingEventStepper() = default;

void InteractingEventStepper::start(RunObserver& out) { impl_->start(out); }
bool InteractingEventStepper::finished() const { return impl_->finished; }
std::int64_t InteractingEventStepper::slips() const { return impl_->junctions.slips(); }
void InteractingEventStepper::advance(RunObserver& out) { impl_->advance(out); }
void InteractingEventStepper::stop_early() { impl_->stop_early(); }
void InteractingEventStepper::set_deadline(std::chrono::steady_clock::time_point deadline) {
  impl_->junctions.set_deadline(deadline);
}
void InteractingEventStepper::clear_deadline() { impl_->junctions.clear_deadline(); }
void InteractingEventStepper::finish(RunInfo& info) const { impl_->finish(info); }
const InteractingJunctions& InteractingEventStepper::junctions() const { return impl_->junctions; }
InteractingJunctions& InteractingEventStepper::junctions() { return impl_->junctions; }
double InteractingEventStepper::X() const { return impl_->y[0] * impl_->L; }

}  // namespace asperity
