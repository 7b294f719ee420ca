#include "population.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Cholesky>

namespace default_model {

namespace {

// Anthropometric summary statistics (mean, SD), cm and kg, of the 2012 U.S. Army
// Anthropometric Survey (ANSUR II): C. C. Gordon et al., "2012 Anthropometric Survey of U.S.
// Army Personnel: Methods and Summary Statistics", NATICK/TR-15/007, 2014 (n = 4082 men,
// 1986 women). Values rounded; see docs/default-model.md for the list and caveats.
struct Stat {
  double mean, sd;
};
struct SexStats {
  Stat stature, weight, chest, waist, hip, biacromial, chest_depth, neck, head;
};
constexpr SexStats kMale{{175.6, 6.9}, {85.5, 14.2}, {106.4, 8.6}, {94.2, 11.1}, {102.3, 7.6},
                         {41.6, 1.9},  {25.3, 2.3},  {39.6, 2.4},  {57.3, 1.6}};
constexpr SexStats kFemale{{162.9, 6.4}, {67.8, 11.4}, {95.2, 7.8}, {85.6, 9.8}, {101.5, 7.6},
                           {36.5, 1.8},  {24.1, 2.3},  {33.1, 1.9}, {55.4, 1.6}};

constexpr int kFactors =
    12;  // stature weight chest waist hip shoulder cdepth neck head leg arm muscle

// Within-sex correlations, rounded from the correlation tables of the Army surveys (Cheverud
// et al. 1990, NATICK/TR-90/032, for the 1988 survey; the 2012 survey shows the same pattern).
Eigen::MatrixXd correlation() {
  Eigen::MatrixXd R = Eigen::MatrixXd::Identity(kFactors, kFactors);
  auto set = [&](int a, int b, double r) { R(a, b) = R(b, a) = r; };
  enum { St, Wt, Ch, Wa, Hp, Sh, Cd, Nk, Hd, Lg, Ar, Mu };
  set(St, Wt, 0.45);
  set(St, Ch, 0.20);
  set(St, Wa, 0.15);
  set(St, Hp, 0.30);
  set(St, Sh, 0.45);
  set(St, Cd, 0.10);
  set(St, Nk, 0.25);
  set(St, Hd, 0.30);
  set(St, Lg, 0.10);
  set(Wt, Ch, 0.85);
  set(Wt, Wa, 0.85);
  set(Wt, Hp, 0.85);
  set(Wt, Sh, 0.50);
  set(Wt, Cd, 0.75);
  set(Wt, Nk, 0.75);
  set(Wt, Hd, 0.25);
  set(Wt, Mu, 0.20);
  set(Ch, Wa, 0.80);
  set(Ch, Hp, 0.70);
  set(Ch, Sh, 0.45);
  set(Ch, Cd, 0.80);
  set(Ch, Nk, 0.70);
  set(Ch, Mu, 0.25);
  set(Wa, Hp, 0.75);
  set(Wa, Sh, 0.30);
  set(Wa, Cd, 0.75);
  set(Wa, Nk, 0.65);
  set(Wa, Mu, -0.10);
  set(Hp, Sh, 0.30);
  set(Hp, Cd, 0.60);
  set(Hp, Nk, 0.50);
  set(Sh, Cd, 0.35);
  set(Sh, Nk, 0.45);
  set(Sh, Mu, 0.35);
  set(Cd, Nk, 0.60);
  set(Nk, Mu, 0.35);
  // Rounded correlations need not be positive definite; shrink towards I until they are.
  for (double alpha = 0.0; alpha < 1.0; alpha += 0.02) {
    Eigen::MatrixXd S = (1 - alpha) * R + alpha * Eigen::MatrixXd::Identity(kFactors, kFactors);
    Eigen::LLT<Eigen::MatrixXd> llt(S);
    if (llt.info() == Eigen::Success && llt.matrixL().toDenseMatrix().diagonal().minCoeff() > 0.05)
      return S;
  }
  return Eigen::MatrixXd::Identity(kFactors, kFactors);
}

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
  std::uint64_t bits() { return engine_(); }

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0;
};

double value(const Stat& s, double z) {
  return s.mean + s.sd * z;
}
double mid(const Stat& a, const Stat& b) {
  return 0.5 * (a.mean + b.mean);
}

}  // namespace

