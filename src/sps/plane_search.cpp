#include "sps/plane_search.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "sps/expected_improvement.hpp"
#include "sps/json_fields.hpp"
#include "sps/plane_construction.hpp"

namespace sps {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "sequential-gallery/plane-search";
constexpr int kVersion = 1;

const char* current_best_name(CurrentBest c) {
  return c == CurrentBest::kPosteriorMean ? "posterior-mean" : "last-selection";
}

json vec_to_json(const Eigen::VectorXd& v) {
  return json(std::vector<double>(v.data(), v.data() + v.size()));
}

// Stored numbers are checked before they are used or sized anything (sps/json_fields.hpp).
long long int_from_json(const json& j, const std::string& what, long long lo, long long hi) {
  return json_fields::integer(j, what, lo, hi);
}
double double_from_json(const json& j, const std::string& what, double lo, double hi) {
  return json_fields::number(j, what, lo, hi);
}

// Sizes are checked before the vector is allocated; entries must be finite and within
// [lo, hi].
Eigen::VectorXd vec_from_json(const json& j, const char* what, Eigen::Index expected, double lo,
                              double hi) {
  if (!j.is_array()) throw std::runtime_error(std::string(what) + " is not an array");
  if (static_cast<Eigen::Index>(j.size()) != expected) {
    throw std::runtime_error(std::string(what) + " has " + std::to_string(j.size()) +
                             " entries, expected " + std::to_string(expected));
  }
  Eigen::VectorXd v(expected);
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_number()) throw std::runtime_error(std::string(what) + " holds a non-number");
    const double x = j[i].get<double>();
    if (!std::isfinite(x)) throw std::runtime_error(std::string(what) + " holds NaN or infinity");
    if (x < lo || x > hi) {
      std::ostringstream out;
      out << what << " holds " << x << ", outside [" << lo << ", " << hi << "]";
      throw std::runtime_error(out.str());
    }
    v(static_cast<Eigen::Index>(i)) = x;
  }
  return v;
}

// Limits of stored state. Plane vectors: c in the unit box, u and v differences of box points
// (with generous room); hyperparameters far outside these are nonsense that overflows the
// kernel (an amplitude of 1e300 turns every later value into NaN).
constexpr double kMaxPlaneExtent = 10.0;
constexpr double kMinHyper = 1e-6;
constexpr double kMaxHyper = 1e6;
constexpr double kMaxLatent = 1e6;
constexpr long long kMaxStoredPoints = 100000;
constexpr long long kMaxStoredPreferences = 100000;

json plane_to_json(const Plane& p) {
  return {{"c", vec_to_json(p.c)},        {"u", vec_to_json(p.u)}, {"v", vec_to_json(p.v)},
          {"u_neg_scale", p.u_neg_scale}, {"best_s", p.best_s},    {"best_t", p.best_t}};
}

Plane plane_from_json(const json& j, int dims) {
  Plane p;
  p.c = vec_from_json(j.at("c"), "plane.c", dims, 0.0, 1.0);
  p.u = vec_from_json(j.at("u"), "plane.u", dims, -kMaxPlaneExtent, kMaxPlaneExtent);
  p.v = vec_from_json(j.at("v"), "plane.v", dims, -kMaxPlaneExtent, kMaxPlaneExtent);
  p.u_neg_scale = double_from_json(j.at("u_neg_scale"), "plane.u_neg_scale", 0.0, 1.0);
  // Files saved before the current best could lie off the centre: the centre.
  if (j.contains("best_s")) p.best_s = double_from_json(j.at("best_s"), "plane.best_s", -1.0, 1.0);
  if (j.contains("best_t")) p.best_t = double_from_json(j.at("best_t"), "plane.best_t", -1.0, 1.0);
  return p;
}

json params_to_json(const KernelParams& p) {
  return {{"amplitude", p.amplitude}, {"length_scales", vec_to_json(p.length_scales)}};
}

KernelParams params_from_json(const json& j, int dims) {
  KernelParams p;
  p.amplitude = double_from_json(j.at("amplitude"), "kernel amplitude", kMinHyper, kMaxHyper);
  p.length_scales =
      vec_from_json(j.at("length_scales"), "length_scales", dims, kMinHyper, kMaxHyper);
  return p;
}

void check_rng_state(const std::string& state, const std::string& what) {
  std::mt19937_64 probe;
  std::istringstream in(state);
  in >> probe;
  if (in.fail()) throw std::runtime_error(what + ": the random generator state is unreadable");
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// The smallest side of an uncertainty plane: what a person sees at all (min_plane_length, in
// the lengths the space asks for) or what they need to tell a deep zoom level's cells apart,
// whichever is longer.
double uncertainty_min_side_of(const SearchOptions& options) {
  return std::max(options.uncertainty_min_lengths * options.min_plane_length,
                  options.uncertainty_min_side);
}

}  // namespace

UncertaintyPlaneSize uncertainty_size(const SearchOptions& options) {
  return {options.uncertainty_extent, options.uncertainty_min_lengths, options.choice_region_slack};
}

void validate_uncertainty_size(const UncertaintyPlaneSize& size) {
  const auto in = [](double v, double lo, double hi) {
    return std::isfinite(v) && v >= lo && v <= hi;
  };
  require(in(size.extent, 0.1, 10.0),
          "the uncertainty planes' extent (uncertainty_extent) must lie in [0.1, 10]");
  require(in(size.min_lengths, 0.0, 10.0),
          "the uncertainty planes' smallest length (uncertainty_min_lengths) must lie in [0, 10]");
  require(in(size.region_slack, -1.0, 1e3),
          "the choice regions' slack (choice_region_slack) must lie in [-1, 1000]; negative: off");
}

