// The target solve (body/measurement_solve.hpp) on the built-in model: random reachable
// targets are reached within tolerance and near the start, absurd ones are reported with the
// nearest reachable values, bad values are refused, and solutions never leave the box.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <Eigen/SVD>

#include "body/measurement_solve.hpp"
#include "body/model_loader.hpp"
#include "npz_fixtures.hpp"

namespace {

std::shared_ptr<const body::Model> default_model() {
  static const auto model = std::make_shared<const body::Model>(body::load_default_model(10));
  return model;
}

body::MeasurementTarget target(const char* name, double value) {
  return {body::find_measurement(name), value};
}

}  // namespace

TEST_CASE("solve: random reachable targets are met near the start", "[solve]") {
  const auto model = default_model();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0.2, 0.8);
  const std::vector<std::vector<const char*>> sets = {{"height", "mass"},
                                                      {"height"},
                                                      {"mass", "inseam"},
                                                      {"shoulder_width", "arm_length", "bmi"},
                                                      {"height", "waist"}};
  for (std::size_t trial = 0; trial < sets.size(); ++trial) {
    CAPTURE(trial);
    Eigen::VectorXd goal(10);
    for (int k = 0; k < 10; ++k) goal[k] = uniform(rng);
    const body::Measurements m = body::measure(*model, body::betas_from_unit(goal));
    std::vector<body::MeasurementTarget> targets;
    for (const char* name : sets[trial]) {
      targets.push_back(target(name, m.*(body::find_measurement(name)->field)));
    }
    const body::MeasurementConstraints constraints(model, targets);
    const Eigen::VectorXd start = Eigen::VectorXd::Constant(10, 0.5);
    const auto result = constraints.solve(start);
    INFO(result.message);
    CHECK(result.reached);
    for (std::size_t i = 0; i < targets.size(); ++i) {
      // Solves aim for half the hold tolerance: 5 mm, 0.75 kg, 0.25 kg/m^2.
      CHECK(std::abs(result.values[i] - targets[i].value) <=
            0.5 * targets[i].kind->hold_tolerance + 1e-9);
    }
    // Nearest: no farther from the start than the body the targets were taken from.
    CHECK((result.x - start).norm() <= (goal - start).norm() + 1e-6);
    CHECK(result.x.minCoeff() >= 0.0);
    CHECK(result.x.maxCoeff() <= 1.0);
  }
}

TEST_CASE("solve: a curving measurement is reached where the pull towards the start stalls",
          "[solve]") {
  // The waist moves between slices as the body changes: from the mean body, minimum-norm
  // steps towards the start stopped at 107.4 cm of 108 (+1.8 SD) and 111.1 of 112; the
  // Gauss-Newton steps that take over there reach them.
  for (const double waist : {1.08, 1.12}) {
    CAPTURE(waist);
    const body::MeasurementConstraints constraints(default_model(), {target("waist", waist)});
    const auto result = constraints.solve(Eigen::VectorXd::Constant(10, 0.5));
    INFO(result.message);
    CHECK(result.reached);
    CHECK(std::abs(result.values[0] - waist) <=
          0.5 * body::find_measurement("waist")->hold_tolerance);
  }
}

TEST_CASE("solve: a start that already meets the targets costs one body and stays put", "[solve]") {
  // A plane's centre the optimizer already put on a hold is solved again for every plane:
  // no Jacobian (2K bodies, ~80 ms for a girth) when nothing has to move.
  Eigen::VectorXd x = Eigen::VectorXd::Constant(10, 0.45);
  x[3] = 0.6;
  const body::Measurements m = body::measure(*default_model(), body::betas_from_unit(x));
  for (const char* name : {"height", "chest"}) {
    CAPTURE(name);
    const double value = m.*(body::find_measurement(name)->field);
    const body::MeasurementConstraints constraints(default_model(), {target(name, value)});
    const auto result = constraints.solve(x);
    CHECK(result.reached);
    CHECK(result.evaluations == 1);
    CHECK((result.x - x).norm() == 0.0);
    REQUIRE(result.values.size() == 1);
    CHECK(result.values[0] == Approx(value).epsilon(1e-12));
    // Off the target it still takes its steps (and its Jacobian) and gets there.
    const body::MeasurementConstraints off(default_model(), {target(name, 1.03 * value)});
    const auto moved = off.solve(x);
    CHECK(moved.reached);
    CHECK(moved.evaluations > 2 * 10);
    CHECK(std::abs(moved.values[0] - 1.03 * value) <=
          0.5 * body::find_measurement(name)->hold_tolerance + 1e-9);
  }
}

