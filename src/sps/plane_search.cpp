#include "sps/plane_search.hpp"

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "sps/expected_improvement.hpp"
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

Eigen::VectorXd vec_from_json(const json& j, const char* what, Eigen::Index expected = -1) {
  if (!j.is_array()) throw std::runtime_error(std::string(what) + " is not an array");
  Eigen::VectorXd v(static_cast<Eigen::Index>(j.size()));
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_number()) throw std::runtime_error(std::string(what) + " holds a non-number");
    v(static_cast<Eigen::Index>(i)) = j[i].get<double>();
  }
  if (!v.allFinite()) throw std::runtime_error(std::string(what) + " holds NaN or infinity");
  if (expected >= 0 && v.size() != expected) {
    throw std::runtime_error(std::string(what) + " has " + std::to_string(v.size()) +
                             " entries, expected " + std::to_string(expected));
  }
  return v;
}

json plane_to_json(const Plane& p) {
  return {{"c", vec_to_json(p.c)},
          {"u", vec_to_json(p.u)},
          {"v", vec_to_json(p.v)},
          {"u_neg_scale", p.u_neg_scale}};
}

Plane plane_from_json(const json& j, int dims) {
  Plane p;
  p.c = vec_from_json(j.at("c"), "plane.c", dims);
  p.u = vec_from_json(j.at("u"), "plane.u", dims);
  p.v = vec_from_json(j.at("v"), "plane.v", dims);
  p.u_neg_scale = j.at("u_neg_scale").get<double>();
  if (!(p.u_neg_scale >= 0.0 && p.u_neg_scale <= 1.0)) {
    throw std::runtime_error("plane.u_neg_scale must lie in [0, 1]");
  }
  return p;
}

json params_to_json(const KernelParams& p) {
  return {{"amplitude", p.amplitude}, {"length_scales", vec_to_json(p.length_scales)}};
}

KernelParams params_from_json(const json& j, int dims) {
  KernelParams p;
  p.amplitude = j.at("amplitude").get<double>();
  p.length_scales = vec_from_json(j.at("length_scales"), "length_scales", dims);
  if (!(p.amplitude > 0.0) || (p.length_scales.array() <= 0.0).any()) {
    throw std::runtime_error("kernel hyperparameters must be positive");
  }
  return p;
}

}  // namespace

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

bool parse_method(const std::string& name, Method& out) {
  for (Method m : {Method::kSps, Method::kSpsRandom, Method::kSls}) {
    if (name == method_name(m)) {
      out = m;
      return true;
    }
  }
  return false;
}

PlaneSearch::PlaneSearch(const SearchOptions& options)
    : options_(options),
      rng_(options.seed),
      data_(options.dims),
      model_(std::make_shared<PreferenceModel>(options.dims, options.model)) {
  if (options.dims < 1 || options.dims > 1000) {
    throw std::invalid_argument("the number of dimensions must be between 1 and 1000");
  }
  plane_ = first_plane(options_.dims, rng_);
  const Eigen::VectorXd scale = options_.perceptual_scale;
  set_perceptual_scale(scale);
}

void PlaneSearch::set_perceptual_scale(const Eigen::VectorXd& scale) {
  if (scale.size() == 0) {
    options_.perceptual_scale.resize(0);
    options_.model.length_scale_factors.resize(0);
    return;
  }
  if (scale.size() != options_.dims || !scale.allFinite() || (scale.array() <= 0.0).any()) {
    throw std::invalid_argument("the perceptual scale needs " + std::to_string(options_.dims) +
                                " positive finite entries");
  }
  options_.perceptual_scale = scale;
  // Relative to the geometric mean, so the overall prior is unchanged; limited to a factor of
  // 4 either way so that no direction is frozen or ignored entirely.
  const double mean_log = scale.array().log().mean();
  if (options_.perceptual_length_scales) {
    options_.model.length_scale_factors =
        (mean_log - scale.array().log()).exp().max(0.25).min(4.0).matrix();
  } else {
    options_.model.length_scale_factors.resize(0);
  }
}

