#pragma once
// Checks across scene keys, once every value is known: the work a scene asks for must be
// bounded, and the area law must stay meaningful (load.hpp lists the bounds). One function for
// the loader and for scenes whose numbers a sweep or a fit set, so both report a bad
// combination with the same message, naming the key the user set.
#include <cstddef>
#include <optional>
#include <string>
#include <utility>

#include "scene/scene.hpp"

namespace asperity {

// Where each key's value came from, so that an error names the line (or override) that set it.
class KeyOrigins {
 public:
  virtual ~KeyOrigins() = default;
  // The key has a value in the scene (from its file or from an override).
  virtual bool given(const std::string& dotted) const = 0;
  // The key was set from outside the file (--set, a sweep, a fit): no file line.
  virtual bool overridden(const std::string& dotted) const = 0;
  // Throws InputError for `dotted` (given or not) with `message`.
  [[noreturn]] virtual void fail(const std::string& dotted, const std::string& message) const = 0;
};

// Throws InputError (through origins.fail, or naming the junctions file) on the first bound broken.
void validate_scene(const Scene& s, const KeyOrigins& origins);

// Two junctions whose discs (radius sqrt(A0/π) around (x_m, y_m)) overlap, lowest indices of
// the first such pair found; nullopt when none do. Needs positions. O(N) for similar sizes.
std::optional<std::pair<std::size_t, std::size_t>> first_overlap(const JunctionPopulation& junctions);

}  // namespace asperity
