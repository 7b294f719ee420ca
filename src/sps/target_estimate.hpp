// Where the design the person has in mind probably is, estimated from their choices with an
// ideal-point model of choice (Coombs' unfolding): the person prefers what looks closer to
// the one design in mind, so a choice among shown points is a softmax of minus their
// perceptual distances to it. With a population prior on that design (a body model's shape
// coefficients are standardized: N(0, 1) over the people it was built from) the MAP estimate
// averages many guesses between look-alike cells and falls back on typical bodies along
// directions the choices never resolved, where the GP's posterior-mean maximum wanders with
// the guesses (docs/benchmarks.md).
#pragma once

#include <Eigen/Core>

#include "sps/perceptual_metric.hpp"
#include "sps/preference_data.hpp"

namespace sps {

// Where designs typically lie in the search box and how far they spread, per coordinate
// (a body model: mean 0.5, SD 1/6, as beta = 6x - 3 is N(0, 1)), and which coordinates
// typically change together (a photo edit's colour balance across the tones).
struct Population {
  Eigen::VectorXd mean;
  Eigen::VectorXd sd;
  // Empty (independent coordinates, as a body model's standardized components are), or the
  // coordinates' correlation matrix: symmetric, unit diagonal, positive definite.
  Eigen::MatrixXd correlation;
  bool empty() const { return mean.size() == 0; }
};

// The population's covariance and its precision (inverse), in box units. Assume a validated
// population.
Eigen::MatrixXd population_covariance(const Population& population);
Eigen::MatrixXd population_precision(const Population& population);

struct TargetModel {
  // How far apart two points look (mm): the scale alone where the coordinates are seen
  // independently, else the full metric (perceptual_metric.hpp). Validated when made.
  PerceptualMetric metric;
  Population population;
  // Softmax temperature of a choice (mm): a cell 3 mm closer to the design in mind is e times
  // as likely to be chosen. The window sets it from the cells' size
  // (app::choice_temperature_for_cells), the body benchmark from its person's threshold.
  double temperature_mm = 3.0;
  // With how many temperatures of slack a choice's region bounds the design in mind in
  // target_posterior_covariance (below); negative: not at all.
  double region_slack_temperatures = -1.0;
};

// Throws std::invalid_argument naming the first problem: sizes differ from `dims`, a
// non-finite or non-positive SD, a mean outside [0, 1], a correlation matrix that is not
// symmetric with a unit diagonal or not positive definite, a temperature outside (0, 1e4].
void validate_target_model(const TargetModel& model, int dims);

// Log posterior (up to a constant) of the design in mind being at t, with its gradient:
// the population prior plus, for every preference, log softmax(-distance / temperature) of
// the chosen point among the compared ones; distance is sqrt((x - t)^T M (x - t)) (smoothed at
// 0), M the model's metric.
double target_log_posterior(const PreferenceData& data, const TargetModel& model,
                            const Eigen::VectorXd& t, Eigen::VectorXd* gradient = nullptr);

// The MAP estimate inside [0,1]^d, from `start` and from the population mean (the better of
// the two). Without data: the population mean (clamped into the box).
Eigen::VectorXd estimate_target(const PreferenceData& data, const TargetModel& model,
                                const Eigen::VectorXd& start);

// How uncertain the estimate at t (the MAP estimate) still is: the inverse of the expected
// information there (box units), the population prior's precision plus, for every choice, the
// covariance of the compared points' utility gradients under the softmax of the choice (the
// Fisher information of a multinomial logit). Unlike the observed Hessian it is positive
// definite everywhere and has no spikes where t meets a chosen point (the distance's kink).
// Plus what the choice's region says: a point chosen over one L mm away puts the design on
// its side of the boundary between them, within a slab of width about L along the line
// joining them (its neighbour on the far side bounds the other side), so each such pair adds
// the information of a uniform spread over half that width, 6 / W^2 along that line, with
// W = L + region_slack_temperatures * temperature (a person who confuses near cells bounds
// it less sharply). The softmax's own information vanishes where the compared points are
// many temperatures apart: a careful chooser who picks the centre of grid after grid centred
// on the estimate then left the estimate as uncertain as before, and the planes kept the same
// axes and size plane after plane (the body benchmark's perfect chooser on these planes sat
// at 10.9 mm from plane 5 to 10).
Eigen::MatrixXd target_posterior_covariance(const PreferenceData& data, const TargetModel& model,
                                            const Eigen::VectorXd& t);

// That covariance once the held quantities are known exactly (a hold: the design in mind keeps
// them, so it lies on the held surface): the Gaussian conditioned on N (t - estimate) = 0,
// C - C N^T (N C N^T)^+ N C, with the rows of `normals` (N) the held quantities' gradients at
// the estimate. It is zero along the normals' directions (in the C-metric sense), so the
// principal axes of what is left lie in the surface's tangent space. No normals: C itself.
Eigen::MatrixXd covariance_given_holds(const Eigen::MatrixXd& covariance,
                                       const Eigen::MatrixXd& normals);

// The estimate t once the held quantities are known, to first order about t: the posterior's
// mean given N (x - t) = N (nearest - t), with `nearest` the surface point nearest t (so the
// held quantities take their held values), t + C N^T (N C N^T)^+ N (nearest - t). It reaches
// the surface along the directions the choices left least certain, where `nearest` moves t
// along the normals alone, through directions the choices had settled (height held, 40
// people, seeds 2000-2039, mean gap at plane 15 5.91 mm with `nearest` against 5.07). A
// coordinate the move takes out of the box is held at the face it crosses and the rest
// conditioned again, so the result lies in the box and still meets the holds to first order.
Eigen::VectorXd estimate_given_holds(const Eigen::VectorXd& t, const Eigen::VectorXd& nearest,
                                     const Eigen::MatrixXd& covariance,
                                     const Eigen::MatrixXd& normals);

}  // namespace sps
