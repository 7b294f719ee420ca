// Robustness: damaged files must give a ModelError/NpyError, never a crash or another
// exception. Deterministic mutations (fixed seed) of valid fixtures.
#include <catch2/catch.hpp>

#include <random>

#include "body/model_loader.hpp"
#include "body/npy_reader.hpp"
#include "npz_fixtures.hpp"

TEST_CASE("fuzz: mutated .npy headers and data never crash the parser", "[fuzz]") {
  fixtures::Array a{{4, 3, 2}, {}, fixtures::Dtype::f8};
  for (int i = 0; i < 24; ++i) a.values.push_back(i);
  const std::string good = fixtures::encode_npy(a, {true, true});
  std::mt19937 rng(42);
  int errors = 0;
  for (int round = 0; round < 3000; ++round) {
    std::string bad = good;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) {
      // Mostly the header (first 128 bytes), sometimes anywhere; sometimes truncate.
      const std::size_t at = (rng() % 4 != 0) ? rng() % 128 : rng() % bad.size();
      bad[at] = static_cast<char>(rng() % 256);
    }
    if (rng() % 5 == 0) bad.resize(rng() % bad.size());
    try {
      const auto arr =
          body::parse_npy(reinterpret_cast<const std::uint8_t*>(bad.data()), bad.size());
      if (arr.header.is_numeric()) (void)arr.to_double();
    } catch (const body::NpyError&) {
      ++errors;
    }
  }
  CHECK(errors > 100);  // the mutations did reach the error paths
}

TEST_CASE("fuzz: damaged .npz files give ModelError", "[fuzz]") {
  fixtures::Cylinder c;
  c.segments = 8;
  c.rings = 6;
  const auto path = fixtures::scratch_dir("fuzz") / "small.npz";
  for (bool compressed : {false, true}) {
    fixtures::write_npz(path, fixtures::encode_model(fixtures::cylinder_model(c)), compressed);
    const std::string good = fixtures::read_file(path);
    REQUIRE_NOTHROW(body::load_model_from_memory(good.data(), good.size(), "good.npz"));
    std::mt19937 rng(compressed ? 7 : 8);
    int failures = 0;
    for (int round = 0; round < 400; ++round) {
      std::string bad = good;
      const int flips = 1 + static_cast<int>(rng() % 8);
      for (int f = 0; f < flips; ++f) bad[rng() % bad.size()] = static_cast<char>(rng() % 256);
      if (rng() % 6 == 0) bad.resize(1 + rng() % (bad.size() - 1));
      try {
        body::load_model_from_memory(bad.data(), bad.size(), "bad.npz");
      } catch (const body::ModelError& e) {
        ++failures;
        CHECK_THAT(e.what(), Catch::StartsWith("bad.npz"));
      }
    }
    CHECK(failures > 200);
  }
}
