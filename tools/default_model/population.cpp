#include "population.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include <Eigen/Cholesky>

#include "body/measurements.hpp"

namespace default_model {

namespace {

// Standard normal numbers from a 64-bit Mersenne twister by Box-Muller, so the sequence does
// not depend on the standard library's distribution implementation.
class Normal {
 public:
  explicit Normal(std::uint64_t seed) : engine_(seed) {}
  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = ((engine_() >> 11) + 0.5) * (1.0 / 9007199254740992.0);
    const double u2 = ((engine_() >> 11) + 0.5) * (1.0 / 9007199254740992.0);
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * M_PI * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * M_PI * u2);
  }
  double truncated(double limit) {
    double x = (*this)();
    while (std::abs(x) > limit) x = (*this)();
    return x;
  }

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0;
};

Eigen::MatrixXd cholesky_of(const SurveyTable& t) {
  Eigen::MatrixXd R(kSurveyMeasures, kSurveyMeasures);
  for (int a = 0; a < kSurveyMeasures; ++a)
    for (int b = 0; b < kSurveyMeasures; ++b) R(a, b) = t.corr[a][b];
  // The table is rounded to 3 decimals; shrink towards I in the unlikely case that made it
  // indefinite.
  for (double alpha = 0.0; alpha < 1.0; alpha += 0.01) {
    const Eigen::MatrixXd S =
        (1 - alpha) * R + alpha * Eigen::MatrixXd::Identity(kSurveyMeasures, kSurveyMeasures);
    Eigen::LLT<Eigen::MatrixXd> llt(S);
    if (llt.info() == Eigen::Success) return llt.matrixL();
  }
  return Eigen::MatrixXd::Identity(kSurveyMeasures, kSurveyMeasures);
}

// The independent factors' amplitudes below are per unit of this; 1.45 makes each of them big
// enough to be seen in a grid cell (1 px ~ 4.5 mm) as its own principal component.
constexpr double kFactorScale = 1.5;

// Where each sex sits on the factors that differ between the sexes, in SDs of the factor
// (the factor's SD is the within-sex spread). Men carry their fat centrally (belly, flanks:
// "android"), women on the hips, buttocks and thighs ("gynoid") and more of it on the limbs
// (J. Vague, "The degree of masculine differentiation of obesities", Am. J. Clin. Nutr. 4,
// 1956; DXA studies find women's leg fat share about 1.3 times men's). Men have about 40%
// more skeletal muscle, most of the difference in the upper body (I. Janssen et al.,
// "Skeletal muscle mass and distribution in 468 men and women aged 18-88 yr", J. Appl.
// Physiol. 89, 2000). Women's shoulders slope more and their lumbar curve is deeper. The
// girths these shifts change are calibrated back to the survey's means (Calibration below).
struct FactorShift {
  double fat_distribution, muscle, shoulder_slope, lordosis, limb_fat;
};
constexpr FactorShift kFemaleShift{-0.2, -0.6, -0.3, 0.3, 0.5};
constexpr FactorShift kMaleShift{0.8, 0.7, 0.3, -0.3, -0.5};
constexpr double kStatureTruncation = 2.3;

}  // namespace

std::vector<Anthropometry> sample_population(bool female, int count, std::uint64_t seed,
                                             double truncate_survey, double truncate_factors) {
  const SurveyTable& t = female ? kFemale : kMale;
  const Eigen::MatrixXd L = cholesky_of(t);
  Normal normal(seed);
  // The bideltoid breadth came last (it only steers a calibration band): its normals come
  // from a stream of their own, so that the other measures and the factors are drawn as they
  // were before it (the Cholesky factor being lower triangular).
  static_assert(k_bideltoid == kSurveyMeasures - 1, "the bideltoid breadth is drawn last");
  Normal bideltoid_normal(seed ^ 0x9e3779b97f4a7c15ULL);
  std::vector<Anthropometry> people;
  people.reserve(count);
  for (int i = 0; i < count; ++i) {
    Anthropometry a;
    a.female = female;
    Eigen::VectorXd z(kSurveyMeasures);
    // Stature (the first measure: z[0] alone makes it, the Cholesky factor being lower
    // triangular) is held to a narrower range than the other measures, so that no body along
    // a single component at +-3, nor far combinations of several, falls below 1.45 m.
    for (int k = 0; k < k_bideltoid; ++k)
      z[k] = normal.truncated(k == k_stature ? kStatureTruncation * truncate_survey / 2.3
                                             : truncate_survey);
    z[k_bideltoid] = bideltoid_normal.truncated(truncate_survey);
    z = L * z;
    for (int k = 0; k < kSurveyMeasures; ++k) a.m[k] = t.mean[k] + t.sd[k] * z[k];
    IndependentFactors& f = a.f;
    const FactorShift& shift = female ? kFemaleShift : kMaleShift;
    // Each factor with its sex's mean (in the order the normals are drawn).
    const std::array<double, kFactorCount> means = {shift.fat_distribution,
                                                    0.0,
                                                    shift.muscle,
                                                    0.0,
                                                    shift.shoulder_slope,
                                                    0.0,
                                                    shift.lordosis,
                                                    0.0,
                                                    0.0,
                                                    0.0,
                                                    0.0,
                                                    shift.limb_fat};
    for (int k = 0; k < kFactorCount; ++k)
      f.*factor_members()[k] = kFactorScale * (means[k] + normal.truncated(truncate_factors));
    people.push_back(a);
  }
  return people;
}

