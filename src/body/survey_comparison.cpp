#include "body/survey_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "body/measurements.hpp"

namespace body {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The p-quantile of values sorted with their weights: each value stands at the middle of its
// share of the cumulative weight, rescaled so that the first stands at 0 and the last at 1, and
// quantiles between two values are interpolated. With equal weights the k-th of n stands at
// k / (n - 1), the plain sample quantile.
double percentile(const std::vector<std::pair<double, double>>& sorted, double p) {
  if (sorted.size() == 1) return sorted[0].first;
  double total = 0.0;
  for (const auto& v : sorted) total += v.second;
  const double first = 0.5 * sorted.front().second;
  const double span = total - first - 0.5 * sorted.back().second;
  double before = 0.0;
  for (std::size_t k = 0; k + 1 < sorted.size(); ++k) {
    const double lo = (before + 0.5 * sorted[k].second - first) / span;
    const double hi = (before + sorted[k].second + 0.5 * sorted[k + 1].second - first) / span;
    if (p <= hi || k + 2 == sorted.size()) {
      const double t = hi > lo ? std::clamp((p - lo) / (hi - lo), 0.0, 1.0) : 0.0;
      return sorted[k].first + t * (sorted[k + 1].first - sorted[k].first);
    }
    before += sorted[k].second;
  }
  return sorted.back().first;
}

// Weighted statistics take positive, finite weights only.
void require_weights(const std::vector<double>& weights, const char* who) {
  for (const double w : weights) {
    if (!(w > 0.0) || !std::isfinite(w)) {
      throw std::invalid_argument(std::string(who) + ": weights must be positive and finite");
    }
  }
}

// The tool's value of a measure for one body (ratios from the girths).
double model_value(const std::string& name, const Measurements& m) {
  if (name == "waist/hips") return m.waist / m.hips;
  if (name == "chest/hips") return m.chest / m.hips;
  const MeasurementKind* kind = find_measurement(name);
  if (kind == nullptr) throw std::logic_error("no measurement " + name);
  return m.*(kind->field);
}

}  // namespace

double survey_value(const SurveyMeasure& measure, const SurveyTable& table, Eigen::Index row) {
  const auto col = [&](const std::string& c) { return table.values(row, table.column(c)); };
  if (measure.name == "bmi") {
    const double h = col("stature") * 0.001;
    return col("weightkg") * 0.1 / (h * h);
  }
  if (measure.name == "waist/hips") return col("waistcircumference") / col("buttockcircumference");
  if (measure.name == "chest/hips") return col("chestcircumference") / col("buttockcircumference");
  double sum = 0.0;
  for (const auto& c : measure.columns) sum += col(c);
  return sum * measure.scale;
}

Distribution distribution_of(std::vector<double> values) {
  return distribution_of(values, std::vector<double>(values.size(), 1.0));
}

Distribution distribution_of(const std::vector<double>& values,
                             const std::vector<double>& weights) {
  if (values.size() != weights.size()) {
    throw std::invalid_argument("distribution_of: values and weights differ in length");
  }
  require_weights(weights, "distribution_of");
  std::vector<std::pair<double, double>> kept;
  kept.reserve(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isnan(values[i])) kept.emplace_back(values[i], weights[i]);
  }
  Distribution d;
  d.count = static_cast<int>(kept.size());
  if (kept.empty()) {
    d.mean = d.sd = d.p5 = d.p50 = d.p95 = kNaN;
    return d;
  }
  double w = 0.0, w2 = 0.0, sum = 0.0;
  for (const auto& [v, wi] : kept) {
    w += wi;
    w2 += wi * wi;
    sum += wi * v;
  }
  d.mean = sum / w;
  double squares = 0.0;
  for (const auto& [v, wi] : kept) squares += wi * (v - d.mean) * (v - d.mean);
  // Reliability weights: with equal weights the denominator is n - 1, the sample SD's.
  const double dof = w - w2 / w;
  d.sd = kept.size() > 1 && dof > 0.0 ? std::sqrt(squares / dof) : 0.0;
  std::sort(kept.begin(), kept.end());
  d.p5 = percentile(kept, 0.05);
  d.p50 = percentile(kept, 0.50);
  d.p95 = percentile(kept, 0.95);
  return d;
}

const std::vector<SurveyMeasure>& survey_measures() {
  // ANSUR II lengths are millimetres; weightkg is tenths of a kilogram. The tool's landmarks
  // (src/body/measurements.hpp) follow the survey's: stature, chest, waist and buttock
  // circumference, biacromial breadth, crotch height for the inseam, acromion-radiale plus
  // radiale-stylion for the arm, and the neck, deltoid, biceps (flexed in the survey), thigh
  // and calf measures.
  static const std::vector<SurveyMeasure> measures = {
      {"height", {"stature"}, 0.001},
      {"mass", {"weightkg"}, 0.1},
      {"bmi", {"stature", "weightkg"}, 1.0},
      {"chest", {"chestcircumference"}, 0.001},
      {"waist", {"waistcircumference"}, 0.001},
      {"hips", {"buttockcircumference"}, 0.001},
      {"shoulder_width", {"biacromialbreadth"}, 0.001},
      {"inseam", {"crotchheight"}, 0.001},
      {"arm_length", {"acromionradialelength", "radialestylionlength"}, 0.001},
      {"neck", {"neckcircumference"}, 0.001},
      {"bideltoid", {"bideltoidbreadth"}, 0.001},
      {"upper_arm", {"bicepscircumferenceflexed"}, 0.001},
      {"thigh", {"thighcircumference"}, 0.001},
      {"calf", {"calfcircumference"}, 0.001},
      {"waist/hips", {"waistcircumference", "buttockcircumference"}, 1.0},
      {"chest/hips", {"chestcircumference", "buttockcircumference"}, 1.0},
  };
  return measures;
}