void validate_options(const SearchOptions& o) {
  require(o.dims >= 1 && o.dims <= kMaxSearchDims,
          "the number of dimensions must be between 1 and " + std::to_string(kMaxSearchDims) +
              ", got " + std::to_string(o.dims));
  require(o.plane_restarts >= 0 && o.plane_restarts <= 1000, "plane_restarts must be 0-1000");
  require(o.ei_restarts >= 0 && o.ei_restarts <= 100000, "ei_restarts must be 0-100000");
  require(o.threads >= 1 && o.threads <= 256, "threads must be 1-256");
  require(o.representatives == 5 || o.representatives == 9, "representatives must be 5 or 9");
  const ModelSettings& m = o.model;
  const auto in = [](double v, double lo, double hi) {
    return std::isfinite(v) && v >= lo && v <= hi;
  };
  require(in(m.amplitude_prior, kMinHyper, kMaxHyper), "amplitude_prior must lie in [1e-6, 1e6]");
  require(in(m.length_scale_prior, kMinHyper, kMaxHyper),
          "length_scale_prior must lie in [1e-6, 1e6]");
  require(in(m.prior_log_variance, 1e-8, 100.0), "prior_log_variance must lie in [1e-8, 100]");
  require(in(m.btl_scale, 1e-8, 1e3), "btl_scale must lie in [1e-8, 1000]");
  require(in(o.perceptual_btl_scale, 1e-8, 1e3), "perceptual_btl_scale must lie in [1e-8, 1000]");
  require(in(o.choice_temperature_mm, 1e-6, 1e4),
          "choice_temperature_mm must lie in [1e-6, 10000]");
  validate_uncertainty_size(uncertainty_size(o));
  require(in(o.uncertainty_min_side, 0.0, 1e4), "uncertainty_min_side must lie in [0, 10000]");
  require(o.population.empty() ||
              (o.population.mean.size() == o.dims && o.population.sd.size() == o.dims),
          "the population mean and SD need one entry per dimension");
  require(o.perceptual_metric.size() == 0 ||
              (o.perceptual_scale.size() == o.dims && o.perceptual_metric.rows() == o.dims &&
               o.perceptual_metric.cols() == o.dims),
          "the perceptual metric needs a perceptual scale and dims x dims entries");
  require(o.population.correlation.size() == 0 || (o.population.correlation.rows() == o.dims &&
                                                   o.population.correlation.cols() == o.dims),
          "the population correlation needs dims x dims entries");
  require(in(m.noise_variance, 1e-12, 1.0), "noise_variance must lie in [1e-12, 1]");
  require(m.max_hyper_iterations >= 0 && m.max_hyper_iterations <= 100000,
          "max_hyper_iterations must be 0-100000");
  require(m.max_points >= 2 && m.max_points <= 10000, "max_points must be 2-10000");
}

const char* method_name(Method m) {
  switch (m) {
    case Method::kSps:
      return "sps";
    case Method::kSpsRandom:
      return "sps-random";
    case Method::kSls:
      return "sls";
  }
  return "sps";
}

const char* plane_axes_name(PlaneAxes a) {
  switch (a) {
    case PlaneAxes::kExpectedImprovement:
      return "expected-improvement";
    case PlaneAxes::kTargetUncertainty:
      return "uncertainty";
  }
  return "expected-improvement";
}

bool parse_plane_axes(const std::string& name, PlaneAxes& out) {
  for (PlaneAxes a : {PlaneAxes::kExpectedImprovement, PlaneAxes::kTargetUncertainty}) {
    if (name == plane_axes_name(a)) {
      out = a;
      return true;
    }
  }
  return false;
}

bool parse_method(const std::string& name, Method& out) {
  for (Method m : {Method::kSps, Method::kSpsRandom, Method::kSls}) {
    if (name == method_name(m)) {
      out = m;
      return true;
    }
  }
  return false;
}

namespace {

const SearchOptions& validated(const SearchOptions& options) {
  validate_options(options);
  return options;
}

}  // namespace

PlaneSearch::PlaneSearch(const SearchOptions& options)
    : options_(validated(options)),
      rng_(options.seed),
      data_(options.dims),
      model_(std::make_shared<PreferenceModel>(options.dims, options.model)),
      plain_btl_scale_(options.model.btl_scale) {
  plane_ = first_plane(options_.dims, rng_);
  const Eigen::VectorXd scale = options_.perceptual_scale;
  const Eigen::MatrixXd metric = options_.perceptual_metric;
  set_perceptual_scale(scale, metric);
  const Population population = options_.population;
  set_population(population);
}

void PlaneSearch::set_population(const Population& population) {
  // The perceptual scale may come later: a unit scale stands in for it here.
  if (!population.empty()) {
    validate_target_model({PerceptualMetric(Eigen::VectorXd::Ones(options_.dims)), population,
                           options_.choice_temperature_mm},
                          options_.dims);
  }
  options_.population = population;
}

void PlaneSearch::set_min_plane_length(double length) {
  if (!(length >= 0.0 && length <= 1e4)) {
    throw std::invalid_argument("the smallest plane length must lie in [0, 10000]");
  }
  options_.min_plane_length = length;
}

void PlaneSearch::set_uncertainty_min_side(double length) {
  if (!(length >= 0.0 && length <= 1e4)) {
    throw std::invalid_argument("the uncertainty planes' smallest side must lie in [0, 10000]");
  }
  options_.uncertainty_min_side = length;
}