std::vector<Anthropometry> sample_population(int count, std::uint64_t seed) {
  const Eigen::MatrixXd L = correlation().llt().matrixL();
  Normal normal(seed);
  std::vector<Anthropometry> people;
  people.reserve(count);
  for (int i = 0; i < count; ++i) {
    Anthropometry a;
    a.female = (normal.bits() >> 63) != 0;  // 50/50 mixture
    Eigen::VectorXd z(kFactors);
    for (int k = 0; k < kFactors; ++k) {
      // Truncate at 2.5 SD: the population models plausible adults, not the survey's tails.
      double x = normal();
      while (std::abs(x) > 2.5) x = normal();
      z[k] = x;
    }
    z = L * z;
    const SexStats& s = a.female ? kFemale : kMale;
    a.stature_cm = value(s.stature, z[0]);
    a.weight_kg = value(s.weight, z[1]);
    a.chest_cm = value(s.chest, z[2]);
    a.waist_cm = value(s.waist, z[3]);
    a.hip_cm = value(s.hip, z[4]);
    a.biacromial_cm = value(s.biacromial, z[5]);
    a.chest_depth_cm = value(s.chest_depth, z[6]);
    a.neck_cm = value(s.neck, z[7]);
    a.head_cm = value(s.head, z[8]);
    a.leg_ratio_z = z[9];
    a.arm_z = z[10];
    a.muscle_z = z[11] + (a.female ? -0.5 : 0.5);
    people.push_back(a);
  }
  return people;
}

Anthropometry mean_person() {
  Anthropometry a;
  a.stature_cm = mid(kMale.stature, kFemale.stature);
  a.weight_kg = mid(kMale.weight, kFemale.weight);
  a.chest_cm = mid(kMale.chest, kFemale.chest);
  a.waist_cm = mid(kMale.waist, kFemale.waist);
  a.hip_cm = mid(kMale.hip, kFemale.hip);
  a.biacromial_cm = mid(kMale.biacromial, kFemale.biacromial);
  a.chest_depth_cm = mid(kMale.chest_depth, kFemale.chest_depth);
  a.neck_cm = mid(kMale.neck, kFemale.neck);
  a.head_cm = mid(kMale.head, kFemale.head);
  return a;
}

namespace {

// Parameter layout: for each joint j, 3 entries for the new bone anchor, then 3 scales (along,
// u, v); then the two breast amplitudes and the vertical shift.
constexpr int kAnchor = 0;
constexpr int kScale = 3 * kJointCount;
constexpr int kBreast = 6 * kJointCount;
constexpr int kShift = kBreast + 2;
constexpr int kParams = kShift + 1;

Vec3 breast_centre(int side) {
  return Vec3(side == 0 ? 0.085 : -0.085, 1.255, 0.10);
}

double breast_bump(const Vec3& p, int side) {
  if (p.z() < 0.0) return 0.0;
  const Vec3 d = p - breast_centre(side);
  const double r2 = d.x() * d.x() + 1.3 * d.y() * d.y() + 0.5 * d.z() * d.z();
  return std::exp(-r2 / (2 * 0.05 * 0.05)) * smoothstep(0.0, 0.06, p.z());
}

}  // namespace

