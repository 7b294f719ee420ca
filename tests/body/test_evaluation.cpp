// betas -> vertices, joints, normals against a hand-computed case and the cylinder fixture.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "body/mesh_normals.hpp"
#include "body/model_loader.hpp"
#include "npz_fixtures.hpp"

namespace {

// One triangle, two components, two joints; values chosen to be checked by hand.
body::Model triangle_model() {
  body::Model m;
  m.name = "triangle";
  m.v_template.resize(3, 3);
  m.v_template << 0, 0, 0,  //
      1, 0, 0,              //
      0, 1, 0;
  m.shapedirs = Eigen::MatrixXf::Zero(9, 2);
  m.shapedirs(3 * 1 + 0, 0) = 1.0f;  // component 0 moves vertex 1 along +x
  m.shapedirs(3 * 2 + 1, 1) = 0.5f;  // component 1 moves vertex 2 along +y by 0.5 per unit
  m.shapedirs(3 * 0 + 2, 1) = 1.0f;  // ... and vertex 0 along +z
  m.faces.resize(1, 3);
  m.faces << 0, 1, 2;
  m.j_regressor.resize(2, 3);
  m.j_regressor << 1.f / 3, 1.f / 3, 1.f / 3,  //
      1, 0, 0;
  m.weights = Eigen::MatrixXf::Constant(3, 2, 0.5f);
  m.parents = {-1, 0};
  m.joint_names = {"root", "tip"};
  m.total_components = 2;
  return m;
}

}  // namespace

TEST_CASE("evaluate: hand-computed triangle", "[evaluation]") {
  for (bool prepared : {false, true}) {
    body::Model m = triangle_model();
    if (prepared) m.prepare();
    Eigen::VectorXf betas(2);
    betas << 0.5f, -2.0f;
    const auto mesh = body::evaluate(m, betas);
    // v0 = (0, 0, 0) + (-2) * (0, 0, 1)   = (0, 0, -2)
    // v1 = (1, 0, 0) + 0.5 * (1, 0, 0)    = (1.5, 0, 0)
    // v2 = (0, 1, 0) + (-2) * (0, 0.5, 0) = (0, 0, 0)
    body::Vertices expected(3, 3);
    expected << 0, 0, -2, 1.5, 0, 0, 0, 0, 0;
    CHECK(mesh.vertices.isApprox(expected));
    // joints: mean of the three = (0.5, 0, -2/3); second = v0.
    CHECK(mesh.joints(0, 0) == Approx(0.5));
    CHECK(mesh.joints(0, 1) == Approx(0.0).margin(1e-7));
    CHECK(mesh.joints(0, 2) == Approx(-2.0 / 3.0));
    CHECK(mesh.joints.row(1).isApprox(expected.row(0)));
    // (v1 - v0) x (v2 - v0) = (1.5, 0, 2) x (0, 0, 2) = (0, -3, 0) -> (0, -1, 0) everywhere.
    for (int v = 0; v < 3; ++v) {
      CHECK(mesh.normals(v, 0) == Approx(0.0).margin(1e-7));
      CHECK(mesh.normals(v, 1) == Approx(-1.0));
      CHECK(mesh.normals(v, 2) == Approx(0.0).margin(1e-7));
    }
  }
}

TEST_CASE("evaluate: short betas are padded with zeros, bad betas are rejected", "[evaluation]") {
  const body::Model m = triangle_model();
  Eigen::VectorXf one(1);
  one << 2.0f;
  const auto mesh = body::evaluate(m, one);
  CHECK(mesh.vertices(1, 0) == Approx(3.0));
  CHECK(mesh.vertices(0, 2) == Approx(0.0));
  CHECK(body::evaluate(m, Eigen::VectorXf()).vertices.isApprox(m.v_template));
  CHECK_THROWS_AS(body::evaluate(m, Eigen::VectorXf::Zero(3)), std::invalid_argument);
  Eigen::VectorXf nan(2);
  nan << 0.0f, std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_WITH(body::evaluate(m, nan), Catch::Contains("beta 1 is not finite"));
}

TEST_CASE("evaluate: the cylinder from a file", "[evaluation]") {
  const auto path = fixtures::scratch_dir("eval") / "cyl.npz";
  fixtures::Cylinder c;
  fixtures::write_npz(path, fixtures::encode_model(fixtures::cylinder_model(c)));
  const auto m = body::load_model(path, 2);
  Eigen::VectorXf betas(2);
  betas << 0.2f, 0.1f;  // radius x 1.2, height x 1.1
  auto mesh = body::evaluate(m, betas);
  for (int v = 0; v < c.segments * c.rings; v += 37) {
    const double r = std::hypot(mesh.vertices(v, 0), mesh.vertices(v, 2));
    CHECK(r == Approx(c.radius * 1.2).epsilon(1e-5));
    // Side normals point outward, horizontally (the ring's own ring-neighbours are level);
    // skip the cap rings, whose normals lean up or down.
    const int ring = v / c.segments;
    if (ring > 0 && ring + 1 < c.rings) {
      CHECK(mesh.normals(v, 0) * mesh.vertices(v, 0) + mesh.normals(v, 2) * mesh.vertices(v, 2) ==
            Approx(r).epsilon(1e-4));
      CHECK(mesh.normals(v, 1) == Approx(0.0).margin(1e-5));
    }
  }
  CHECK(mesh.vertices.col(1).maxCoeff() - mesh.vertices.col(1).minCoeff() ==
        Approx(c.height * 1.1).epsilon(1e-5));
  // Joint 0 regresses ring 0 (the bottom), joint 23 the top ring.
  CHECK(mesh.joints(0, 1) == Approx(c.base_y).margin(1e-5));
  CHECK(mesh.joints(23, 1) == Approx(c.base_y + 1.1 * c.height).epsilon(1e-5));
  // The fast joint path (precomputed J_regressor * shapedirs) equals J_regressor * vertices.
  const body::Vertices direct = m.j_regressor * mesh.vertices;
  CHECK(mesh.joints.isApprox(direct, 1e-5f));

  const float offset = body::place_on_ground(mesh);
  CHECK(offset == Approx(-c.base_y));
  CHECK(mesh.vertices.col(1).minCoeff() == Approx(0.0).margin(1e-6));
  CHECK(mesh.joints(0, 1) == Approx(0.0).margin(1e-5));
}

