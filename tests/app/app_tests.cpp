// Session logic without any window: clicks -> chosen point, extra comparisons, undo, start
// over, autosave round trip, corrupt files set aside and reported.
#include <catch2/catch.hpp>

#include "common/first_difference.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>
#include "app/session.hpp"
#include "app/session_store.hpp"
#include "app/session_writer.hpp"
#include "app/space_catalogue.hpp"

#include "app/worker.hpp"
#include "bench/window_timing.hpp"
#include "session_fixtures.hpp"
#include "sps/target_estimate.hpp"

namespace fs = std::filesystem;

namespace {

app::SessionSettings small_settings() {
  app::SessionSettings s;
  s.components = 4;
  s.grid_size = 3;
  s.zoom_levels = 4;
  s.seed = 7;
  return s;
}

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() /
           ("sg_app_tests_" +
            std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Completes the current plane by clicking `cells`, running submit() synchronously.
void finish_plane(app::Session& session, const std::vector<sps::GridCell>& cells) {
  for (size_t i = 0; i < cells.size(); ++i) {
    const auto r = session.click(cells[i]);
    REQUIRE(r ==
            (i + 1 == cells.size() ? app::ClickResult::kPlaneFinished : app::ClickResult::kZoomed));
  }
  const auto sub = session.submission();
  sps::PlaneSearch next = session.search();
  next.submit(sub.chosen, sub.extra_comparisons);
  session.finish_plane(std::move(next));
}

}  // namespace

TEST_CASE("clicks zoom in and the last click is the chosen point", "[app]") {
  app::Session session(small_settings());
  CHECK(session.cells().size() == 9u);
  const auto plane = session.search().current_plane();
  const std::vector<sps::GridCell> path{{0, 0}, {2, 1}, {1, 1}, {2, 2}};
  for (int i = 0; i < 3; ++i)
    CHECK(session.click(path[static_cast<size_t>(i)]) == app::ClickResult::kZoomed);
  CHECK_FALSE(session.submission_pending());
  CHECK(session.view().spacing == Approx(0.125));  // 1, halved three times
  for (const auto& p : session.cells()) CHECK_FALSE(p.clamped);
  CHECK(session.click(path[3]) == app::ClickResult::kPlaneFinished);
  CHECK(session.submission_pending());
  CHECK(session.click({0, 0}) == app::ClickResult::kIgnored);

  const auto sub = session.submission();
  // The last click's cell as shown on the last grid (zoomed views stay inside the plane's
  // square, so after the corner click the grids are not centred on the clicked cell).
  const auto& views = session.views();
  REQUIRE(views.size() == 5u);
  const auto expected = sps::grid_points(plane, 3, views[3])[8].x;
  CHECK((sub.chosen - expected).norm() < 1e-12);
  CHECK((session.current_best() - expected).norm() < 1e-12);
  // One extra comparison per zoom level, the clicked cell first.
  REQUIRE(sub.extra_comparisons.size() == 4u);
  const auto level0 = sps::grid_points(plane, 3, std::vector<sps::GridCell>{});
  CHECK((sub.extra_comparisons[0][0] - level0[0].x).norm() < 1e-12);
  CHECK(sub.extra_comparisons[0].size() >= 2u);
  for (const auto& comparison : sub.extra_comparisons) {
    for (const auto& x : comparison) {
      CHECK(x.minCoeff() >= 0.0);
      CHECK(x.maxCoeff() <= 1.0);
    }
  }
}

TEST_CASE("out-of-grid clicks are ignored", "[app]") {
  app::Session session(small_settings());
  CHECK(session.click({3, 0}) == app::ClickResult::kIgnored);
  CHECK(session.click({0, -1}) == app::ClickResult::kIgnored);
  CHECK(session.clicks_on_plane() == 0);
}

TEST_CASE("a finished plane goes into the history and a new plane starts", "[app]") {
  app::Session session(small_settings());
  finish_plane(session, {{1, 1}, {0, 0}, {2, 2}, {1, 0}});
  CHECK(session.planes_done() == 1);
  CHECK(session.clicks_on_plane() == 0);
  CHECK(session.search().iteration() == 1);
  REQUIRE(session.history().size() == 1u);
  CHECK(session.history()[0].path.size() == 4u);
  CHECK((session.current_best() - session.search().x_plus()).norm() < 1e-12);
}

TEST_CASE("undo click, undo across a plane, undo plane, start over", "[app]") {
  app::Session session(small_settings());
  const auto first_plane = session.search().current_plane();
  CHECK_FALSE(session.undo_click());
  CHECK_FALSE(session.undo_plane());

  session.click({0, 0});
  session.click({1, 2});
  CHECK(session.undo_click());
  CHECK(session.clicks_on_plane() == 1);
  CHECK(session.undo_plane());
  CHECK(session.clicks_on_plane() == 0);

  finish_plane(session, {{2, 0}, {1, 1}, {0, 1}, {2, 2}});
  // Undoing a click right after a finished plane reopens it with its first three clicks.
  CHECK(session.undo_click());
  CHECK(session.planes_done() == 0);
  CHECK(session.clicks_on_plane() == 3);
  CHECK((session.search().current_plane().c - first_plane.c).norm() < 1e-12);
  CHECK((session.search().current_plane().u - first_plane.u).norm() < 1e-12);
  session.click({2, 2});
  const auto sub = session.submission();
  sps::PlaneSearch next = session.search();
  next.submit(sub.chosen, sub.extra_comparisons);
  session.finish_plane(std::move(next));
  CHECK(session.planes_done() == 1);

  CHECK(session.undo_plane());
  CHECK(session.planes_done() == 0);
  CHECK(session.clicks_on_plane() == 0);

  finish_plane(session, {{2, 0}, {1, 1}, {0, 1}, {2, 2}});
  session.start_over();
  CHECK(session.planes_done() == 0);
  CHECK(session.search().iteration() == 0);
  CHECK(session.clicks_on_plane() == 0);
}

TEST_CASE("session JSON round trip reproduces state and the next plane", "[app]") {
  app::Session session(small_settings());
  finish_plane(session, {{0, 2}, {1, 1}, {2, 1}, {0, 0}});
  session.click({2, 2});
  session.click({1, 0});
  const std::string text = session.to_json();
  const app::Session back = app::Session::from_json(text);
  CHECK(test_support::first_difference(back.to_json(), text) == "");
  CHECK(back.planes_done() == 1);
  CHECK(back.clicks_on_plane() == 2);
  CHECK((back.current_best() - session.current_best()).norm() < 1e-12);
  CHECK((back.search().current_plane().u - session.search().current_plane().u).norm() < 1e-12);
}

TEST_CASE("a session killed while the optimizer ran resumes with the choice pending", "[app]") {
  app::Session session(small_settings());
  for (const auto& c : std::vector<sps::GridCell>{{0, 1}, {2, 2}, {1, 0}, {0, 0}}) session.click(c);
  REQUIRE(session.submission_pending());
  const app::Session back = app::Session::from_json(session.to_json());
  CHECK(back.submission_pending());
  const auto a = session.submission();
  const auto b = back.submission();
  CHECK((a.chosen - b.chosen).norm() < 1e-12);
  CHECK(a.extra_comparisons.size() == b.extra_comparisons.size());
}

TEST_CASE("autosave writes atomically and loads back", "[app]") {
  TempDir dir;
  const fs::path file = dir.path / "nested" / "session.json";
  app::Session session(small_settings());
  session.click({1, 2});
  app::save_session(session, file);
  CHECK(fs::exists(file));
  // No temporary files are left behind.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(file.parent_path())) {
    (void)e;
    ++entries;
  }
  CHECK(entries == 1);
  const auto loaded = app::load_session(file);
  CHECK(loaded.problem.empty());
  REQUIRE(loaded.session.has_value());
  CHECK(loaded.session->clicks_on_plane() == 1);

