// Test fixtures: a small .npy/.npz writer (libzip) and a synthetic SMPL-layout model (a closed
// cylinder with a 24-joint skeleton), so no SMPL data is needed anywhere.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace fixtures {

enum class Dtype { f4, f8, i4, i8, u4, u8 };

struct Encoding {
  bool big_endian = false;
  bool fortran = false;
};

struct Array {
  std::vector<std::size_t> shape;
  std::vector<double> values;  // C order
  Dtype dtype = Dtype::f4;
};

// A complete .npy file for the array.
std::string encode_npy(const Array& a, const Encoding& enc = {});
// A .npy with the given header fields and raw data bytes, for odd or broken arrays.
std::string encode_npy_raw(const std::string& descr, const std::string& shape_text, bool fortran,
                           const std::string& data);

struct Entry {
  std::string name;   // without .npy
  std::string bytes;  // the .npy file
};

void write_npz(const std::filesystem::path& path, const std::vector<Entry>& entries,
               bool compressed = false);
std::string read_file(const std::filesystem::path& path);

// A closed cylinder (tube + two cap fans): radius r, height h, its axis on y with the base at
// y = base_y, `segments` around and `rings` rings. Shape components:
//   0: radial growth (x, z) -> radius r * (1 + b0)
//   1: vertical stretch (0, y - base_y, 0) -> height h * (1 + b1)
//   k >= 2: a smooth small field sin/cos(k ...)
// 24 joints (SMPL's parents; SMPL+H's and SMPL-X's hierarchy for 52 and 55 joints) regressed
// from ring averages; skin weights on up to 5 joints.
// Optional look-alikes of the SMPL family's extra arrays: `vt`/`ft` texture coordinates (u
// around, v up, with a seam at segment 0), and `posedirs` with `pose_columns` columns whose
// column 135 (in SMPL's layout: R(0,0) - 1 of joint 16, left_shoulder; the last column if
// there are fewer) lifts every vertex by `pose_lift` metres per unit of its pose feature.
// `vertices` above segments * rings + 2 pads the mesh with points on the axis at mid height
// that no face uses, for look-alikes of a model's size (SMPL-X: 10,475 vertices).
struct Cylinder {
  double radius = 0.15;
  double height = 1.7;
  double base_y = -1.0;
  int segments = 32;
  int rings = 41;
  int components = 10;
  int joints = 24;
  bool uvs = false;
  int pose_columns = 0;
  double pose_lift = 0.05;
  int vertices = 0;
};
std::map<std::string, Array> cylinder_model(const Cylinder& c = {});

// Encodes a model's arrays (in the map's order) with a dtype for floats and an encoding.
std::vector<Entry> encode_model(const std::map<std::string, Array>& arrays,
                                const Encoding& enc = {}, bool float64 = false);

// A fresh scratch folder for a test under $TMPDIR/sg_body_tests_<pid>/ (removed at exit
// unless SG_KEEP_TEST_FILES is set).
std::filesystem::path scratch_dir(const std::string& name);

}  // namespace fixtures