void PlaneSearch::set_choice_temperature(double mm) {
  if (!(mm >= 1e-6 && mm <= 1e4)) {
    throw std::invalid_argument("the choice temperature must lie in [1e-6, 10000]");
  }
  options_.choice_temperature_mm = mm;
}

void PlaneSearch::set_uncertainty_size(const UncertaintyPlaneSize& size) {
  validate_uncertainty_size(size);
  options_.uncertainty_extent = size.extent;
  options_.uncertainty_min_lengths = size.min_lengths;
  options_.choice_region_slack = size.region_slack;
}

void PlaneSearch::set_perceptual_scale(const Eigen::VectorXd& scale,
                                       const Eigen::MatrixXd& metric) {
  if (scale.size() == 0) {
    options_.perceptual_scale.resize(0);
    options_.perceptual_metric.resize(0, 0);
    metric_.reset();
    options_.model.length_scale_factors.resize(0);
    options_.model.btl_scale = plain_btl_scale_;
    return;
  }
  if (scale.size() != options_.dims || !scale.allFinite() || (scale.array() <= 0.0).any()) {
    throw std::invalid_argument("the perceptual scale needs " + std::to_string(options_.dims) +
                                " positive finite entries");
  }
  PerceptualMetric checked(scale, metric);  // throws before anything changes
  metric_ = std::move(checked);
  options_.perceptual_scale = scale;
  options_.perceptual_metric = metric;
  options_.model.btl_scale = options_.perceptual_btl_scale;
  // Relative to the geometric mean, so the overall prior is unchanged; limited to a factor of
  // 16 either way so that no direction is frozen or ignored entirely (the default body
  // model's directions span 22-354 mm, a factor of 4.6 either side of their mean).
  const double mean_log = scale.array().log().mean();
  if (options_.perceptual_length_scales) {
    options_.model.length_scale_factors =
        (mean_log - scale.array().log()).exp().max(1.0 / 16.0).min(16.0).matrix();
  } else {
    options_.model.length_scale_factors.resize(0);
  }
}

std::vector<std::pair<double, double>> PlaneSearch::representative_coordinates() const {
  std::vector<std::pair<double, double>> st{{0.0, 0.0}, {1.0, 1.0}};
  if (!plane_.is_line()) {
    st.insert(st.end(), {{-1.0, -1.0}, {1.0, -1.0}, {-1.0, 1.0}});
    if (options_.representatives >= 9)
      st.insert(st.end(), {{-1.0, 0.0}, {0.0, -1.0}, {1.0, 0.0}, {0.0, 1.0}});
  }
  return st;
}

Plane visible_first_plane(const Eigen::VectorXd& scale) {
  const Eigen::Index d = scale.size();
  Plane p;
  p.c = Eigen::VectorXd::Constant(d, 0.5);
  p.u = Eigen::VectorXd::Zero(d);
  p.v = Eigen::VectorXd::Zero(d);
  if (d == 0) return p;
  Eigen::Index first = 0;
  for (Eigen::Index k = 1; k < d; ++k) {
    if (scale(k) > scale(first)) first = k;
  }
  p.u(first) = kVisibleFirstPlaneExtent;
  if (d > 1) {
    Eigen::Index second = first == 0 ? 1 : 0;
    for (Eigen::Index k = 0; k < d; ++k) {
      if (k != first && scale(k) > scale(second)) second = k;
    }
    p.v(second) = kVisibleFirstPlaneExtent;
  } else {
    // A line (SLS-style segment) needs u to span both sides: c - u .. c + u is not a line's
    // meaning (c .. c + u), so start at the lower end instead.
    p.c(0) = 0.5 - kVisibleFirstPlaneExtent;
    p.u(0) = 2.0 * kVisibleFirstPlaneExtent;
    p.u_neg_scale = 0.0;
  }
  return p;
}

bool PlaneSearch::use_visible_first_plane() {
  if (options_.perceptual_scale.size() != options_.dims || !history_.empty() ||
      data_.point_count() > 0) {
    return false;
  }
  return visible_start(plane_);
}

bool PlaneSearch::visible_start(Plane& plane) const {
  if (options_.perceptual_scale.size() != options_.dims) return false;
  // A population whose coordinates change together (a photo's colour balance across the
  // tones): the first plane spans the directions in which its designs differ most as a person
  // sees them, its principal axes, as the later uncertainty planes span the estimate's. With
  // independent coordinates those are the most visible coordinates, which
  // visible_first_plane takes at the extent measured for bodies.
  if (options_.population.correlation.size() > 0) {
    if (auto first = population_plane(options_.population.mean)) {
      plane = *first;
      return true;
    }
  }
  plane = hold_ ? held_first_plane(*hold_, options_.perceptual_scale, kHeldFirstPlaneExtent)
                : visible_first_plane(options_.perceptual_scale);
  return true;
}

void PlaneSearch::set_hold(std::shared_ptr<const SearchHold> hold) {
  hold_ = std::move(hold);
}