  SECTION("a missing file is no problem and no session") {
    const auto none = app::load_session(dir.path / "nothing.json");
    CHECK_FALSE(none.session.has_value());
    CHECK(none.problem.empty());
  }
  SECTION("saving into an unwritable place reports the file") {
    CHECK_THROWS_WITH(app::save_session(session, "/proc/version/x/session.json"),
                      Catch::Contains("/proc/version/x/session.json"));
  }
}

TEST_CASE("a corrupt session file is set aside and reported, never overwritten", "[app]") {
  TempDir dir;
  const fs::path file = dir.path / "session.json";
  app::Session session(small_settings());
  const std::string good = session.to_json();

  const std::vector<std::string> corrupt{"", "{not json", good.substr(0, good.size() / 2),
                                         "{\"format\": \"something else\"}", [&] {
                                           std::string s = good;
                                           const auto at = s.find("\"grid_size\": 3");
                                           REQUIRE(at != std::string::npos);
                                           s.replace(at, 14, "\"grid_size\": 4");
                                           return s;
                                         }()};
  for (const auto& text : corrupt) {
    {
      std::ofstream out(file, std::ios::binary);
      out << text;
    }
    const auto result = app::load_session(file);
    CHECK_FALSE(result.session.has_value());
    CHECK_THAT(result.problem, Catch::Contains("corrupt") && Catch::Contains(file.string()));
    CHECK_FALSE(fs::exists(file));
    REQUIRE(fs::exists(result.set_aside));
    CHECK(test_support::first_difference(read_text(result.set_aside), text) == "");  // kept
    fs::remove(result.set_aside);
  }
}