std::vector<std::string> survey_columns() {
  std::vector<std::string> columns;
  for (const auto& m : survey_measures()) {
    for (const auto& c : m.columns) {
      if (std::find(columns.begin(), columns.end(), c) == columns.end()) columns.push_back(c);
    }
  }
  return columns;
}

double correlation_of(const std::vector<double>& x, const std::vector<double>& y) {
  return correlation_of(x, y, std::vector<double>(x.size(), 1.0));
}

double correlation_of(const std::vector<double>& x, const std::vector<double>& y,
                      const std::vector<double>& weights) {
  if (x.size() != y.size() || x.size() != weights.size()) {
    throw std::invalid_argument("correlation_of: lengths differ");
  }
  require_weights(weights, "correlation_of");
  double n = 0.0, w = 0.0, sx = 0.0, sy = 0.0;
  const auto kept = [&](std::size_t i) { return std::isfinite(x[i]) && std::isfinite(y[i]); };
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!kept(i)) continue;
    n += 1.0;
    w += weights[i];
    sx += weights[i] * x[i];
    sy += weights[i] * y[i];
  }
  if (n < 3.0 || !(w > 0.0)) return kNaN;
  const double mx = sx / w, my = sy / w;
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!kept(i)) continue;
    sxx += weights[i] * (x[i] - mx) * (x[i] - mx);
    syy += weights[i] * (y[i] - my) * (y[i] - my);
    sxy += weights[i] * (x[i] - mx) * (y[i] - my);
  }
  return sxx > 0.0 && syy > 0.0 ? sxy / std::sqrt(sxx * syy) : kNaN;
}

PopulationComparison compare_with_survey(const Model& model,
                                         const std::vector<const SurveyTable*>& survey, int samples,
                                         unsigned seed) {
  if (samples < 2 || samples > 100000) throw std::invalid_argument("samples must be 2..100000");
  PopulationComparison out;
  out.model_name = model.name;
  out.bodies = samples;
  const auto& measures = survey_measures();
  std::vector<std::vector<double>> model_values(measures.size()), survey_values(measures.size());
  std::mt19937 rng(seed);
  std::normal_distribution<float> n01(0.0f, 1.0f);
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXf betas(model.component_count());
    for (Eigen::Index k = 0; k < betas.size(); ++k) betas[k] = n01(rng);
    const Measurements m = measure(model, betas);
    for (std::size_t i = 0; i < measures.size(); ++i) {
      model_values[i].push_back(model_value(measures[i].name, m));
    }
  }
  // Each table counts as much as the others, whatever its number of people: a model built from
  // equal numbers of women and men (the neutral one) is compared with the survey reweighted to
  // equal numbers of each sex, not with ANSUR II's two men to every woman.
  std::vector<double> survey_weights;
  for (const SurveyTable* table : survey) {
    const Eigen::Index people = table->values.rows();
    out.people += static_cast<int>(people);
    for (Eigen::Index r = 0; r < people; ++r) {
      for (std::size_t i = 0; i < measures.size(); ++i) {
        survey_values[i].push_back(survey_value(measures[i], *table, r));
      }
      survey_weights.push_back(1.0 / static_cast<double>(people));
    }
  }
  for (std::size_t i = 0; i < measures.size(); ++i) {
    ComparisonRow row;
    row.name = measures[i].name;
    row.survey = distribution_of(survey_values[i], survey_weights);
    row.model = distribution_of(model_values[i]);
    row.mean_gap_sd =
        row.survey.sd > 0.0 ? (row.model.mean - row.survey.mean) / row.survey.sd : kNaN;
    out.rows.push_back(row);
  }
  // The correlations of the measures themselves (ratios and BMI follow from them).
  for (std::size_t i = 0; i < measures.size(); ++i) {
    for (std::size_t j = i + 1; j < measures.size(); ++j) {
      const auto plain = [&](std::size_t k) {
        return measures[k].name != "bmi" && measures[k].name.find('/') == std::string::npos;
      };
      if (!plain(i) || !plain(j)) continue;
      out.correlations.push_back(
          {measures[i].name, measures[j].name,
           correlation_of(survey_values[i], survey_values[j], survey_weights),
           correlation_of(model_values[i], model_values[j])});
    }
  }
  std::stable_sort(out.correlations.begin(), out.correlations.end(),
                   [](const CorrelationGap& p, const CorrelationGap& q) {
                     const double a = std::abs(p.model - p.survey),
                                  b = std::abs(q.model - q.survey);
                     return (std::isnan(b) && !std::isnan(a)) || a > b;
                   });
  return out;
}

}  // namespace body