void PlaneSearch::submit(const Eigen::VectorXd& chosen,
                         const std::vector<std::vector<Eigen::VectorXd>>& extra_comparisons) {
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
  data_.add_preference(x, representatives);
  for (const auto& comparison : extra_comparisons) {
    if (comparison.size() < 2) continue;
    data_.add_preference(comparison.front(),
                         std::vector<Eigen::VectorXd>(comparison.begin() + 1, comparison.end()));
  }
  model_ = std::make_shared<PreferenceModel>(PreferenceModel::fit(data_, options_.model, *model_));
  propose_next_plane(x);
  last_submit_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void PlaneSearch::propose_next_plane(const Eigen::VectorXd& last_choice) {
  Eigen::VectorXd x_plus = last_choice;
  if (options_.current_best == CurrentBest::kPosteriorMean) {
    const int best = model_->best_observed_index();
    if (best >= 0) x_plus = model_->points().col(best);
  }
  if (options_.method == Method::kSpsRandom) {
    plane_ = random_plane(x_plus, rng_);
    return;
  }
  const double best_mean = model_->mean(x_plus);
  EiSearchSettings ei;
  ei.starts = options_.ei_restarts;
  ei.threads = options_.threads;
  const Eigen::VectorXd x_ei = maximize_expected_improvement(*model_, best_mean, x_plus, rng_, ei);
  if (options_.method == Method::kSls) {
    plane_ = sls_line(x_plus, x_ei);
    return;
  }
  PlaneSearchSettings ps;
  ps.restarts = options_.plane_restarts;
  ps.threads = options_.threads;
  ps.perceptual_scale = options_.perceptual_scale;
  ps.min_plane_length = options_.min_plane_length;
  plane_ = sps_plane(*model_, x_plus, x_ei, best_mean, rng_, ps);
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
  plane_ = first_plane(options_.dims, rng_);
}

bool PlaneSearch::undo() {
  if (history_.empty()) return false;
  const Snapshot s = history_.back();
  history_.pop_back();
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
    j["options"]["min_plane_length"] = options_.min_plane_length;
    j["options"]["perceptual_length_scales"] = options_.perceptual_length_scales;
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
    const json j = json::parse(json_text);
    if (j.value("format", "") != kFormat) {
      throw std::runtime_error("not a plane-search state (format field missing or different)");
    }
    if (j.at("version").get<int>() != kVersion) {
      throw std::runtime_error("unsupported version " + j.at("version").dump());
    }
    const json& o = j.at("options");
    SearchOptions options;
    options.dims = o.at("dims").get<int>();
    options.seed = o.at("seed").get<std::uint64_t>();
    if (!parse_method(o.at("method").get<std::string>(), options.method)) {
      throw std::runtime_error("unknown method " + o.at("method").dump());
    }
    options.current_best = o.at("current_best").get<std::string>() == "last-selection"
                               ? CurrentBest::kLastSelection
                               : CurrentBest::kPosteriorMean;
    options.plane_restarts = o.at("plane_restarts").get<int>();
    options.ei_restarts = o.at("ei_restarts").get<int>();
    options.threads = o.at("threads").get<int>();
    options.representatives = o.value("representatives", 5);
    const json& m = o.at("model");
    options.model.amplitude_prior = m.at("amplitude_prior").get<double>();
    options.model.length_scale_prior = m.at("length_scale_prior").get<double>();
    options.model.prior_log_variance = m.at("prior_log_variance").get<double>();
    options.model.btl_scale = m.at("btl_scale").get<double>();
    options.model.noise_variance = m.at("noise_variance").get<double>();
    options.model.max_hyper_iterations = m.at("max_hyper_iterations").get<int>();
    options.model.max_points = m.value("max_points", options.model.max_points);
    if (options.model.max_points < 2) throw std::runtime_error("max_points must be at least 2");

    if (o.contains("perceptual_scale")) {
      options.perceptual_scale = vec_from_json(o.at("perceptual_scale"), "perceptual_scale");
      options.min_plane_length = o.value("min_plane_length", 12.0);
      options.perceptual_length_scales = o.value("perceptual_length_scales", false);
    }
    PlaneSearch search(options);
    const int d = options.dims;
    for (const json& p : j.at("points")) search.data_.add_point_exact(vec_from_json(p, "point", d));
    for (const json& p : j.at("preferences")) {
      Preference pref;
      pref.chosen = p.at("chosen").get<int>();
      pref.others = p.at("others").get<std::vector<int>>();
      search.data_.add_preference_indices(std::move(pref));
    }
    const int n = search.data_.point_count();
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
        vec_from_json(j.at("latent"), "latent", window_points(n, search.data_.preference_count()));
    search.model_ =
        n == 0 ? std::make_shared<PreferenceModel>(d, options.model)
               : std::make_shared<PreferenceModel>(search.data_, options.model, params, latent);
    search.plane_ = plane_from_json(j.at("plane"), d);
    for (const json& h : j.at("history")) {
      Snapshot s;
      s.plane = plane_from_json(h.at("plane"), d);
      s.points = h.at("points").get<int>();
      s.preferences = h.at("preferences").get<int>();
      if (s.points < 0 || s.points > n || s.preferences < 0 ||
          s.preferences > search.data_.preference_count()) {
        throw std::runtime_error("history refers to data that does not exist");
      }
      s.params = params_from_json(h.at("params"), d);
      s.latent =
          vec_from_json(h.at("latent"), "history latent", window_points(s.points, s.preferences));
      s.rng_state = h.at("rng").get<std::string>();
      search.history_.push_back(std::move(s));
    }
    search.start_overs_ = j.value("start_overs", 0);
    return search;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("plane-search state: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("plane-search state: ") + e.what());
  }
}

}  // namespace sps