TEST_CASE("the worker computes the next plane off the calling thread", "[app]") {
  app::Session session(small_settings());
  for (const auto& c : std::vector<sps::GridCell>{{0, 0}, {1, 1}, {1, 1}, {2, 1}}) session.click(c);
  app::SubmitWorker worker;
  CHECK(worker.start(session.search(), session.submission(), 3));
  CHECK_FALSE(worker.start(session.search(), session.submission(), 4));  // one at a time
  std::optional<app::SubmitWorker::Result> result;
  for (int i = 0; i < 600 && !result; ++i) {
    result = worker.poll();
    if (!result) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  REQUIRE(result.has_value());
  CHECK(result->generation == 3);
  REQUIRE(result->search.has_value());
  CHECK(result->search->iteration() == 1);
  CHECK(session.search().iteration() == 0);  // the session's own search is untouched
  session.finish_plane(std::move(*result->search));
  CHECK(session.planes_done() == 1);
  CHECK_FALSE(worker.busy());
}

TEST_CASE("the good session fixture loads, undoes to every history entry and round-trips",
          "[app][session-file]") {
  app::Session session = app::Session::from_json(test_fixtures::good_session_json());
  CHECK(session.planes_done() == 3);
  CHECK(session.clicks_on_plane() == 1);
  // The fixture's window is smaller than its data (what defect 1 needed).
  CHECK(session.search().data().point_count() > session.search().options().model.max_points);
  const std::string text = session.to_json();
  CHECK(test_support::first_difference(app::Session::from_json(text).to_json(), text) == "");
  while (session.undo_click()) {
    const app::Session again = app::Session::from_json(session.to_json());
    CHECK(again.planes_done() == session.planes_done());
  }
  CHECK(session.planes_done() == 0);
}

TEST_CASE("every broken session fixture is refused with a message naming the problem",
          "[app][session-file]") {
  const auto fixtures = test_fixtures::broken_session_fixtures();
  CHECK(fixtures.size() >= 20);
  for (const auto& f : fixtures) {
    INFO("fixture " << f.name);
    CHECK_THROWS_WITH(app::Session::from_json(f.text), Catch::Contains(f.expected));
  }
}

TEST_CASE("a corrupt session is set aside by load_session and the window starts fresh",
          "[app][session-file]") {
  TempDir dir;
  const fs::path file = dir.path / "session.json";
  for (const auto& f : test_fixtures::broken_session_fixtures()) {
    INFO("fixture " << f.name);
    std::ofstream(file, std::ios::binary) << f.text;
    const auto result = app::load_session(file);
    CHECK_FALSE(result.session.has_value());
    CHECK_THAT(result.problem, Catch::Contains(f.expected));
    CHECK(fs::exists(result.set_aside));
  }
}

TEST_CASE("set-aside sessions rotate: five .previous copies are kept, the oldest dropped",
          "[app][session-file]") {
  TempDir dir;
  const fs::path file = dir.path / "session.json";
  for (int i = 1; i <= 7; ++i) {
    std::ofstream(file, std::ios::binary) << "session " << i;
    const fs::path aside = app::set_aside_session(file);
    CHECK(aside == fs::path(file.string() + ".previous"));
    CHECK_FALSE(fs::exists(file));
  }
  CHECK(read_text(file.string() + ".previous") == "session 7");
  for (int k = 1; k < app::kKeptPreviousSessions; ++k) {
    CHECK(read_text(file.string() + ".previous." + std::to_string(k)) ==
          "session " + std::to_string(7 - k));
  }
  CHECK_FALSE(
      fs::exists(file.string() + ".previous." + std::to_string(app::kKeptPreviousSessions)));
  CHECK_THROWS_WITH(app::set_aside_session(file), Catch::Contains(file.string()));
}

TEST_CASE("saving keeps the last good file when the new one cannot be written",
          "[app][session-file]") {
  TempDir dir;
  const fs::path file = dir.path / "session.json";
  app::Session session(small_settings());
  app::save_session(session, file);
  const std::string good = read_text(file);
  session.click({0, 0});
  // A folder where the file should be cannot be replaced: the error names it.
  const fs::path folder = dir.path / "folder.json";
  fs::create_directories(folder);
  CHECK_THROWS_WITH(app::save_session(session, folder), Catch::Contains("folder.json"));
  CHECK(fs::is_directory(folder));
  CHECK(test_support::first_difference(read_text(file), good) == "");  // untouched
  // A model path that is not UTF-8 cannot go into JSON as it is; it is saved with replacement
  // characters instead of failing every autosave.
  app::SessionSettings odd = small_settings();
  odd.model_path = "/tmp/caf\xe9.npz";
  app::Session odd_session(odd);
  REQUIRE_NOTHROW(app::save_session(odd_session, file));
  CHECK(app::load_session(file).session.has_value());
}

TEST_CASE("a session that would not read back is never written, and the last good file stays",
          "[app][session-file]") {
  TempDir dir;
  const fs::path file = dir.path / "session.json";
  app::Session session(small_settings());
  app::save_session(session, file);
  const std::string good = read_text(file);
  // A search of another dimension than the session's components: to_json works, from_json
  // refuses it -- so save_session must refuse too and leave the good file alone.
  sps::SearchOptions other;
  other.dims = small_settings().components + 1;
  for (const auto& c : std::vector<sps::GridCell>{{0, 0}, {1, 1}, {2, 2}, {1, 0}}) session.click(c);
  session.finish_plane(sps::PlaneSearch(other));
  CHECK_THROWS_WITH(app::save_session(session, file),
                    Catch::Contains("did not save") && Catch::Contains("kept the last good file"));
  CHECK(test_support::first_difference(read_text(file), good) == "");
}

TEST_CASE("a history entry set with the sliders (no clicks) loads and undoes",
          "[app][session-file]") {
  auto j = nlohmann::json::parse(test_fixtures::good_session_json());
  j["history"][1]["path"] = nlohmann::json::array();
  app::Session session = app::Session::from_json(j.dump());
  CHECK(session.history()[1].path.empty());
  while (session.undo_click()) {
  }
  CHECK(session.planes_done() == 0);
}

// ---------------------------------------------------------------------------------------------
// Perception-aware zooming and the body benchmark's simulated user.

#include <limits>
#include <random>

#include "bench/simulated_person.hpp"

namespace {

// A stand-in for the body space: bodies differ by `mm_per_unit` times the Euclidean distance.
app::PairwiseDistance euclidean_mm(double mm_per_unit) {
  return [mm_per_unit](const std::vector<Eigen::VectorXd>& xs) {
    const auto n = static_cast<Eigen::Index>(xs.size());
    Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      for (Eigen::Index j = 0; j < n; ++j) {
        d(i, j) = mm_per_unit * (xs[static_cast<size_t>(i)] - xs[static_cast<size_t>(j)]).norm();
      }
    }
    return d;
  };
}

double min_pair(const Eigen::MatrixXd& d) {
  double m = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < d.rows(); ++i) {
    for (Eigen::Index j = i + 1; j < d.cols(); ++j) m = std::min(m, d(i, j));
  }
  return m;
}

std::vector<Eigen::VectorXd> xs_of(const std::vector<sps::GridPoint>& points) {
  std::vector<Eigen::VectorXd> xs;
  for (const auto& p : points) xs.push_back(p.x);
  return xs;
}

}  // namespace

TEST_CASE("the jnd user picks uniformly among the cells within D of the best", "[app][jnd]") {
  std::mt19937_64 rng(3);
  const std::vector<double> d{10.0, 12.0, 20.0, 14.9, 15.1, 30.0};
  std::vector<int> counts(d.size(), 0);
  for (int i = 0; i < 3000; ++i) ++counts[static_cast<size_t>(bench::jnd_pick(d, 5.0, rng))];
  CHECK(counts[2] == 0);
  CHECK(counts[4] == 0);
  CHECK(counts[5] == 0);
  for (int i : {0, 1, 3}) {
    CHECK(counts[static_cast<size_t>(i)] > 850);  // 1000 expected each
    CHECK(counts[static_cast<size_t>(i)] < 1150);
  }
  // D = 0: the best cell only (a perfect user).
  for (int i = 0; i < 20; ++i) CHECK(bench::jnd_pick(d, 0.0, rng) == 0);
  CHECK_THROWS(bench::jnd_pick({}, 5.0, rng));
}

