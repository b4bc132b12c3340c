// io/csv.hpp: the CSV codec (text fields, numbers, numeric input tables).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "support_files.hpp"

using namespace asperity;
namespace fs = std::filesystem;
using asperity::testing::temp_path;
using asperity::testing::write_text;

namespace {

// The one-line message `read` gives for a file holding `text` (empty when it reads).
template <class Read>
std::string message_of(const std::string& text, Read read) {
  const fs::path p = write_text(temp_path("asperity-io-csv", ".csv"), text);
  std::string message;
  try {
    read(p);
  } catch (const io::InputError& e) {
    message = e.what();
  }
  fs::remove(p);
  return message;
}

// ... of read_numeric_csv.
std::string error_of(const std::string& text) {
  return message_of(text, [](const fs::path& p) { io::read_numeric_csv(p, "t.csv", {"a", "b"}, {"a"}); });
}

}  // namespace

TEST_CASE("csv_field and csv_split round-trip any field", "[io][csv]") {
  const std::vector<std::string> fields{"plain", "", "a,b", "say \"hi\"", " lead", "trail ", "\ttab", "\"", ",,"};
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i) line += ',';
    line += io::csv_field(fields[i]);
  }
  CHECK(io::csv_split(line) == fields);
  CHECK(io::csv_field("a,b") == "\"a,b\"");
  CHECK(io::csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(io::csv_field("two\nlines\rhere") == "two lines here");  // one line per row, always
  CHECK(io::csv_split("1,,x") == std::vector<std::string>{"1", "", "x"});
  CHECK_THROWS_WITH(io::csv_split("\"open,1"), "unterminated quote in CSV line");
}

TEST_CASE("csv_number is the shortest text that reads back to the same double", "[io][csv]") {
  CHECK(io::csv_number(0.1) == "0.1");
  CHECK(io::csv_number(2e-8) == "2e-08");
  CHECK(io::csv_number(7.25e-16) == "7.25e-16");
  for (const double x : {0.1 + 0.2, 1.0 / 3.0, 5e-324, std::numeric_limits<double>::max(), -1e-20}) {
    const std::string s = io::csv_number(x);
    CHECK(std::strtod(s.c_str(), nullptr) == x);
    CHECK(s.size() <= 24);  // never the 17-digit %.17g spelling when shorter suffices
  }
  CHECK(io::csv_number(0.3) == "0.3");  // %.17g would give 0.29999999999999999
}

TEST_CASE("read_numeric_csv reads a header, comments, blanks and numbers", "[io][csv]") {
  const fs::path p = write_text(temp_path("asperity-io-csv-ok", ".csv"),
                                "\xEF\xBB\xBF# made by hand\n\nb , a\n# a comment row\n 2.5e-3,1\n-4,+0.125\n\n");
  const io::CsvTable t = io::read_numeric_csv(p, "t.csv", {"a", "b"}, {"a"});
  CHECK(t.columns == std::vector<std::string>{"b", "a"});
  CHECK(t.header_line == 3);
  CHECK(t.lines == std::vector<int>{5, 6});
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0] == std::vector<double>{2.5e-3, 1.0});
  CHECK(t.rows[1] == std::vector<double>{-4.0, 0.125});
  CHECK(t.column("a") == 1);
  CHECK(t.column("c") == -1);
  fs::remove(p);
}

TEST_CASE("read_numeric_csv errors name file, line, column and column name", "[io][csv]") {
  CHECK(error_of("a,b\n1,2 MPa\n") == "t.csv:2:2: b: expected a plain number in SI units, got '2 MPa'");
  CHECK(error_of("a,b\n1,\n") == "t.csv:2:2: b: empty field (expected a number)");
  CHECK(error_of("a,b\nnan,1\n") == "t.csv:2:1: a: must be a finite number, got 'nan'");
  CHECK(error_of("a,b\nx1,1\n") == "t.csv:2:1: a: expected a number, got 'x1'");
  CHECK(error_of("a,b\n1,2,3\n") == "t.csv:2:3: expected 2 fields (a, b), got 3");
  CHECK(error_of("a,a\n1,2\n") == "t.csv:1:2: a: duplicate column");
  CHECK(error_of("a,,b\n") == "t.csv:1:2: empty column name in the header");
  CHECK(error_of("b\n1\n") == "t.csv:1: a: missing required column (header must name a)");
  CHECK(error_of("a\n1\n\n2\n") == "t.csv:3: blank line inside the data (only trailing blank lines are allowed)");
  CHECK(error_of("# only a comment\n") == "t.csv:1: a: missing header row (expected columns a, b)");
  CHECK(error_of("a\n") == "t.csv:1: a: no data rows after the header");
  CHECK(error_of("a,wxyz\n1,2\n").rfind("t.csv:1:2: wxyz: unknown column 'wxyz'", 0) == 0);
  CHECK(error_of("a\n1\n") == "");
}

