#include "io/warnings.hpp"

#include <cstdio>
#include <mutex>
#include <set>

#include "io/progress.hpp"

namespace asperity::io {

namespace {

struct Warnings {
  std::mutex mutex;
  WarningSink sink = [](const std::string& text) { print_line(stderr, "warning: " + text); };
  std::set<std::string> said;
};

Warnings& warnings() {
  static Warnings w;
  return w;
}

thread_local HeldWarnings* held = nullptr;  // the innermost one of this thread

}  // namespace

HeldWarnings::HeldWarnings() : outer_(held) { held = this; }

HeldWarnings::~HeldWarnings() {
  if (holding_) held = outer_;
}

void HeldWarnings::release() {
  if (!holding_) return;
  holding_ = false;
  held = outer_;
  for (const std::string& t : texts_) warn(t);
  texts_.clear();
}

void warn(const std::string& text) {
  if (held) {
    held->texts_.push_back(text);
    return;
  }
  Warnings& w = warnings();
  const std::lock_guard<std::mutex> lock(w.mutex);
  if (!w.sink || !w.said.insert(text).second) return;
  w.sink(text);
}

WarningSink set_warning_sink(WarningSink sink) {
  Warnings& w = warnings();
  const std::lock_guard<std::mutex> lock(w.mutex);
  w.sink.swap(sink);
  w.said.clear();  // a new sink hears every warning once
  return sink;
}

}  // namespace asperity::io
