#include "report/units.hpp"

#include "observe/observables.hpp"
#include "scene/scene_keys.hpp"

namespace asperity {

std::string column_unit(const std::string& column) {
  if (const SceneKey* k = find_scene_key(column)) {
    if (k->kind != KeyKind::number && k->kind != KeyKind::integer) return "";
    return k->unit ? k->unit : "1";
  }
  for (const ObservableField& f : observable_fields())
    if (column == f.name) {
      if (f.kind == ObservableKind::label || f.kind == ObservableKind::flag) return "";
      return *f.unit ? f.unit : "1";
    }
  return "";
}

std::string axis_label(const std::string& column) {
  const std::string unit = column_unit(column);
  return unit.empty() ? column : column + " [" + unit + "]";
}

}  // namespace asperity
