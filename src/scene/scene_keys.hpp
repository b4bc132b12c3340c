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

// Where a number of a real experiment lies (a slider on an elastomer, wide margins around the
// paper's values, docs/model.md#2-parameter-values-the-papers); lo == hi: no such range. A value
// outside is accepted (the model runs it) but warned about, naming the unit slip that explains it.
struct PlausibleRange {
  double lo = 0, hi = 0;
  double typical = 0;   // the paper's value: of two unit slips, the one landing nearer wins
  const char* of = "";  // whose range, e.g. "an elastomer's"
};

struct SceneKey {
  const char* name;  // dotted key, e.g. "model.eta"
  KeyKind kind;
  const char* unit;  // SI unit named in messages; nullptr: dimensionless (or not a number)
  // Numbers: the allowed range as messages print it ("in (0, 1]"), its check, and why the
  // limit is there when that is not obvious ("" otherwise). nullptr/nullptr for other kinds.
  const char* range;
  bool (*allowed)(double);
  const char* why;
  double default_value;               // numbers: the struct default; NaN: required (experiment)
  bool fittable;                      // a fit parameter / error-bar key (one number of the model)
  double (*get)(const Scene&);        // numbers only
  void (*set)(Scene&, double);        // numbers only
  std::string (*text)(const Scene&);  // the value as scene_to_yaml writes it (YAML text)
  bool (*written)(const Scene&);      // nullptr: always written; else written when this is true
  PlausibleRange plausible{};         // numbers only
  std::string leaf() const;           // "eta" of "model.eta"
  std::string section() const;        // "model" of "model.eta"
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

// "KEY = X UNIT is far below OF LO to HI UNIT; was it meant in MPa (1.6e+06 Pa)?" when x lies
// outside the key's plausible range ("" inside it, or when it has none): the loader's warning.
std::string implausible_message(const SceneKey& key, double x);

// The text of a scalar value as written (`model.eta` → "100", a name unquoted); empty when
// `key` names a map (experiment), a list (output.series), nothing, or a value not written.
std::string scene_value_text(const Scene& scene, const std::string& key);

}  // namespace asperity
