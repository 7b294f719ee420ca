#include "survey_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

#include <Eigen/Dense>

#include "body/body_model.hpp"
#include "body/joint_names.hpp"
#include "body/measurements.hpp"

namespace default_model {

namespace {

// What each knob steers, in CrossSectionKnob's order: the measurement's name, the survey
// measure it is drawn as (cm) and where body::measure reports it on the body (metres).
struct KnobTarget {
  const char* name;
  int survey_measure;
  double body::Measurements::*measured;
  double survey_unit = 0.01;  // the survey's unit in body::measure's (cm -> m; kg stays kg)
};
// The survey's biceps girth is taken flexed and the tool's upper arm relaxed; the survey has
// no relaxed girth to convert with, so the flexed value is the target (bench-survey compares
// them the same way).
constexpr std::array<KnobTarget, kKnobCount> kKnobTargets = {{
    {"chest", k_chest_circ, &body::Measurements::chest},
    {"waist", k_waist_circ, &body::Measurements::waist},
    {"hips", k_buttock_circ, &body::Measurements::hips},
    {"neck", k_neck_circ, &body::Measurements::neck},
    {"thigh", k_thigh_circ, &body::Measurements::thigh},
    {"calf", k_calf_circ, &body::Measurements::calf},
    {"upper_arm", k_biceps_circ, &body::Measurements::upper_arm},
    {"bideltoid", k_bideltoid, &body::Measurements::bideltoid},
    {"shoulder_width", k_biacromial, &body::Measurements::shoulder_width},
    {"mass", k_weight, &body::Measurements::mass, 1.0},
}};

constexpr double kDamping = 0.01;

std::array<double, kKnobCount> knob_measures(const body::Measurements& m) {
  std::array<double, kKnobCount> out{};
  for (int k = 0; k < kKnobCount; ++k) out[k] = m.*kKnobTargets[k].measured;
  return out;
}

class BodyMeasurer {
 public:
  BodyMeasurer(const DeformationModel& deformation, const std::vector<std::array<int, 3>>& faces,
               const Eigen::MatrixXd& regressor)
      : deformation_(deformation) {
    model_.name = "generator calibration";
    model_.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (int a = 0; a < 3; ++a)
        model_.faces(static_cast<Eigen::Index>(f), a) = static_cast<std::uint32_t>(faces[f][a]);
    model_.j_regressor = regressor.cast<float>();
    model_.joint_names = body::smpl_joint_names();
    model_.parents.assign(joint_parents().begin(), joint_parents().end());
  }

  // The log of each knob's girth measured on the person's body (NaN where a slice failed).
  std::array<double, kKnobCount> log_girths(const Anthropometry& a) const {
    const Eigen::VectorXd x = deformation_.vertices(deformation_.parameters(a));
    body::BodyMesh mesh;
    const Eigen::Index V = x.size() / 3;
    mesh.vertices.resize(V, 3);
    for (Eigen::Index v = 0; v < V; ++v)
      for (int c = 0; c < 3; ++c) mesh.vertices(v, c) = static_cast<float>(x[3 * v + c]);
    mesh.joints = model_.j_regressor * mesh.vertices;
    const std::array<double, kKnobCount> g = knob_measures(body::measure(model_, mesh, true));
    std::array<double, kKnobCount> out{};
    for (int k = 0; k < kKnobCount; ++k) out[k] = g[k] > 0.0 ? std::log(g[k]) : std::nan("");
    return out;
  }