const std::array<double IndependentFactors::*, kFactorCount>& factor_members() {
  using F = IndependentFactors;
  static const std::array<double F::*, kFactorCount> members = {
      &F::fat_distribution, &F::fat_layer,         &F::muscle,         &F::bust,
      &F::shoulder_slope,   &F::posture,           &F::lordosis,       &F::head_forward,
      &F::neck_length,      &F::shoulders_forward, &F::knee_alignment, &F::limb_fat};
  return members;
}

Eigen::VectorXd person_features(const Anthropometry& a) {
  const SurveyTable& t = a.female ? kFemale : kMale;
  Eigen::VectorXd phi(kPersonFeatures);
  phi[0] = 1.0;
  for (int k = 0; k < kSurveyMeasures; ++k) phi[1 + k] = (a.m[k] - t.mean[k]) / t.sd[k];
  for (int k = 0; k < kFactorCount; ++k)
    phi[1 + kSurveyMeasures + k] = a.f.*factor_members()[k] / kFactorScale;
  return phi;
}

Anthropometry reference_person() {
  Anthropometry a;
  for (int k = 0; k < kSurveyMeasures; ++k) a.m[k] = 0.5 * (kFemale.mean[k] + kMale.mean[k]);
  return a;
}

namespace {

// Parameter layout: for each joint j, 3 entries for the new bone anchor, then 3 scales (along,
// u, v); then the amplitudes of the displacement fields and the vertical shift.
enum Field : int {
  kBreastLeft,
  kBreastRight,
  kBelly,
  kGluteofemoral,
  kFatLayer,
  kMuscle,
  kPostureShear,
  kHeadForward,
  kLordosis,
  kShouldersForward,
  kKneeAlignment,
  kLimbFat,
  kThighTop,
  // Girth bands, one per CrossSectionKnob and in its order: soft tissue round the level at
  // which the tool measures each girth, each a person's own calibration (metres at a thigh's
  // radius). Local, so that each steers its own girth and hardly the others.
  kChestBand,
  kWaistBand,
  kHipBand,
  kNeckBand,
  kThighBand,
  kCalfBand,
  kUpperArmBand,
  kDeltoidBand,
  kFieldCount
};
constexpr int kAnchor = 0;
constexpr int kScale = 3 * kJointCount;
constexpr int kFields = 6 * kJointCount;
constexpr int kShift = kFields + kFieldCount;
constexpr int kParams = kShift + 1;

// Template landmarks (the mannequin is 1.70 m tall, see mannequin_shape.cpp).
constexpr double kTemplateStature = 1.70;
// Soft-tissue layers are amplitudes at this distance from the bone (about a thigh's radius),
// growing in proportion to the distance up to kLayerCap (the trunk).
constexpr double kLayerRadius = 0.08;
constexpr double kLayerCap = 0.11;

// Per-sex calibration of the cross sections and of the shoulders' and arms' lengths (see
// DeformationModel::parameters).
struct Calibration {
  double pelvis, waist, chest, neck, thigh, calf, biceps;
  // Metres of soft tissue added round the top of the thighs (kThighTop): the thigh's scale
  // acts along the whole femur, and raised far enough to give the survey's thigh girth (taken
  // just below the buttock's fold) it bulged the lower thigh into a ring above the knee.
  double thigh_top;
  // The shoulders' spread (the collar and shoulder joints' distance from the midline) and the
  // upper arm's and forearm's lengths: the mannequin's were modelled by eye, the survey takes
  // them from the acromion (body/measurements.hpp); these give the mean bodies the survey's
  // biacromial breadth and acromion-radiale-stylion length as the tool measures them (each
  // person's shoulder knob then corrects the spread body by body, about 0 on average).
  double shoulder, arm;
  // The crotch's height: the template's crotch, scaled by the survey's crotch height,
  // measured about 2% high (bench-survey: the inseam 79.7 cm against the survey's 78.2 for
  // women, 86.3 against 84.6 for men). The women's is only halved: lower legs lengthen the
  // trunk, and at 0.98 the neutral model's shortest bodies (component 1 at -3) fell to
  // 1.449 m, under the 1.45 m every body of the box must reach. (For the same reason the
  // stature is not scaled, though the female mean body stands 0.8% tall.)
  double crotch;
};
constexpr Calibration kFemaleCalibration{0.96, 1.45,  0.80, 0.80,  1.25, 1.24,
                                         1.12, 0.005, 0.94, 1.088, 0.99};
constexpr Calibration kMaleCalibration{0.95, 1.28,  1.04,  0.87,  1.28, 1.12,
                                       1.10, 0.018, 0.955, 1.105, 0.980};

double gauss(double x, double centre, double sd) {
  const double t = (x - centre) / sd;
  return std::exp(-0.5 * t * t);
}

Vec3 breast_centre(int side) {
  return Vec3(side == 0 ? 0.088 : -0.088, 1.25, 0.10);
}

double breast_bump(const Vec3& p, int side) {
  if (p.z() < 0.0) return 0.0;
  const Vec3 d = p - breast_centre(side);
  const double r2 = d.x() * d.x() + 1.3 * d.y() * d.y() + 0.5 * d.z() * d.z();
  // Narrow enough across that the cleavage between the breasts stays back (the fields are
  // smoothed over the mesh afterwards, which widens them).
  return std::exp(-r2 / (2 * 0.044 * 0.044)) * smoothstep(0.0, 0.06, p.z());
}

// Forward lean of everything above the lower back, as a shear (dz per metre above 1.0 m).
double posture_height(double y) {
  return (y - 1.0) * smoothstep(0.95, 1.12, y);
}
double head_forward_height(double y) {
  return (y - 1.42) * smoothstep(1.40, 1.52, y);
}

}  // namespace