TEST_CASE("a grid with two identical cells is counted as showing look-alikes", "[app][jnd]") {
  const auto distance = euclidean_mm(1000.0);
  std::vector<Eigen::VectorXd> grid;
  for (int i = 0; i < 9; ++i) grid.push_back(Eigen::VectorXd::Constant(3, 0.1 * i));
  CHECK_FALSE(bench::has_look_alikes(distance(grid)));
  grid[7] = grid[2];
  CHECK(bench::has_look_alikes(distance(grid)));
  // 4 mm apart at most is a look-alike, 6 mm is not.
  grid[7] = grid[2] + Eigen::VectorXd::Unit(3, 0) * 0.004;
  CHECK(bench::has_look_alikes(distance(grid)));
  grid[7] = grid[2] + Eigen::VectorXd::Unit(3, 0) * 0.006;
  CHECK_FALSE(bench::has_look_alikes(distance(grid)));
}

TEST_CASE("pinned coordinates are counted", "[app][jnd]") {
  Eigen::VectorXd x(5);
  x << 0.0, 0.5, 1.0, 0.9995, 0.002;
  CHECK(bench::pinned_fraction(x) == Approx(3.0 / 5.0));
  CHECK(bench::pinned_fraction(Eigen::VectorXd::Constant(4, 0.5)) == 0.0);
}

TEST_CASE("the jnd user plays a plane through the session and its grids are counted",
          "[app][jnd]") {
  app::Session session(small_settings());
  const Eigen::VectorXd target = Eigen::VectorXd::Constant(4, 0.3);
  const bench::TargetDistance to_target = [&](const std::vector<Eigen::VectorXd>& xs) {
    std::vector<double> d;
    for (const auto& x : xs) d.push_back(1000.0 * (x - target).norm());
    return d;
  };
  std::mt19937_64 rng(5);
  // Every grid counted when every pair looks alike; none when all differ.
  const app::PairwiseDistance all_alike = [](const std::vector<Eigen::VectorXd>& xs) {
    return Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(xs.size()),
                                 static_cast<Eigen::Index>(xs.size()));
  };
  const auto first = bench::play_plane_jnd(session, to_target, all_alike, 5.0, rng);
  CHECK(first.grids == 4);
  CHECK(first.look_alike_grids == 4);
  CHECK(session.planes_done() == 1);
  CHECK(session.search().iteration() == 1);
  const auto second = bench::play_plane_jnd(session, to_target, euclidean_mm(1e6), 0.0, rng);
  CHECK(second.grids == 4);
  CHECK(second.look_alike_grids == 0);
  // The perfect user (D = 0) clicked the cell nearest the target at every level.
  CHECK(session.planes_done() == 2);
  const auto& path = session.history().back().path;
  REQUIRE(path.size() == 4u);
}

TEST_CASE("with a perceptual distance no zoomed grid shows look-alikes", "[app][jnd]") {
  for (double mm_per_unit : {60.0, 150.0, 400.0}) {
    app::Session session(small_settings());
    app::ZoomPolicy policy;
    policy.distinct_mm = 10.0;
    const auto distance = euclidean_mm(mm_per_unit);
    session.set_perceptual_distance(distance, policy);
    std::mt19937_64 rng(11);
    int ended_early = 0;
    for (int plane = 0; plane < 3; ++plane) {
      while (!session.submission_pending()) {
        const auto cells = session.cells();
        if (session.clicks_on_plane() > 0) {
          CHECK(min_pair(distance(xs_of(cells))) >= policy.distinct_mm);
        }
        for (const auto& c : cells) CHECK_FALSE(c.clamped);
        const int index = std::uniform_int_distribution<int>(0, 8)(rng);
        session.click({index % 3, index / 3});
      }
      if (session.ended_early()) {
        ++ended_early;
        CHECK(session.clicks_on_plane() < 4);
      }
      const auto sub = session.submission();
      // At most one comparison per level; each holds only cells clearly different from the
      // clicked one (policy.compare_mm).
      CHECK(sub.extra_comparisons.size() <= static_cast<size_t>(session.clicks_on_plane()));
      for (const auto& comparison : sub.extra_comparisons) {
        REQUIRE(comparison.size() >= 2u);
        const Eigen::MatrixXd d = distance(comparison);
        for (Eigen::Index k = 1; k < d.cols(); ++k) CHECK(d(0, k) >= policy.compare_mm);
      }
      sps::PlaneSearch next = session.search();
      next.submit(sub.chosen, sub.extra_comparisons);
      session.finish_plane(std::move(next));
    }
    // Bodies that barely change end their planes early; clearly visible ones do not.
    if (mm_per_unit < 100.0) CHECK(ended_early > 0);
    if (mm_per_unit > 300.0) CHECK(ended_early == 0);
  }
}

