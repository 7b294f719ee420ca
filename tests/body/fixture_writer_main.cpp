// Writes the cylinder fixture model as .npz for the CLI tests (no SMPL data needed).
#include <cstdio>
#include <exception>
#include <string>

#include "npz_fixtures.hpp"

int main(int argc, char** argv) {
  const std::string family = argc == 3 ? argv[2] : "plain";
  if (argc < 2 || argc > 3 ||
      (family != "plain" && family != "smpl" && family != "smplh" && family != "smplx" &&
       family != "star")) {
    std::fprintf(stderr, "usage: body_fixture_writer OUT.npz [plain|smpl|smplh|smplx|star]\n");
    return 2;
  }
  try {
    // Look-alikes of the SMPL family's layouts (never their data): joint counts, SMPL-X's
    // 10 shape + 10 expression columns, UVs, pose correctives in SMPL's or STAR's layout.
    fixtures::Cylinder c;
    c.base_y = -0.9;
    if (family == "smpl") c.pose_columns = 9 * 23;
    if (family == "star") c.pose_columns = 93;
    if (family == "smplh") c.joints = 52, c.components = 16, c.uvs = true, c.pose_columns = 9 * 51;
    if (family == "smplx") c.joints = 55, c.components = 20, c.uvs = true, c.pose_columns = 9 * 54;
    fixtures::write_npz(argv[1], fixtures::encode_model(fixtures::cylinder_model(c)), true);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "body_fixture_writer: %s\n", e.what());
    return 1;
  }
  return 0;
}