DeformationModel::DeformationModel(const std::vector<Vec3>& template_vertices,
                                   const std::vector<Vec3>& template_normals,
                                   const Skeleton& skeleton, const Eigen::MatrixXd& weights)
    : skeleton_(skeleton) {
  const int V = static_cast<int>(template_vertices.size());
  for (int j = 0; j < kJointCount; ++j) {
    const Vec3 along = (skeleton.bone_end[j] - skeleton.bone_start[j]).normalized();
    // u: the body's width direction for the torso and legs, front-back for the arms.
    const bool arm = j >= kLeftShoulder;
    Vec3 hint = arm ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
    if (std::abs(along.dot(hint)) > 0.8) hint = Vec3(0, 1, 0);
    Vec3 u = (hint - along * along.dot(hint)).normalized();
    Vec3 v = along.cross(u);
    frames_[j].col(0) = along;
    frames_[j].col(1) = u;
    frames_[j].col(2) = v;
  }
  basis_ = Eigen::MatrixXd::Zero(3 * V, kParams);
  const auto& J = skeleton.joints;
  // Where the tool's acromion ray (body/measurements.hpp) leaves the template's skin, per
  // side: the template vertex farthest along the ray within 1 cm of it.
  std::array<Vec3, 2> acromion_exit;
  for (int side = 0; side < 2; ++side) {
    const Vec3 c = J[side == 0 ? kLeftShoulder : kRightShoulder];
    const double angle = body::kAcromionAngleDegrees * M_PI / 180.0;
    const Vec3 ray(std::sin(angle) * (side == 0 ? 1.0 : -1.0), std::cos(angle), 0.0);
    double farthest = -1.0;
    acromion_exit[side] = c;
    for (int i = 0; i < V; ++i) {
      const Vec3 d = template_vertices[i] - c;
      const double t = d.dot(ray);
      if (t > farthest && (d - t * ray).norm() < 0.01)
        farthest = t, acromion_exit[side] = template_vertices[i];
    }
  }
  for (int i = 0; i < V; ++i) {
    const Vec3& p = template_vertices[i];
    const Vec3& n = template_normals[i];
    auto w = [&](int j) { return weights(i, j); };
    // Soft tissue grows less at the crotch, where the layers of both thighs and the buttocks
    // meet in a tight crease that folds when all of them shrink or grow far at once; the hip
    // and buttock fields (gluteofemoral, lordosis) fade there too.
    const double crotch_core =
        1.0 - 0.8 * std::exp(-(p - Vec3(0, 0.79, -0.045)).squaredNorm() / (2 * 0.055 * 0.055));
    const double crotch_fade =
        crotch_core * (1.0 - 0.5 * std::exp(-0.5 * (std::pow(p.x() / 0.2, 2) +
                                                    std::pow((p.y() - 0.79) / 0.045, 2))));
    // The vertex's offset from its bones (weighted), in units of a thigh's radius: soft-tissue
    // layers (fat, muscle) grow along it. A layer then scales each limb about its axis in
    // proportion to the limb's thickness, so even far outside the population (betas of +-3
    // on several thinning components at once) a thin forearm or calf shrinks towards its axis
    // instead of being pushed through itself, and creases (armpit, knee pit) do not fold.
    Vec3 radial = Vec3::Zero();
    for (int j = 0; j < kJointCount; ++j) {
      const double wj = w(j);
      if (wj == 0.0) continue;
      const Vec3 a = skeleton.bone_start[j], ab = skeleton.bone_end[j] - a;
      const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      radial += wj * (p - (a + t * ab));
    }
    {
      const double r = radial.norm();
      radial = r > 1e-9 ? Vec3(radial / r * std::min(r, kLayerCap) / kLayerRadius) : Vec3(n);
      radial *= crotch_fade;
    }
    for (int j = 0; j < kJointCount; ++j) {
      const double wj = w(j);
      if (wj == 0.0) continue;
      for (int a = 0; a < 3; ++a) basis_(3 * i + a, kAnchor + 3 * j + a) += wj;
      const Vec3 d = p - skeleton.bone_start[j];
      for (int k = 0; k < 3; ++k) {
        const Vec3 r = frames_[j].col(k);
        const Vec3 contrib = wj * r * r.dot(d);
        for (int a = 0; a < 3; ++a) basis_(3 * i + a, kScale + 3 * j + k) += contrib[a];
      }
    }
    // Little soft tissue grows over the acromion (a bony landmark under thin skin): the fat,
    // muscle, upper-arm and deltoid layers fade by 80% within about 4.5 cm of where the tool
    // finds it. With them the measured shoulder width grew by about 4% per SD of muscle and 3%
    // per SD of fat, which the survey's biacromial breadth does not. (Over 3 cm and without
    // the deltoid band, the top of the shoulder folded at about one far corner of the box in
    // 300-500: a thin body's deltoid band pulled in round an acromion that stood still.)
    const double acromion_fade =
        1.0 - 0.8 * std::exp(-(p - acromion_exit[p.x() >= 0 ? 0 : 1]).squaredNorm() /
                             (2 * 0.045 * 0.045));
    auto set_field = [&](int field, const Vec3& disp) {
      const bool layer = field == kFatLayer || field == kMuscle || field == kLimbFat ||
                         field == kUpperArmBand || field == kDeltoidBand;
      const double f = layer ? acromion_fade : 1.0;
      for (int a = 0; a < 3; ++a) basis_(3 * i + a, kFields + field) = f * disp[a];
    };
    const double arm = w(kLeftShoulder) + w(kRightShoulder) + w(kLeftElbow) + w(kRightElbow) +
                       w(kLeftWrist) + w(kRightWrist) + w(kLeftHand) + w(kRightHand);
    const double head = w(kHead);
    const double extremity = w(kLeftHand) + w(kRightHand) + w(kLeftWrist) + w(kRightWrist) +
                             w(kLeftFoot) + w(kRightFoot) + 0.6 * (w(kLeftAnkle) + w(kRightAnkle));
    const double torso = std::max(0.0, 1.0 - arm - head - extremity);
    // Soft-tissue fields fade out towards the soles: feet keep their shape (a sole pushed
    // along its normal folds).
    const double above_feet = smoothstep(0.05, 0.16, p.y());
    const double front = smoothstep(-0.02, 0.07, p.z());
    const double back = smoothstep(0.0, -0.08, p.z());

    for (int side = 0; side < 2; ++side) {
      const double b = breast_bump(p, side);
      const Vec3 dir = Vec3(side == 0 ? 0.25 : -0.25, -0.35, 1.0).normalized();
      set_field(kBreastLeft + side, b * dir);
    }
    // Belly: the front of the abdomen, centred a little below the navel.
    // Belly and flanks: the front of the abdomen, centred a little below the navel, and
    // less at the sides and the lower back.
    set_field(kBelly, torso * (0.35 + 0.65 * front) * gauss(p.y(), 1.0, 0.11) *
                          (0.4 + 0.6 * gauss(p.x(), 0.0, 0.14)) *
                          (0.6 * n + Vec3(0, 0, 0.4 * front)));
    // Hips, buttocks and outer thighs (gynoid fat), fading down the thighs.
    set_field(kGluteofemoral,
              crotch_core * torso * gauss(p.y(), 0.83, 0.11) * (0.55 + 0.45 * back) * n);
    // Fat layer: all over the torso and limbs, thinner on head, hands and feet.
    set_field(kFatLayer,
              above_feet * std::max(0.0, 1.0 - head - extremity) * (0.6 + 0.4 * torso) * radial);
    // Muscles: deltoids and upper arms, forearms, trapezius, the neck, pectorals (a plate on
    // each side of the sternum, not a round bump), thighs, calves.
    const double pectoral = front * gauss(p.y(), 1.285, 0.045) *
                            smoothstep(0.0, 0.04, std::abs(p.x())) *
                            (1.0 - smoothstep(0.12, 0.17, std::abs(p.x())));
    const double muscle = w(kLeftShoulder) + w(kRightShoulder) +
                          0.3 * (w(kLeftElbow) + w(kRightElbow)) + w(kLeftCollar) +
                          w(kRightCollar) + 0.6 * w(kNeck) * (1.0 - front) +
                          0.6 * w(kSpine3) * pectoral + 0.8 * (w(kLeftHip) + w(kRightHip)) +
                          0.8 * (w(kLeftKnee) + w(kRightKnee));
    set_field(kMuscle, above_feet * muscle * radial);
    // Posture: the upper body leans forward; arms move with their shoulder.
    const double lean =
        (1.0 - arm) * posture_height(p.y()) + arm * posture_height(J[kLeftShoulder].y());
    set_field(kPostureShear, Vec3(0, 0, lean));
    set_field(kHeadForward, Vec3(0, 0, (1.0 - arm) * head_forward_height(p.y())));
    // Lordosis: buttocks back, lower back in (forwards), belly out.
    {
      // A wide transition from front to rear: a steeper one folds the sides of the hips when
      // the buttocks move forward far (lordosis at -3 on top of other components).
      const double rear = smoothstep(0.08, -0.14, p.z());
      const double dz = (-gauss(p.y(), 0.84, 0.12) + 0.8 * gauss(p.y(), 1.05, 0.10)) * rear +
                        0.5 * gauss(p.y(), 0.98, 0.10) * front;
      set_field(kLordosis, Vec3(0, 0, crotch_core * torso * dz));
    }
    // Rounded shoulders: arms and the shoulder girdle forward.
    set_field(kShouldersForward, Vec3(0, 0, arm + 0.6 * (w(kLeftCollar) + w(kRightCollar))));
    // Knee alignment: the knees move apart (bow legs) or together, most at the knee, fading
    // towards hip and ankle, which stay.
    {
      const double legs = w(kLeftHip) + w(kRightHip) + w(kLeftKnee) + w(kRightKnee) +
                          w(kLeftAnkle) + w(kRightAnkle) + w(kLeftFoot) + w(kRightFoot);
      const double side = p.x() >= 0 ? 1.0 : -1.0;
      set_field(kKneeAlignment, Vec3(side * legs * gauss(p.y(), 0.45, 0.16), 0, 0));
    }
    // Peripheral versus central fat: upper arms, forearms, thighs and calves fuller, the
    // trunk a little slimmer. Thinner segments get less, so a slim forearm never collapses.
    {
      const double limbs = 0.6 * (w(kLeftShoulder) + w(kRightShoulder)) +
                           0.25 * (w(kLeftElbow) + w(kRightElbow)) + (w(kLeftHip) + w(kRightHip)) +
                           0.6 * (w(kLeftKnee) + w(kRightKnee));
      set_field(kLimbFat, above_feet * (limbs - 0.4 * torso * (1.0 - limbs)) * radial);
    }
    // The top of the thighs, fading out towards the knees and into the buttocks and crotch.
    // (Below the crotch only legs and hands are at these heights; the hands are left out.)
    set_field(kThighTop, (1.0 - arm) * crotch_core * gauss(p.y(), 0.78, 0.045) * n);
    // The girth bands at the template's measuring levels (src/body/measurements.hpp: chest the
    // largest girth in 0.65-0.75 H, waist the smallest in 0.56-0.67 H, hips the largest in
    // 0.45-0.55 H, neck at 30-70% of neck -> head, thigh 1% of H below the crotch, calf the
    // largest at 20-50% of knee -> ankle, upper arm at 40-60% of shoulder -> elbow), wide
    // enough to cover where those levels fall on other bodies.
    {
      const double trunk = std::max(0.0, 1.0 - arm - head - extremity);
      // The offset from one bone's axis, in units of a thigh's radius.
      auto from_axis = [&](int bone) {
        const Vec3 a = skeleton.bone_start[bone], ab = skeleton.bone_end[bone] - a;
        const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        const Vec3 d = p - (a + t * ab);
        const double r = d.norm();
        return r > 1e-9 ? Vec3(d / r * std::min(r, kLayerCap) / kLayerRadius) : Vec3(n);
      };
      // Less on the inner thighs, where the thighs meet when both grow.
      const double medial = smoothstep(0.0, 0.7, -(p.x() >= 0 ? 1.0 : -1.0) * n.x());
      const double legs = w(kLeftHip) + w(kRightHip) + w(kLeftKnee) + w(kRightKnee) +
                          w(kLeftAnkle) + w(kRightAnkle);
      set_field(kChestBand, trunk * gauss(p.y(), 1.23, 0.05) * radial);
      // The waist is the smallest girth of its range: a band narrower than the range moves
      // the smallest girth out of the band instead of widening it.
      set_field(kWaistBand, trunk * smoothstep(0.84, 0.98, p.y()) *
                                (1.0 - smoothstep(1.10, 1.22, p.y())) * radial);
      set_field(kHipBand, trunk * (1.0 - 0.7 * medial * (1.0 - smoothstep(0.80, 0.86, p.y()))) *
                              gauss(p.y(), 0.87, 0.065) * radial);
      const double neck_mid = 0.5 * (J[kNeck].y() + J[kHead].y());
      // Not the head, and less under the chin: pushed along the radial direction, the lips
      // and the crease between chin and throat fold. A thick neck grows at the sides and the
      // back (sternocleidomastoids, trapezius).
      const double under_chin = front * smoothstep(neck_mid - 0.035, neck_mid, p.y());
      set_field(kNeckBand, (1.0 - arm) * (1.0 - head) * (1.0 - 0.8 * under_chin) *
                               (w(kNeck) + w(kSpine3)) * gauss(p.y(), neck_mid, 0.03) * radial);
      // Rising from above the knee (lower, the knee pit folds) to the furrow and on into the
      // buttocks, as a full thigh tapers: a band round the furrow alone showed as a ring when
      // raised. Away from the thigh bone's own axis, not faded at the crotch as the other
      // soft-tissue fields are: the thigh is measured just below it, and a band faded there
      // had to be raised so far that it ballooned the thigh below.
      const double thigh_profile = smoothstep(0.50, 0.78, p.y());
      set_field(kThighBand, legs * (1.0 - 0.8 * medial) * thigh_profile *
                                from_axis(p.x() >= 0 ? kLeftHip : kRightHip));
      const double calf_y = J[kLeftKnee].y() - 0.35 * (J[kLeftKnee].y() - J[kLeftAnkle].y());
      set_field(kCalfBand, above_feet * legs * gauss(p.y(), calf_y, 0.06) *
                               from_axis(p.x() >= 0 ? kLeftKnee : kRightKnee));
      const int shoulder = p.x() >= 0 ? kLeftShoulder : kRightShoulder;
      const Vec3 s0 = skeleton.bone_start[shoulder], s1 = skeleton.bone_end[shoulder];
      const double along = (p - s0).dot(s1 - s0) / (s1 - s0).squaredNorm();
      const Vec3 off_axis = from_axis(shoulder);
      set_field(kUpperArmBand,
                (w(kLeftShoulder) + w(kRightShoulder)) * gauss(along, 0.5, 0.2) * off_axis);
      // The deltoid: over the shoulder's cap and the top of the outer upper arm, where the
      // survey takes the bideltoid breadth (body/measurements.hpp: the arm's largest lateral
      // reach at 10-30% of shoulder -> elbow); little on the armpit's side. Centred at 25%
      // and wider, it raised the upper arm's girth (40-60%) more than the bideltoid breadth,
      // and the two bands, calibrated against each other, folded the shoulders of far bodies.
      const double outward = off_axis.x() * (p.x() >= 0 ? 1.0 : -1.0) / off_axis.norm();
      set_field(kDeltoidBand, (w(kLeftShoulder) + w(kRightShoulder)) * gauss(along, 0.15, 0.1) *
                                  smoothstep(-0.3, 0.6, outward) * off_axis);
    }
    basis_(3 * i + 1, kShift) = 1.0;
    if (p.y() < 0.03) sole_vertices_.push_back(i);
  }
}