TEST_CASE("a person who wants an edit near the box's faces keeps it as the current best",
          "[app][jnd]") {
  // The photo defect: a warm, bright edit chosen near +90 on its sliders came back as +14
  // after the next plane, because the plane had been moved to fit the box and its centre,
  // not the estimate, was shown as the current best (and the estimate was in no cell).
  app::Session session(small_settings());
  app::ZoomPolicy policy;
  policy.distinct_mm = 10.0;
  policy.look_alike_mm = 10.0;
  const double mm_per_unit = 150.0;
  session.set_perceptual_distance(euclidean_mm(mm_per_unit), policy);
  session.set_perceptual_scale(Eigen::VectorXd::Constant(4, mm_per_unit));
  sps::Population population;
  population.mean = Eigen::VectorXd::Constant(4, 0.5);
  population.sd = Eigen::Vector4d(0.35, 0.3, 0.25, 0.2);
  session.set_population(population);
  session.set_plane_axes(sps::PlaneAxes::kTargetUncertainty);
  session.set_min_plane_length(20.0);
  // The choices' regions bound the estimate (as the body's window does): without them a
  // person who keeps the centre leaves the planes where they are.
  sps::UncertaintyPlaneSize size;
  size.region_slack = 8.0;
  session.set_uncertainty_size(size);
  const Eigen::Vector4d wanted(0.97, 0.96, 0.95, 0.5);
  int moved = 0;
  for (int plane = 0; plane < 8; ++plane) {
    while (!session.submission_pending()) {
      const auto cells = session.cells();
      int nearest = 0;
      for (int k = 1; k < static_cast<int>(cells.size()); ++k) {
        if ((cells[static_cast<size_t>(k)].x - wanted).norm() <
            (cells[static_cast<size_t>(nearest)].x - wanted).norm()) {
          nearest = k;
        }
      }
      session.click({nearest % 3, nearest / 3});
    }
    const auto sub = session.submission();
    sps::PlaneSearch next = session.search();
    next.submit(sub.chosen, sub.extra_comparisons);
    session.finish_plane(std::move(next), std::nullopt);
    // The current best is the estimate of the design in mind the plane was built around
    // (the MAP of the choices, where its optimizer stays), and a cell of its first grid: the
    // person can keep it.
    const Eigen::VectorXd best = session.current_best();
    CHECK((best - session.search().x_plus()).norm() < 1e-12);
    const sps::SearchOptions& o = session.search().options();
    const sps::TargetModel model{sps::PerceptualMetric(o.perceptual_scale, o.perceptual_metric),
                                 o.population, o.choice_temperature_mm, o.choice_region_slack};
    CHECK((sps::estimate_target(session.search().data(), model, best) - best).norm() < 1e-4);
    double nearest_cell = 1e9;
    for (const auto& cell : session.cells()) {
      nearest_cell = std::min(nearest_cell, (cell.x - best).norm());
    }
    CHECK(nearest_cell < 1e-9);
    if (!session.search().current_plane().best_is_centre()) ++moved;
  }
  // The estimate reached the faces, so planes had to be moved, and it kept what was chosen.
  CHECK(moved > 0);
  CHECK(session.current_best()(0) > 0.8);
  CHECK(session.current_best()(1) > 0.8);
}

TEST_CASE("with a perceptual distance the zoom is gentler than the paper's halving", "[app][jnd]") {
  // The default policy zooms by less than the paper's factor 2 (each level's cells stay far
  // enough apart for a person's click to mean something); without a distance hook the
  // session keeps the paper's zoom.
  const app::ZoomPolicy defaults;
  REQUIRE_FALSE(defaults.factors.empty());
  CHECK(defaults.factors.front() > app::kPaperZoomFactor);
  CHECK(defaults.factors.front() < 1.0);
  for (const bool with_distance : {false, true}) {
    app::Session session(small_settings());
    // 1e6 mm per unit: every grid is clearly distinct, so the first factor is always taken.
    if (with_distance) session.set_perceptual_distance(euclidean_mm(1e6));
    const double expected = with_distance ? defaults.factors.front() : app::kPaperZoomFactor;
    while (!session.submission_pending()) {
      const int level = session.clicks_on_plane();
      session.click({1, 1});
      const auto& views = session.views();
      REQUIRE(views.size() == static_cast<std::size_t>(level) + 2);
      CHECK(views.back().spacing / views[views.size() - 2].spacing ==
            Approx(expected).epsilon(1e-12));
    }
    CHECK(session.clicks_on_plane() == small_settings().zoom_levels);
  }
}

TEST_CASE("zoom-level clicks count only over clearly different cells", "[app][jnd]") {
  const auto distance = euclidean_mm(1000.0);
  std::vector<std::size_t> totals;
  for (double compare_mm : {0.0, 60.0, 150.0, 1e9}) {
    app::Session session(small_settings());
    app::ZoomPolicy policy;
    policy.compare_mm = compare_mm;
    // The paper's halving, so that the levels span the distances the thresholds below split.
    policy.factors = {app::kPaperZoomFactor};
    session.set_perceptual_distance(distance, policy);
    while (!session.submission_pending()) session.click({2, 0});
    const auto sub = session.submission();
    // Expected: per level, the cells at least compare_mm from the clicked one.
    std::size_t expected_levels = 0, expected_cells = 0;
    for (int level = 0; level < session.clicks_on_plane(); ++level) {
      const auto cells = session.cells_at(session.views()[static_cast<std::size_t>(level)]);
      const Eigen::MatrixXd d = distance(xs_of(cells));
      std::size_t far = 0;
      for (Eigen::Index k = 0; k < d.cols(); ++k) far += k != 2 && d(2, k) >= compare_mm;
      expected_levels += far > 0;
      expected_cells += far;
    }
    std::size_t compared = 0;
    for (const auto& comparison : sub.extra_comparisons) {
      compared += comparison.size() - 1;
      const Eigen::MatrixXd d = distance(comparison);
      for (Eigen::Index k = 1; k < d.cols(); ++k) CHECK(d(0, k) >= compare_mm);
    }
    CHECK(sub.extra_comparisons.size() == expected_levels);
    CHECK(compared == expected_cells);
    if (compare_mm == 0.0)
      CHECK(compared == 8u * static_cast<std::size_t>(session.clicks_on_plane()));
    if (compare_mm == 1e9) CHECK(sub.extra_comparisons.empty());
    totals.push_back(compared);
  }
  // A stricter threshold never keeps more cells, and the middle ones drop some but not all.
  CHECK(totals[1] < totals[0]);
  CHECK(totals[2] < totals[1]);
  CHECK(totals[2] > 0u);
}

TEST_CASE("undo after a plane that ended early reopens it", "[app][jnd]") {
  app::Session session(small_settings());
  // Bodies that barely change (30 mm over the whole range): the plane ends before level 4.
  session.set_perceptual_distance(euclidean_mm(30.0));
  int clicks = 0;
  while (!session.submission_pending()) {
    session.click({2, 2});
    ++clicks;
  }
  CHECK(session.plane_note().find("No visible change") != std::string::npos);
  REQUIRE(session.undo_click());
  CHECK_FALSE(session.submission_pending());
  CHECK_FALSE(session.ended_early());
  CHECK(session.plane_note().empty());
  CHECK(session.clicks_on_plane() == clicks - 1);
}

