// Writes the cylinder fixture model as .npz for the CLI test (no SMPL data needed).
#include <cstdio>
#include <exception>
#include <string>

#include "npz_fixtures.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: body_fixture_writer OUT.npz\n");
    return 2;
  }
  try {
    fixtures::Cylinder c;
    c.base_y = -0.9;
    fixtures::write_npz(argv[1], fixtures::encode_model(fixtures::cylinder_model(c)), true);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "body_fixture_writer: %s\n", e.what());
    return 1;
  }
  return 0;
}
