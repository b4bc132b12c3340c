#pragma once
// The options several commands share, spelled and checked the same way everywhere:
//   -j/--threads N   worker threads (1–1024, io/arguments.hpp; default: every hardware thread, except bench: 1)
//   -s/--set K=V     a scene value for every scene the command runs (repeatable)
//   -q/--quiet       nothing on stdout or stderr on success
//   --figures LIST   the formats of the figures a command draws: png, svg, pdf, comma-separated
//                    (default png; SVG and PDF sized for a journal column: report/gnuplot.hpp)
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "io/arguments.hpp"    // hardware_threads(), the thread count's range
#include "report/gnuplot.hpp"  // FigureFormats

namespace asperity::cli {

// -j/--threads into `threads`; `what` says what runs in parallel. 0 in `threads` (the default
// left untouched) means every hardware thread: resolve it with threads_or_all().
void add_threads_option(CLI::App* sub, int& threads, const std::string& what);
int threads_or_all(int threads);

void add_set_option(CLI::App* sub, std::vector<std::string>& sets, const std::string& what);
void add_quiet_flag(CLI::App* sub, bool& quiet);
void add_figures_option(CLI::App* sub, FigureFormats& formats);

}  // namespace asperity::cli
