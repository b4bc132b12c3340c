#pragma once
// The `optimizer:` section of a fit file (fit_load.cpp reads the rest of the file).
#include <yaml-cpp/yaml.h>

#include <string>

#include "fit/fit_spec.hpp"
#include "io/yaml_util.hpp"

namespace asperity {

// `optimizer:` into spec; the node that named the algorithm (undefined: none).
YAML::Node read_optimizer(const io::Source& src, const io::MapView& root, FitSpec& spec);

// The algorithm must accept this many variables (e.g. LN_NEWUOA_BOUND needs ≥ 2): a 3-evaluation
// trial. Refused at `algorithm_node` (else naming `display`, line 0).
void check_algorithm_accepts(const FitSpec& spec, const io::MapView& root, const YAML::Node& algorithm_node,
                             const std::string& display);

}  // namespace asperity