Vec3 DeformationModel::bone_start(const Eigen::VectorXd& theta, int bone) const {
  return theta.segment<3>(kAnchor + 3 * bone) + Vec3(0.0, theta[kShift], 0.0);
}

void DeformationModel::smooth_fields(const std::vector<std::vector<int>>& neighbours,
                                     int iterations) {
  const int V = static_cast<int>(neighbours.size());
  Eigen::MatrixXd fields(3 * V, kFieldCount);
  fields = basis_.middleCols(kFields, kFieldCount);
  for (int it = 0; it < iterations; ++it) {
    Eigen::MatrixXd next(3 * V, kFieldCount);
    for (int v = 0; v < V; ++v) {
      Eigen::Matrix<double, 3, kFieldCount> sum = fields.middleRows<3>(3 * v);
      for (int u : neighbours[v]) sum += fields.middleRows<3>(3 * u) / neighbours[v].size();
      next.middleRows<3>(3 * v) = 0.5 * sum;
    }
    fields.swap(next);
  }
  basis_.middleCols(kFields, kFieldCount) = fields;
}

Eigen::VectorXd DeformationModel::rest_parameters() const {
  Eigen::VectorXd t = Eigen::VectorXd::Zero(kParams);
  for (int j = 0; j < kJointCount; ++j) {
    t.segment<3>(kAnchor + 3 * j) = skeleton_.bone_start[j];
    t.segment<3>(kScale + 3 * j).setOnes();
  }
  return t;
}

