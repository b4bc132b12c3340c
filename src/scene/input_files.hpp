#pragma once
// The files a scene was read from, for provenance: the scene, its experiment, the junctions and
// measured CSVs (those it has); a topography scene's recipe file and height map instead.
#include <vector>

#include "io/provenance.hpp"
#include "scene/scene.hpp"

namespace asperity {

inline std::vector<io::DataFile> input_files(const Scene& scene) {
  const Experiment& e = scene.experiment;
  if (const auto& t = scene.topography)
    return {{"scene", scene.file}, {"topography", t->file}, {"height map", t->map_file}};
  return {
      {"scene", scene.file}, {"experiment", e.file}, {"junctions", e.junctions_file}, {"measured", e.measured_file}};
}

}  // namespace asperity
