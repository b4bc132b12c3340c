// io/safe_open.hpp: files inside an output folder are opened without following any link below the
// folder, and only when they are regular files (a FIFO is refused at once, not waited on).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <string>

#include "io/input_error.hpp"
#include "io/safe_open.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;

TEST_CASE("open_in_folder: regular files open, links anywhere below the folder and special files are refused",
          "[io][safe_open]") {
  const fs::path d = fresh_dir("safe_open");
  fs::create_directories(d / "out" / "tasks" / "0-of-2");
  write_text(d / "outside.csv", "outside\n");
  write_text(d / "out" / "journal.csv", "ours\n");

  // A regular file: opened; its text read back.
  const int fd = io::open_in_folder(d / "out", "journal.csv", O_RDONLY);
  REQUIRE(fd >= 0);
  ::close(fd);
  std::string text;
  CHECK(io::read_regular(d / "out" / "journal.csv", text));
  CHECK(text == "ours\n");
  // Absent: -1 with ENOENT (O_CREAT makes it), in a subfolder too.
  CHECK(io::open_in_folder(d / "out", "tasks/0-of-2/journal.csv", O_RDONLY) == -1);
  CHECK(errno == ENOENT);
  const int made = io::open_in_folder(d / "out", "tasks/0-of-2/journal.csv", O_WRONLY | O_CREAT | O_APPEND);
  REQUIRE(made >= 0);
  ::close(made);
  CHECK(fs::is_regular_file(d / "out" / "tasks" / "0-of-2" / "journal.csv"));

  // The file itself a link to a file outside: refused, naming the link; the outside file untouched.
  fs::remove(d / "out" / "journal.csv");
  fs::create_symlink(d / "outside.csv", d / "out" / "journal.csv");
  for (const int flags : {O_RDONLY, O_WRONLY | O_APPEND, O_RDWR | O_CREAT}) {
    try {
      io::open_in_folder(d / "out", "journal.csv", flags, "--out");
      FAIL("a link was opened");
    } catch (const io::InputError& e) {
      CHECK(e.file == (d / "out" / "journal.csv").string());
      CHECK(e.key == "--out");
      CHECK(e.message.rfind("is a symbolic link", 0) == 0);
    }
  }
  CHECK_THROWS_AS(io::read_regular(d / "out" / "journal.csv", text), io::InputError);
  CHECK(slurp(d / "outside.csv") == "outside\n");

  // A folder on the way a link (tasks -> outside folder): refused at that folder.
  fs::create_directories(d / "elsewhere" / "0-of-2");
  fs::rename(d / "out" / "tasks", d / "tasks.bak");
  fs::create_directory_symlink(d / "elsewhere", d / "out" / "tasks");
  CHECK_THROWS_WITH(io::open_in_folder(d / "out", "tasks/0-of-2/journal.csv", O_WRONLY | O_CREAT),
                    Catch::Contains((d / "out" / "tasks").string() + ": is a symbolic link"));
  CHECK_THROWS_WITH(io::check_real_folders(d / "out", "tasks/0-of-2"), Catch::Contains("tasks: is a symbolic link"));
  CHECK(!fs::exists(d / "elsewhere" / "0-of-2" / "journal.csv"));
  CHECK_NOTHROW(io::check_real_folders(d / "out", "new/sub"));  // absent folders are fine

  // A FIFO: refused at once (a blocking open would wait for a writer forever).
  REQUIRE(::mkfifo((d / "out" / "fifo.csv").c_str(), 0644) == 0);
  const auto t0 = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(io::open_in_folder(d / "out", "fifo.csv", O_RDONLY), Catch::Contains("is a FIFO"));
  CHECK_THROWS_WITH(io::open_in_folder(d / "out", "fifo.csv", O_RDWR | O_APPEND), Catch::Contains("is a FIFO"));
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(1));
  // A device (here /dev/null, reached as a folder's own entry) and a folder are no result files.
  CHECK_THROWS_WITH(io::open_in_folder("/dev", "null", O_RDONLY), Catch::Contains("is a device"));
  CHECK_THROWS_WITH(io::open_in_folder(d / "out", "tasks", O_RDONLY), Catch::Contains("symbolic link"));
  fs::create_directories(d / "out" / "adir");
  CHECK_THROWS_WITH(io::open_in_folder(d / "out", "adir", O_RDONLY), Catch::Contains("is a folder"));
  fs::remove_all(d);
}
