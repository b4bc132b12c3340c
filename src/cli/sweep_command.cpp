// asperity sweep CAMPAIGN.yaml [--threads N] [--shard I/N] [--balance cost|index] [--out DIR] [--quiet] [--retry-failed]
//                [--sync-every N] [--sync-seconds S]
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "campaign/campaign_load.hpp"
#include "campaign/sweep.hpp"
#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/options.hpp"
#include "io/numbers.hpp"
#include "observe/run_monitor.hpp"
#include "report/output_dir.hpp"
#include "scene/load.hpp"

namespace asperity::cli {
namespace {

struct SweepArgs {
  std::string campaign, out, shard = "0/1", balance;
  int threads = 0;
  bool quiet = false, retry_failed = false;
  JournalSync sync = SweepOptions{}.sync;
  std::vector<std::string> overrides;
};

int sweep(const SweepArgs& a, const Invocation& inv) {
  SweepOptions opt;
  opt.command_line = inv.command_line;
  try {
    opt.shard = io::parse_shard(a.shard);
  } catch (const std::invalid_argument& e) {
    throw io::InputError("", 0, "--shard", e.what());
  }
  try {
    if (!a.balance.empty()) opt.balance = parse_shard_balance(a.balance);
  } catch (const std::invalid_argument& e) {
    throw io::InputError("", 0, "--balance", e.what());
  }
  Campaign c = load_campaign(a.campaign);
  // --set: checked on every base scene (one-line errors as `run --set`), then applied to every
  // point like the campaign's own `set:` (after it; the grids' axes still win).
  if (!a.overrides.empty()) {
    for (const auto& scene : c.scenes) (void)load_scene(scene, a.overrides);
    for (const std::string& o : a.overrides) {
      const std::size_t eq = o.find('=');
      c.set.emplace_back(o.substr(0, eq), AxisValue{false, true, 0, eq == std::string::npos ? "" : o.substr(eq + 1)});
    }
  }
  // Only into a new or empty folder or a store (its provenance.yaml, or what a sweep killed at its
  // very start leaves): never among a user's files.
  const std::filesystem::path store =
      a.out.empty() ? std::filesystem::path("results") / c.name : std::filesystem::path(a.out);
  check_ours(store, "sweep", "--out", is_sweep_store_folder);
  opt.threads = a.threads;
  opt.out = a.out;
  opt.quiet = a.quiet;
  opt.retry_failed = a.retry_failed;
  opt.sync = a.sync;
  SweepReport r;
  try {
    const InterruptRequest ctrl_c;  // Ctrl-C: the points in flight stop, the journal keeps the rest
    opt.stop = ctrl_c.flag();
    r = run_sweep(c, opt);
  } catch (const RunInterrupted& e) {
    std::fprintf(stderr, "%s%s: %s\n", a.quiet ? "" : "\n", c.name.c_str(), e.what());
    return exit_interrupted;
  }
  if (!a.quiet || r.failed > 0) {
    std::fprintf(
        stderr, "%s: %llu points in shard %s; %llu already stored, %llu run now (%llu failed) in %.1f s",
        c.name.c_str(), static_cast<unsigned long long>(r.points),
        (std::to_string(opt.shard.index) + "/" + std::to_string(opt.shard.count) + (a.shard == "auto" ? " (auto)" : ""))
            .c_str(),
        static_cast<unsigned long long>(r.skipped), static_cast<unsigned long long>(r.ran),
        static_cast<unsigned long long>(r.failed_now), r.wall_s);
    if (r.ran > 0) std::fprintf(stderr, " (%.2f points/s)", static_cast<double>(r.ran) / r.wall_s);
    if (std::isfinite(r.expected_s))
      std::fprintf(stderr, "\n  balanced by expected cost: this shard %s s on one core, shards %s to %s s",
                   io::format_short(r.expected_s).c_str(), io::format_short(r.expected_min_s).c_str(),
                   io::format_short(r.expected_max_s).c_str());
    std::fprintf(
        stderr, "\n  store %s: %llu ok, %llu failed%s; %s\n", (r.store / "points.csv").string().c_str(),
        static_cast<unsigned long long>(r.ok), static_cast<unsigned long long>(r.failed),
        r.dropped_lines
            ? (", " + std::to_string(r.dropped_lines) + " torn/corrupt journal line(s) dropped and rerun").c_str()
            : "",
        r.trusted ? "stored hashes trusted (inputs.txt unchanged)"
                  : (std::to_string(r.rehashed) + " stored point(s) re-hashed").c_str());
  }
  // Said even with --quiet: stored values were replaced.
  if (r.changed > 0)
    std::fprintf(stderr,
                 "%s: %llu stored point(s) recomputed: their scene or data (the bytes of a junctions or measured CSV) "
                 "changed since they were stored; the new rows supersede the stale ones\n",
                 c.name.c_str(), static_cast<unsigned long long>(r.changed));
  return r.failed > 0 ? exit_failure : exit_ok;
}

}  // namespace

Command add_sweep_command(CLI::App& app) {
  auto a = std::make_shared<SweepArgs>();
  CLI::App* sub = app.add_subcommand("sweep", "Run a campaign (sweeps/*.yaml) into a resumable result store");
  sub->add_option("campaign", a->campaign, "Campaign YAML file")->required();
  add_threads_option(sub, a->threads, "Points run in parallel");
  add_set_option(sub, a->overrides, "in every point's scene (the campaign's axes win)");
  sub->add_option("--shard", a->shard,
                  "Run only shard I of N, given as I/N (default 0/1), or auto: the task of a SLURM job array");
  sub->add_option(
      "--balance", a->balance,
      "How points are dealt to shards: cost (a new store's default: by expected run time, each point to the "
      "shard with the least so far; equal costs give round robin) or index (round robin, index % N == I). "
      "Default: what the store recorded (stores from before it was recorded: index)");
  sub->add_option("--out,-o", a->out, "Store folder (default results/<campaign name>/)");
  sub->add_flag("-q,--quiet", a->quiet, "No progress and no summary (failures are still reported)");
  sub->add_flag("--retry-failed", a->retry_failed, "Rerun the points the store holds as failed");
  sub->add_option("--sync-every", a->sync.every,
                  "fdatasync the journal once per N points (default " + std::to_string(a->sync.every) +
                      "; 1: per point). A power cut may lose up to N-1 journaled points, which the next run recomputes")
      ->check(CLI::Range(1u, 1000000000u));
  sub->add_option("--sync-seconds", a->sync.seconds,
                  "... or sooner, at the first point journaled S seconds after the last fdatasync (default " +
                      io::format_short(a->sync.seconds) + "; 0: no time bound)")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            double x = -1;
            return io::parse_double(v, x) == io::NumberParse::ok && x >= 0 && x <= 86400
                       ? ""
                       : "Value " + v + " not in range 0 to 86400";
          },
          "SECONDS"));
  return Command{sub, [a](const Invocation& inv) { return sweep(*a, inv); }};
}

}  // namespace asperity::cli