TEST_CASE("normals: unused vertices get a unit normal", "[evaluation]") {
  body::Vertices v(4, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5;
  body::Faces f(1, 3);
  f << 0, 1, 2;
  body::Vertices n;
  body::compute_vertex_normals(v, f, n);
  CHECK(n.row(0).isApprox(Eigen::RowVector3f(0, 0, 1)));
  CHECK(n.row(3).norm() == Approx(1.0));
}

TEST_CASE("unit box mapping: beta = 6x - 3 and back", "[evaluation]") {
  Eigen::VectorXd x(3);
  x << 0.0, 0.5, 1.0;
  const Eigen::VectorXf b = body::betas_from_unit(x);
  CHECK(b[0] == Approx(-3.0));
  CHECK(b[1] == Approx(0.0));
  CHECK(b[2] == Approx(3.0));
  CHECK(body::unit_from_betas(b).isApprox(x));
}

TEST_CASE("evaluate_batch equals evaluate body by body", "[evaluation]") {
  const auto path = fixtures::scratch_dir("eval-batch") / "cyl.npz";
  fixtures::write_npz(path, fixtures::encode_model(fixtures::cylinder_model()));
  for (bool prepared : {true, false}) {
    auto m = body::load_model(path, 10);
    if (!prepared) m.joint_shapedirs.resize(0, 0);  // the J_regressor * vertices path
    std::vector<Eigen::VectorXf> betas;
    for (int i = 0; i < 9; ++i) {
      Eigen::VectorXf b(1 + i);  // different lengths, padded with zeros
      for (int k = 0; k <= i; ++k) b[k] = 0.1f * static_cast<float>(k - i) + 0.05f;
      betas.push_back(b);
    }
    const auto batch = body::evaluate_batch(m, betas);
    REQUIRE(batch.size() == 9);
    for (std::size_t i = 0; i < 9; ++i) {
      const auto one = body::evaluate(m, betas[i]);
      CHECK(batch[i].vertices.isApprox(one.vertices, 1e-6f));
      CHECK(batch[i].joints.isApprox(one.joints, 1e-5f));
      CHECK(batch[i].normals.isApprox(one.normals, 1e-5f));
    }
    betas.push_back(Eigen::VectorXf::Zero(11));
    CHECK_THROWS_AS(body::evaluate_batch(m, betas), std::invalid_argument);
  }
}

TEST_CASE("evaluate_batch with many components: plane (rank 3) and random betas", "[evaluation]") {
  fixtures::Cylinder c;
  c.components = 40;  // above the batch threshold, so the matrix-product path runs
  c.segments = 16;
  c.rings = 12;
  const auto path = fixtures::scratch_dir("eval-batch-many") / "cyl40.npz";
  fixtures::write_npz(path, fixtures::encode_model(fixtures::cylinder_model(c)));
  const auto m = body::load_model(path, 0);
  REQUIRE(m.component_count() == 40);
  Eigen::VectorXf centre(40), u(40), v(40);
  for (int k = 0; k < 40; ++k) {
    centre[k] = 0.02f * static_cast<float>(k % 7) - 0.05f;
    u[k] = 0.03f * std::sin(static_cast<float>(k));
    v[k] = 0.03f * std::cos(static_cast<float>(3 * k));
  }
  for (bool plane : {true, false}) {
    std::vector<Eigen::VectorXf> betas;
    for (int cell = 0; cell < 9; ++cell) {
      if (plane) {
        betas.push_back(centre + static_cast<float>(cell % 3 - 1) * u +
                        static_cast<float>(cell / 3 - 1) * v);
      } else {
        Eigen::VectorXf b(40);
        for (int k = 0; k < 40; ++k) b[k] = 0.1f * std::sin(static_cast<float>(7 * cell + k));
        betas.push_back(b);
      }
    }
    const auto batch = body::evaluate_batch(m, betas);
    for (std::size_t i = 0; i < 9; ++i) {
      const auto one = body::evaluate(m, betas[i]);
      CHECK((batch[i].vertices - one.vertices).cwiseAbs().maxCoeff() < 1e-5f);
      CHECK((batch[i].joints - one.joints).cwiseAbs().maxCoeff() < 1e-5f);
    }
  }
}