DeformationModel::DeformationModel(const std::vector<Vec3>& template_vertices,
                                   const Skeleton& skeleton, const Eigen::MatrixXd& weights)
    : skeleton_(skeleton), vertices_(template_vertices), weights_(weights) {
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
  for (int i = 0; i < V; ++i) {
    const Vec3& p = template_vertices[i];
    for (int j = 0; j < kJointCount; ++j) {
      const double w = weights(i, j);
      if (w == 0.0) continue;
      for (int a = 0; a < 3; ++a) basis_(3 * i + a, kAnchor + 3 * j + a) += w;
      const Vec3 d = p - skeleton.bone_start[j];
      for (int k = 0; k < 3; ++k) {
        const Vec3 r = frames_[j].col(k);
        const Vec3 contrib = w * r * r.dot(d);
        for (int a = 0; a < 3; ++a) basis_(3 * i + a, kScale + 3 * j + k) += contrib[a];
      }
    }
    for (int side = 0; side < 2; ++side) {
      const double b = breast_bump(p, side);
      const Vec3 dir = Vec3(side == 0 ? 0.25 : -0.25, -0.35, 1.0).normalized();
      for (int a = 0; a < 3; ++a) basis_(3 * i + a, kBreast + side) = b * dir[a];
    }
    basis_(3 * i + 1, kShift) = 1.0;
    if (p.y() < 0.03) sole_vertices_.push_back(i);
  }
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
  const Anthropometry m = mean_person();
  const double s = a.stature_cm / m.stature_cm;
  // Leg length (hip joint height) varies +-2.2 % (1 SD) relative to stature; the torso takes
  // up the rest so stature is kept.
  const double leg_share = skeleton_.joints[kLeftHip].y() / 1.70;
  const double leg = 1.0 + 0.022 * a.leg_ratio_z;
  const double torso = (1.0 - leg_share * leg) / (1.0 - leg_share);
  const double ls = s * leg, ts = s * torso;
  const double arm = s * (1.0 + 0.025 * a.arm_z);
  const double chest = a.chest_cm / m.chest_cm;
  const double waist = a.waist_cm / m.waist_cm;
  const double hip = a.hip_cm / m.hip_cm;
  const double shoulder = a.biacromial_cm / m.biacromial_cm;
  const double depth = a.chest_depth_cm / m.chest_depth_cm;
  const double neck = a.neck_cm / m.neck_cm;
  const double head = a.head_cm / m.head_cm;
  const double muscle = a.muscle_z;
  // Limb girth from body mass at the given stature (mass ~ length x girth^2).
  const double limb = std::sqrt(a.weight_kg / m.weight_kg / s);
  const double arm_girth = limb * (1.0 + 0.045 * muscle);
  const double thigh_girth = limb * std::sqrt(hip / limb) * (1.0 + 0.025 * muscle);
  const double calf_girth = std::pow(limb, 0.6) * (1.0 + 0.02 * muscle);

  const auto& J = skeleton_.joints;
  std::array<Vec3, kJointCount> Jn;
  auto place = [&](int j, const Vec3& scale) {
    const int p = joint_parents()[j];
    Jn[j] = Jn[p] + (J[j] - J[p]).cwiseProduct(scale);
  };
  const double hip_breadth = std::pow(hip, 0.8) * std::pow(thigh_girth, 0.2);
  Jn[kPelvis] = J[kPelvis];
  for (int side = 0; side < 2; ++side) {
    place(kLeftHip + side, Vec3(hip_breadth, ts, s));
    place(kLeftKnee + side, Vec3(hip_breadth, ls, s));
    place(kLeftAnkle + side, Vec3(hip_breadth, ls, s));
    place(kLeftFoot + side, Vec3(s, s, s));
  }
  place(kSpine1, Vec3(1, ts, s));
  place(kSpine2, Vec3(1, ts, s));
  place(kSpine3, Vec3(1, ts, s));
  place(kNeck, Vec3(1, ts, depth));
  place(kHead, Vec3(1, head * ts / s, head));
  for (int side = 0; side < 2; ++side) {
    place(kLeftCollar + side, Vec3(shoulder, ts, s));
    place(kLeftShoulder + side, Vec3(shoulder, ts, s));
    place(kLeftElbow + side, Vec3(arm, arm, arm));
    place(kLeftWrist + side, Vec3(arm, arm, arm));
    place(kLeftHand + side, Vec3(arm, arm, arm));
  }

  Eigen::VectorXd t = Eigen::VectorXd::Zero(kParams);
  std::array<Vec3, kJointCount> scale;
  scale[kPelvis] = Vec3(ts, hip, hip);
  scale[kSpine1] = Vec3(ts, waist, waist * std::pow(waist, 0.3));
  scale[kSpine2] = Vec3(ts, std::sqrt(waist * chest), std::sqrt(waist * depth));
  scale[kSpine3] = Vec3(ts, std::pow(chest, 0.7) * std::pow(shoulder, 0.3), depth);
  scale[kNeck] = Vec3(ts, neck, neck);
  scale[kHead] = Vec3(head, head, head);
  for (int side = 0; side < 2; ++side) {
    const double trap = std::sqrt(chest * neck) * (1.0 + 0.02 * muscle);
    scale[kLeftCollar + side] = Vec3(shoulder, trap, trap);
    scale[kLeftShoulder + side] = Vec3(arm, arm_girth, arm_girth);
    scale[kLeftElbow + side] = Vec3(arm, std::pow(arm_girth, 0.7), std::pow(arm_girth, 0.7));
    scale[kLeftWrist + side] = Vec3(arm, s, s);
    scale[kLeftHand + side] = Vec3(arm, s, s);
    scale[kLeftHip + side] = Vec3(ls, thigh_girth, thigh_girth);
    scale[kLeftKnee + side] = Vec3(ls, calf_girth, calf_girth);
    scale[kLeftAnkle + side] = Vec3(s, s, s);
    scale[kLeftFoot + side] = Vec3(s, s, s);
  }
  for (int j = 0; j < kJointCount; ++j) {
    // Bone anchors move with their joint (the pelvis bone's anchor sits below its joint).
    const Vec3 offset = skeleton_.bone_start[j] - J[j];
    t.segment<3>(kAnchor + 3 * j) = Jn[j] + offset.cwiseProduct(Vec3(1, ts, s));
    t.segment<3>(kScale + 3 * j) = scale[j];
  }
  const double breast = a.female ? std::max(0.0, 0.022 + 0.012 * (a.chest_cm - 95.2) / 7.8)
                                 : std::max(0.0, 0.004 + 0.004 * muscle);
  t[kBreast] = t[kBreast + 1] = breast;
  // Soles on y = 0.
  double lowest = 1e9;
  for (int i : sole_vertices_) lowest = std::min(lowest, basis_.row(3 * i + 1).dot(t));
  t[kShift] = -lowest;
  return t;
}

}  // namespace default_model
