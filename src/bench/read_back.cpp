#include "bench/read_back.hpp"

#include <cstdint>
#include <limits>
#include <system_error>

#include "io/input_error.hpp"

namespace asperity {
namespace fs = std::filesystem;

io::TextTable read_bench_csv(const fs::path& file, const std::string& command, std::size_t max_rows) {
  const std::string display = io::input_path(file);
  std::error_code ec;
  // read_text_table reads a missing file as an empty table (a store not yet written); here the
  // bench must have written it.
  if (!fs::exists(file, ec)) throw io::InputError(display, 0, "", "file not found (written by `" + command + "`)");
  io::TextTable table = io::read_text_table(file, display, max_rows);
  if (table.rows.empty())
    throw io::InputError(display, table.header_line, "", "no data rows (written by `" + command + "`)");
  return table;
}

int read_repeats(const io::TextTable& table, std::size_t row) {
  const std::int64_t repeats = table.count(row, "repeats");
  if (repeats < 1 || repeats > std::numeric_limits<int>::max()) table.fail(row, "repeats", "expected a run count >= 1");
  return static_cast<int>(repeats);
}

void check_redraw_targets(const fs::path& figure, const FigureFormats& formats) {
  std::error_code ec;
  for (const fs::path& f : figure_files(figure, formats))
    if (fs::exists(fs::symlink_status(f, ec)) && !png_is_ours(f))
      throw io::InputError(io::input_path(f), 0, "", "refusing to replace a file that asperity did not draw");
}

}  // namespace asperity
