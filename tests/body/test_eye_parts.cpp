// The eyes' whites and irises (body/eye_parts.hpp) on the built-in model and on a model
// without eye joints.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "body/eye_parts.hpp"
#include "body/model_loader.hpp"

TEST_CASE("eye parts: the built-in eyeballs are white with a forward-facing iris", "[eyes]") {
  const body::Model model = body::load_default_model(10);
  const std::vector<body::EyePart> parts = body::eye_parts(model);
  REQUIRE(parts.size() == static_cast<std::size_t>(model.vertex_count()));
  for (const char* name : {"left_eye_smplhf", "right_eye_smplhf"}) {
    INFO(name);
    const auto it = std::find(model.joint_names.begin(), model.joint_names.end(), name);
    REQUIRE(it != model.joint_names.end());
    const auto e = static_cast<Eigen::Index>(it - model.joint_names.begin());
    const Eigen::RowVector3f centre = model.j_regressor.row(e) * model.v_template;
    int white = 0, iris = 0;
    float iris_z = 1e9f;
    for (Eigen::Index v = 0; v < model.vertex_count(); ++v) {
      const body::EyePart p = parts[static_cast<std::size_t>(v)];
      if (p == body::EyePart::kSkin) continue;
      // Only the eyeball: every eye vertex is near this eye or the other one, and moves with
      // its eye joint alone.
      const float d = (model.v_template.row(v) - centre).norm();
      if (d > 0.03f) continue;  // the other eye
      CHECK(d < 0.02f);
      CHECK(model.weights(v, e) >= 0.99f);
      const float z = model.v_template(v, 2) - centre.z();
      if (p == body::EyePart::kIris) {
        ++iris;
        iris_z = std::min(iris_z, z);
      } else {
        ++white;
      }
    }
    CHECK(iris > 0);
    CHECK(white > 0);
    // The iris is the front of the eyeball: every iris vertex lies forward of its centre.
    CHECK(iris_z > 0.0f);
  }
}

TEST_CASE("eye parts: a model without eye joints is skin everywhere", "[eyes]") {
  body::Model model = body::load_default_model(10);
  for (std::string& n : model.joint_names)
    if (n.find("eye") != std::string::npos) n = "renamed";
  const std::vector<body::EyePart> parts = body::eye_parts(model);
  CHECK(std::all_of(parts.begin(), parts.end(),
                    [](body::EyePart p) { return p == body::EyePart::kSkin; }));
}
