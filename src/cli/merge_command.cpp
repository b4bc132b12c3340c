// asperity merge DIR1 DIR2 ... --out DIR
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "campaign/merge.hpp"
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "report/output_dir.hpp"

namespace asperity::cli {

Command add_merge_command(CLI::App& app) {
  struct Args {
    std::vector<std::string> in;
    std::string out;
    bool quiet = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("merge", "Merge sweep stores of one campaign (e.g. its shards) into one store");
  sub->add_option("stores", a->in, "Store folders")->required();
  sub->add_option("--out,-o", a->out, "New store folder")->required();
  add_quiet_flag(sub, a->quiet);
  return Command{sub, [a](const Invocation&) {
                   const std::vector<std::filesystem::path> in(a->in.begin(), a->in.end());
                   // Only into a new or empty folder, or one a stopped merge left: the result is a
                   // store (no marker, so that sweep can resume it), and merge never adds to an
                   // existing one.
                   check_ours(a->out, "merge", "--out", merge_remnant);
                   const MergeReport r = merge_stores(in, a->out);
                   if (!a->quiet)
                     std::printf("merged %zu stores: %llu points (%llu failed, %llu in more than one store) -> %s\n",
                                 in.size(), static_cast<unsigned long long>(r.rows),
                                 static_cast<unsigned long long>(r.failed),
                                 static_cast<unsigned long long>(r.duplicates),
                                 (std::filesystem::path(a->out) / "points.csv").string().c_str());
                   return exit_ok;
                 }};
}

}  // namespace asperity::cli