namespace {

// The one-line message read_numeric_matrix_csv gives for `text` (empty when it reads), with
// caps of 3 rows and 3 columns.
std::string matrix_error_of(const std::string& text) {
  return message_of(text, [](const fs::path& p) { io::read_numeric_matrix_csv(p, "m.csv", "h_m", 3, 3); });
}

}  // namespace

TEST_CASE("numeric matrices: rows without a header, comments, caps and located errors", "[io][csv]") {
  const fs::path p = write_text(temp_path("asperity-io-csv-matrix-ok", ".csv"),
                                "# heights\n\n1, -2e-6,3\n# between rows\n4,5,6.5\n\n");
  const io::CsvMatrix m = io::read_numeric_matrix_csv(p, "m.csv", "h_m", 3, 3);
  fs::remove(p);
  CHECK(m.rows == 2);
  CHECK(m.columns == 3);
  CHECK(m.first_line == 3);
  CHECK(m.values == std::vector<double>{1, -2e-6, 3, 4, 5, 6.5});

  CHECK(matrix_error_of("1,2\n3,nan\n") == "m.csv:2:2: h_m: must be a finite number, got 'nan'");
  CHECK(matrix_error_of("1,2\n3\n") == "m.csv:2:2: h_m: expected 2 values (as in the first row, line 1), got 1");
  CHECK(matrix_error_of("1,2,3,4\n") == "m.csv:1:4: h_m: row of 4 values, more than the 3 allowed");
  CHECK(matrix_error_of("1\n2\n3\n4\n") == "m.csv:4: h_m: more than the 3 rows allowed");
  CHECK(matrix_error_of("1,2\n\n3,4\n") ==
        "m.csv:2: blank line inside the data (only trailing blank lines are allowed)");
  CHECK(matrix_error_of("# nothing\n") == "m.csv:1: h_m: no rows of numbers");
  CHECK(matrix_error_of("1,2 um\n").rfind("m.csv:1:2: h_m: expected a plain number in SI units", 0) == 0);
}

TEST_CASE("read_text_table: comments and blanks skipped, quoted fields kept, bad rows at their line", "[io][csv]") {
  using asperity::testing::fresh_dir;
  using asperity::testing::write_text;
  const std::filesystem::path dir = fresh_dir("asperity-text-table");
  CHECK(io::read_text_table(dir / "absent.csv", "absent.csv", 10).columns.empty());
  const io::TextTable t = io::read_text_table(
      write_text(dir / "t.csv", "# a table we wrote\n\na,b,c\n1,\"x, y\",3\n# between\n4,5,6\r\n"), "t.csv", 10);
  REQUIRE(t.columns == std::vector<std::string>{"a", "b", "c"});
  CHECK(t.header_line == 3);
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0][1] == "x, y");
  CHECK(t.rows[1][2] == "6");  // the CR of a CRLF line dropped
  CHECK(t.lines == std::vector<int>{4, 6});
  CHECK(t.column("c") == 2);
  auto error = [&](const std::string& text, std::size_t max_rows) {
    try {
      io::read_text_table(write_text(dir / "bad.csv", text), "bad.csv", max_rows);
    } catch (const io::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error("a,b\n1,2\n3\n", 10).rfind("bad.csv:3: 1 fields where the header has 2", 0) == 0);
  CHECK(error("a,b\n1,2\n3,4\n", 1).rfind("bad.csv:3: more than 1 rows", 0) == 0);
  CHECK(error("a,b\n\"1,2\n", 10).rfind("bad.csv:2: ", 0) == 0);
  try {
    (void)t.column("d");
    FAIL("no error");
  } catch (const io::InputError& e) {
    CHECK(std::string(e.what()).rfind("t.csv:3: d: column missing", 0) == 0);
  }
  std::filesystem::remove_all(dir);
}
