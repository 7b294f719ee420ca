// Writes the cylinder fixture model as .npz for the CLI tests and benchmarks (no SMPL data
// needed).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "npz_fixtures.hpp"

namespace {

int usage() {
  std::fprintf(stderr,
               "usage: body_fixture_writer OUT.npz [plain|smpl|smplh|smplx|star]\n"
               "           [--vertices N] [--components K] [--pose-columns P] [--float64]\n"
               "           [--fortran] [--stored]\n"
               "  --vertices N      N vertices (more rings, then unused points on the axis)\n"
               "  --components K    K shape columns in shapedirs (SMPL-X: shape + expressions)\n"
               "  --pose-columns P  P columns of posedirs (0: none)\n"
               "  --float64         float arrays as float64 (default float32)\n"
               "  --fortran         arrays in Fortran order (default C order)\n"
               "  --stored          entries stored uncompressed (default deflated)\n");
  return 2;
}

bool non_negative_int(const char* text, int& out) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || v < 0 || v > 100000000) return false;
  out = static_cast<int>(v);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  int next = 2;
  std::string family = "plain";
  if (argc > 2 && argv[2][0] != '-') family = argv[next++];
  if (family != "plain" && family != "smpl" && family != "smplh" && family != "smplx" &&
      family != "star") {
    return usage();
  }
  // Look-alikes of the SMPL family's layouts (never their data): joint counts, SMPL-X's
  // 10 shape + 10 expression columns, UVs, pose correctives in SMPL's or STAR's layout.
  fixtures::Cylinder c;
  c.base_y = -0.9;
  if (family == "smpl") c.pose_columns = 9 * 23;
  if (family == "star") c.pose_columns = 93;
  if (family == "smplh") c.joints = 52, c.components = 16, c.uvs = true, c.pose_columns = 9 * 51;
  if (family == "smplx") c.joints = 55, c.components = 20, c.uvs = true, c.pose_columns = 9 * 54;
  fixtures::Encoding enc;
  bool float64 = false, compressed = true;
  for (; next < argc; ++next) {
    const std::string a = argv[next];
    const bool has_value = next + 1 < argc;
    if (a == "--vertices" && has_value && non_negative_int(argv[next + 1], c.vertices)) {
      ++next;
    } else if (a == "--components" && has_value && non_negative_int(argv[next + 1], c.components) &&
               c.components > 0) {
      ++next;
    } else if (a == "--pose-columns" && has_value &&
               non_negative_int(argv[next + 1], c.pose_columns)) {
      ++next;
    } else if (a == "--float64") {
      float64 = true;
    } else if (a == "--fortran") {
      enc.fortran = true;
    } else if (a == "--stored") {
      compressed = false;
    } else {
      return usage();
    }
  }
  // A bigger mesh rather than many unused padding points: as many rings as fit.
  if (c.vertices > 0) c.rings = std::max(c.rings, (c.vertices - 2) / c.segments);
  try {
    fixtures::write_npz(argv[1], fixtures::encode_model(fixtures::cylinder_model(c), enc, float64),
                        compressed);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "body_fixture_writer: %s\n", e.what());
    return 1;
  }
  return 0;
}
