// Writes the fuzz seed corpora (tests/fuzz/corpus/<target>/) from the project's own test
// fixtures: small cylinder models (.npz, and their arrays as .npy), real sessions and
// plane-search states, and the broken session fixtures. Run by tools/fuzz.sh --seeds.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "app/session_fixtures.hpp"
#include "body/npz_fixtures.hpp"
#include "sps/json_fields.hpp"

namespace fs = std::filesystem;

namespace {

void write(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_corpus_writer CORPUS_FOLDER\n");
    return 2;
  }
  try {
    const fs::path root = argv[1];
    for (const char* t : {"npy", "npz_model", "session", "plane_search"}) {
      fs::create_directories(root / t);
    }
    // Small models: few vertices keep every execution fast.
    int n = 0;
    for (int joints : {24, 5}) {
      for (int variant = 0; variant < 3; ++variant) {
        fixtures::Cylinder c;
        c.segments = 6;
        c.rings = 4;
        c.components = 4;
        c.joints = joints;
        const auto arrays = fixtures::cylinder_model(c);
        fixtures::Encoding enc;
        enc.big_endian = variant == 1;
        enc.fortran = variant == 2;
        const auto entries = fixtures::encode_model(arrays, enc, variant == 2);
        const fs::path npz = root / "npz_model" / ("cylinder-" + std::to_string(++n) + ".npz");
        fixtures::write_npz(npz, entries, variant == 0);
        for (const auto& e : entries) {
          write(root / "npy" / (e.name + "-" + std::to_string(n) + ".npy"), e.bytes);
        }
      }
    }
    std::string names;
    for (const char* s : {"root", "a", "b", "c", "dd"}) {
      std::string padded(s);
      padded.resize(4, '\0');
      names += padded;
    }
    write(root / "npy" / "strings-S4.npy", fixtures::encode_npy_raw("|S4", "(5,)", false, names));
    write(root / "npy" / "object.npy", fixtures::encode_npy_raw("|O", "(2,)", false, ""));
    write(root / "npy" / "scalar.npy",
          fixtures::encode_npy_raw("<f8", "()", false, std::string(8, '\0')));

    const std::string good = test_fixtures::good_session_json();
    write(root / "session" / "good.json", good);
    const auto j = nlohmann::json::parse(good);
    write(root / "plane_search" / "good.json", j.at("search").dump());
    for (const auto& f : test_fixtures::broken_session_fixtures()) {
      write(root / "session" / (f.name + ".json"), f.text);
      try {
        // Bounded: the deep fixtures must never become a tree (dumping one overflows the stack).
        const auto b = sps::json_fields::parse_bounded(f.text);
        if (b.is_object() && b.contains("search")) {
          write(root / "plane_search" / (f.name + ".json"), b.at("search").dump());
        }
      } catch (const std::runtime_error&) {
      }
    }
    // The plane-search state nested 100,000 deep, as text.
    write(root / "plane_search" / "deep.json",
          "{\"format\": " + std::string(100000, '[') + std::string(100000, ']') + "}");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_corpus_writer: %s\n", e.what());
    return 1;
  }
  return 0;
}
