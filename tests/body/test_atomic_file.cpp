// The project's one atomic file writer (src/util/atomic_file.hpp).
#include <catch2/catch.hpp>

#include <string>

#include "npz_fixtures.hpp"
#include "util/atomic_file.hpp"

TEST_CASE("atomic writer: names up to NAME_MAX work, and the temporary name always fits",
          "[atomic]") {
  const auto dir = fixtures::scratch_dir("atomic-names");
  for (std::size_t length : {5u, 200u, 243u, 244u, 250u, 255u}) {
    INFO("name length " << length);
    const std::string name = std::string(length - 4, 'n') + ".glb";
    CHECK(util::temporary_name_for(dir / name).filename().string().size() <= 255);
    REQUIRE_NOTHROW(util::write_file_atomically(dir / name, std::string("bytes")));
    CHECK(fixtures::read_file(dir / name) == "bytes");
  }
  CHECK_THROWS_WITH(util::write_file_atomically(dir / std::string(256, 'x'), std::string("b")),
                    Catch::Contains("longer than 255"));
  CHECK_THROWS_WITH(util::write_file_atomically(dir, std::string("b")), Catch::Contains("folder"));
}
