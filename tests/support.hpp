#pragma once
// The simulation helpers of the tests: run a scene to its end (observe level), plus the scenes
// built in code (support_scenes.hpp) and the file helpers (support_files.hpp).
#include "observe/recorder.hpp"
#include "scene/scene.hpp"
#include "solve/integrate.hpp"
#include "support_files.hpp"
#include "support_scenes.hpp"

namespace asperity::testing {

struct Outcome {
  RunInfo info;
  Recorder rec;
};

inline Outcome run(const Scene& s, bool keep_series = true) {
  Recorder rec(s.output.every, keep_series, s.output.peak_min_drop, s.stop.at_first_peak, s.stop.cycles);
  RunInfo info = integrate(s, rec);
  return {info, std::move(rec)};
}

}  // namespace asperity::testing
