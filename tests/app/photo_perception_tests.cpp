// The photo space's colour-difference measure (spaces/photo_perception.hpp) and the photo
// session it drives: CIEDE2000 against published test data, the two picture measures, the
// perceptual scale, and a photo session that never shows look-alike cells.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <random>

#include "app/session.hpp"
#include "bench/simulated_person.hpp"
#include "spaces/photo_enhancement.hpp"
#include "spaces/photo_image.hpp"
#include "spaces/photo_perception.hpp"

namespace {

Eigen::VectorXd no_edit() {
  return Eigen::VectorXd::Constant(spaces::kPhotoParameters, 0.5);
}

// A photo session on the window's 3x3 grid with the photo space's hooks installed, as the
// window installs them: its perceptual scale, population and colour-difference zoom.
app::Session photo_session(std::uint64_t seed, const sps::SearchOptions& options,
                           const spaces::PhotoDistance& distance,
                           const app::PairwiseDistance& pairwise) {
  app::SessionSettings settings;
  settings.space = "photo";
  settings.components = spaces::kPhotoParameters;
  settings.grid_size = 3;
  settings.seed = seed;
  app::Session session(settings, options);
  session.set_perceptual_scale(distance.direction_scale());
  session.set_population(spaces::photo_population());
  session.set_perceptual_distance(pairwise, spaces::photo_zoom_policy());
  return session;
}

app::PairwiseDistance pairwise_of(const spaces::PhotoDistance& distance) {
  return [&distance](const std::vector<Eigen::VectorXd>& xs) { return distance.pairwise(xs); };
}

// The optimizer's options as the window sets them for photos: its smallest plane length and
// uncertainty planes of the photo space's size.
sps::SearchOptions window_photo_options() {
  sps::SearchOptions options;
  options.min_plane_length = spaces::kPhotoMinPlaneDeltaE;
  options.plane_axes = sps::PlaneAxes::kTargetUncertainty;
  const sps::UncertaintyPlaneSize size = spaces::photo_uncertainty_size();
  options.uncertainty_extent = size.extent;
  options.uncertainty_min_lengths = size.min_lengths;
  return options;
}

}  // namespace