void PlaneSearch::submit(const Eigen::VectorXd& chosen,
                         const std::vector<std::vector<Eigen::VectorXd>>& extra_comparisons,
                         const std::vector<Eigen::VectorXd>& shown_representatives,
                         bool set_directly) {
  const auto start = std::chrono::steady_clock::now();
  if (chosen.size() != options_.dims) {
    throw std::invalid_argument("the chosen point has " + std::to_string(chosen.size()) +
                                " entries, expected " + std::to_string(options_.dims));
  }
  if (!chosen.allFinite()) throw std::invalid_argument("the chosen point has NaN or infinity");
  for (const auto& comparison : extra_comparisons) {
    for (const auto& x : comparison) {
      if (x.size() != options_.dims || !x.allFinite()) {
        throw std::invalid_argument("an extra comparison holds a malformed point");
      }
    }
  }
  if (!shown_representatives.empty()) {
    const std::size_t expected = representative_coordinates().size();
    if (shown_representatives.size() != expected) {
      throw std::invalid_argument("expected " + std::to_string(expected) +
                                  " shown representatives, got " +
                                  std::to_string(shown_representatives.size()));
    }
    for (const auto& r : shown_representatives) {
      if (r.size() != options_.dims || !r.allFinite()) {
        throw std::invalid_argument("a shown representative is a malformed point");
      }
    }
  }

  history_.push_back(Snapshot{plane_, data_.point_count(), data_.preference_count(),
                              model_->params(), model_->latent(), rng_state()});

  const Eigen::VectorXd x = chosen.cwiseMax(0.0).cwiseMin(1.0);
  std::vector<Eigen::VectorXd> representatives{plane_.c, plane_.c + plane_.u};
  if (!plane_.is_line()) {
    representatives.push_back(plane_.c - plane_.u_neg_scale * plane_.u);
    representatives.push_back(plane_.c + plane_.v);
    representatives.push_back(plane_.c - plane_.v);
    if (options_.representatives >= 9) {
      for (double s : {-1.0, 1.0}) {
        representatives.push_back(plane_.point(s, 0.0).cwiseMax(0.0).cwiseMin(1.0));
        representatives.push_back(plane_.point(0.0, s).cwiseMax(0.0).cwiseMin(1.0));
      }
    }
  }
  if (!shown_representatives.empty()) {
    representatives.clear();
    for (const auto& r : shown_representatives) {
      representatives.push_back(r.cwiseMax(0.0).cwiseMin(1.0));
    }
  }
  data_.add_preference(x, representatives);
  for (const auto& comparison : extra_comparisons) {
    if (comparison.size() < 2) continue;
    data_.add_preference(comparison.front(),
                         std::vector<Eigen::VectorXd>(comparison.begin() + 1, comparison.end()));
  }
  try {
    model_ =
        std::make_shared<PreferenceModel>(PreferenceModel::fit(data_, options_.model, *model_));
    propose_next_plane(x, set_directly);
    // Never keep a state that could not be saved and read back (from_json's limits): go back
    // to the state before this submission instead.
    const KernelParams& p = model_->params();
    const auto in = [](double v, double lo, double hi) {
      return std::isfinite(v) && v >= lo && v <= hi;
    };
    bool ok =
        in(p.amplitude, kMinHyper, kMaxHyper) && model_->latent().allFinite() &&
        (model_->latent().size() == 0 || model_->latent().cwiseAbs().maxCoeff() <= kMaxLatent) &&
        plane_.c.allFinite() && plane_.u.allFinite() && plane_.v.allFinite() &&
        plane_.c.minCoeff() >= 0.0 && plane_.c.maxCoeff() <= 1.0 &&
        plane_.u.cwiseAbs().maxCoeff() <= kMaxPlaneExtent &&
        (plane_.v.size() == 0 || plane_.v.cwiseAbs().maxCoeff() <= kMaxPlaneExtent) &&
        in(plane_.u_neg_scale, 0.0, 1.0);
    for (Eigen::Index i = 0; ok && i < p.length_scales.size(); ++i) {
      ok = in(p.length_scales[i], kMinHyper, kMaxHyper);
    }
    if (!ok) throw std::runtime_error("the optimizer produced non-finite or absurd values");
  } catch (...) {
    undo();
    throw;
  }
  last_submit_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool PlaneSearch::replace_uncertainty_plane() {
  if (!uncertainty_plane_) return false;
  const PlaneAxes axes = options_.plane_axes;
  options_.plane_axes = PlaneAxes::kExpectedImprovement;
  try {
    propose_next_plane(last_choice_, last_set_directly_);
  } catch (...) {
    options_.plane_axes = axes;
    throw;
  }
  options_.plane_axes = axes;
  uncertainty_plane_ = false;
  return true;
}

std::optional<Plane> PlaneSearch::population_plane(const Eigen::VectorXd& c, int axes_pair) const {
  const Population& population = options_.population;
  if (hold_ || options_.method != Method::kSps ||
      options_.plane_axes != PlaneAxes::kTargetUncertainty || population.empty() || !metric_) {
    return std::nullopt;
  }
  return uncertainty_plane(c, population_covariance(population), *metric_,
                           options_.uncertainty_extent, uncertainty_min_side_of(options_),
                           axes_pair);
}

bool PlaneSearch::replace_with_population_plane(int axes_pair) {
  if (plane_.is_line()) return false;
  auto plane = population_plane(plane_.best(), axes_pair);
  if (!plane) return false;
  plane_ = *plane;
  uncertainty_plane_ = false;
  return true;
}

bool PlaneSearch::replace_with_plane_part(double s, double t, double half) {
  auto part = plane_part(plane_, s, t, half);
  if (!part) return false;
  plane_ = *part;
  uncertainty_plane_ = false;
  return true;
}

void PlaneSearch::propose_next_plane(const Eigen::VectorXd& last_choice, bool set_directly) {
  const Eigen::VectorXd best = build_next_plane(last_choice, set_directly);
  // The current best is the point the plane was built around, wherever the construction put
  // the plane's centre (moved into the box, or forward so that x+ is a corner); where it is
  // not on the plane's square (it should be), the centre as before.
  if ((plane_.best() - best).norm() > 1e-9) {
    const auto at = plane_coordinates(plane_, best);
    plane_.best_s = at ? at->first : 0.0;
    plane_.best_t = at ? at->second : 0.0;
  }
}

Eigen::VectorXd PlaneSearch::build_next_plane(const Eigen::VectorXd& last_choice,
                                              bool set_directly) {
  last_choice_ = last_choice;
  last_set_directly_ = set_directly;
  uncertainty_plane_ = false;
  Eigen::VectorXd x_plus = last_choice;
  // A point the user set directly is where the search goes on from, as they asked.
  if (!set_directly && options_.current_best == CurrentBest::kPosteriorMean) {
    const int best = model_->best_observed_index();
    if (best >= 0) x_plus = model_->points().col(best);
  }
  const bool mean_centre = !set_directly && options_.centre_on_mean_maximum && metric_;
  // None: no estimate of the design in mind (no population, or not centring on it).
  const std::optional<TargetModel> target =
      mean_centre && !options_.population.empty()
          ? std::optional<TargetModel>(TargetModel{*metric_, options_.population,
                                                   options_.choice_temperature_mm,
                                                   options_.choice_region_slack})
          : std::nullopt;
  if (hold_) {
    // Every point shown lies on the held surface: the centre is sought there too (on the
    // tangent plane through the best point, then moved onto the surface; the estimate of the
    // design in mind, made from choices that all lie on the surface, is moved onto it).
    x_plus = hold_->project(x_plus);
    if (target) {
      // Moved onto the surface as the choices allow (estimate_given_holds), then projected
      // the rest of the way (the surface is curved; the move is first order).
      const Eigen::VectorXd estimate = estimate_target(data_, *target, x_plus);
      const Eigen::VectorXd given = estimate_given_holds(
          estimate, hold_->project(estimate), target_posterior_covariance(data_, *target, estimate),
          hold_->normals(estimate));
      x_plus = hold_->project(given);
    } else if (mean_centre) {
      const TangentSpace tangent(hold_->normals(x_plus), options_.dims);
      x_plus = hold_->project(
          maximize_posterior_mean_on_tangent(*model_, x_plus, tangent, 4, options_.threads));
    }
  } else if (target) {
    x_plus = estimate_target(data_, *target, x_plus);
  } else if (mean_centre) {
    x_plus = maximize_posterior_mean(*model_, x_plus, 4, 60, options_.threads);
  }
  if (options_.method == Method::kSpsRandom) {
    plane_ = random_plane(x_plus, rng_);
    return x_plus;
  }
  const bool uncertain_axes = options_.method == Method::kSps && target &&
                              options_.plane_axes != PlaneAxes::kExpectedImprovement;
  if (uncertain_axes) {
    // With holds the design in mind keeps the held values: the uncertainty left is the one
    // given them, whose axes lie in the held surface's tangent space at the estimate.
    Eigen::MatrixXd covariance = target_posterior_covariance(data_, *target, x_plus);
    if (hold_) covariance = covariance_given_holds(covariance, hold_->normals(x_plus));
    // Where the box leaves no such plane (the estimate near a face, uncertain along barely
    // visible directions), the paper's plane, built inside the box.
    if (auto plane = uncertainty_plane(x_plus, covariance, *metric_, options_.uncertainty_extent,
                                       uncertainty_min_side_of(options_))) {
      plane_ = *plane;
      uncertainty_plane_ = true;
      return x_plus;
    }
  }
  const double best_mean = model_->mean(x_plus);
  // One construction for both: a free search is a held one whose tangent space is the whole
  // space.
  const TangentSpace space =
      hold_ ? TangentSpace(hold_->normals(x_plus), options_.dims) : TangentSpace();
  EiSearchSettings ei;
  ei.starts = options_.ei_restarts;
  ei.threads = options_.threads;
  const Eigen::VectorXd x_ei =
      maximize_expected_improvement(*model_, best_mean, x_plus, rng_, ei, space);
  if (options_.method == Method::kSls) {
    plane_ = sls_line(x_plus, x_ei);
    return x_plus;
  }
  PlaneSearchSettings ps;
  ps.restarts = options_.plane_restarts;
  ps.threads = options_.threads;
  ps.perceptual_scale = options_.perceptual_scale;
  ps.min_plane_length = options_.min_plane_length;
  ps.keep_centre = set_directly;
  plane_ = sps_plane(*model_, x_plus, x_ei, best_mean, rng_, ps, space);
  return x_plus;
}

double PlaneSearch::posterior_mean(const Eigen::VectorXd& x) const {
  return model_->mean(x);
}

double PlaneSearch::posterior_variance(const Eigen::VectorXd& x) const {
  return model_->variance(x);
}

double PlaneSearch::expected_improvement(const Eigen::VectorXd& x) const {
  const int best = model_->best_observed_index();
  const double best_mean = best >= 0 ? model_->mean(model_->points().col(best)) : 0.0;
  return sps::expected_improvement(*model_, x, best_mean);
}

void PlaneSearch::start_over() {
  data_ = PreferenceData(options_.dims);
  model_ = std::make_shared<PreferenceModel>(options_.dims, options_.model);
  history_.clear();
  ++start_overs_;
  uncertainty_plane_ = false;
  plane_ = first_plane(options_.dims, rng_);
  visible_start(plane_);
}

bool PlaneSearch::undo() {
  if (history_.empty()) return false;
  const Snapshot s = history_.back();
  history_.pop_back();
  uncertainty_plane_ = false;
  data_.truncate(s.points, s.preferences);
  model_ = s.points == 0
               ? std::make_shared<PreferenceModel>(options_.dims, options_.model)
               : std::make_shared<PreferenceModel>(data_, options_.model, s.params, s.latent);
  plane_ = s.plane;
  set_rng_state(s.rng_state);
  return true;
}

std::string PlaneSearch::rng_state() const {
  std::ostringstream out;
  out << rng_;
  return out.str();
}

void PlaneSearch::set_rng_state(const std::string& state) {
  std::istringstream in(state);
  in >> rng_;
  if (in.fail()) throw std::runtime_error("the random generator state is unreadable");
}

std::string PlaneSearch::to_json() const {
  const ModelSettings& m = options_.model;
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["options"] = {{"dims", options_.dims},
                  {"seed", options_.seed},
                  {"method", method_name(options_.method)},
                  {"current_best", current_best_name(options_.current_best)},
                  {"plane_restarts", options_.plane_restarts},
                  {"ei_restarts", options_.ei_restarts},
                  {"threads", options_.threads},
                  {"representatives", options_.representatives},
                  {"model",
                   {{"amplitude_prior", m.amplitude_prior},
                    {"length_scale_prior", m.length_scale_prior},
                    {"prior_log_variance", m.prior_log_variance},
                    {"btl_scale", m.btl_scale},
                    {"noise_variance", m.noise_variance},
                    {"max_hyper_iterations", m.max_hyper_iterations},
                    {"max_points", m.max_points}}}};
  if (options_.perceptual_scale.size() > 0) {
    j["options"]["perceptual_scale"] = vec_to_json(options_.perceptual_scale);
    if (options_.perceptual_metric.size() > 0) {
      // Row by row, dims x dims entries.
      const Eigen::MatrixXd rows = options_.perceptual_metric.transpose();
      j["options"]["perceptual_metric"] =
          vec_to_json(Eigen::Map<const Eigen::VectorXd>(rows.data(), rows.size()));
    }
    j["options"]["min_plane_length"] = options_.min_plane_length;
    j["options"]["perceptual_length_scales"] = options_.perceptual_length_scales;
    j["options"]["centre_on_mean_maximum"] = options_.centre_on_mean_maximum;
    j["options"]["perceptual_btl_scale"] = options_.perceptual_btl_scale;
    j["options"]["plain_btl_scale"] = plain_btl_scale_;
  }
  if (!options_.population.empty()) {
    j["options"]["population_mean"] = vec_to_json(options_.population.mean);
    j["options"]["population_sd"] = vec_to_json(options_.population.sd);
    if (options_.population.correlation.size() > 0) {
      // Row by row, dims x dims entries.
      const Eigen::MatrixXd rows = options_.population.correlation.transpose();
      j["options"]["population_correlation"] =
          vec_to_json(Eigen::Map<const Eigen::VectorXd>(rows.data(), rows.size()));
    }
    j["options"]["choice_temperature_mm"] = options_.choice_temperature_mm;
    j["options"]["plane_axes"] = plane_axes_name(options_.plane_axes);
    j["options"]["uncertainty_extent"] = options_.uncertainty_extent;
    j["options"]["uncertainty_min_lengths"] = options_.uncertainty_min_lengths;
    j["options"]["uncertainty_min_side"] = options_.uncertainty_min_side;
    j["options"]["choice_region_slack"] = options_.choice_region_slack;
  }
  j["rng"] = rng_state();
  json points = json::array();
  for (Eigen::Index i = 0; i < data_.points().cols(); ++i) {
    points.push_back(vec_to_json(data_.points().col(i)));
  }
  j["points"] = std::move(points);
  json prefs = json::array();
  for (const Preference& p : data_.preferences()) {
    prefs.push_back({{"chosen", p.chosen}, {"others", p.others}});
  }
  j["preferences"] = std::move(prefs);
  j["params"] = params_to_json(model_->params());
  j["latent"] = vec_to_json(model_->latent());
  j["plane"] = plane_to_json(plane_);
  json history = json::array();
  for (const Snapshot& s : history_) {
    history.push_back({{"plane", plane_to_json(s.plane)},
                       {"points", s.points},
                       {"preferences", s.preferences},
                       {"params", params_to_json(s.params)},
                       {"latent", vec_to_json(s.latent)},
                       {"rng", s.rng_state}});
  }
  j["history"] = std::move(history);
  j["start_overs"] = start_overs_;
  return j.dump();
}

PlaneSearch PlaneSearch::from_json(const std::string& json_text) {
  try {
    const json j = json_fields::parse_bounded(json_text);
    if (!j.is_object() || j.value("format", "") != kFormat) {
      throw std::runtime_error("not a plane-search state (format field missing or different)");
    }
    if (int_from_json(j.at("version"), "version", 0, 1000000) != kVersion) {
      throw std::runtime_error("unsupported version " + json_fields::brief(j.at("version")));
    }
    // Every option is checked before the search (and its per-dimension arrays) exists.
    const json& o = j.at("options");
    SearchOptions options;
    options.dims = static_cast<int>(int_from_json(o.at("dims"), "dims", 1, kMaxSearchDims));
    if (!o.at("seed").is_number_unsigned() && !o.at("seed").is_number_integer()) {
      throw std::runtime_error("seed must be an integer");
    }
    options.seed = static_cast<std::uint64_t>(
        o.at("seed").is_number_unsigned()
            ? o.at("seed").get<std::uint64_t>()
            : static_cast<std::uint64_t>(int_from_json(o.at("seed"), "seed", 0, LLONG_MAX)));
    if (!parse_method(json_fields::text(o, "method", "method", 64), options.method)) {
      throw std::runtime_error("unknown method " + json_fields::brief(o.at("method")));
    }
    options.current_best =
        json_fields::text(o, "current_best", "current_best", 64) == "last-selection"
            ? CurrentBest::kLastSelection
            : CurrentBest::kPosteriorMean;
    options.plane_restarts =
        static_cast<int>(int_from_json(o.at("plane_restarts"), "plane_restarts", 0, 1000));
    options.ei_restarts =
        static_cast<int>(int_from_json(o.at("ei_restarts"), "ei_restarts", 0, 100000));
    options.threads = static_cast<int>(int_from_json(o.at("threads"), "threads", 1, 256));
    options.representatives =
        o.contains("representatives")
            ? static_cast<int>(int_from_json(o.at("representatives"), "representatives", 5, 9))
            : 5;
    const json& m = o.at("model");
    ModelSettings& ms = options.model;
    ms.amplitude_prior =
        double_from_json(m.at("amplitude_prior"), "amplitude_prior", kMinHyper, kMaxHyper);
    ms.length_scale_prior =
        double_from_json(m.at("length_scale_prior"), "length_scale_prior", kMinHyper, kMaxHyper);
    ms.prior_log_variance =
        double_from_json(m.at("prior_log_variance"), "prior_log_variance", 1e-8, 100.0);
    ms.btl_scale = double_from_json(m.at("btl_scale"), "btl_scale", 1e-8, 1e3);
    ms.noise_variance = double_from_json(m.at("noise_variance"), "noise_variance", 1e-12, 1.0);
    ms.max_hyper_iterations = static_cast<int>(
        int_from_json(m.at("max_hyper_iterations"), "max_hyper_iterations", 0, 100000));
    if (m.contains("max_points")) {
      ms.max_points = static_cast<int>(int_from_json(m.at("max_points"), "max_points", 2, 10000));
    }

    if (o.contains("perceptual_scale")) {
      options.perceptual_scale =
          vec_from_json(o.at("perceptual_scale"), "perceptual_scale", options.dims, 1e-9, 1e9);
      // Files from before the full metric see the coordinates independently. Symmetry and
      // definiteness are checked with the scale (set_perceptual_scale).
      if (o.contains("perceptual_metric")) {
        const Eigen::VectorXd entries =
            vec_from_json(o.at("perceptual_metric"), "perceptual_metric",
                          static_cast<Eigen::Index>(options.dims) * options.dims, -1e18, 1e18);
        options.perceptual_metric =
            Eigen::Map<const Eigen::MatrixXd>(entries.data(), options.dims, options.dims)
                .transpose();
      }
      if (o.contains("min_plane_length")) {
        options.min_plane_length =
            double_from_json(o.at("min_plane_length"), "min_plane_length", 0.0, 1e4);
      }
      // Files from before these options were searched with the paper's centre and sharp
      // likelihood and without perceptual length scales; they keep that behaviour.
      options.perceptual_length_scales = o.value("perceptual_length_scales", false);
      options.centre_on_mean_maximum = o.value("centre_on_mean_maximum", false);
      options.perceptual_btl_scale =
          o.contains("perceptual_btl_scale")
              ? double_from_json(o.at("perceptual_btl_scale"), "perceptual_btl_scale", 1e-8, 1e3)
              : ms.btl_scale;
      if (o.contains("plain_btl_scale")) {
        ms.btl_scale = double_from_json(o.at("plain_btl_scale"), "plain_btl_scale", 1e-8, 1e3);
      }
    }
    // Files from before the target estimate have no population: their planes stay centred
    // on the posterior-mean maximum.
    if (o.contains("population_mean") || o.contains("population_sd")) {
      if (!o.contains("population_mean") || !o.contains("population_sd")) {
        throw std::runtime_error(o.contains("population_mean")
                                     ? "population_mean is given without population_sd"
                                     : "population_sd is given without population_mean");
      }
      options.population.mean =
          vec_from_json(o.at("population_mean"), "population_mean", options.dims, 0.0, 1.0);
      options.population.sd =
          vec_from_json(o.at("population_sd"), "population_sd", options.dims, 1e-9, 1e3);
      // Files from before correlated populations have independent coordinates. The matrix's
      // symmetry and definiteness are checked with the rest of the population (set_population).
      if (o.contains("population_correlation")) {
        const Eigen::VectorXd entries =
            vec_from_json(o.at("population_correlation"), "population_correlation",
                          static_cast<Eigen::Index>(options.dims) * options.dims, -1.0, 1.0);
        options.population.correlation =
            Eigen::Map<const Eigen::MatrixXd>(entries.data(), options.dims, options.dims)
                .transpose();
      }
      if (o.contains("choice_temperature_mm")) {
        options.choice_temperature_mm =
            double_from_json(o.at("choice_temperature_mm"), "choice_temperature_mm", 1e-6, 1e4);
      }
      // Files from before the uncertainty planes keep the paper's axes.
      if (o.contains("plane_axes") &&
          !parse_plane_axes(json_fields::text(o, "plane_axes", "plane_axes", 64),
                            options.plane_axes)) {
        throw std::runtime_error("unknown plane_axes " + json_fields::brief(o.at("plane_axes")));
      }
      // Read as numbers here; their ranges are validate_uncertainty_size's, checked when the
      // search is made from the options.
      const auto number = [&o](const char* name, double& value) {
        if (o.contains(name)) value = double_from_json(o.at(name), name, -1e6, 1e6);
      };
      number("uncertainty_extent", options.uncertainty_extent);
      number("uncertainty_min_lengths", options.uncertainty_min_lengths);
      // Files saved before it keep their planes' sides as they were.
      if (o.contains("uncertainty_min_side")) {
        options.uncertainty_min_side =
            double_from_json(o.at("uncertainty_min_side"), "uncertainty_min_side", 0.0, 1e4);
      }
      // Files saved before it get it for their planes still to come (it reads their choices).
      number("choice_region_slack", options.choice_region_slack);
    }
    PlaneSearch search(options);
    const int d = options.dims;
    const json& points = j.at("points");
    const json& preferences = j.at("preferences");
    if (!points.is_array() || !preferences.is_array()) {
      throw std::runtime_error("points and preferences must be arrays");
    }
    if (static_cast<long long>(points.size()) > kMaxStoredPoints ||
        static_cast<long long>(preferences.size()) > kMaxStoredPreferences) {
      throw std::runtime_error("more points or preferences than a session can hold");
    }
    for (const json& p : points)
      search.data_.add_point_exact(vec_from_json(p, "point", d, 0.0, 1.0));
    const int n = search.data_.point_count();
    // max_index[k]: the largest point index used by the first k preferences; a snapshot of
    // (points, preferences) is consistent only if max_index[preferences] < points.
    std::vector<int> max_index{-1};
    for (const json& p : preferences) {
      Preference pref;
      pref.chosen = static_cast<int>(int_from_json(p.at("chosen"), "preference index", 0, n - 1));
      const json& others = p.at("others");
      if (!others.is_array() || others.empty() || others.size() > static_cast<std::size_t>(n)) {
        throw std::runtime_error("a preference has no or too many rejected points");
      }
      std::vector<bool> seen(static_cast<std::size_t>(n), false);
      seen[static_cast<std::size_t>(pref.chosen)] = true;
      int largest = pref.chosen;
      for (const json& other : others) {
        const int index = static_cast<int>(int_from_json(other, "preference index", 0, n - 1));
        if (seen[static_cast<std::size_t>(index)]) {
          throw std::runtime_error("a preference repeats a point");
        }
        seen[static_cast<std::size_t>(index)] = true;
        pref.others.push_back(index);
        largest = std::max(largest, index);
      }
      search.data_.add_preference_indices(std::move(pref));
      max_index.push_back(std::max(max_index.back(), largest));
    }
    search.set_rng_state(j.at("rng").get<std::string>());
    const KernelParams params = params_from_json(j.at("params"), d);
    // The model holds latent values for the points of its window (all points in a short
    // session, the newest ones in a long one).
    const auto window_points = [&](int points, int preferences) {
      PreferenceData prefix = search.data_;
      prefix.truncate(points, preferences);
      return static_cast<Eigen::Index>(model_window(prefix, options.model).point_count());
    };
    const Eigen::VectorXd latent =
        vec_from_json(j.at("latent"), "latent", window_points(n, search.data_.preference_count()),
                      -kMaxLatent, kMaxLatent);
    search.model_ = n == 0 ? std::make_shared<PreferenceModel>(d, search.options_.model)
                           : std::make_shared<PreferenceModel>(search.data_, search.options_.model,
                                                               params, latent);
    search.plane_ = plane_from_json(j.at("plane"), d);
    const json& history = j.at("history");
    if (!history.is_array() || static_cast<long long>(history.size()) > kMaxStoredPreferences) {
      throw std::runtime_error("history must be an array of at most " +
                               std::to_string(kMaxStoredPreferences) + " entries");
    }
    int previous_points = 0;
    int previous_preferences = 0;
    for (const json& h : history) {
      // Undo restores each snapshot, so each one must be a state the search could have had:
      // a prefix of the data (growing from one snapshot to the next) whose preferences refer
      // only to its own points, valid hyperparameters and a readable generator state.
      Snapshot s;
      s.points = static_cast<int>(int_from_json(h.at("points"), "history points", 0, n));
      s.preferences = static_cast<int>(int_from_json(h.at("preferences"), "history preferences", 0,
                                                     search.data_.preference_count()));
      if (s.points < previous_points || s.preferences < previous_preferences) {
        throw std::runtime_error("history snapshots are out of order");
      }
      if (max_index[static_cast<std::size_t>(s.preferences)] >= s.points) {
        throw std::runtime_error("a history snapshot has preferences pointing past its " +
                                 std::to_string(s.points) + " points");
      }
      previous_points = s.points;
      previous_preferences = s.preferences;
      s.plane = plane_from_json(h.at("plane"), d);
      s.params = params_from_json(h.at("params"), d);
      s.latent = vec_from_json(h.at("latent"), "history latent",
                               window_points(s.points, s.preferences), -kMaxLatent, kMaxLatent);
      s.rng_state = h.at("rng").get<std::string>();
      check_rng_state(s.rng_state, "history entry " + std::to_string(search.history_.size() + 1));
      search.history_.push_back(std::move(s));
    }
    search.start_overs_ =
        j.contains("start_overs")
            ? static_cast<int>(int_from_json(j.at("start_overs"), "start_overs", 0, INT_MAX))
            : 0;
    return search;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error("plane-search state: " + json_fields::library_message(e));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("plane-search state: ") + e.what());
  } catch (const std::length_error& e) {
    throw std::runtime_error(std::string("plane-search state: sizes out of range (") + e.what() +
                             ")");
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("plane-search state: too large to load (out of memory)");
  }
}

}  // namespace sps
