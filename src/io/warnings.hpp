#pragma once
// Warnings: an input accepted but probably not meant (a plausible number in the wrong unit:
// scene/scene_keys.hpp). One line "warning: TEXT" on stderr, never glued onto a progress line
// (progress.hpp's print_line), each text once per process (a scene loaded for every sweep point
// says it once), and only for an input accepted (HeldWarnings). The command line's -q/--quiet
// drops them; tests capture them. Thread-safe.
#include <functional>
#include <string>
#include <vector>

namespace asperity::io {

void warn(const std::string& text);

// Where warnings go from now on (an empty function: nowhere); returns the sink it replaces.
// The default prints them on stderr. A sink gets each text once.
using WarningSink = std::function<void(const std::string& text)>;
WarningSink set_warning_sink(WarningSink sink);

// Holds the warnings given on this thread while it lives: release() passes them on (to the
// HeldWarnings it is nested in, else the sink); destroyed before that, it drops them, so an input
// refused after a warning says its error alone.
class HeldWarnings {
 public:
  HeldWarnings();
  ~HeldWarnings();
  HeldWarnings(const HeldWarnings&) = delete;
  HeldWarnings& operator=(const HeldWarnings&) = delete;
  void release();

 private:
  friend void warn(const std::string& text);
  std::vector<std::string> texts_;
  HeldWarnings* outer_;
  bool holding_ = true;
};

}  // namespace asperity::io