TEST_CASE("solve: absurd targets are reported with the nearest reachable values", "[solve]") {
  const body::MeasurementConstraints constraints(default_model(), {target("height", 2.6)});
  const auto result = constraints.solve(Eigen::VectorXd::Constant(10, 0.5));
  CHECK_FALSE(result.reached);
  CHECK_THAT(result.message, Catch::Contains("out of reach") &&
                                 Catch::Contains("height 260.0 cm") &&
                                 Catch::Contains("nearest reachable"));
  REQUIRE(result.values.size() == 1);
  CHECK(result.values[0] < 2.6);
  CHECK(result.values[0] > 1.9);  // went as far as the box allows, not stuck at the start
  CHECK(result.x.minCoeff() >= 0.0);
  CHECK(result.x.maxCoeff() <= 1.0);
  // Each reachable alone, not together: a short body with the legs of a tall one.
  const body::MeasurementConstraints clash(default_model(),
                                           {target("height", 1.50), target("inseam", 0.95)});
  const auto clashed = clash.solve(Eigen::VectorXd::Constant(10, 0.5));
  INFO(clashed.message);
  CHECK_FALSE(clashed.reached);
}

TEST_CASE("solve: bad target values and names are refused with a clear message", "[solve]") {
  CHECK_THROWS_WITH(body::parse_target("height=nan"), Catch::Contains("not a number"));
  CHECK_THROWS_WITH(body::parse_target("height=-1.7"), Catch::Contains("out of range"));
  CHECK_THROWS_WITH(body::parse_target("mass=1e6"), Catch::Contains("out of range"));
  CHECK_THROWS_WITH(body::parse_target("weight=80"),
                    Catch::Contains("unknown measurement") && Catch::Contains("mass"));
  CHECK_THROWS_WITH(body::parse_target("height"), Catch::Contains("needs a value"));
  CHECK(std::isnan(body::parse_target("height", false).value));
  CHECK(body::parse_target("mass=90").value == Approx(90.0));
  CHECK_THROWS_AS(body::MeasurementConstraints(default_model(), {target("height", std::nan(""))}),
                  std::invalid_argument);
  CHECK_THROWS_WITH(
      body::MeasurementConstraints(default_model(), {target("height", 1.7), target("height", 1.8)}),
      Catch::Contains("twice"));
  // A cylinder fixture whose joints carry no SMPL names has no shoulders to measure.
  fixtures::Cylinder c;
  auto arrays = fixtures::cylinder_model(c);
  const auto path = fixtures::scratch_dir("solve-cyl") / "cyl.npz";
  fixtures::write_npz(path, fixtures::encode_model(arrays));
  auto cylinder = body::load_model(path, 10);
  cylinder.joint_names.assign(cylinder.joint_names.size(), "joint");
  CHECK_THROWS_WITH(body::MeasurementConstraints(std::make_shared<const body::Model>(cylinder),
                                                 {target("shoulder_width", 0.4)}),
                    Catch::Contains("cannot be measured"));
}

TEST_CASE(
    "solve: tangent directions keep the measurements to first order - projections stay "
    "in the box",
    "[solve]") {
  const auto model = default_model();
  const body::MeasurementConstraints constraints(
      model, {target("height", 1.65), target("mass", 90.0)}, 0.3);
  const Eigen::VectorXd c = Eigen::VectorXd::Constant(10, 0.5);
  const Eigen::MatrixXd dirs = Eigen::MatrixXd::Identity(10, 10);
  const Eigen::MatrixXd t = constraints.tangent(c, dirs);
  const Eigen::MatrixXd J = constraints.jacobian(c);
  CHECK((J * t).cwiseAbs().maxCoeff() <= 1e-9 * (1.0 + J.cwiseAbs().maxCoeff()));
  // Not projected away: two held quantities leave 8 free directions. (Not "the first
  // coordinate stays free": the built-in models' first component carries stature alone, so
  // a height hold takes it away entirely.)
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(t);
  CHECK((svd.singularValues().array() > 0.5).count() == 8);
  // Corners and faces of the box: the projection never leaves it.
  for (const double corner : {0.0, 1.0}) {
    Eigen::VectorXd x = Eigen::VectorXd::Constant(10, corner);
    x[0] = 1.0 - corner;
    const auto r = constraints.solve(x);
    INFO(r.message);
    CHECK(r.x.minCoeff() >= 0.0);
    CHECK(r.x.maxCoeff() <= 1.0);
  }
}

