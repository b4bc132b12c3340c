#pragma once
// DIR/inputs.txt beside a fit journal (batch/inputs_fingerprint.hpp): what its evaluations were computed from, so a resume never
// mixes evaluations of two fits, two data sets or two codes. Written (durably) before the journal
// is created; a run resumes the journal only when the text it computes now is the same:
//   # asperity fit journal inputs ...           (first line: recognises the file)
//   build asperity 0.1.0 commit 519059f0c2ab Release GCC 12.2.0    (code_build_id(): a -dirty
//                                                 build is named by its executable's bytes)
//   task 0/1                                     (array task I/N; 0/1 unsharded)
//   set 5e1c…                                    (FNV-1a 64 of each --set override, in order)
//   file 1a2b… fit fits/x.yaml                   (FNV-1a 64 of the bytes, role, path relative to
//   file …     scene ../scenes/paper/P0.98N.yaml  the fit file's folder: the fit file, and each
//   …                                             experiment's scene, experiment, junctions, measured)
#include <filesystem>
#include <string>
#include <vector>

#include "fit/fit_spec.hpp"
#include "io/shard.hpp"

namespace asperity {

std::string fit_inputs_text(const FitSpec& spec, const std::vector<std::string>& overrides, const std::string& build_id,
                            const io::Shard& task);

// Throws InputError naming `file` (an inputs.txt), the line that differs and what differs, when
// its text is not `expected` ("build", "task", "set", "file PATH" keys; exit 2 in the CLI).
void check_fit_inputs(const std::filesystem::path& file, const std::string& expected);

}  // namespace asperity
