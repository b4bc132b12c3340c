#include "fit/fit_inputs.hpp"

#include <algorithm>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/hash.hpp"
#include "io/input_error.hpp"
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
                            const Shard& task) {
  std::string t = std::string(kFirstLine) + "\nbuild " + build_id + "\ntask " + std::to_string(task.index) + "/" +
                  std::to_string(task.count) + "\n";
  for (const std::string& o : overrides) t += "set " + hex16(fnv1a64(o)) + "\n";
  std::vector<DataFile> files{{"fit", spec.file}};
  for (const FitExperiment& e : spec.experiments) {
    const std::vector<DataFile> f = input_files(e.scene.build());
    files.insert(files.end(), f.begin(), f.end());
  }
  const fs::path base = fs::absolute(spec.file).lexically_normal().parent_path();
  std::vector<std::string> seen;
  for (const DataFile& f : files) {
    if (f.path.empty()) continue;
    const std::string rel = fs::absolute(f.path).lexically_normal().lexically_relative(base).generic_string();
    if (std::find(seen.begin(), seen.end(), rel) != seen.end()) continue;
    seen.push_back(rel);
    std::string sum(16, '-');  // unreadable: never equal to a hash
    try {
      sum = hex16(fnv1a64(read_file_text(f.path)));
    } catch (const std::exception&) {
    }
    t += "file " + sum + " " + f.role + " " + rel + "\n";
  }
  return t;
}

void check_fit_inputs(const fs::path& file, const std::string& expected) {
  const std::string name = file.string();
  const std::string old = read_file_text(file);
  if (expected.find("\nbuild \n") != std::string::npos)
    throw InputError(name, 2, "build", "this binary's code cannot be identified (unknown commit and no /proc/self/exe), so it "
                                       "resumes no journal; use another --out or remove the folder");
  if (old == expected) return;
  const std::vector<std::string> was = lines_of(old), now = lines_of(expected);
  if (was.empty() || was[0] != kFirstLine)
    throw InputError(name, 1, "", "not an asperity fit inputs file; this folder's journal cannot be resumed");
  for (std::size_t i = 1; i < std::max(was.size(), now.size()); ++i) {
    const int line = static_cast<int>(std::min(i, was.size() - 1)) + 1;
    if (i >= was.size())
      throw InputError(name, line, key_of(now[i]), "the fit now reads an input its journal was not computed from ('" +
                                                       now[i] + "'); use another --out or remove the folder");
    if (i >= now.size() || key_of(was[i]) != key_of(now[i]))
      throw InputError(name, line, key_of(was[i]), "the journal was computed from '" + was[i] +
                                                       "', which this fit does not match; use another --out or remove the folder");
    if (was[i] == now[i]) continue;
    const std::string key = key_of(was[i]);
    std::string why;
    if (key == "build")
      why = "the journal was computed by '" + was[i].substr(6) + "', this is '" + now[i].substr(6) +
            "' (a journal resumes only with the code that wrote it)";
    else if (key == "task")
      why = "the journal is array task " + was[i].substr(5) + ", this run is " + now[i].substr(5);
    else if (key == "set")
      why = "the --set overrides differ from those the journal was computed with";
    else
      why = "the file changed since the journal was computed (fnv1a64 " + was[i].substr(5, 16) + " then, " +
            now[i].substr(5, 16) + " now)";
    throw InputError(name, line, key, why + "; use another --out or remove the folder");
  }
}

}  // namespace asperity
