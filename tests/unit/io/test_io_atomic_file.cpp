// io/atomic_file.hpp: the one file writer (temporary sibling + rename, fsync when asked).
#include <fcntl.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "io/atomic_file.hpp"
#include "support_files.hpp"

using namespace asperity;
namespace fs = std::filesystem;

namespace {

fs::path fresh(const std::string& name) { return asperity::testing::fresh_dir("asperity-io-atomic-" + name); }

std::size_t entries(const fs::path& d) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(d)) ++n;
  return n;
}

}  // namespace

TEST_CASE("write_file_atomically writes the exact bytes and leaves no temporary", "[io][file]") {
  const fs::path d = fresh("bytes");
  std::string bytes = "a,b\n1,2\r\n";
  bytes += '\0';
  bytes += "\xff tail without newline";
  for (const io::Durability how : {io::Durability::unsynced, io::Durability::synced}) {
    io::write_file_atomically(d / "f.csv", bytes, how);
    CHECK(io::read_file_text(d / "f.csv") == bytes);
    CHECK(entries(d) == 1);  // the temporary was renamed, not left beside it
  }
  // Replacing a file: the new text, whole.
  io::write_file_durably(d / "f.csv", "short\n");
  CHECK(io::read_file_text(d / "f.csv") == "short\n");
  io::write_text_file(d / "g.txt", "");
  CHECK(fs::file_size(d / "g.txt") == 0);
  CHECK(entries(d) == 2);
  fs::remove_all(d);
}

TEST_CASE("write_file_atomically fails with the path and reason, leaving nothing", "[io][file]") {
  const fs::path d = fresh("fail");
  try {
    io::write_file_atomically(d / "missing" / "f.csv", "x", io::Durability::synced);
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    CHECK(what.rfind("cannot create " + (d / "missing").string() + "/.f.csv.tmp-", 0) == 0);
    CHECK(what.find("No such file or directory") != std::string::npos);
  }
  // Renaming over a directory fails; the temporary is removed again.
  fs::create_directories(d / "dir.csv");
  CHECK_THROWS_WITH(io::write_file_atomically(d / "dir.csv", "x", io::Durability::unsynced),
                    Catch::Matchers::StartsWith("cannot rename into " + (d / "dir.csv").string()));
  CHECK(entries(d) == 1);
  CHECK(fs::is_empty(d / "dir.csv"));
  CHECK_THROWS_WITH(io::read_file_text(d / "none"), "cannot open " + (d / "none").string());
  fs::remove_all(d);
}

TEST_CASE("write_fully appends all bytes to a descriptor", "[io][file]") {
  const fs::path d = fresh("fully");
  const int fd = ::open((d / "j").c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  REQUIRE(fd >= 0);
  const std::string big(1 << 20, 'x');
  CHECK(io::write_fully(fd, "head\n"));
  CHECK(io::write_fully(fd, big));
  ::close(fd);
  CHECK(io::read_file_text(d / "j") == "head\n" + big);
  CHECK_FALSE(io::write_fully(-1, "x"));
  CHECK(io::unique_tmp_suffix() != io::unique_tmp_suffix());
  fs::remove_all(d);
}

TEST_CASE("store AtomicFileWriter streams pieces across its buffer and publishes only on commit", "[io][file][store]") {
  const fs::path d = fresh("writer");
  const fs::path p = d / "points.csv";
  io::write_file_durably(p, "old\n");
  // 3 MiB in pieces of 1 B to 1.5 MiB: small ones are buffered, large ones written straight through.
  std::string expected;
  {
    io::AtomicFileWriter w(p, io::Durability::synced);
    for (std::size_t n :
         {std::size_t{1}, std::size_t{1000}, std::size_t{1} << 20, std::size_t{3} << 19, std::size_t{524287}}) {
      const std::string piece(n, static_cast<char>('a' + expected.size() % 26));
      w.write(piece);
      expected += piece;
    }
    CHECK(asperity::testing::slurp(p) == "old\n");  // not yet published
    CHECK(entries(d) == 2);                         // the file and the temporary
    w.commit();
  }
  CHECK(expected.size() == 3146728);  // 1 + 1000 + 1048576 + 1572864 + 524287
  CHECK(asperity::testing::slurp(p) == expected);
  CHECK(entries(d) == 1);
  {
    io::AtomicFileWriter w(p, io::Durability::unsynced);
    w.write("never published\n");
  }  // destroyed uncommitted: the old file stays, the temporary is gone
  CHECK(asperity::testing::slurp(p) == expected);
  CHECK(entries(d) == 1);
  fs::remove_all(d);
}