 private:
  const DeformationModel& deformation_;
  body::Model model_;
};

std::array<double, kKnobCount> log_targets(const Anthropometry& a) {
  std::array<double, kKnobCount> t{};
  for (int k = 0; k < kKnobCount; ++k)
    t[k] = std::log(kKnobTargets[k].survey_unit * a.m[kKnobTargets[k].survey_measure]);
  return t;
}

// Log residuals (target - measured) of people[0, n), measured on `threads` threads; each
// person's row is computed alone, so the result does not depend on the thread count.
Eigen::MatrixXd residuals(const BodyMeasurer& measurer, const std::vector<Anthropometry>& people,
                          int n, int threads) {
  Eigen::MatrixXd r(n, kKnobCount);
  auto work = [&](int first) {
    for (int i = first; i < n; i += threads) {
      const auto g = measurer.log_girths(people[i]);
      const auto t = log_targets(people[i]);
      for (int k = 0; k < kKnobCount; ++k) r(i, k) = t[k] - g[k];
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& t : pool) t.join();
  return r;
}

// The sum of squares of the finite residuals (a person whose slice failed counts nothing).
double finite_square_sum(const Eigen::MatrixXd& r) {
  return r.unaryExpr([](double x) { return std::isfinite(x) ? x * x : 0.0; }).sum();
}

void set_knobs(const Eigen::MatrixXd& D, std::vector<Anthropometry>& people) {
  for (auto& a : people) {
    const Eigen::VectorXd knobs = D * person_features(a);
    for (int k = 0; k < kKnobCount; ++k) a.knobs[k] = knobs[k];
  }
}

}  // namespace

const std::array<const char*, kKnobCount>& knob_measurement_names() {
  static const std::array<const char*, kKnobCount> names = [] {
    std::array<const char*, kKnobCount> n{};
    for (int k = 0; k < kKnobCount; ++k) n[k] = kKnobTargets[k].name;
    return n;
  }();
  return names;
}

CalibrationReport calibrate_population(std::vector<Anthropometry>& people,
                                       const DeformationModel& deformation,
                                       const std::vector<std::array<int, 3>>& faces,
                                       const Eigen::MatrixXd& regressor, int sample, int rounds,
                                       int threads) {
  CalibrationReport report;
  if (people.empty()) return report;
  report.female = people.front().female;
  threads = std::max(1, threads);
  const int n = std::clamp(sample, 1, static_cast<int>(people.size()));
  report.sample = n;
  const BodyMeasurer measurer(deformation, faces, regressor);

  // The knobs' Jacobian (d log girth / d knob) at the sex's mean person: the survey's means
  // and the sample's mean factors.
  Eigen::Matrix<double, kKnobCount, kKnobCount> G;
  {
    Anthropometry mean = people.front();
    const SurveyTable& t = mean.female ? kFemale : kMale;
    for (int k = 0; k < kSurveyMeasures; ++k) mean.m[k] = t.mean[k];
    mean.f = IndependentFactors{};
    for (int i = 0; i < n; ++i)
      for (const auto member : factor_members()) mean.f.*member += people[i].f.*member / n;
    constexpr double h = 0.004;
    for (int k = 0; k < kKnobCount; ++k) {
      Anthropometry up = mean, down = mean;
      up.knobs[k] += h;
      down.knobs[k] -= h;
      const auto gu = measurer.log_girths(up), gd = measurer.log_girths(down);
      for (int o = 0; o < kKnobCount; ++o) G(o, k) = (gu[o] - gd[o]) / (2 * h);
    }
  }
  // The bands overlap a little (the hips' reaches the thigh, the chest's the waist and the
  // upper arm) and the sample's own response refitted below can be poorly conditioned: a
  // damped least-squares step (Levenberg-Marquardt) keeps the steps bounded.
  using Square = Eigen::Matrix<double, kKnobCount, kKnobCount>;
  auto damped_inverse = [](const Square& J) {
    return Square((J.transpose() * J + kDamping * Square::Identity()).inverse() * J.transpose());
  };
  Square G_inverse = damped_inverse(G);

  Eigen::MatrixXd features(n, kPersonFeatures);
  for (int i = 0; i < n; ++i) features.row(i) = person_features(people[i]).transpose();

  auto summarise = [&](const Eigen::MatrixXd& r, std::array<double, kKnobCount>& rms,
                       std::array<double, kKnobCount>* bias) {
    for (int k = 0; k < kKnobCount; ++k) {
      double sum = 0, squares = 0;
      int count = 0;
      for (int i = 0; i < n; ++i) {
        if (!std::isfinite(r(i, k))) continue;
        sum += r(i, k), squares += r(i, k) * r(i, k), ++count;
      }
      rms[k] = count > 0 ? std::sqrt(squares / count) : std::nan("");
      if (bias) (*bias)[k] = count > 0 ? sum / count : std::nan("");
    }
  };

  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(kKnobCount, kPersonFeatures);
  set_knobs(D, people);
  Eigen::MatrixXd r = residuals(measurer, people, n, threads);
  summarise(r, report.rms_before, &report.bias_before);
  Eigen::MatrixXd best_D = D, best_r = r;
  double best_total = finite_square_sum(r);
  for (int round = 0; round < rounds; ++round) {
    // Ridge regression of each girth's residual on the features, over the people whose every
    // slice was found (the intercept is not shrunk).
    std::vector<int> rows;
    for (int i = 0; i < n; ++i)
      if (r.row(i).allFinite()) rows.push_back(i);
    if (rows.size() < static_cast<std::size_t>(2 * kPersonFeatures)) break;
    Eigen::MatrixXd X(rows.size(), kPersonFeatures), Y(rows.size(), kKnobCount);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      X.row(i) = features.row(rows[i]);
      Y.row(i) = r.row(rows[i]);
    }
    Eigen::MatrixXd A = X.transpose() * X;
    const double ridge = 1e-3 * static_cast<double>(rows.size());
    for (int c = 1; c < kPersonFeatures; ++c) A(c, c) += ridge;
    const Eigen::MatrixXd W = A.ldlt().solve(X.transpose() * Y).transpose();  // K x features
    const Eigen::MatrixXd step = G_inverse * W;
    D += step;
    set_knobs(D, people);
    const Eigen::MatrixXd r_before = r;
    r = residuals(measurer, people, n, threads);
    ++report.rounds;
    // The mean person's Jacobian misjudges where the girth's level moves (the waist is the
    // smallest girth of a range, the hips the largest): from the step just taken, refit it as
    // the sample's own response, residual change against knob change, person by person.
    {
      std::vector<int> both;
      for (int i = 0; i < n; ++i)
        if (r.row(i).allFinite() && r_before.row(i).allFinite()) both.push_back(i);
      if (both.size() >= static_cast<std::size_t>(4 * kKnobCount)) {
        Eigen::MatrixXd dK(both.size(), kKnobCount), dR(both.size(), kKnobCount);
        for (std::size_t i = 0; i < both.size(); ++i) {
          dK.row(i) = (step * features.row(both[i]).transpose()).transpose();
          dR.row(i) = r_before.row(both[i]) - r.row(both[i]);
        }
        const Square normal = dK.transpose() * dK;
        const Square fitted = (normal + 1e-6 * normal.trace() * Square::Identity())
                                  .ldlt()
                                  .solve(dK.transpose() * dR)
                                  .transpose();
        if (fitted.allFinite()) G_inverse = damped_inverse(fitted);
      }
    }
    const double total = finite_square_sum(r);
    if (total < best_total) best_total = total, best_D = D, best_r = r;
  }
  // Keep the best round's calibration (a later one can be worse where the levels jump).
  set_knobs(best_D, people);
  for (int k = 0; k < kKnobCount; ++k) {
    double sum = 0, squares = 0;
    for (const auto& a : people) sum += a.knobs[k], squares += a.knobs[k] * a.knobs[k];
    const double m = sum / people.size();
    report.knob_mean[k] = m;
    report.knob_sd[k] = std::sqrt(std::max(0.0, squares / people.size() - m * m));
  }
  summarise(best_r, report.rms_after, &report.bias_after);
  return report;
}

std::string describe(const CalibrationReport& report) {
  std::string s = std::string(report.female ? "female" : "male") +
                  " girths and breadths vs their draw (" + std::to_string(report.sample) +
                  " bodies, " + std::to_string(report.rounds) +
                  " rounds), RMS (bias) before -> after:";
  for (int k = 0; k < kKnobCount; ++k) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, " %s %.1f%% (%+.1f%%) -> %.1f%% (%+.1f%%)",
                  knob_measurement_names()[k], 100 * report.rms_before[k],
                  100 * report.bias_before[k], 100 * report.rms_after[k],
                  100 * report.bias_after[k]);
    s += buffer;
  }
  s += "; bands (mm at a thigh's radius, mean +- SD):";
  for (int k = 0; k < kKnobBands; ++k) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, " %s %+.1f +- %.1f", knob_measurement_names()[k],
                  1000 * report.knob_mean[k], 1000 * report.knob_sd[k]);
    s += buffer;
  }
  char spread[160];
  std::snprintf(spread, sizeof spread,
                "; the shoulders' spread %+.1f%% +- %.1f%%; the fat layer for the mass %+.1f +- "
                "%.1f mm",
                100 * report.knob_mean[kKnobShoulder], 100 * report.knob_sd[kKnobShoulder],
                1000 * report.knob_mean[kKnobMass], 1000 * report.knob_sd[kKnobMass]);
  s += spread;
  return s;
}

}  // namespace default_model
