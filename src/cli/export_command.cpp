// asperity export STORE --sqlite FILE
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "campaign/export_sqlite.hpp"
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "io/input_error.hpp"

namespace asperity::cli {

Command add_export_command(CLI::App& app) {
  struct Args {
    std::string store, sqlite;
    bool quiet = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("export", "Export a sweep store's points to another format (an SQLite database)");
  sub->add_option("store", a->store, "Store folder (results/<campaign>)")->required();
  sub->add_option("--sqlite", a->sqlite, "New SQLite database file (table points; never overwritten)")->required();
  add_quiet_flag(sub, a->quiet);
  return Command{sub, [a](const Invocation&) {
                   namespace fs = std::filesystem;
                   if (!fs::is_directory(a->store)) throw io::InputError(a->store, 0, "store", "no such store folder");
                   const SqliteExportReport r = export_sqlite(a->store, a->sqlite);
                   if (!a->quiet)
                     std::printf("exported %llu points, %zu columns, %zu indexes -> %s (table points)\n",
                                 static_cast<unsigned long long>(r.rows), r.columns, r.indexes, a->sqlite.c_str());
                   return exit_ok;
                 }};
}

}  // namespace asperity::cli