TEST_CASE("solve: holds on an SMPL-layout model (24 named joints, its own mesh)", "[solve]") {
  // The cylinder fixture has SMPL's file layout and skeleton: component 0 widens it, component
  // 1 stretches it (height 1.7 (1 + b1)), the others are small ripples.
  fixtures::Cylinder c;
  c.base_y = 0.0;
  const auto path = fixtures::scratch_dir("solve-smpl-layout") / "cyl.npz";
  fixtures::write_npz(path, fixtures::encode_model(fixtures::cylinder_model(c)));
  const auto model = std::make_shared<const body::Model>(body::load_model(path, 10));
  REQUIRE(model->joint_names.at(16) == "left_shoulder");
  const body::MeasurementConstraints hold(model, {target("height", 1.7), target("mass", 120.0)},
                                          0.3);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(10, 0.5);
  x[0] = 0.6;   // wider
  x[1] = 0.55;  // taller
  x[4] = 0.8;
  const auto r = hold.solve(x);
  INFO(r.message);
  REQUIRE(r.reached);
  CHECK(std::abs(r.values[0] - 1.7) <= 0.003);
  CHECK(std::abs(r.values[1] - 120.0) <= 0.45);
  CHECK(r.x[1] == Approx(0.5).margin(0.01));  // the stretch undone
  CHECK(std::abs(r.x[4] - 0.8) < 0.05);       // a ripple nobody held stays where it was
  // First order: the stretch direction is (almost) all held; a ripple is (almost) free.
  const Eigen::MatrixXd t = hold.tangent(r.x, Eigen::MatrixXd::Identity(10, 10));
  CHECK(t.col(1).norm() < 0.2);
  CHECK(t.col(4).norm() > 0.9);
}

TEST_CASE("solve: height, mass and BMI that no body has together are refused up front", "[solve]") {
  // 120 kg at 1.90 m is a BMI of 33.2: the solver used to name the unchanged start body as
  // "nearest reachable".
  CHECK_THROWS_WITH(
      body::MeasurementConstraints(
          default_model(), {target("bmi", 10.0), target("mass", 120.0), target("height", 1.9)}),
      Catch::Contains("make a BMI of 33.2, not 10.0"));
  CHECK_THROWS_WITH(
      body::MeasurementConstraints(
          default_model(), {target("height", 1.9), target("mass", 40.0), target("bmi", 40.0)}),
      Catch::Contains("no body has all three"));
  // Values that agree (within the tolerances) are accepted: 80 kg at 1.80 m is BMI 24.7.
  CHECK_NOTHROW(body::MeasurementConstraints(
      default_model(), {target("height", 1.80), target("mass", 80.0), target("bmi", 24.9)}));
}

TEST_CASE("solve: targets keep what is held, and a target against a hold is refused", "[solve]") {
  const auto merged = body::targets_with_holds({target("mass", 80.0)}, {target("height", 1.80)});
  REQUIRE(merged.size() == 2);
  CHECK(std::string(merged[1].kind->name) == "height");
  // The same value (within the hold tolerance) is one target, not "given twice".
  CHECK(body::targets_with_holds({target("height", 1.805)}, {target("height", 1.80)}).size() == 1);
  // A bare hold (no value yet) adds nothing.
  CHECK(body::targets_with_holds({target("mass", 80.0)}, {target("height", std::nan(""))}).size() ==
        1);
  CHECK_THROWS_WITH(body::targets_with_holds({target("height", 1.70)}, {target("height", 1.80)}),
                    Catch::Contains("target height 170.0 cm contradicts the hold on height at "
                                    "180.0 cm"));
}