TEST_CASE("CIEDE2000 matches Sharma, Wu and Dalal's test data", "[photo]") {
  // Pairs from the supplementary test data of Sharma, Wu & Dalal (2005), Table 1: chosen to
  // exercise the hue-angle branches (blue, near-neutral, wrapping around 0/360 degrees) and
  // the rotation term.
  struct Pair {
    spaces::Lab x, y;
    double expected;
  };
  const Pair pairs[] = {
      {{50.0, 2.6772, -79.7751}, {50.0, 0.0, -82.7485}, 2.0425},
      {{50.0, 3.1571, -77.2803}, {50.0, 0.0, -82.7485}, 2.8615},
      {{50.0, 2.8361, -74.0200}, {50.0, 0.0, -82.7485}, 3.4412},
      {{50.0, 0.0, 0.0}, {50.0, -1.0, 2.0}, 2.3669},
      {{50.0, 2.5, 0.0}, {73.0, 25.0, -18.0}, 27.1492},
      {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
  };
  for (const auto& p : pairs) {
    INFO("Lab " << p.x.l << " " << p.x.a << " " << p.x.b << " vs " << p.y.l << " " << p.y.a << " "
                << p.y.b);
    CHECK(spaces::ciede2000(p.x, p.y) == Approx(p.expected).margin(1e-4));
    CHECK(spaces::ciede2000(p.y, p.x) == Approx(p.expected).margin(1e-4));
  }
  CHECK(spaces::ciede2000({40.0, 10.0, -5.0}, {40.0, 10.0, -5.0}) == 0.0);
}

TEST_CASE("sRGB to CIELAB: white, black and a pure red", "[photo]") {
  const spaces::Lab white = spaces::srgb_to_lab({1.0f, 1.0f, 1.0f});
  CHECK(white.l == Approx(100.0).margin(0.01));
  CHECK(std::abs(white.a) < 0.01);
  CHECK(std::abs(white.b) < 0.01);
  const spaces::Lab black = spaces::srgb_to_lab({0.0f, 0.0f, 0.0f});
  CHECK(black.l == Approx(0.0).margin(0.01));
  // sRGB red is L* 53.24, a* 80.09, b* 67.20 (D65).
  const spaces::Lab red = spaces::srgb_to_lab({1.0f, 0.0f, 0.0f});
  CHECK(red.l == Approx(53.24).margin(0.05));
  CHECK(red.a == Approx(80.09).margin(0.1));
  CHECK(red.b == Approx(67.20).margin(0.1));
}

TEST_CASE("the photo distance: zero for equal edits, the visible difference above the mean",
          "[photo]") {
  const spaces::PhotoDistance distance(spaces::default_photo());
  REQUIRE(distance.pixels() > 500);
  REQUIRE(distance.pixels() <= 40 * 40);
  Eigen::VectorXd warm = no_edit();
  warm[6] = 0.8;   // midtones towards red
  warm[8] = 0.25;  // and towards yellow
  Eigen::VectorXd highlights = no_edit();
  highlights[11] = 0.9;  // highlights towards blue: only the bright pixels change
  const Eigen::MatrixXd d = distance.pairwise({no_edit(), warm, highlights});
  CHECK(d(0, 0) == 0.0);
  CHECK(d(0, 1) == Approx(d(1, 0)));
  CHECK(d(0, 1) > spaces::kPhotoJndDeltaE);
  const auto a = distance.lab_of(no_edit());
  const auto b = distance.lab_of(highlights);
  const double mean = spaces::PhotoDistance::mean_difference(a, b);
  const double visible = spaces::PhotoDistance::visible_difference(a, b);
  INFO("highlights edit: mean " << mean << ", visible " << visible);
  CHECK(visible == Approx(d(0, 2)));
  // Confined to part of the picture, the edit is far more visible where it is than on average.
  CHECK(visible > 1.5 * mean);
  CHECK(distance.to_target({warm}, warm).front() == Approx(0.0).margin(1e-12));
}

TEST_CASE("every photo parameter changes the picture visibly over its range, within reason",
          "[photo]") {
  const spaces::PhotoDistance distance(spaces::default_photo());
  const Eigen::VectorXd scale = distance.direction_scale();
  REQUIRE(scale.size() == spaces::kPhotoParameters);
  for (int i = 0; i < spaces::kPhotoParameters; ++i) {
    INFO(spaces::photo_parameter_name(i) << ": " << scale[i] << " Delta E over its range");
    // Visible (several JNDs) but not an effect: the strongest edit of one slider stays under
    // what turns a landscape into another picture.
    CHECK(scale[i] > 3.0 * spaces::kPhotoJndDeltaE);
    CHECK(scale[i] < 40.0);
  }
}

TEST_CASE("a photo session with the colour-difference hook shows no cells closer than 3.5",
          "[photo][session]") {
  const spaces::PhotoDistance distance(spaces::default_photo());
  const app::PairwiseDistance pairwise = pairwise_of(distance);
  sps::SearchOptions options;
  options.min_plane_length = spaces::kPhotoMinPlaneDeltaE;
  int grids = 0;
  int look_alike_grids = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    app::Session session = photo_session(seed, options, distance, pairwise);
    Eigen::VectorXd target = no_edit();
    target[0] = 0.7;
    target[6] = 0.65;
    target[8] = 0.3;
    const bench::TargetDistance to_target = [&](const std::vector<Eigen::VectorXd>& xs) {
      return distance.to_target(xs, target);
    };
    std::mt19937_64 rng(seed);
    double first = 0.0;
    double best = 1e9;
    for (int plane = 0; plane < 4; ++plane) {
      const bench::PlaneOutcome outcome = bench::play_plane_jnd(
          session, to_target, pairwise, spaces::kPhotoJndDeltaE, rng, spaces::kPhotoDistinctDeltaE);
      grids += outcome.grids;
      look_alike_grids += outcome.look_alike_grids;
      const double gap = to_target({outcome.chosen}).front();
      if (plane == 0) first = distance.to_target({session.start_point()}, target).front();
      best = std::min(best, gap);
    }
    INFO("seed " << seed << ": start " << first << ", best after 4 planes " << best);
    CHECK(best < first);
  }
  INFO(look_alike_grids << " of " << grids << " grids held look-alike cells");
  CHECK(grids >= 12);
  CHECK(look_alike_grids == 0);
}