Eigen::VectorXd DeformationModel::parameters(const Anthropometry& a) const {
  const Anthropometry ref = reference_person();
  auto r = [&](int k) { return a.m[k] / ref.m[k]; };
  const IndependentFactors& f = a.f;
  const auto& J = skeleton_.joints;

  // Vertical proportions: the hip joints follow the crotch height, the torso and head take
  // up the rest of the stature.
  const Calibration& cal = a.female ? kFemaleCalibration : kMaleCalibration;
  const double s = r(k_stature);
  const double ls = cal.crotch * r(k_crotch_height);
  // The legs hang from the pelvis joint (everything below it scales by ls), so the torso and
  // head above it take ts with 1.70 s = pelvis_y ls + (1.70 - pelvis_y) ts: a longer leg at
  // the same stature shortens the trunk and leaves the stature alone.
  const double pelvis_y = J[kPelvis].y();
  const double ts = (kTemplateStature * s - pelvis_y * ls) / (kTemplateStature - pelvis_y);
  const double upper_arm = cal.arm * r(k_upper_arm_length);
  // forearm + hand length: the forearm takes what the hand does not.
  const double hand = r(k_hand_length);
  const double forearm =
      cal.arm * (r(k_forearm_hand_length) * 0.33 - hand * 0.085) / (0.33 - 0.085);
  const double foot = r(k_foot_length);
  const double head = std::sqrt(r(k_head_circ) * r(k_head_length));

  // Cross sections. The mannequin was modelled slimmer than the survey's reference person, and
  // the fields each sex gets on average (breasts, fat distribution, muscle) add to some
  // girths: these factors calibrate both, per sex, so that the mean bodies' girths measured
  // by the tool's own code (`bench-survey --models-dir`) match the survey's means.
  // The person's own girth bands (survey_calibration.hpp) then correct what is left, body by
  // body.
  const double pelvis_w = cal.pelvis * r(k_hip_breadth);
  const double pelvis_d = cal.pelvis * r(k_buttock_depth);
  const double waist_w = cal.waist * r(k_waist_breadth), waist_d = cal.waist * r(k_waist_depth);
  const double chest_w = cal.chest * r(k_chest_breadth), chest_d = cal.chest * r(k_chest_depth);
  const double neck = cal.neck * r(k_neck_circ);
  const double thigh = cal.thigh * r(k_thigh_circ), calf = cal.calf * r(k_calf_circ);
  const double ankle = r(k_ankle_circ);
  const double biceps = cal.biceps * r(k_biceps_circ), forearm_g = r(k_forearm_circ);
  const double wrist = r(k_wrist_circ);
  const double shoulder = cal.shoulder * r(k_biacromial) * (1.0 + a.knobs[kKnobShoulder]);
  const double pelvis_breadth = r(k_bicristal);

  std::array<Vec3, kJointCount> Jn;
  auto place = [&](int j, const Vec3& scale) {
    const int p = joint_parents()[j];
    Jn[j] = Jn[p] + (J[j] - J[p]).cwiseProduct(scale);
  };
  Jn[kPelvis] = J[kPelvis];
  for (int side = 0; side < 2; ++side) {
    place(kLeftHip + side, Vec3(pelvis_breadth, ls, s));
    place(kLeftKnee + side, Vec3(pelvis_breadth, ls, s));
    place(kLeftAnkle + side, Vec3(pelvis_breadth, ls, s));
    place(kLeftFoot + side, Vec3(foot, foot, foot));
  }
  place(kSpine1, Vec3(1, ts, s));
  place(kSpine2, Vec3(1, ts, s));
  place(kSpine3, Vec3(1, ts, s));
  place(kNeck, Vec3(1, ts, chest_d));
  // Neck length: +-1 SD moves the head by 13 mm (times kFactorScale).
  place(kHead, Vec3(1, head * ts / s, head));
  Jn[kHead].y() += 0.013 * f.neck_length;
  for (int side = 0; side < 2; ++side) {
    place(kLeftCollar + side, Vec3(shoulder, ts, s));
    place(kLeftShoulder + side, Vec3(shoulder, ts, s));
    // Shoulder slope: the shoulder joint 23 mm higher or lower per SD (times kFactorScale).
    Jn[kLeftShoulder + side].y() += 0.023 * f.shoulder_slope;
    place(kLeftElbow + side, Vec3(upper_arm, upper_arm, upper_arm));
    place(kLeftWrist + side, Vec3(forearm, forearm, forearm));
    place(kLeftHand + side, Vec3(hand, hand, hand));
  }

  Eigen::VectorXd t = Eigen::VectorXd::Zero(kParams);
  std::array<Vec3, kJointCount> scale;
  scale[kPelvis] = Vec3(ts, pelvis_w, pelvis_d);
  scale[kSpine1] = Vec3(ts, waist_w, waist_d);
  scale[kSpine2] = Vec3(ts, std::sqrt(waist_w * chest_w), std::sqrt(waist_d * chest_d));
  scale[kSpine3] = Vec3(ts, chest_w, chest_d);
  scale[kNeck] = Vec3(ts, neck, neck);
  scale[kHead] = Vec3(head, head, head);
  for (int side = 0; side < 2; ++side) {
    scale[kLeftCollar + side] =
        Vec3(shoulder, std::sqrt(chest_d * neck), std::sqrt(chest_d * neck));
    scale[kLeftShoulder + side] = Vec3(upper_arm, biceps, biceps);
    scale[kLeftElbow + side] = Vec3(forearm, forearm_g, forearm_g);
    scale[kLeftWrist + side] = Vec3(hand, wrist, wrist);
    scale[kLeftHand + side] = Vec3(hand, std::sqrt(hand * wrist), std::sqrt(hand * wrist));
    scale[kLeftHip + side] = Vec3(ls, thigh, thigh);
    scale[kLeftKnee + side] = Vec3(ls, calf, calf);
    scale[kLeftAnkle + side] = Vec3(ls, ankle, ankle);
    scale[kLeftFoot + side] = Vec3(foot, std::sqrt(foot * ankle), std::sqrt(foot * ankle));
  }
  for (int j = 0; j < kJointCount; ++j) {
    // Bone anchors move with their joint (the pelvis bone's anchor sits below its joint).
    const Vec3 offset = skeleton_.bone_start[j] - J[j];
    t.segment<3>(kAnchor + 3 * j) = Jn[j] + offset.cwiseProduct(Vec3(1, ts, s));
    t.segment<3>(kScale + 3 * j) = scale[j];
  }

  // Breasts: women's grow with the chest girth at the given chest breadth and depth and with
  // their own factor; men's are a slight pectoral curve.
  const SurveyTable& own = a.female ? kFemale : kMale;
  const double chest_z = (a.m[k_chest_circ] - own.mean[k_chest_circ]) / own.sd[k_chest_circ];
  // Men get none: the template's flat pectorals and the muscle field shape their chest, and
  // no male body anywhere in the box may show breasts.
  const double breast = a.female ? std::max(0.0, 0.070 + 0.008 * chest_z + 0.016 * f.bust) : 0.0;
  t[kFields + kBreastLeft] = t[kFields + kBreastRight] = breast;
  t[kFields + kBelly] = 0.018 * f.fat_distribution;
  t[kFields + kGluteofemoral] = -0.015 * f.fat_distribution;
  t[kFields + kFatLayer] = 0.0065 * f.fat_layer + a.knobs[kKnobMass];
  t[kFields + kMuscle] = 0.009 * f.muscle;
  t[kFields + kPostureShear] = 0.021 * f.posture;
  t[kFields + kHeadForward] = 0.045 * f.head_forward;
  t[kFields + kLordosis] = 0.023 * f.lordosis;
  t[kFields + kShouldersForward] = 0.0115 * f.shoulders_forward;
  t[kFields + kLimbFat] = 0.006 * f.limb_fat;
  t[kFields + kKneeAlignment] = 0.0105 * f.knee_alignment;
  t[kFields + kThighTop] = cal.thigh_top;
  for (int k = 0; k < kKnobBands; ++k) t[kFields + kChestBand + k] = a.knobs[k];
  // Soles on y = 0.
  double lowest = 1e9;
  for (int i : sole_vertices_) lowest = std::min(lowest, basis_.row(3 * i + 1).dot(t));
  t[kShift] = -lowest;
  return t;
}

}  // namespace default_model
