// Real people in a body model's space: for surveyed people, the body of the model nearest to
// each person's measurements (the measurement solve, inside the +-3 SD box) and how far its
// measurements end up from the person's. What `fit-survey` prints.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "body/survey_table.hpp"

namespace body {

// The measurements fitted, by the tool's names: stature, mass, chest, waist, buttock (hips),
// neck, bideltoid breadth, flexed biceps (the tool's upper arm is relaxed), thigh, calf,
// crotch height (inseam) and the arm (acromion-radiale plus radiale-stylion, from the
// acromion as the tool's arm length).
const std::vector<std::string>& fit_measure_names();

struct FitRow {
  std::string name;
  std::string unit;                                    // "cm" or "kg"
  double median_abs_error = 0.0, p95_abs_error = 0.0;  // in `unit`
};

struct SurveyFit {
  std::string model_name;
  int components = 0;
  int people = 0;
  int reached = 0;  // people whose every measurement was met within the solve's tolerance
  std::vector<FitRow> rows;
};

// `sample` people of the tables (all of them pooled, drawn without replacement by a seeded
// shuffle that is the same on every platform), each solved for from the model's mean body on
// `threads` threads. Throws std::invalid_argument for a sample outside 1..100000 or larger
// than the tables.
// `names`: the measurements fitted (a subset of fit_measure_names(); empty: all of them).
// Throws std::invalid_argument for a name that is not one of them.
SurveyFit fit_survey(const std::shared_ptr<const Model>& model,
                     const std::vector<const SurveyTable*>& survey, int sample, unsigned seed,
                     int threads, std::vector<std::string> names = {});

}  // namespace body
