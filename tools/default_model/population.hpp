// The body populations of the default models. Per sex, 30 anthropometric measures (stature,
// mass, girths, breadths, depths, segment lengths) are drawn from a correlated normal whose
// means, SDs and correlations were derived from the ANSUR II public data
// (tools/ansur2_stats.py -> ansur2_table.inc), plus independent factors that vary in people
// apart from those measures (fat distribution, fat layer, muscularity, bust, shoulder slope,
// posture, neck). They are mapped to a deformation of the one template mesh: per-bone affine
// maps (bone moved to its new joint, scaled along and across itself) blended by smooth
// weights, plus displacement fields (breasts, belly, hips and thighs, fat layer, muscles,
// postural shears) and a vertical shift that keeps the soles on y = 0. The deformation is
// linear in the per-body parameter vector theta, so every body is B * theta for one fixed
// basis B (3V x P); PCA uses that without materialising all bodies.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "mannequin_shape.hpp"

namespace default_model {

#include "ansur2_table.inc"

// Factors drawn independently of the survey measures (standard normal, within sex).
struct IndependentFactors {
  double fat_distribution = 0;  // + belly (android), - hips and thighs (gynoid)
  double fat_layer = 0;         // subcutaneous layer over torso and limbs
  double muscle = 0;            // deltoids, pectorals, arms, thighs, calves, trapezius
  double bust = 0;              // breast volume beyond what the chest girth implies
  double shoulder_slope = 0;    // + square shoulders, - sloping
  double posture = 0;           // + upper body leaning forward (rounded back)
  double lordosis = 0;          // + hollow back, prominent buttocks
  double head_forward = 0;      // + head carried forward
  double neck_length = 0;
  double shoulders_forward = 0;  // + rounded (protracted) shoulders, arms carried forward
  double knee_alignment = 0;     // + bow legs (knees apart), - knock knees
  double limb_fat = 0;           // + fuller limbs for the trunk (peripheral vs central fat)
};

// Per-person corrections of the girths and the shoulders' breadths: the amplitudes (metres of
// soft tissue at a thigh's radius) of bands round the levels at which the tool measures them,
// and the shoulders' spread, set by calibrate_population (survey_calibration.hpp) so that what
// the tool measures on the body meets the person's draw.
enum CrossSectionKnob : int {
  kKnobChest,
  kKnobWaist,
  kKnobPelvis,  // steers the hips (buttock) girth
  kKnobNeck,
  kKnobThigh,
  kKnobCalf,
  kKnobBiceps,   // steers the upper arm girth
  kKnobDeltoid,  // steers the bideltoid breadth
  // Not a band: the relative change of the shoulders' spread (the collar and shoulder joints'
  // distance from the midline), which steers the shoulder width.
  kKnobShoulder,
  // Not a band: metres of a fat layer over torso and limbs, which steers the mass (the bands
  // then hold the girths they measure, so the layer fills out what lies between them).
  kKnobMass,
  kKnobCount
};
// The knobs that are soft-tissue bands (the first ones).
constexpr int kKnobBands = kKnobShoulder;

// The independent factors in the order they are drawn (each as a member of
// IndependentFactors), for the code that goes through all of them.
constexpr int kFactorCount = 12;
const std::array<double IndependentFactors::*, kFactorCount>& factor_members();

struct Anthropometry {
  bool female = false;
  std::array<double, kSurveyMeasures> m{};  // survey measures, cm (weight in kg)
  IndependentFactors f;
  std::array<double, kKnobCount> knobs{};
};

// The features a calibration is a linear function of: 1, the survey measures in SDs of the
// person's sex, the independent factors in their own SDs.
constexpr int kPersonFeatures = 1 + kSurveyMeasures + kFactorCount;
Eigen::VectorXd person_features(const Anthropometry& a);

// Deterministic: the same seed gives the same population on every platform with IEEE doubles.
// The standard normals behind the survey's correlated measures are truncated at
// `truncate_survey` SD, those of the independent factors at `truncate_factors` SD.
std::vector<Anthropometry> sample_population(bool female, int count, std::uint64_t seed,
                                             double truncate_survey = 2.3,
                                             double truncate_factors = 2.3);

// The reference person the template mannequin was built for: the average of the female and
// male survey means (1.69 m), with all independent factors 0.
Anthropometry reference_person();

class DeformationModel {
 public:
  DeformationModel(const std::vector<Vec3>& template_vertices,
                   const std::vector<Vec3>& template_normals, const Skeleton& skeleton,
                   const Eigen::MatrixXd& weights);

  int parameter_count() const { return static_cast<int>(basis_.cols()); }
  const Eigen::MatrixXd& basis() const { return basis_; }  // 3V x P
  Eigen::VectorXd parameters(const Anthropometry& a) const;
  Eigen::VectorXd rest_parameters() const;  // reproduces the template exactly
  Eigen::VectorXd vertices(const Eigen::VectorXd& theta) const { return basis_ * theta; }
  // Where bone `bone`'s start (its joint, for the limbs) lands with `theta`, soles on y = 0.
  Vec3 bone_start(const Eigen::VectorXd& theta, int bone) const;
  // Averages the displacement fields (not the bone maps, which reproduce the template) over
  // each vertex's mesh neighbours, `iterations` times: fields that turn quickly across a
  // crease fold the surface there when several components push far along them at once.
  void smooth_fields(const std::vector<std::vector<int>>& neighbours, int iterations);

 private:
  Eigen::MatrixXd basis_;
  Skeleton skeleton_;
  std::array<Eigen::Matrix3d, kJointCount> frames_;  // columns: along, u, v
  std::vector<int> sole_vertices_;
};

}  // namespace default_model