TEST_CASE("cell notes say 'edge of the search range' in plain words", "[app][jnd]") {
  sps::GridPoint inside;
  inside.x = Eigen::Vector3d(0.2, 0.5, 0.9);
  CHECK(app::Session::cell_note(inside).empty());
  sps::GridPoint edge = inside;
  edge.x(1) = 1.0;
  CHECK(app::Session::cell_note(edge) == "At the edge of the search range.");
  edge.clamped = true;
  CHECK(app::Session::cell_note(edge).find("Beyond the edge") == 0);
}

TEST_CASE("a plane that ended early is saved, loaded back and undone like any other",
          "[app][jnd]") {
  app::Session session(small_settings());
  session.set_perceptual_distance(euclidean_mm(60.0));
  for (int plane = 0; plane < 4 && session.planes_done() == plane; ++plane) {
    while (!session.submission_pending()) session.click({2, 2});
    const auto sub = session.submission();
    sps::PlaneSearch next = session.search();
    next.submit(sub.chosen, sub.extra_comparisons);
    session.finish_plane(std::move(next));
  }
  bool shorter = false;
  for (const auto& h : session.history()) shorter = shorter || h.path.size() < 4u;
  REQUIRE(shorter);  // at least one plane ended before its fourth click
  app::Session loaded = app::Session::from_json(session.to_json());
  CHECK(loaded.planes_done() == session.planes_done());
  CHECK(loaded.undo_click());
  CHECK(loaded.clicks_on_plane() == static_cast<int>(session.history().back().path.size()) - 1);
}

namespace {

// A hold on a linear quantity: the sum of the first two coordinates stays `value`. Its
// tangent directions have d0 + d1 = 0; the projection is the nearest point on the line,
// clamped into the box.
class SumHold : public app::ConstraintProjector {
 public:
  explicit SumHold(double value) : value_(value) {}
  Eigen::VectorXd project(const Eigen::VectorXd& x) const override {
    Eigen::VectorXd y = x;
    const double m = 0.5 * (value_ - x[0] - x[1]);
    y[0] = std::clamp(x[0] + m, std::max(0.0, value_ - 1.0), std::min(1.0, value_));
    y[1] = value_ - y[0];
    return y;
  }
  Eigen::MatrixXd normals(const Eigen::VectorXd& x) const override {
    Eigen::MatrixXd n = Eigen::MatrixXd::Zero(1, x.size());
    n(0, 0) = n(0, 1) = 1.0;
    return n;
  }
  std::string description() const override { return "x1 + x2"; }
  std::vector<app::HeldValue> held_values() const override { return {{"sum", value_}}; }

 private:
  double value_;
};

}  // namespace

TEST_CASE("holds: every cell and every choice lies on the hold - release keeps the data",
          "[app][holds]") {
  app::Session session(small_settings());
  finish_plane(session, {{0, 0}, {2, 1}, {1, 1}, {2, 2}});
  const int iteration = session.search().iteration();
  session.set_constraint_projector(std::make_shared<SumHold>(0.9));
  REQUIRE(session.constraint_projector() != nullptr);
  const auto on_hold = [](const Eigen::VectorXd& x) { return std::abs(x[0] + x[1] - 0.9) < 1e-12; };
  const auto cells = session.cells();
  for (std::size_t i = 0; i < cells.size(); ++i) {
    CHECK(on_hold(cells[i].x));
    CHECK(cells[i].x.minCoeff() >= 0.0);
    CHECK(cells[i].x.maxCoeff() <= 1.0);
    for (std::size_t j = 0; j < i; ++j) CHECK((cells[i].x - cells[j].x).norm() > 1e-3);
  }
  CHECK(on_hold(session.current_best()));
  // The choice and every extra comparison the optimizer gets lie on the hold.
  for (const sps::GridCell c : {sps::GridCell{2, 0}, sps::GridCell{0, 2}, sps::GridCell{1, 0}}) {
    session.click(c);
    CHECK(on_hold(session.current_best()));
  }
  session.click({1, 1});
  REQUIRE(session.submission_pending());
  const auto sub = session.submission();
  CHECK(on_hold(sub.chosen));
  for (const auto& comparison : sub.extra_comparisons) {
    for (const auto& x : comparison) CHECK(on_hold(x));
  }
  // The plane's representatives the optimizer compares with are the held ones, as shown.
  REQUIRE(sub.representatives.size() == session.search().representative_coordinates().size());
  CHECK(sub.representatives.size() == 9);
  const auto coarsest = session.cells_at(session.views().front());
  for (std::size_t i = 0; i < sub.representatives.size(); ++i) {
    CHECK(on_hold(sub.representatives[i]));
    const auto [s, t] = session.search().representative_coordinates()[i];
    bool shown = false;  // on the first grid (the whole plane) the cell at (s, t)
    for (const auto& cell : coarsest) {
      if (std::abs(cell.s - s) < 1e-9 && std::abs(cell.t - t) < 1e-9) {
        shown = (cell.x - sub.representatives[i]).norm() < 1e-12;
      }
    }
    CHECK(shown);
  }
  CHECK((sub.representatives[0] - session.search().current_plane().c).norm() > 1e-6);
  sps::PlaneSearch next = session.search();
  // A wrong count is refused before anything changes.
  CHECK_THROWS_WITH(next.submit(sub.chosen, sub.extra_comparisons, {sub.chosen}),
                    Catch::Contains("shown representatives"));
  CHECK(next.iteration() == session.search().iteration());
  next.submit(sub.chosen, sub.extra_comparisons, sub.representatives);
  session.finish_plane(std::move(next));
  CHECK(on_hold(session.current_best()));
  // Released: the optimizer's own plane again, with every choice kept.
  const int preferences = session.search().data().preference_count();
  session.set_constraint_projector(nullptr);
  CHECK(session.search().iteration() == iteration + 1);
  CHECK(session.search().data().preference_count() == preferences);
  CHECK((session.current_best() - session.search().x_plus()).norm() < 1e-12);
}

