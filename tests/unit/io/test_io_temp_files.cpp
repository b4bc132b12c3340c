// io/temp_files.hpp: temporaries removed when a signal stops the process, and stale ones (their
// process gone) removed by the next start; live ones and other names are left alone.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/atomic_file.hpp"
#include "io/temp_files.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;

namespace {

// A PID that no longer exists: a child that has exited and been reaped.
pid_t dead_pid() {
  const pid_t p = ::fork();
  if (p == 0) ::_exit(0);
  int st = 0;
  ::waitpid(p, &st, 0);
  return p;
}

std::string host_of_suffix() {
  const std::string s = io::unique_tmp_suffix();  // HOST-PID-N
  const std::size_t n = s.rfind('-'), p = s.rfind('-', n - 1);
  return s.substr(0, p);
}

}  // namespace

TEST_CASE("remove_stale_temporaries: only temporaries whose process is gone, or a day old", "[io][temp]") {
  const fs::path d = fresh_dir("stale");
  fs::create_directories(d);
  const std::string host = host_of_suffix();
  const std::string dead = std::to_string(dead_pid()), alive = std::to_string(::getpid());
  write_text(d / (".points.csv.tmp-" + host + "-" + dead + "-3"), "half a file");
  fs::create_directories(d / (".run.tmp-" + host + "-" + dead + "-0") / "sub");
  write_text(d / (".run.tmp-" + host + "-" + dead + "-0") / "sub" / "series.csv", "x");
  write_text(d / (".old.tmp-" + dead + "-1"), "written before hosts were recorded");
  write_text(d / (".live.tmp-" + host + "-" + alive + "-2"), "this process is writing it");
  write_text(d / ".other.tmp-othernode-1-2", "another node's, recent");
  write_text(d / ".ancient.tmp-othernode-1-3", "another node's, two days old");
  fs::last_write_time(d / ".ancient.tmp-othernode-1-3", fs::file_time_type::clock::now() - std::chrono::hours(48));
  write_text(d / "notes.tmp-1-2", "a user's file (no leading dot)");
  write_text(d / "points.csv", "ours, not a temporary");
  CHECK(io::remove_stale_temporaries(d) == 4);
  CHECK(!fs::exists(d / (".points.csv.tmp-" + host + "-" + dead + "-3")));
  CHECK(!fs::exists(d / (".run.tmp-" + host + "-" + dead + "-0")));
  CHECK(!fs::exists(d / (".old.tmp-" + dead + "-1")));
  CHECK(!fs::exists(d / ".ancient.tmp-othernode-1-3"));
  CHECK(fs::exists(d / (".live.tmp-" + host + "-" + alive + "-2")));
  CHECK(fs::exists(d / ".other.tmp-othernode-1-2"));
  CHECK(fs::exists(d / "notes.tmp-1-2"));
  CHECK(fs::exists(d / "points.csv"));
  // A prefix limits it to one output's temporaries.
  write_text(d / (".a.tmp-" + host + "-" + dead + "-0"), "");
  write_text(d / (".b.tmp-" + host + "-" + dead + "-0"), "");
  CHECK(io::remove_stale_temporaries(d, ".a.") == 1);
  CHECK(fs::exists(d / (".b.tmp-" + host + "-" + dead + "-0")));
  fs::remove_all(d);
}

TEST_CASE("a signal removes the temporaries being written and ends the process as the signal would", "[io][temp]") {
  const fs::path d = fresh_dir("onsignal");
  fs::create_directories(d);
  for (const int sig : {SIGTERM, SIGINT, SIGHUP}) {
    int ready[2];
    REQUIRE(::pipe(ready) == 0);
    const pid_t child = ::fork();
    if (child == 0) {  // install, write a temporary folder and an atomic file, wait to be stopped
      io::install_signal_cleanup();
      const fs::path tmp = d / (".out.tmp-" + io::unique_tmp_suffix());
      fs::create_directories(tmp / "sub");
      write_text(tmp / "sub" / "fit.yaml", "half");
      const io::TempGuard guard(tmp);
      io::AtomicFileWriter w(d / "points.csv", io::Durability::unsynced);
      w.write("index,hash\n");
      (void)!::write(ready[1], "x", 1);
      for (;;) ::pause();
    }
    char c;
    REQUIRE(::read(ready[0], &c, 1) == 1);
    ::kill(child, sig);
    int st = 0;
    ::waitpid(child, &st, 0);
    ::close(ready[0]), ::close(ready[1]);
    CHECK(WIFSIGNALED(st));
    CHECK(WTERMSIG(st) == sig);
    CHECK(fs::is_empty(d));  // the folder and the atomic file's temporary are gone
  }
  fs::remove_all(d);
}

TEST_CASE("past the file-size limit a write fails (EFBIG) and leaves no temporary", "[io][temp]") {
  const fs::path d = fresh_dir("xfsz");
  fs::create_directories(d);
  const pid_t child = ::fork();
  if (child == 0) {
    io::install_signal_cleanup();  // SIGXFSZ ignored
    const rlimit lim{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &lim);
    try {
      io::write_file_atomically(d / "points.csv", std::string(1 << 20, 'x'), io::Durability::synced);
      ::_exit(3);
    } catch (const std::runtime_error& e) {
      ::_exit(std::string(e.what()).find("File too large") != std::string::npos ? 0 : 4);
    }
  }
  int st = 0;
  ::waitpid(child, &st, 0);
  CHECK(WIFEXITED(st));
  CHECK(WEXITSTATUS(st) == 0);
  CHECK(fs::is_empty(d));
  fs::remove_all(d);
}

TEST_CASE("temporaries of names up to 255 bytes stay within NAME_MAX and are found again as stale", "[io][temp]") {
  const fs::path d = temp_path("asperity_temp_long_names");
  fs::remove_all(d);
  fs::create_directories(d);
  // Short names keep their name; long ones (ASCII and 2-byte UTF-8) a cut at a character and a hash.
  CHECK(io::temp_prefix("points.csv") == ".points.csv.");
  std::string utf8;
  while (utf8.size() < 250) utf8 += "é";
  for (const std::string& name : {std::string(250, 'a'), std::string(255, 'b'), utf8}) {
    const std::string p = io::temp_prefix(name), t = io::temp_name(name);
    CHECK(t.rfind(p + "tmp-", 0) == 0);
    CHECK(t.size() <= 255);
    CHECK(p == io::temp_prefix(name));                                    // the same name, the same prefix
    CHECK(p != io::temp_prefix(name.substr(0, name.size() - 2) + "zz"));  // another name, another one
    const std::string kept = p.substr(1, p.find('~') - 1);
    CHECK(kept.size() >= 140);
    CHECK(name.rfind(kept, 0) == 0);
    CHECK((static_cast<unsigned char>(name[kept.size()]) & 0xC0) != 0x80);  // cut between characters
    // The file is made, written and published, and a dead process's temporary is found again.
    io::write_file_atomically(d / name, "x\n", io::Durability::unsynced);
    CHECK(io::read_file_text(d / name) == "x\n");
    std::string stale = p + "tmp-" + host_of_suffix() + "-" + std::to_string(dead_pid()) + "-0";
    CHECK(stale.size() <= 255);
    { std::ofstream(d / stale) << "half"; }
    REQUIRE(fs::exists(d / stale));
    CHECK(io::remove_stale_temporaries(d, p) == 1);
    CHECK_FALSE(fs::exists(d / stale));
  }
  fs::remove_all(d);
}
