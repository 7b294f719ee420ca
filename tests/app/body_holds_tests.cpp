// Holds on the built-in body model through the session, as the window and the body benchmark
// use them (spaces/body_holds.hpp, sps/held_search.hpp): the first plane with a height hold
// shows nine bodies that really differ, the optimizer's planes lie on the held surface, and
// the next plane prepared on the worker is the one the window would have made.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <random>

#include "app/session.hpp"
#include "app/worker.hpp"
#include "bench/simulated_person.hpp"
#include "body/measurement_solve.hpp"
#include "body/measurements.hpp"
#include "body/model_loader.hpp"
#include "body/shape_distance.hpp"
#include "spaces/body_holds.hpp"

namespace {

std::shared_ptr<const body::Model> default_model() {
  static const auto model = std::make_shared<const body::Model>(body::load_default_model(10));
  return model;
}

double height_m(const Eigen::VectorXd& x) {
  return body::measure(*default_model(), body::betas_from_unit(x)).height;
}

struct HeldSession {
  body::ShapeDistance distance{*default_model()};
  app::Session session;
  app::PairwiseDistance pairwise;
  explicit HeldSession(double height) : session(settings()) {
    session.set_constraint_projector(spaces::make_body_holds(
        default_model(), {"height=" + std::to_string(height)}, session.current_best()));
    session.set_perceptual_scale(distance.direction_rms_mm());
    pairwise = [this](const std::vector<Eigen::VectorXd>& xs) {
      return distance.pairwise_max_mm(xs);
    };
    session.set_perceptual_distance(pairwise);
  }
  static app::SessionSettings settings() {
    app::SessionSettings s;
    s.components = 10;
    s.seed = 5;
    return s;
  }
};

}  // namespace

TEST_CASE("height held: the first plane shows nine bodies of that height that clearly differ",
          "[holds][body]") {
  for (double height : {1.62, 1.80}) {
    CAPTURE(height);
    HeldSession held(height);
    const auto cells = held.session.cells();
    REQUIRE(cells.size() == 9u);
    std::vector<Eigen::VectorXd> xs;
    for (const auto& c : cells) {
      CHECK(std::abs(height_m(c.x) - height) <= 0.01);
      CHECK(c.x.minCoeff() >= 0.0);
      CHECK(c.x.maxCoeff() <= 1.0);
      xs.push_back(c.x);
    }
    // Pairwise at least twice the session's "distinct" threshold (10 mm, largest vertex
    // distance): the plane spans the most visible directions the hold leaves.
    const Eigen::MatrixXd d = held.distance.pairwise_max_mm(xs);
    for (Eigen::Index i = 0; i < d.rows(); ++i) {
      for (Eigen::Index j = i + 1; j < d.cols(); ++j) CHECK(d(i, j) > 20.0);
    }
    // The optimizer's own plane is the held one (centre on the surface, directions that
    // keep the height), not a plane projected afterwards.
    const sps::Plane& p = held.session.search().current_plane();
    CHECK(std::abs(height_m(p.c) - height) <= 0.003 + 1e-6);
    CHECK(std::abs(height_m(p.c + p.u) - height) <= 0.005);
    CHECK(std::abs(height_m(p.c + p.v) - height) <= 0.005);
  }
}

TEST_CASE(
    "height held: every plane's centre lies on the held surface and the prepared plane "
    "matches the window's",
    "[holds][body]") {
  HeldSession held(1.74);
  const Eigen::VectorXf target = Eigen::VectorXf::Constant(10, 0.4f);
  const bench::TargetDistance to_target = [&](const std::vector<Eigen::VectorXd>& xs) {
    return held.distance.rms_to_betas_mm(xs, target);
  };
  std::mt19937_64 rng(3);
  for (int plane = 0; plane < 3; ++plane) {
    CAPTURE(plane);
    // Zoom decisions are taken on the held plane's own points; the grids shown (projected)
    // still hold no look-alikes.
    const auto outcome = bench::play_plane_jnd(held.session, to_target, held.pairwise, 5.0, rng);
    CHECK(outcome.grids >= 2);
    CHECK(outcome.look_alike_grids == 0);
    // The search's centre and the plane shown: on the held height (the solve aims for 30% of
    // the 1 cm tolerance).
    CHECK(std::abs(height_m(held.session.search().current_plane().c) - 1.74) <= 0.003 + 1e-6);
    CHECK(std::abs(height_m(held.session.shown_plane().c) - 1.74) <= 0.003 + 1e-6);
    // The plane the worker prepared (play_plane_jnd installs it) is the one the window would
    // make itself: the same cells.
    app::Session fresh = app::Session::from_json(held.session.to_json());
    fresh.set_constraint_projector(
        spaces::make_body_holds(default_model(), {"height=1.74"}, fresh.current_best()));
    fresh.set_perceptual_scale(held.distance.direction_rms_mm());
    const auto a = held.session.cells_at(held.session.views().front());
    const auto b = fresh.cells_at(held.session.views().front());
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) CHECK((a[i].x - b[i].x).norm() < 1e-9);
  }
}

TEST_CASE("a hold set before the first click re-chooses the first plane, after it keeps it",
          "[holds][body]") {
  const body::ShapeDistance distance(*default_model());
  app::Session fresh(HeldSession::settings());
  fresh.set_perceptual_scale(distance.direction_rms_mm());
  const auto holds = [&](const app::Session& s) {
    return spaces::make_body_holds(default_model(), {"height=1.70"}, s.current_best());
  };
  fresh.set_constraint_projector(holds(fresh));
  CHECK(std::abs(height_m(fresh.search().current_plane().c) - 1.70) <= 0.003 + 1e-6);
  CHECK((fresh.start_point() - fresh.search().current_plane().c).norm() == 0.0);

  app::Session clicked(HeldSession::settings());
  clicked.set_perceptual_scale(distance.direction_rms_mm());
  const sps::Plane before = clicked.search().current_plane();
  REQUIRE(clicked.click({0, 0}) == app::ClickResult::kZoomed);
  clicked.set_constraint_projector(holds(clicked));
  // The plane clicked on stays (shown projected onto the hold); the next one is held.
  CHECK(clicked.search().current_plane().c == before.c);
  CHECK(clicked.search().current_plane().u == before.u);
  for (const auto& cell : clicked.cells()) CHECK(std::abs(height_m(cell.x) - 1.70) <= 0.01);
}
