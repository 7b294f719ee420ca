// Calibrates a generated population against its own survey draw. DeformationModel::parameters
// maps each person's survey measures (breadths, depths, girths) to scales of the template's
// cross sections, but the template's shape, the fields every body gets (breasts, belly, hips,
// muscle) and the couplings between neighbouring bones (the waist's scale widens the hips too)
// make the girths the tool itself measures on the body differ from the drawn ones, person by
// person: the population's means, spreads and correlations then drift from the survey's.
//
// The calibration measures a sample of the population with the tool's own code
// (body::measure, the same landmarks as `measure`, holds and `bench-survey`) and sets each
// person's knobs (Anthropometry::knobs: soft tissue round each girth's level and round the
// deltoids, the shoulders' spread for the shoulder width) to a linear
// function of their survey measures and independent factors, fitted so that the measured
// girths meet the drawn ones: the correction a person gets depends only on who they are, so
// the population keeps the survey's joint distribution and stays a linear image of it, and the
// generator stays deterministic. A few rounds of: measure the sample, fit the log residual
// (ridge regression on the person's features), divide by the knobs' Jacobian at the sex's mean
// person.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "population.hpp"

namespace default_model {

struct CalibrationReport {
  bool female = false;
  int sample = 0;
  int rounds = 0;
  // Per knob's girth (chest, waist, hips, neck, thigh, calf, upper arm): RMS of the relative
  // difference between the measured and the drawn girth over the sample, before the first and
  // after the last round, and the mean differences (biases).
  std::array<double, kKnobCount> rms_before{}, rms_after{}, bias_before{}, bias_after{};
  // The bands' amplitudes over the whole population (metres at a thigh's radius).
  std::array<double, kKnobCount> knob_mean{}, knob_sd{};
};

// The girth each knob steers, by its measurement name ("chest", "waist", ...).
const std::array<const char*, kKnobCount>& knob_measurement_names();

// Sets `knobs` of every person in `people` (all of one sex). `faces` and `regressor` (J x V)
// describe the template mesh the deformation acts on. `sample` people (the first ones) are
// measured per round; `threads` share the measuring (the result does not depend on it).
CalibrationReport calibrate_population(std::vector<Anthropometry>& people,
                                       const DeformationModel& deformation,
                                       const std::vector<std::array<int, 3>>& faces,
                                       const Eigen::MatrixXd& regressor, int sample, int rounds,
                                       int threads);

std::string describe(const CalibrationReport& report);

}  // namespace default_model
