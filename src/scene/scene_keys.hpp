#pragma once
// Every key of a scene in one table: dotted name, kind, unit, allowed range, default, and typed
// access to its Scene field. The loader checks numbers with it, the writer prints every key
// from it, and sweeps, fits and error bars set numbers through it (no YAML text in between).
// Table order is file order: the order scene_to_yaml writes and the loader checks keys.
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.hpp"

namespace asperity {

enum class KeyKind { number, integer, boolean, choice, text, list };

struct SceneKey {
  const char* name;   // dotted key, e.g. "model.eta"
  KeyKind kind;
  const char* unit;   // SI unit named in messages; nullptr: dimensionless (or not a number)
  // Numbers: the allowed range as messages print it ("in (0, 1]"), its check, and why the
  // limit is there when that is not obvious ("" otherwise). nullptr/nullptr for other kinds.
  const char* range;
  bool (*allowed)(double);
  const char* why;
  double default_value;             // numbers: the struct default; NaN: required (experiment)
  bool fittable;                    // a fit parameter / error-bar key (one number of the model)
  double (*get)(const Scene&);      // numbers only
  void (*set)(Scene&, double);      // numbers only
  std::string (*text)(const Scene&);   // the value as scene_to_yaml writes it (YAML text)
  bool (*written)(const Scene&);    // nullptr: always written; else written when this is true
  std::string leaf() const;         // "eta" of "model.eta"
  std::string section() const;      // "model" of "model.eta"
};

const std::vector<SceneKey>& scene_keys();
const SceneKey* find_scene_key(std::string_view dotted);  // nullptr: not a key of the table

// Dotted keys holding one number that a fit may vary (experiment.mass, model.alpha_b, ...).
const std::vector<std::string>& numeric_scene_keys();
// Every key's dotted name, in table order (where an unknown key of a scene file belongs).
const std::vector<std::string>& scene_key_names();
// The value of a fittable numeric key (std::invalid_argument for any other key).
double scene_value(const Scene& scene, const std::string& key);

// "must be RANGE, got X" (+ " (WHY)"): the loader's message for a number out of its range.
std::string out_of_range_message(const SceneKey& key, double x);

// The text of a scalar value as written (`model.eta` → "100", a name unquoted); empty when
// `key` names a map (experiment), a list (output.series), nothing, or a value not written.
std::string scene_value_text(const Scene& scene, const std::string& key);

}  // namespace asperity
