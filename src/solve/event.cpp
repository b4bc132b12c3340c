#include "solve/integrate.hpp"
namespace asperity {
RunInfo integrate_event(const Scene& scene, Recorder& rec) { return integrate_reference(scene, rec); }  // placeholder until the event solver lands
}
