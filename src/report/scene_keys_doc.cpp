#include "report/scene_keys_doc.hpp"

#include <cmath>

#include "io/numbers.hpp"
#include "scene/scene_keys.hpp"

namespace asperity {
namespace {

const char* kind_name(KeyKind k) {
  switch (k) {
    case KeyKind::number:
      return "number";
    case KeyKind::integer:
      return "whole number";
    case KeyKind::boolean:
      return "true/false";
    case KeyKind::choice:
      return "choice";
    case KeyKind::text:
      return "text";
    case KeyKind::list:
      return "list";
  }
  return "";
}

// '|' would end a table cell.
std::string cell(std::string s) {
  for (std::size_t at = 0; (at = s.find('|', at)) != std::string::npos; at += 2) s.replace(at, 1, "\\|");
  return s;
}

// "1e+05 to 1e+08 (an elastomer's)", or "" when the key has no plausible range.
std::string plausible_text(const SceneKey& k) {
  const PlausibleRange& p = k.plausible;
  if (!(p.lo < p.hi)) return "";
  return io::format_short(p.lo) + " to " + io::format_short(p.hi) + " (" + p.of + ")";
}

}  // namespace

std::string scene_keys_markdown() {
  std::string md =
      "# Scene keys\n\n"
      "Generated from the key table (`src/scene/scene_keys.cpp`, written by `src/report/scene_keys_doc.cpp`;\n"
      "`tests/unit/report/test_report_scene_keys_doc.cpp` keeps this file equal to it). The loader checks every\n"
      "value against these ranges (one line `file:line: key: message`, exit 2), and `--set`, campaign\n"
      "axes and fit parameters go through the same checks. Defaults are the paper's values; `required`:\n"
      "the experiment file must give it. Units are SI (`1`: dimensionless). Checks that involve\n"
      "several keys (time scales, area-law domain, sample count) are in `src/scene/validate.cpp`; the\n"
      "choices of each choice key and what the keys mean: [commands.md](commands.md).\n\n"
      "A value allowed but outside its key's `plausible` range (where a real slider on an elastomer\n"
      "puts it) is run, with one warning on stderr naming the file and line (or the `--set`) and the\n"
      "unit slip that would explain it, e.g. `warning: --set experiment.E=1.6: experiment.E = 1.6 Pa is\n"
      "far below an elastomer's 1e+05 to 1e+08 Pa; was it meant in MPa (1.6e+06 Pa)?`; `-q` keeps it (a warning is not "
      "a success's chatter).\n\n"
      "| key | kind | unit | allowed | plausible | default | fit parameter | why the limit |\n"
      "|---|---|---|---|---|---|---|---|\n";
  const Scene defaults{};
  for (const SceneKey& k : scene_keys()) {
    const bool numeric = k.kind == KeyKind::number;
    std::string unit = numeric ? (k.unit ? k.unit : "1") : "";
    std::string def;
    if (numeric)
      def = std::isnan(k.default_value) ? "required" : io::format_double(k.default_value);
    else if (k.text)
      def = k.text(defaults);
    if (std::string(k.name).rfind("experiment.", 0) == 0 && !numeric) def = "(from the experiment file)";
    if (std::string(k.name).rfind("topography.", 0) == 0) def = "(from the recipe)";  // only in topography scenes
    md += "| `" + std::string(k.name) + "` | " + kind_name(k.kind) + " | " + cell(unit) + " | " +
          cell(k.range ? k.range : "") + " | " + plausible_text(k) + " | " +
          (def.empty() ? "" : "`" + cell(def) + "`") + " | " + (k.fittable ? "yes" : "") + " | " +
          cell(k.why ? k.why : "") + " |\n";
  }
  return md;
}

}  // namespace asperity
