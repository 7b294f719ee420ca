// A body model's population against a survey's: the tool's measurements of bodies drawn as
// the model is meant to be sampled (betas ~ N(0, I), the SMPL convention) beside the same
// measurements of the surveyed people. What `bench-survey` prints.
#pragma once

#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "body/survey_table.hpp"

namespace body {

struct Distribution {
  double mean = 0.0, sd = 0.0, p5 = 0.0, p50 = 0.0, p95 = 0.0;
  int count = 0;
};
// NaN values are skipped; an empty input gives count 0 and NaN statistics.
Distribution distribution_of(std::vector<double> values);
// The same with a weight per value (positive and finite; throws otherwise): a weighted mean,
// the SD with reliability weights and quantiles on the weights' cumulative share. Equal
// weights give distribution_of(values).
Distribution distribution_of(const std::vector<double>& values, const std::vector<double>& weights);

// One measurement as the survey takes it and as the tool does.
struct SurveyMeasure {
  std::string name;                  // the tool's name ("height") or a ratio ("waist/hips")
  std::vector<std::string> columns;  // survey columns it needs
  double scale = 0.001;              // survey unit -> SI (mm -> m; weightkg is 0.1 kg)
};

// The measures compared, and every survey column they need (for read_survey_csv).
const std::vector<SurveyMeasure>& survey_measures();
std::vector<std::string> survey_columns();
// The survey's value of `measure` for the person in `row`, in SI (ratios and BMI as they are).
double survey_value(const SurveyMeasure& measure, const SurveyTable& table, Eigen::Index row);

struct ComparisonRow {
  std::string name;
  Distribution survey, model;
  double mean_gap_sd = 0.0;  // (model mean - survey mean) / survey SD
};

// One entry of the correlation matrices: Pearson's r between two measures, in the survey and
// in the model's population.
struct CorrelationGap {
  std::string a, b;
  double survey = 0.0, model = 0.0;
};

struct PopulationComparison {
  std::string model_name;
  int bodies = 0, people = 0;
  std::vector<ComparisonRow> rows;
  // Every pair of the measures that are not ratios or BMI, the largest |model - survey| first.
  std::vector<CorrelationGap> correlations;
};

// Pearson's correlation of two equally long series (pairs with a NaN skipped); NaN with fewer
// than 3 pairs or no spread.
double correlation_of(const std::vector<double>& x, const std::vector<double>& y);
// The weighted Pearson's r (a weight per pair, positive and finite, else it throws; equal
// weights give the plain one).
double correlation_of(const std::vector<double>& x, const std::vector<double>& y,
                      const std::vector<double>& weights);

// `samples` bodies of `model` (first `components` betas ~ N(0, 1), seeded) measured and
// compared with `survey` (one table or two pooled, e.g. both sexes for the neutral model; each
// table then weighs the same, as the neutral model is built from equal numbers of each sex).
PopulationComparison compare_with_survey(const Model& model,
                                         const std::vector<const SurveyTable*>& survey, int samples,
                                         unsigned seed);

}  // namespace body