TEST_CASE("holds are saved with the session and read back - files without them still load",
          "[app][holds][session-file]") {
  app::Session session(small_settings());
  finish_plane(session, {{0, 0}, {2, 1}, {1, 1}, {2, 2}});
  CHECK(session.to_json().find("\"holds\"") == std::string::npos);  // none: no field
  session.set_constraint_projector(std::make_shared<SumHold>(0.9));
  const std::string text = session.to_json();
  app::Session back = app::Session::from_json(text);
  REQUIRE(back.saved_holds().size() == 1);
  CHECK(back.saved_holds()[0].name == "sum");
  CHECK(std::abs(back.saved_holds()[0].value - 0.9) < 1e-12);
  CHECK(back.constraint_projector() == nullptr);  // the window makes the projector
  // Saved again before the window held them: still there.
  CHECK(app::Session::from_json(back.to_json()).saved_holds().size() == 1);
  // Held again: the same cells as before the save.
  back.set_constraint_projector(std::make_shared<SumHold>(back.saved_holds()[0].value));
  const auto before = session.cells();
  const auto after = back.cells();
  REQUIRE(before.size() == after.size());
  for (std::size_t i = 0; i < before.size(); ++i) CHECK((before[i].x - after[i].x).norm() < 1e-9);
  // Released: nothing saved.
  back.set_constraint_projector(nullptr);
  CHECK(back.saved_holds().empty());
  CHECK(app::Session::from_json(back.to_json()).saved_holds().empty());
}

TEST_CASE("the catalogue of space kinds: the first is the default, names and files find kinds",
          "[app][catalogue]") {
  app::SpaceCatalogue kinds;
  CHECK_THROWS_AS(kinds.default_kind(), std::logic_error);
  std::vector<std::string> opened;
  auto kind = [&opened](const std::string& name, int dims, std::vector<std::string> ext) {
    app::SpaceKind k;
    k.name = name;
    k.dimensions = dims;
    k.file_extensions = std::move(ext);
    k.open = [&opened](const app::SpaceSettings& s) -> std::unique_ptr<app::DesignSpace> {
      opened.push_back(s.kind + ":" + s.source);
      return nullptr;
    };
    return k;
  };
  kinds.add(kind("shape", 10, {".npz"}));
  kinds.add(kind("colour", 12, {".png", ".jpg"}));
  CHECK_THROWS_AS(kinds.add(kind("colour", 3, {})), std::logic_error);  // twice
  app::SpaceKind nameless = kind("", 3, {});
  CHECK_THROWS_AS(kinds.add(nameless), std::logic_error);
  CHECK(kinds.default_kind().name == "shape");
  CHECK(kinds.names() == "shape, colour");
  REQUIRE(kinds.find("colour") != nullptr);
  CHECK(kinds.find("sound") == nullptr);
  try {
    (void)kinds.get("sound");
    FAIL("an unknown kind was accepted");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Catch::Contains("'sound'") && Catch::Contains("shape, colour"));
  }
  REQUIRE(kinds.kind_for_file("/a/B.JPG") != nullptr);
  CHECK(kinds.kind_for_file("/a/B.JPG")->name == "colour");
  CHECK(kinds.kind_for_file("model.npz")->name == "shape");
  CHECK(kinds.kind_for_file("notes.txt") == nullptr);
  CHECK(kinds.kind_for_file("no-extension") == nullptr);
  CHECK(kinds.default_settings("colour").dimensions == 12);
  CHECK(kinds.default_settings("colour").kind == "colour");
  // A settings without a kind (as before kinds were named) opens the default kind.
  (void)kinds.open(app::SpaceSettings{"", "m.npz", 4});
  (void)kinds.open(app::SpaceSettings{"colour", "", 12});
  REQUIRE(opened.size() == 2);
  CHECK(opened[0] == "shape:m.npz");
  CHECK(opened[1] == "colour:");
}

TEST_CASE("the redo stack is saved with the session and Redo brings each step back after a reload",
          "[app][session-file][redo]") {
  app::Session session(small_settings());
  finish_plane(session, {{0, 0}, {2, 1}, {1, 1}, {2, 2}});
  finish_plane(session, {{1, 0}, {0, 2}, {2, 2}, {1, 1}});
  session.click({2, 0});
  // Each state as it was before an undo, oldest first: what the redos must give back.
  std::vector<std::string> states;
  const auto undo = [&](bool plane) {
    app::Session before = session;
    states.push_back(session.to_json());
    REQUIRE((plane ? session.undo_plane() : session.undo_click()));
    session.push_redo(std::move(before), true);
  };
  undo(false);  // the click on the third plane
  undo(false);  // reopens the second plane with three of its clicks
  undo(true);   // those clicks
  undo(true);   // the first plane
  REQUIRE(session.planes_done() == 0);
  REQUIRE(session.redo_depth() == 4);

  const std::string text = session.to_json();
  const auto j = nlohmann::json::parse(text);
  REQUIRE(j.contains("redo"));
  REQUIRE(j["redo"].size() == 4);
  // Only the oldest step holds a whole search; the others are it with submissions undone.
  CHECK(j["redo"][0].contains("search"));
  for (std::size_t i = 1; i < 4; ++i) {
    CHECK_FALSE(j["redo"][i].contains("search"));
    CHECK(j["redo"][i].contains("search_undos"));
  }
  CHECK(j["redo"][1]["search_undos"] == 0);  // the click on the third plane: no submission
  CHECK(j["redo"][2]["search_undos"] == 1);

  app::Session back = app::Session::from_json(text);
  CHECK(back.redo_problem().empty());
  CHECK(back.redo_depth() == 4);
  CHECK(test_support::first_difference(back.to_json(), text) == "");
  for (int k = 3; k >= 0; --k) {
    auto next = back.pop_redo();
    REQUIRE(next);
    back = std::move(*next);
    CHECK(test_support::first_difference(back.to_json(), states[static_cast<std::size_t>(k)]) ==
          "");
  }
  CHECK_FALSE(back.pop_redo());
  CHECK(back.planes_done() == 2);
  CHECK(back.clicks_on_plane() == 1);
  CHECK((back.current_best() - app::Session::from_json(states[0]).current_best()).norm() < 1e-12);
}

