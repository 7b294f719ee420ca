// Measurements a body designer reads: stature, tape-measure girths, body volume and mass.
#pragma once

#include <string>
#include <vector>

#include "body/body_model.hpp"

namespace body {

struct Measurements {
  double height = 0.0;  // metres, top of head to sole
  double chest = 0.0;   // circumferences in metres (convex hull of a horizontal slice)
  double waist = 0.0;
  double hips = 0.0;
  // Heights above the sole (metres) of the slices the girths were taken at; NaN if the
  // band held no torso slice (then the girth is 0).
  double chest_height = 0.0;
  double waist_height = 0.0;
  double hips_height = 0.0;
  // Enclosed volume (m^3, signed tetrahedra; its absolute value, so either winding works) and
  // the body mass it implies at kBodyDensity (kg). Meaningful for closed meshes (the built-in
  // models, SMPL); open meshes (holes at the neck of a head-less model...) read low.
  double volume = 0.0;
  double mass = 0.0;
  // Body mass index, kg/m^2: mass / height^2 (both as above).
  double bmi = 0.0;
  // Lengths from the skeleton and the surface (metres); NaN when the model lacks what the
  // landmark needs (joint names of the SMPL family, skin over the shoulders, a crotch between
  // two legs). See below.
  double shoulder_width = 0.0;  // biacromial breadth
  double inseam = 0.0;          // crotch to sole
  double arm_length = 0.0;      // acromion - elbow - wrist
  // Girths and a breadth across the limbs and the neck, from slices perpendicular to a bone
  // (see below); NaN when the model lacks the joints, 0 when not taken (`bands`).
  double neck = 0.0;       // neck circumference, mid-neck
  double bideltoid = 0.0;  // breadth across the deltoids
  double upper_arm = 0.0;  // upper-arm (biceps) circumference, relaxed
  double thigh = 0.0;      // thigh circumference below the gluteal furrow
  double calf = 0.0;       // calf circumference, its largest
};

// The acromion's ray from the shoulder joint, degrees out from straight up (see below).
constexpr double kAcromionAngleDegrees = 27.0;

// Whole-body density, kg/m^3. Densitometry of adults gives about 1.06-1.07 g/cm^3 for lean
// tissue and 0.90 for fat; whole-body densities with the lungs' air included are close to
// water: 985 kg/m^3 is the value of the project's domain notes (Anny uses 980). Brozek et al.
// 1963 (Ann. N. Y. Acad. Sci. 110:113) and Siri 1961 give the tissue densities.
constexpr double kBodyDensity = 985.0;

// Volume enclosed by a closed triangle mesh (m^3): |sum over triangles of det(a, b, c) / 6|.
double enclosed_volume(const Vertices& vertices, const Faces& faces);

// Landmarks (see measurements.cpp for the sources): with H the stature and the body standing
// in y, slices every H/200 through three bands of relative height,
//   chest = largest torso girth in [0.65, 0.75] H   (bust line, below the armpits; the
//           search stops where the girth jumps by > 15% between slices: arms joining),
//   waist = smallest torso girth in [0.56, 0.67] H  (natural waist),
//   hips  = largest torso girth in [0.45, 0.55] H     (seat / buttocks: ANSUR II's buttock
//           height is 0.512 H for women and 0.505 H for men, SD 0.016 H; 0.55 H is 2.5 SD
//           above, below the navel at 0.60 H. Not bounded by the waist slice: 9% of the
//           survey's men have a waist larger than their buttock circumference, a belly the
//           old bound, the largest girth up to the waist, took for the hips).
// A girth is the perimeter of the convex hull of the slice piece that surrounds the body's
// vertical axis (mean x and z of all vertices), so arms and hands beside the torso and the two
// legs below the crotch are left out, as a tape measure would leave them out.
//
// The lengths use the skeleton's joints, which every SMPL-family model (and the built-in
// models) regresses from its own vertices, found by their SMPL names (left_shoulder,
// right_elbow, left_hip...; body/joint_names.hpp) -- never vertex ids of one mesh:
//   acromion = where the ray from the shoulder joint centre, kAcromionAngleDegrees out from
//           straight up towards the body's side (in the vertical plane through both shoulder
//           joints), leaves the skin: the top of the shoulder over the humeral head's lateral
//           margin, the surface point a calliper's biacromial breadth and the survey's arm
//           lengths start from (ANSUR II, Gordon et al. 2014: the acromion's lateral tip).
//           The joint centre lies in the humeral head, which has a radius of about 2.3 cm
//           (Boileau & Walch 1997, J. Bone Joint Surg. 79-B:857); the acromion's edge lies
//           over the head's lateral margin, about 2 cm out from and 4 cm above the centre,
//           27 degrees from vertical. The point moves with the surface, continuously in the
//           betas (one ray per side, no slice).
//   shoulder_width = horizontal distance between the two acromia (the survey's biacromial
//           breadth).
//   arm_length = |acromion - elbow| + |elbow - wrist|, the mean of both sides (the survey's
//           acromion-radiale plus radiale-stylion: the radiale lies at the elbow joint's
//           line, the stylion at the wrist's).
//   inseam = height above the sole of the crotch: the highest downward-facing surface that
//           the vertical line through the midpoint of the hip joints crosses below them (the
//           inner thighs, when they touch, face sideways or lie lower; without hip joints:
//           the line through the mean vertex, below 0.6 H). NaN when that surface is the
//           sole itself (no legs: a cylinder) or lies below 0.2 H.
// The girths across the neck and limbs are taken on planes perpendicular to a bone (the
// segment between two joints), as the survey takes them perpendicular to the limb's long axis
// (ANSUR II, Gordon et al. 2014), so they do not depend on the pose of the arms:
//   neck = the smallest girth at 30-70% of the neck -> head segment (the survey: just below
//          the laryngeal prominence, perpendicular to the neck's axis, about its narrowest);
//   upper_arm = the largest girth at 40, 50 and 60% of shoulder -> elbow, both arms' mean (the
//          survey's biceps circumference is taken flexed and reads 1-3 cm more);
//   thigh = girth 1% of H below the crotch along hip -> knee (the survey: at the gluteal
//          furrow), both legs' mean;
//   calf = the largest girth at 20-50% of knee -> ankle, both legs' mean;
//   bideltoid = the shoulder joints' horizontal distance plus, on each side, how far the deltoid
//   reaches
//          out from the humerus (the largest lateral extent of the upper-arm slices at 10-30%
//          of shoulder -> elbow): the survey's breadth across the deltoids with the arms
//          hanging, whatever the rest pose's arm angle.
// Each girth is the convex hull of the slice piece around the bone, as a tape would lie.
// `girths` = false skips the slices (chest, waist, hips stay 0): the rest costs two passes over
// the faces (the volume and crotch, then both acromia's rays), well under the ~11 ms of the
// slices on the default model, for callers that need only those (holds, targets).
// `bands` picks the girths taken (the others stay 0): holding or solving for one girth slices
// only its band.
enum GirthBand : unsigned {
  kChestBand = 1,
  kWaistBand = 2,
  kHipsBand = 4,
  kNeckBand = 8,  // neck
  kArmBand = 16,  // upper_arm, bideltoid
  kLegBand = 32,  // thigh, calf
  kAllBands = 63
};
Measurements measure(const Model& model, const BodyMesh& mesh, bool girths = true,
                     unsigned bands = kAllBands);

// Convenience: evaluate(model, betas) then measure.
Measurements measure(const Model& model, const Eigen::VectorXf& betas, bool girths = true,
                     unsigned bands = kAllBands);

// --- Named measurements: one table for the command line, targets, holds and the window. ---

enum class Quantity { kLength, kMass, kBmi };
enum class Units { kMetric, kImperial };

struct MeasurementKind {
  const char* name;   // "height", "shoulder_width" (command line, CSV: name + "_m" / "_kg")
  const char* label;  // "Height", "Shoulder width" (window)
  Quantity quantity;
  double Measurements::*field;
  bool needs_girths;  // needs the slices (measure(..., girths = true))
  // How close a held measurement stays in every cell: 1 cm for lengths and girths,
  // 1.5 kg for mass, 0.5 kg/m^2 for BMI (about 1.5 kg at 1.75 m).
  double hold_tolerance;
  // A plausible adult value to type, as the window's placeholder: metric and imperial.
  const char* example_metric;
  const char* example_imperial;
};

// height, mass, bmi, chest, waist, hips, shoulder_width, inseam, arm_length.
const std::vector<MeasurementKind>& measurement_kinds();
// nullptr if no measurement has that name.
const MeasurementKind* find_measurement(const std::string& name);
// The girth band a measurement needs (GirthBand; 0 for those without slices).
unsigned girth_band(const MeasurementKind& kind);
// "height, mass, bmi, ..." for messages.
std::string measurement_names();

// "180.0 cm" / "5 ft 10.9 in", "85.0 kg" / "187.4 lb", "24.1" (BMI has one unit). NaN: "n/a".
std::string format_measurement(Quantity quantity, double value, Units units);
// A difference: "+1.2 cm" / "+0.47 in", "-3.0 kg" / "-6.6 lb".
std::string format_difference(Quantity quantity, double difference, Units units);

// A typed value with an optional unit: "1.80", "180cm", "1.8 m", "71in", "90kg", "198 lb".
// Without a unit: metres for lengths, kg for mass, kg/m^2 for BMI. Returns SI. Throws
// std::invalid_argument naming the measurement and the problem (not a number, NaN, a unit of
// the wrong kind, zero or negative, or beyond what a human body measures).
double parse_measurement_value(const MeasurementKind& kind, const std::string& text);

// Girth of the torso piece at height y (absolute, in the mesh's frame); 0 if no slice piece
// surrounds the vertical axis at (axis_x, axis_z).
double torso_girth(const BodyMesh& mesh, const Faces& faces, double y, double axis_x,
                   double axis_z);

}  // namespace body
