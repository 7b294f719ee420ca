#include "body/survey_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <thread>
#include <utility>

#include "body/measurement_solve.hpp"
#include "body/survey_comparison.hpp"

namespace body {

const std::vector<std::string>& fit_measure_names() {
  static const std::vector<std::string> names = {"height", "mass", "chest",     "waist",
                                                 "hips",   "neck", "bideltoid", "upper_arm",
                                                 "thigh",  "calf", "inseam",    "arm_length"};
  return names;
}

SurveyFit fit_survey(const std::shared_ptr<const Model>& model,
                     const std::vector<const SurveyTable*>& survey, int sample, unsigned seed,
                     int threads, std::vector<std::string> names) {
  if (names.empty()) names = fit_measure_names();
  for (const auto& n : names) {
    const auto& all = fit_measure_names();
    if (std::find(all.begin(), all.end(), n) == all.end()) {
      std::string list;
      for (const auto& a : all) list += (list.empty() ? "" : ", ") + a;
      throw std::invalid_argument("cannot fit \"" + n + "\"; the measurements are: " + list);
    }
  }
  std::vector<std::pair<const SurveyTable*, Eigen::Index>> everyone;
  for (const SurveyTable* t : survey)
    for (Eigen::Index r = 0; r < t->values.rows(); ++r) everyone.emplace_back(t, r);
  if (sample < 1 || sample > 100000) throw std::invalid_argument("the sample must be 1..100000");
  if (static_cast<std::size_t>(sample) > everyone.size()) {
    throw std::invalid_argument("the sample of " + std::to_string(sample) +
                                " is larger than the survey's " + std::to_string(everyone.size()) +
                                " people");
  }
  // Fisher-Yates with our own index draws: std::shuffle's algorithm differs between libraries.
  std::mt19937_64 rng(seed);
  for (std::size_t i = everyone.size() - 1; i > 0; --i) {
    const std::size_t j = static_cast<std::size_t>(rng() % (i + 1));
    std::swap(everyone[i], everyone[j]);
  }
  everyone.resize(static_cast<std::size_t>(sample));

  std::vector<const SurveyMeasure*> measures;
  for (const auto& n : names) {
    const auto& all = survey_measures();
    const auto it =
        std::find_if(all.begin(), all.end(), [&](const SurveyMeasure& m) { return m.name == n; });
    if (it == all.end()) throw std::logic_error("no survey measure " + n);
    measures.push_back(&*it);
  }
  // errors[person][measure], in SI; reached[person].
  std::vector<std::vector<double>> errors(everyone.size());
  std::vector<char> reached(everyone.size(), 0);
  const Eigen::VectorXd start = Eigen::VectorXd::Constant(model->component_count(), 0.5);
  auto work = [&](std::size_t begin, std::size_t step) {
    for (std::size_t p = begin; p < everyone.size(); p += step) {
      std::vector<MeasurementTarget> targets;
      for (std::size_t k = 0; k < measures.size(); ++k) {
        targets.push_back({find_measurement(names[k]),
                           survey_value(*measures[k], *everyone[p].first, everyone[p].second)});
      }
      const MeasurementConstraints constraints(model, targets);
      const SolveResult result = constraints.solve(start);
      reached[p] = result.reached ? 1 : 0;
      for (std::size_t k = 0; k < targets.size(); ++k) {
        errors[p].push_back(std::abs(result.values[k] - targets[k].value));
      }
    }
  };
  const int n = std::clamp(threads, 1, 64);
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(work, static_cast<std::size_t>(t), n);
  work(0, static_cast<std::size_t>(n));
  for (auto& t : pool) t.join();

  SurveyFit out;
  out.model_name = model->name;
  out.components = model->component_count();
  out.people = sample;
  out.reached = static_cast<int>(std::count(reached.begin(), reached.end(), 1));
  for (std::size_t k = 0; k < names.size(); ++k) {
    std::vector<double> e;
    for (const auto& row : errors) e.push_back(row[k]);
    const Distribution d = distribution_of(std::move(e));
    const bool mass = names[k] == "mass";
    const double scale = mass ? 1.0 : 100.0;
    out.rows.push_back({names[k], mass ? "kg" : "cm", scale * d.p50, scale * d.p95});
  }
  return out;
}

}  // namespace body
