#pragma once
// `asperity bench interacting --threads-scan T1 T2 … [--busy]`: the interacting solver's first
// peak at each thread count on a quiet machine, with its wall time by phase (passes over G,
// folds, rebuilds, the rest of the removals, the junctions' laws, the iterate's updates, and
// the serial rest), so that each phase's parallel efficiency t_1 / (p t_p) shows what does not
// scale; with --busy, the same at one thread and the widest count while another process keeps
// one core busy (BusyCore). Populations as `bench interacting` (STAND-IN P4.00N areas repeated
// to N, positions in a contact disc).
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace asperity {

struct ThreadsBenchOptions {
  std::filesystem::path scene = "scenes/paper/P4.00N.yaml";
  std::vector<std::size_t> sizes{1200, 5000};
  std::vector<int> threads{1, 2};
  bool busy = false;
  double contact_radius_m = 4.5e-3;  // at the scene's own N
  std::ostream* log = nullptr;
};

struct ThreadsBenchRow {
  std::string load;  // "quiet" or "busy" (one core held by another process)
  std::size_t N = 0;
  int threads = 0;
  double wall_s = 0, Q_s = 0, A_s = 0, t_peak = 0;
  double pass_s = 0, fold_s = 0, rebuild_s = 0, remove_s = 0, law_s = 0, update_s = 0;
  double rest_s() const { return wall_s - pass_s - fold_s - rebuild_s - remove_s - law_s - update_s; }
  long long slips = 0, iterations = 0;
};

std::vector<ThreadsBenchRow> run_threads_bench(const ThreadsBenchOptions& opt);
// DIR/interacting_threads.csv.
void write_threads_bench(const std::filesystem::path& dir, const std::vector<ThreadsBenchRow>& rows);
// The table the bench prints: per size, each row's wall time and ratio to one thread of the same
// load, and each phase's parallel efficiency against the quiet one-thread row.
std::string threads_bench_table(const std::vector<ThreadsBenchRow>& rows);

}  // namespace asperity
