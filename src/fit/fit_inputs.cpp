#include "fit/fit_inputs.hpp"

#include <algorithm>
#include <sstream>

#include "batch/inputs_fingerprint.hpp"
#include "io/atomic_file.hpp"
#include "io/hash.hpp"
#include "io/input_error.hpp"
#include "io/safe_open.hpp"
#include "scene/input_files.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

const char* const kFirstLine =
    "# asperity fit journal inputs: the evaluations of the journal beside this file were computed from these "
    "(a run resumes the journal only while this text is unchanged)";

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// "file HASH ROLE PATH" → "file PATH", else the line's first word: the key a message names.
std::string key_of(const std::string& line) {
  if (line.rfind("file ", 0) == 0) {
    const std::size_t role = line.find(' ', 5);
    const std::size_t path = role == std::string::npos ? role : line.find(' ', role + 1);
    if (path != std::string::npos) return "file " + line.substr(path + 1);
  }
  return line.substr(0, line.find(' '));
}

}  // namespace

std::string fit_inputs_text(const FitSpec& spec, const std::vector<std::string>& overrides, const std::string& build_id,
                            const io::Shard& task) {
  InputsFingerprint t(kFirstLine, build_id, "task", task);
  for (const std::string& o : overrides) t.add("set", io::hex16(io::fnv1a64(o)));
  if (spec.file.empty())
    t.add("spec", io::hex16(io::fnv1a64(spec.memory_text)));  // given in memory: no fit file to hash
  if (!spec.user_objective_id.empty()) t.add("objective", spec.user_objective_id);
  std::vector<io::DataFile> files{{"fit", spec.file}};
  for (const FitExperiment& e : spec.experiments) {
    const std::vector<io::DataFile> f = input_files(e.scene.build());
    files.insert(files.end(), f.begin(), f.end());
    if (!e.force_file.empty()) files.push_back({"force", e.force_file});
  }
  // Data paths relative to the fit file's folder (a spec in memory: the folder it was read against).
  const fs::path base = !spec.file.empty()       ? fs::absolute(spec.file).lexically_normal().parent_path()
                        : !spec.base_dir.empty() ? spec.base_dir
                                                 : fs::current_path();
  std::vector<std::string> seen;
  for (const io::DataFile& f : files) {
    if (f.path.empty()) continue;
    const std::string rel = fs::absolute(f.path).lexically_normal().lexically_relative(base).generic_string();
    if (std::find(seen.begin(), seen.end(), rel) != seen.end()) continue;
    seen.push_back(rel);
    t.add_file(f.role, rel, [&] { return io::fnv1a64(io::read_file_text(f.path)); });
  }
  return t.text();
}

void check_fit_inputs(const fs::path& file, const std::string& expected) {
  const std::string name = file.string();
  std::string old;
  if (!io::read_regular(file, old, "--out")) throw std::runtime_error("cannot read " + name);
  if (expected.find("\nbuild \n") != std::string::npos)
    throw io::InputError(name, 2, "build",
                         "this binary's code cannot be identified (unknown commit and no /proc/self/exe), so it "
                         "resumes no journal; use another --out or remove the folder");
  if (old == expected) return;
  const std::vector<std::string> was = lines_of(old), now = lines_of(expected);
  if (was.empty() || was[0] != kFirstLine)
    throw io::InputError(name, 1, "", "not an asperity fit inputs file; this folder's journal cannot be resumed");
  const std::string fix = "; use another --out or remove the folder";
  // Compared key by key (build, task, the --set list, each file by path), so the message names
  // what differs rather than the first line that moved.
  const auto line_of = [&](const std::vector<std::string>& v, const std::string& key) -> std::ptrdiff_t {
    for (std::size_t i = 1; i < v.size(); ++i)
      if (key_of(v[i]) == key) return static_cast<std::ptrdiff_t>(i);
    return -1;
  };
  for (const char* key : {"build", "task"}) {
    const std::ptrdiff_t i = line_of(was, key), j = line_of(now, key);
    const std::string a = i < 0 ? "" : was[i].substr(std::string(key).size() + 1);
    const std::string b = j < 0 ? "" : now[j].substr(std::string(key).size() + 1);
    if (a == b) continue;
    const int line = i < 0 ? 1 : static_cast<int>(i) + 1;
    if (std::string(key) == "build")
      throw io::InputError(name, line, key,
                           "the journal was computed by '" + a + "', this is '" + b +
                               "' (a journal resumes only with the code that wrote it)" + fix);
    throw io::InputError(name, line, key, "the journal is array task " + a + ", this run is " + b + fix);
  }
  if (const std::ptrdiff_t i = line_of(was, "spec"), j = line_of(now, "spec");
      (i < 0) != (j < 0) || (i >= 0 && was[i] != now[j]))
    throw io::InputError(
        name, i < 0 ? 1 : static_cast<int>(i) + 1, "spec",
        "the journal was computed from another fit spec (a dict given to asperity.fit, or a fit file)" + fix);
  if (const std::ptrdiff_t i = line_of(was, "objective"), j = line_of(now, "objective");
      (i < 0) != (j < 0) || (i >= 0 && was[i] != now[j]))
    throw io::InputError(name, i < 0 ? 1 : static_cast<int>(i) + 1, "objective",
                         "the journal was computed with another objective (a Python callable is known by the digest of "
                         "its source)" +
                             fix);
  std::vector<std::string> set_was, set_now;
  for (const auto& l : was)
    if (key_of(l) == "set") set_was.push_back(l);
  for (const auto& l : now)
    if (key_of(l) == "set") set_now.push_back(l);
  if (set_was != set_now)
    throw io::InputError(name, static_cast<int>(line_of(was, "set") < 0 ? 1 : line_of(was, "set") + 1), "set",
                         "the journal was computed with " + std::to_string(set_was.size()) +
                             " --set override(s), this run has " + std::to_string(set_now.size()) +
                             (set_was.size() == set_now.size() ? " other ones" : "") + fix);
  for (std::size_t i = 1; i < was.size(); ++i) {
    const std::string key = key_of(was[i]);
    if (key.rfind("file ", 0) != 0) continue;
    const std::ptrdiff_t j = line_of(now, key);
    if (j < 0)
      throw io::InputError(name, static_cast<int>(i) + 1, key,
                           "the journal was computed from it, this fit does not read it" + fix);
    if (was[i] != now[j])
      throw io::InputError(name, static_cast<int>(i) + 1, key,
                           "the file changed since the journal was computed (fnv1a64 " + was[i].substr(5, 16) +
                               " then, " + now[j].substr(5, 16) + " now)" + fix);
  }
  for (const auto& l : now)
    if (key_of(l).rfind("file ", 0) == 0 && line_of(was, key_of(l)) < 0)
      throw io::InputError(name, 0, key_of(l), "this fit reads it, the journal was not computed from it" + fix);
  throw io::InputError(name, 0, "",
                       "differs from what this fit would write (" + std::to_string(was.size()) + " lines, " +
                           std::to_string(now.size()) + " expected)" + fix);
}

}  // namespace asperity