TEST_CASE("the photo population: white-balance shifts across the tones are typical", "[photo]") {
  const sps::Population p = spaces::photo_population();
  const sps::TargetModel m{sps::PerceptualMetric(Eigen::VectorXd::Ones(spaces::kPhotoParameters)),
                           p};
  REQUIRE_NOTHROW(sps::validate_target_model(m, spaces::kPhotoParameters));
  const Eigen::MatrixXd& r = p.correlation;
  // Parameters 3 + 3 band + axis (axes: cyan-red, magenta-green, yellow-blue).
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      if (a != b) CHECK(r(3 + 3 * a, 3 + 3 * b) > 0.4);  // red in one band, red in another
      CHECK(r(3 + 3 * a, 5 + 3 * b) < -0.2);             // red with yellow (negative: yellow)
      CHECK(r(4 + 3 * a, 3 + 3 * b) == Approx(0.0));     // tint apart from temperature
    }
  }
  for (int i = 0; i < 3; ++i) {  // brightness, contrast, saturation on their own
    CHECK(r.row(i).cwiseAbs().sum() == Approx(1.0));
  }
}

TEST_CASE("a photo search's first grid: 3-SD uncertainty planes keep most cells off the ends",
          "[photo][session]") {
  const spaces::PhotoDistance distance(spaces::default_photo());
  const app::PairwiseDistance pairwise = pairwise_of(distance);
  sps::SearchOptions options = window_photo_options();
  options.uncertainty_extent = 5.0;  // the bodies'
  const auto at_an_end = [](const app::Session& s) {
    int n = 0;
    for (const auto& cell : s.cells()) n += bench::pinned_fraction(cell.x) > 0.0 ? 1 : 0;
    return n;
  };
  app::Session session = photo_session(3, options, distance, pairwise);
  const int wide = at_an_end(session);
  const sps::Plane before = session.search().current_plane();
  // Before the first click the session takes its first plane again at the photo space's size.
  session.set_uncertainty_size(spaces::photo_uncertainty_size());
  const int narrow = at_an_end(session);
  INFO(wide << " of 9 cells at an end of a range with 5 SDs, " << narrow << " with 3");
  CHECK((session.search().current_plane().u - before.u).norm() > 1e-6);
  CHECK(narrow < wide);
  CHECK(narrow <= 4);
}

TEST_CASE(
    "a photo search as the window runs it: a temperature among the first planes, a "
    "cooler edit found, no look-alike grids",
    "[photo][session]") {
  const spaces::PhotoDistance distance(spaces::default_photo());
  const app::PairwiseDistance pairwise = pairwise_of(distance);
  const sps::SearchOptions options = window_photo_options();
  // "Cooler": every band towards cyan and blue.
  Eigen::VectorXd target = no_edit();
  for (int band = 0; band < 3; ++band) {
    target[3 + 3 * band] = 0.5 - 0.12;
    target[5 + 3 * band] = 0.5 + 0.18;
  }
  const bench::TargetDistance to_target = [&](const std::vector<Eigen::VectorXd>& xs) {
    return distance.to_target(xs, target);
  };
  int grids = 0;
  int look_alike_grids = 0;
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    app::Session session = photo_session(seed, options, distance, pairwise);
    // One of the first two planes runs along a white-balance temperature: red with yellow (or
    // cyan with blue) in every band, along u or v (the first: the most visible spreads of the
    // population, brightness and tint on the built-in picture).
    const auto has_temperature = [](const sps::Plane& plane) {
      for (const Eigen::VectorXd& axis : {plane.u, plane.v}) {
        bool warm = true;
        for (int band = 0; band < 3; ++band) {
          warm = warm && axis[3 + 3 * band] * axis[5 + 3 * band] < 0.0 &&
                 std::abs(axis[3 + 3 * band]) > 0.1 * axis.cwiseAbs().maxCoeff();
        }
        if (warm) return true;
      }
      return false;
    };
    bool temperature_shown = has_temperature(session.search().current_plane());
    const double start = to_target({session.start_point()}).front();
    std::mt19937_64 rng(seed);
    double best = 1e9;
    for (int plane = 0; plane < 5; ++plane) {
      const bench::PlaneOutcome outcome = bench::play_plane_jnd(
          session, to_target, pairwise, spaces::kPhotoJndDeltaE, rng, spaces::kPhotoDistinctDeltaE);
      grids += outcome.grids;
      look_alike_grids += outcome.look_alike_grids;
      best = std::min(best, to_target({outcome.chosen}).front());
      if (plane == 0) {
        INFO("second plane u " << session.search().current_plane().u.transpose() << "\nv "
                               << session.search().current_plane().v.transpose());
        temperature_shown = temperature_shown || has_temperature(session.search().current_plane());
        CHECK(temperature_shown);
      }
    }
    INFO("seed " << seed << ": start " << start << ", best after 5 planes " << best);
    CHECK(best < 0.5 * start);
  }
  INFO(look_alike_grids << " of " << grids << " grids held look-alike cells");
  CHECK(grids >= 15);
  CHECK(look_alike_grids == 0);
}
