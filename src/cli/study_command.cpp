// asperity study STUDY.yaml [--out DIR] [-j N] [--figures F] [--quiet]
// The study file (studies/study_load.hpp) says which study runs and every path it reads and
// writes: studies/interactions.yaml, studies/recovery.yaml, studies/continuum.yaml.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "report/output_dir.hpp"
#include "studies/study_load.hpp"

namespace asperity::cli {

namespace {

struct StudyFlags {
  std::string file;
  std::string out;  // empty: the study file's
  int threads = 0;  // 0: the study file's
  FigureFormats figures;
  bool figures_given = false;
  bool quiet = false;
};

int run_interactions(InteractionStudyOptions o, const StudyFlags& f) {
  if (f.figures_given) o.figures = f.figures;
  check_ours(o.out, "study interactions", "--out");
  o.log = f.quiet ? nullptr : &std::cout;
  const std::string verdict = run_interaction_study(o);
  write_marker(o.out, "study interactions");
  if (!f.quiet) std::printf("%s\n-> %s/REPORT.md\n", verdict.c_str(), o.out.string().c_str());
  return exit_ok;
}

int run_recovery(RecoveryMatrixOptions o, const StudyFlags& f) {
  check_ours(o.out, "study recovery", "--out");
  o.log = f.quiet ? nullptr : &std::cout;
  const std::vector<RecoveryCell> cells = run_recovery_matrix(o);
  write_marker(o.out, "study recovery");
  if (!f.quiet) {
    for (const LoadVerdict& v : judge_loads(cells)) std::printf("%s: %s\n", v.load.c_str(), v.verdict.c_str());
    std::printf("-> %s/REPORT.md\n", o.out.string().c_str());
  }
  return exit_ok;
}

int run_continuum(ContinuumStudyOptions o, const StudyFlags& f) {
  if (f.figures_given) o.figures = f.figures;
  check_ours(o.out, "study continuum", "--out");
  o.log = f.quiet ? nullptr : &std::cout;
  run_continuum_study(o);
  write_marker(o.out, "study continuum");
  if (!f.quiet) std::printf("-> %s/REPORT.md\n", o.out.string().c_str());
  return exit_ok;
}

}  // namespace

Command add_study_command(CLI::App& app) {
  auto f = std::make_shared<StudyFlags>();
  CLI::App* sub = app.add_subcommand(
      "study",
      "Runs a study file (studies/*.yaml): interactions (independent vs interacting junctions on the stand-ins), "
      "recovery (the recovery matrix, SYNTHETIC experiments) or continuum (junction models against the continuum "
      "tangential contact, SYNTHETIC surfaces)");
  sub->add_option("study", f->file, "Study file, e.g. studies/interactions.yaml")->required();
  sub->add_option("-o,--out", f->out, "Output folder (default: the study file's out)");
  sub->add_option("-j,--threads", f->threads, "Threads (default: the study file's)")->check(CLI::Range(1, 1024));
  add_figures_option(sub, f->figures);
  sub->add_flag("-q,--quiet", f->quiet, "Print nothing on success");
  return Command{sub, [f, sub](const Invocation&) {
                   StudyFlags flags = *f;
                   flags.figures_given = sub->count("--figures") > 0;
                   const StudySpec spec = load_study(flags.file);
                   return std::visit(
                       [&](auto o) {
                         if (!flags.out.empty()) o.out = flags.out;
                         if (flags.threads > 0) o.threads = flags.threads;
                         using Options = decltype(o);
                         if constexpr (std::is_same_v<Options, InteractionStudyOptions>)
                           return run_interactions(o, flags);
                         else if constexpr (std::is_same_v<Options, RecoveryMatrixOptions>)
                           return run_recovery(o, flags);
                         else
                           return run_continuum(o, flags);
                       },
                       spec.options);
                 }};
}

}  // namespace asperity::cli
