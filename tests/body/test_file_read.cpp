// util/file_read.hpp and util/file_lock.hpp: only regular files of a sane size are read (a
// pipe would block, a device never end), and one lock holder at a time.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "npz_fixtures.hpp"
#include "util/atomic_file.hpp"
#include "util/file_lock.hpp"
#include "util/file_read.hpp"

namespace fs = std::filesystem;

TEST_CASE("read_regular_file reads a file and refuses what is not one", "[util][file-read]") {
  const fs::path dir = fixtures::scratch_dir("file-read");
  const fs::path file = dir / "a.txt";
  std::ofstream(file) << "hello";
  CHECK(util::read_regular_file(file, 100) == "hello");
  CHECK_THROWS_WITH(util::read_regular_file(file, 4),
                    Catch::Contains("a.txt: too large") && Catch::Contains("at most 4 bytes"));
  CHECK_THROWS_WITH(util::read_regular_file(dir / "missing", 100),
                    Catch::Contains("missing: no such file"));
  CHECK_THROWS_WITH(util::read_regular_file(dir, 100), Catch::Contains("a folder"));
  CHECK_THROWS_WITH(util::read_regular_file("/dev/zero", 100), Catch::Contains("a device"));
  const fs::path fifo = dir / "pipe";
  fs::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // Opening a FIFO without a writer used to block forever.
  CHECK_THROWS_WITH(util::read_regular_file(fifo, 100),
                    Catch::Contains("pipe: a pipe, not a regular file"));
  // A link to a regular file is read; one to a device is refused.
  fs::remove(dir / "link");
  fs::create_symlink(file, dir / "link");
  CHECK(util::read_regular_file(dir / "link", 100) == "hello");
}

TEST_CASE("the atomic writer refuses to replace a pipe or a device", "[util][atomic]") {
  const fs::path dir = fixtures::scratch_dir("atomic-special");
  const fs::path fifo = dir / "pipe.csv";
  fs::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_AS(util::write_file_atomically(fifo, std::string("x")), util::FileWriteError);
  CHECK(fs::is_fifo(fifo));  // still there, not renamed over
  CHECK_THROWS_WITH(util::write_file_atomically("/dev/full", std::string("x")),
                    Catch::Contains("device, pipe or socket"));
  struct stat st {};
  REQUIRE(::stat("/dev/full", &st) == 0);
  CHECK(S_ISCHR(st.st_mode));
}

TEST_CASE("a file lock has one holder at a time and is released with it", "[util][lock]") {
  const fs::path dir = fixtures::scratch_dir("file-lock");
  const fs::path lock_path = util::lock_path_for(dir / "session.json");
  CHECK(lock_path.filename() == "session.json.lock");
  std::optional<util::FileLock> first, second;
  CHECK(util::FileLock::try_acquire(lock_path, first) == util::FileLock::Outcome::kAcquired);
  CHECK(first.has_value());
  CHECK(util::FileLock::try_acquire(lock_path, second) == util::FileLock::Outcome::kHeldElsewhere);
  CHECK_FALSE(second.has_value());
  first.reset();
  CHECK(util::FileLock::try_acquire(lock_path, second) == util::FileLock::Outcome::kAcquired);
  // A link planted as the lock file is not followed.
  const fs::path planted = dir / "planted.lock";
  fs::remove(planted);
  fs::create_symlink(dir / "elsewhere", planted);
  std::optional<util::FileLock> third;
  std::string problem;
  CHECK(util::FileLock::try_acquire(planted, third, &problem) ==
        util::FileLock::Outcome::kUnavailable);
  CHECK_THAT(problem, Catch::Contains("planted.lock"));
  CHECK_FALSE(fs::exists(dir / "elsewhere"));
}