TEST_CASE(
    "start over is redone after a reload - files without redo load - a broken redo part is "
    "reported by field and costs only the redo steps",
    "[app][session-file][redo]") {
  TempDir dir;
  app::Session session(small_settings());
  finish_plane(session, {{0, 0}, {2, 1}, {1, 1}, {2, 2}});
  finish_plane(session, {{1, 0}, {0, 2}, {2, 2}, {1, 1}});
  const std::string before_start_over = session.to_json();
  {
    app::Session before = session;
    session.start_over();
    session.push_redo(std::move(before), false);
  }
  REQUIRE(session.planes_done() == 0);
  const std::string text = session.to_json();
  auto j = nlohmann::json::parse(text);
  REQUIRE(j["redo"].size() == 1);
  CHECK(j["redo"][0].contains("search"));
  {
    app::Session back = app::Session::from_json(text);
    auto next = back.pop_redo();
    REQUIRE(next);
    CHECK(next->planes_done() == 2);
    CHECK(test_support::first_difference(next->to_json(), before_start_over) == "");
  }

  // A file from before redo was saved.
  auto old = j;
  old.erase("redo");
  const app::Session from_old = app::Session::from_json(old.dump());
  CHECK(from_old.redo_depth() == 0);
  CHECK(from_old.redo_problem().empty());

  // Broken redo parts: the session loads, the redo stack is empty, the problem names the field.
  const auto broken = [&](const std::function<void(nlohmann::json&)>& edit) {
    auto b = j;
    edit(b);
    return b.dump();
  };
  const std::vector<std::pair<std::string, std::string>> cases{
      {broken([](nlohmann::json& b) { b["redo"] = 5; }), "redo must be an array"},
      {broken([](nlohmann::json& b) { b["redo"][0].erase("search"); }), "redo[0]: search"},
      {broken([](nlohmann::json& b) { b["redo"][0]["history"][1]["chosen"][0] = 7.5; }),
       "redo[0]: history chosen"},
      {broken([](nlohmann::json& b) {
         b["redo"].push_back({{"path", nlohmann::json::array()},
                              {"start_point", b["start_point"]},
                              {"search_undos", 3},
                              {"history_kept", 0}});
       }),
       "redo[1]: search_undos"},
      {broken([](nlohmann::json& b) {
         b["redo"].push_back({{"path", nlohmann::json::array()},
                              {"start_point", b["start_point"]},
                              {"search_undos", 1},
                              {"history_kept", 2}});
       }),
       "redo[1]: history length"},
  };
  for (const auto& [bad, expected] : cases) {
    INFO(expected);
    const app::Session loaded = app::Session::from_json(bad);
    CHECK(loaded.planes_done() == 0);
    CHECK(loaded.redo_depth() == 0);
    CHECK(loaded.redo_problem().find(expected) != std::string::npos);
  }
  // Through the store: the file is named, the session is kept, nothing is set aside.
  const fs::path file = dir.path / "s.json";
  {
    std::ofstream out(file);
    out << cases[1].first;
  }
  const auto result = app::load_session(file);
  CHECK(result.problem.empty());
  REQUIRE(result.session);
  CHECK(result.redo_problem.find(file.string()) != std::string::npos);
  CHECK(result.redo_problem.find("redo[0]: search") != std::string::npos);
  CHECK(fs::exists(file));
}

TEST_CASE(
    "the session writer waits its start delay, writes only the newest copy, flush does not wait",
    "[app][background-save]") {
  TempDir dir;
  const fs::path path = dir.path / "s.json";
  app::Session first(small_settings());
  first.click({0, 0});
  app::Session second = first;
  second.click({1, 1});
  {
    // A delay far longer than this test: only flush() or closing makes it write now.
    app::SessionWriter writer(app::stamp_of(path), std::chrono::milliseconds(600000));
    writer.save(first, path);
    writer.save(second, path);  // replaces the first before it was started
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    CHECK_FALSE(fs::exists(path));  // still waiting
    CHECK_FALSE(writer.poll());
    writer.flush();
    REQUIRE(fs::exists(path));
    CHECK(app::read_session_file(path).clicks_on_plane() == 2);
    const auto result = writer.poll();
    REQUIRE(result);
    CHECK_FALSE(result->conflict);
    second.click({2, 2});
    writer.save(second, path);
  }  // closing writes what is queued, without the delay
  CHECK(app::read_session_file(path).clicks_on_plane() == 3);
}

TEST_CASE("bench-gui's timing sorts each click by what its frame did", "[app][bench]") {
  using Clock = app::FrameObserver::Clock;
  bench::WindowTiming timing({/*clicks=*/3, /*orbit_frames=*/0, /*breakdown=*/false});
  const Clock::time_point t0 = Clock::now();
  const auto at = [&](int ms) { return t0 + std::chrono::milliseconds(ms); };
  timing.first_grid(0.1);
  // frame_started(at, settled, first grid shown, previous frame zoomed, previous submitted)
  auto r = timing.frame_started({at(0), true, true, false, false});
  REQUIRE(r.click);  // a settled grid: the first click
  REQUIRE(timing.waits_for_presented());
  timing.frame_presented(at(20));
  // Its frame zoomed in and handed nothing to the optimizer: a zoom click.
  r = timing.frame_started({at(30), true, true, true, false});
  REQUIRE(r.click);
  timing.frame_presented(at(65));
  // This one ended the plane.
  r = timing.frame_started({at(70), true, true, true, true});
  REQUIRE(r.click);
  timing.frame_presented(at(80));
  r = timing.frame_started({at(90), true, true, false, false});
  CHECK(r.quit);  // three clicks done
  REQUIRE(timing.click_ms().size() == 3);
  REQUIRE(timing.zoom_click_ms().size() == 2);
  REQUIRE(timing.ending_click_ms().size() == 1);
  CHECK(timing.zoom_click_ms()[0] == Approx(20.0));
  CHECK(timing.zoom_click_ms()[1] == Approx(10.0));
  CHECK(timing.ending_click_ms()[0] == Approx(35.0));
}
