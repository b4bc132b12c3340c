#pragma once
// One run directory:
//   series.csv    the sampled series the scene asks for (columns in all_series() order; absent
//                 when scene.output.series is empty), values printed with %.17g;
//   summary.yaml  every Observables field (%.17g, exact round trip), the solver settings and the
//                 confirmed peaks, and provenance (build, command line, input files' hashes);
//   scene.yaml    the resolved scene (scene_to_yaml): `asperity run DIR/scene.yaml` repeats it;
//   plot.png      optional: Q(t), A(t) and A(Q) via gnuplot; plot.gp, its script, beside it.
// The directory is built as a hidden temporary sibling and renamed into place, so an interrupted
// run never leaves a half-written DIR (at worst a stale `.NAME.tmp-*` sibling).
#include <filesystem>
#include <string>
#include <vector>

#include "observe/observables.hpp"
#include "observe/recorder.hpp"
#include "report/gnuplot.hpp"  // FigureFormats
#include "scene/scene.hpp"

namespace asperity {

// %.17g (round-trips every double); YAML spellings .nan / .inf / -.inf for non-finite values.
std::string yaml_double(double x);

// The text of summary.yaml; its provenance block names `command_line`.
std::string summary_yaml(const Scene& scene, const Observables& obs, const std::vector<Peak>& peaks,
                         const std::string& command_line = "");

struct RunWriteOptions {
  bool plot = false;         // also write plot.png (skipped silently without gnuplot or series)
  std::string command_line;  // the command that ran it (provenance)
  FigureFormats figures;     // the formats of the plot (--figures; PNG alone by default)
};

// Writes the run directory `dir` atomically, replacing an existing run directory. Throws
// std::runtime_error (with the path) when a file cannot be written, or when `dir` exists but
// holds anything else than a run's files (so `--out .` never deletes unrelated files).
void write_run(const std::filesystem::path& dir, const Scene& scene, const Observables& obs, const Recorder& rec,
               const RunWriteOptions& opt = {});

// Throws the error write_run would give for an existing `dir` that is not a run directory; call
// it before a long run so it fails early.
void check_run_dir(const std::filesystem::path& dir);

// Renders DIR/plot.png from DIR/series.csv (needs columns t, Q, A) and keeps its script as
// DIR/plot.gp. Returns false when the series lacks a column, gnuplot is missing or fails (why in
// *error); write_run says so on stderr. `stand_in`: the figure carries the stand-in mark
// (write_run passes is_stand_in of the scene's experiment).
bool write_run_plot(const std::filesystem::path& dir, std::string* error = nullptr, const FigureFormats& formats = {},
                    bool stand_in = false);

}  // namespace asperity
