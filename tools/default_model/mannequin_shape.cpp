#include "mannequin_shape.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace default_model {

const std::array<const char*, kJointCount>& joint_names() {
  static const std::array<const char*, kJointCount> names = {
      "pelvis",     "left_hip",    "right_hip",    "spine1",      "left_knee",     "right_knee",
      "spine2",     "left_ankle",  "right_ankle",  "spine3",      "left_foot",     "right_foot",
      "neck",       "left_collar", "right_collar", "head",        "left_shoulder", "right_shoulder",
      "left_elbow", "right_elbow", "left_wrist",   "right_wrist", "left_hand",     "right_hand"};
  return names;
}

const std::array<int, kJointCount>& joint_parents() {
  static const std::array<int, kJointCount> parents = {
      -1, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9, 9, 12, 13, 14, 16, 17, 18, 19, 20, 21};
  return parents;
}

double smooth_min(double a, double b, double k) {
  if (k <= 0) return std::min(a, b);
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

void Capsule::finish() {
  Vec3 d = b - a;
  length = d.norm();
  axis = length > 1e-12 ? Vec3(d / length) : Vec3(0, 1, 0);
  u = u_hint - axis * axis.dot(u_hint);
  u.normalize();
  v = axis.cross(u);
}

// Distance estimate of an ellipsoid in the capsule's local frame (Inigo Quilez's bound
// k0 (k0 - 1) / k1), with the along-axis coordinate measured beyond the clamped segment.
double Capsule::distance(const Vec3& p) const {
  return distance(p, nullptr);
}

double Capsule::distance(const Vec3& p, Vec3* normal) const {
  const Vec3 d = p - a;
  const double s = d.dot(axis);
  const double t = length > 0 ? std::clamp(s / length, 0.0, 1.0) : 0.0;
  const double ru = ru_a + (ru_b - ru_a) * t;
  const double rv = rv_a + (rv_b - rv_a) * t;
  const double beyond = s - t * length;
  const double rc = beyond < 0 ? cap_a : cap_b;
  const double qu = d.dot(u), qv = d.dot(v);
  const Vec3 q(qu / ru, qv / rv, beyond / rc);
  const Vec3 q2(qu / (ru * ru), qv / (rv * rv), beyond / (rc * rc));
  const double k0 = q.norm();
  const double k1 = q2.norm();
  if (normal) {
    const Vec3 g = q2.x() * u + q2.y() * v + q2.z() * axis;
    const double l = g.norm();
    *normal = l > 1e-12 ? Vec3(g / l) : axis;
  }
  if (k1 < 1e-12) return -std::min({ru, rv, rc});
  return k0 * (k0 - 1.0) / k1;
}

Dist smooth_union(const Dist& a, const Dist& b, double k) {
  const Dist& lo = a.d <= b.d ? a : b;
  const Dist& hi = a.d <= b.d ? b : a;
  const double gap = hi.d - lo.d;
  if (k <= 0 || gap >= k) return lo;
  static const double kFullAngle = 1.0 - std::cos(50.0 * M_PI / 180.0);
  const double cosine = std::clamp(a.n.dot(b.n), -1.0, 1.0);
  const double ke = k * smoothstep(0.0, kFullAngle, 1.0 - cosine);
  if (ke <= 1e-9 || gap >= ke) return lo;
  const double h = (ke - gap) / ke;
  // d/d(lo) = 1 - h/2 and d/d(hi) = h/2 for the polynomial smooth-min.
  const Vec3 n = (1.0 - 0.5 * h) * lo.n + 0.5 * h * hi.n;
  return {lo.d - h * h * ke * 0.25, n.norm() > 1e-12 ? Vec3(n.normalized()) : lo.n};
}

namespace {

Capsule capsule(const Vec3& a, const Vec3& b, const Vec3& hint, double ru_a, double rv_a,
                double ru_b, double rv_b, double cap_a, double cap_b) {
  Capsule c{a, b, hint, ru_a, rv_a, ru_b, rv_b, cap_a, cap_b, {}, {}, {}, 0};
  c.finish();
  return c;
}

// An ellipsoid with semi-axes ra along `axis`, ru along `hint` (orthogonalised), rv along the
// third direction.
Capsule ellipsoid(const Vec3& centre, const Vec3& axis, const Vec3& hint, double ra, double ru,
                  double rv) {
  Capsule c{centre, centre + 1e-9 * axis.normalized(), hint, ru, rv, ru, rv, ra, ra, {}, {}, {}, 0};
  c.finish();
  return c;
}

// A sphere holding the given primitives (their axes plus their largest radius or cap).
std::pair<Vec3, double> bounding_sphere(const std::vector<std::pair<Capsule, double>>& parts,
                                        std::size_t begin) {
  Vec3 c = Vec3::Zero();
  int n = 0;
  for (std::size_t i = begin; i < parts.size(); ++i, n += 2)
    c += parts[i].first.a + parts[i].first.b;
  c /= std::max(n, 1);
  double r = 0;
  for (std::size_t i = begin; i < parts.size(); ++i) {
    const Capsule& q = parts[i].first;
    const double extent = std::max({q.ru_a, q.rv_a, q.ru_b, q.rv_b, q.cap_a, q.cap_b});
    r = std::max({r, (q.a - c).norm() + extent, (q.b - c).norm() + extent});
  }
  return {c, r};
}

Vec3 mirror(const Vec3& p) {
  return Vec3(-p.x(), p.y(), p.z());
}

}  // namespace

Mannequin::Mannequin() {
  auto& J = skeleton_.joints;
  // Rest joints of the left side; the right side mirrors them.
  J[kPelvis] = Vec3(0, 0.925, -0.005);
  J[kSpine1] = Vec3(0, 1.03, -0.015);
  J[kSpine2] = Vec3(0, 1.15, -0.015);
  J[kSpine3] = Vec3(0, 1.27, -0.02);
  J[kNeck] = Vec3(0, 1.45, -0.025);
  J[kHead] = Vec3(0, 1.54, 0.0);
  J[kLeftHip] = Vec3(0.09, 0.865, 0.0);
  J[kLeftKnee] = Vec3(0.116, 0.48, 0.01);
  J[kLeftAnkle] = Vec3(0.128, 0.075, -0.02);
  J[kLeftFoot] = Vec3(0.138, 0.02, 0.10);
  J[kLeftCollar] = Vec3(0.045, 1.385, -0.02);
  J[kLeftShoulder] = Vec3(0.175, 1.385, -0.03);
  // A-pose: the arms hang 50 degrees from the vertical, palms facing the thighs; wide enough
  // that armpits stay open for bodies far outside the population (betas of +-3 on several
  // components at once).
  const double arm_angle = 50.0 * M_PI / 180.0;
  const Vec3 d_upper(std::sin(arm_angle), -std::cos(arm_angle), 0.0);
  const Vec3 d_fore = Vec3(std::sin(arm_angle), -std::cos(arm_angle), 0.08).normalized();
  J[kLeftElbow] = J[kLeftShoulder] + 0.27 * d_upper;
  J[kLeftWrist] = J[kLeftElbow] + 0.245 * d_fore;
  J[kLeftHand] = J[kLeftWrist] + 0.085 * d_fore;
  for (int j : {kLeftHip, kLeftKnee, kLeftAnkle, kLeftFoot, kLeftCollar, kLeftShoulder, kLeftElbow,
                kLeftWrist, kLeftHand}) {
    J[j + 1] = mirror(J[j]);
  }

  // Bones: the segment each joint drives.
  auto& bs = skeleton_.bone_start;
  auto& be = skeleton_.bone_end;
  auto& br = skeleton_.bone_radius;
  for (int j = 0; j < kJointCount; ++j) bs[j] = J[j];
  bs[kPelvis] = Vec3(0, 0.80, -0.01);
  be[kPelvis] = J[kSpine1];
  br[kPelvis] = 0.15;
  be[kSpine1] = J[kSpine2];
  br[kSpine1] = 0.13;
  be[kSpine2] = J[kSpine3];
  br[kSpine2] = 0.14;
  be[kSpine3] = Vec3(0, 1.40, -0.025);
  br[kSpine3] = 0.15;
  be[kNeck] = J[kHead];
  br[kNeck] = 0.055;
  be[kHead] = Vec3(0, 1.66, 0.01);
  br[kHead] = 0.09;
  const Vec3 n_arm(std::cos(arm_angle), std::sin(arm_angle), 0.0);  // lateral-up normal
  for (int s = 0; s < 2; ++s) {
    const int o = s;  // left joints are odd-even pairs: left = base, right = base + 1
    auto M = [&](const Vec3& p) { return s == 0 ? p : mirror(p); };
    be[kLeftHip + o] = J[kLeftKnee + o];
    br[kLeftHip + o] = 0.075;
    be[kLeftKnee + o] = J[kLeftAnkle + o];
    br[kLeftKnee + o] = 0.045;
    be[kLeftAnkle + o] = J[kLeftFoot + o];
    br[kLeftAnkle + o] = 0.035;
    be[kLeftFoot + o] = M(Vec3(0.145, 0.02, 0.17));
    br[kLeftFoot + o] = 0.025;
    be[kLeftCollar + o] = J[kLeftShoulder + o];
    br[kLeftCollar + o] = 0.05;
    be[kLeftShoulder + o] = J[kLeftElbow + o];
    br[kLeftShoulder + o] = 0.045;
    be[kLeftElbow + o] = J[kLeftWrist + o];
    br[kLeftElbow + o] = 0.035;
    be[kLeftWrist + o] = J[kLeftHand + o];
    br[kLeftWrist + o] = 0.03;
    be[kLeftHand + o] = J[kLeftWrist + o] + M(0.18 * d_fore);
    br[kLeftHand + o] = 0.02;
  }
  // Fix the mirrored directions of the right side's hand bone end (computed with M above).
  be[kRightHand] = mirror(be[kLeftHand]);

  // Torso: superelliptic cross sections (half width in x, half depth in z, centre z).
  levels_ = {
      {0.760, 0.150, 0.095, -0.012}, {0.830, 0.157, 0.100, -0.012}, {0.880, 0.158, 0.102, -0.010},
      {0.940, 0.154, 0.104, -0.002}, {1.010, 0.142, 0.099, 0.008},  {1.070, 0.134, 0.097, 0.010},
      {1.140, 0.141, 0.100, 0.004},  {1.230, 0.156, 0.109, 0.002},  {1.320, 0.160, 0.108, -0.006},
      {1.400, 0.138, 0.088, -0.026}, {1.450, 0.080, 0.060, -0.028}};

  const Vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  for (int s = 0; s < 2; ++s) {
    auto M = [&](const Vec3& p) { return s == 0 ? p : mirror(p); };
    const double sx = s == 0 ? 1.0 : -1.0;
    // Buttocks, pectorals, trapezius. The pectoral is a broad, flat plate from the sternum to
    // the front of the armpit with a nearly level lower border, fuller at the armpit, and the
    // upper chest stays full up to the collar bone (the loft above): round ellipsoids here, or
    // a chest that recedes above its fullest level, read as breasts. The female model's
    // breasts are a displacement field of their own (population.cpp).
    torso_parts_.push_back(
        {ellipsoid(Vec3(sx * 0.072, 0.865, -0.042), Y, X, 0.095, 0.085, 0.068), 0.04});
    torso_parts_.push_back({capsule(Vec3(sx * 0.03, 1.29, 0.083), Vec3(sx * 0.13, 1.31, 0.060), Y,
                                    0.052, 0.021, 0.048, 0.025, 0.02, 0.03),
                            0.035});
    torso_parts_.push_back({capsule(Vec3(0, 1.45, -0.04), M(Vec3(0.16, 1.40, -0.035)), Y, 0.035,
                                    0.05, 0.03, 0.045, 0.03, 0.03),
                            0.04});
  }
  // Neck.
  torso_parts_.push_back({capsule(Vec3(0, 1.40, -0.025), Vec3(0, 1.54, -0.005), X, 0.055, 0.058,
                                  0.052, 0.055, 0.03, 0.03),
                          0.035});
  // Head: cranium, jaw, nose, ears.
  head_parts_.push_back({ellipsoid(Vec3(0, 1.595, 0.005), Y, X, 0.105, 0.077, 0.097), 0.0});
  head_parts_.push_back({ellipsoid(Vec3(0, 1.535, 0.035), Y, X, 0.045, 0.056, 0.06), 0.03});
  // Face: brow ridge, nose (bridge to tip, with the wings), cheeks, lips, chin; the eye
  // sockets are carved out below the brow (head_cuts_).
  head_parts_.push_back({ellipsoid(Vec3(0, 1.621, 0.086), Y, X, 0.011, 0.05, 0.014), 0.014});
  head_parts_.push_back({capsule(Vec3(0, 1.602, 0.096), Vec3(0, 1.566, 0.117), X, 0.0075, 0.006,
                                 0.0105, 0.009, 0.006, 0.008),
                         0.01});
  head_parts_.push_back({ellipsoid(Vec3(0, 1.562, 0.104), Y, X, 0.008, 0.016, 0.01), 0.008});
  // Lips: upper and lower, each fullest at the middle and thinning towards the corners, which
  // sit back on the curve of the jaw; a thin cut between them is the mouth line.
  for (double sx : {1.0, -1.0}) {
    head_parts_.push_back({capsule(Vec3(0, 1.5385, 0.0960), Vec3(sx * 0.021, 1.5355, 0.0885), Y,
                                   0.0062, 0.0085, 0.0032, 0.0045, 0.004, 0.004),
                           0.006});
    head_parts_.push_back({capsule(Vec3(0, 1.5245, 0.0935), Vec3(sx * 0.019, 1.5285, 0.0875), Y,
                                   0.0068, 0.0088, 0.0032, 0.0045, 0.004, 0.004),
                           0.006});
  }
  head_cuts_.push_back({ellipsoid(Vec3(0, 1.5317, 0.103), Y, X, 0.0016, 0.0225, 0.014), 0.0015});
  landmarks_.mouth_y = 1.5317;
  landmarks_.jaw = Vec3(0, 1.55, 0.02);
  landmarks_.chin = Vec3(0, 1.492, 0.082);
  landmarks_.face = Vec3(0, 1.588, 0.072);
  head_parts_.push_back({ellipsoid(Vec3(0, 1.499, 0.079), Y, X, 0.017, 0.022, 0.017), 0.016});
  for (double sx : {1.0, -1.0}) {
    head_parts_.push_back(
        {ellipsoid(Vec3(sx * 0.045, 1.567, 0.068), Y, X, 0.022, 0.022, 0.024), 0.02});
    head_cuts_.push_back(
        {ellipsoid(Vec3(sx * 0.031, 1.599, 0.101), Y, X, 0.013, 0.016, 0.012), 0.008});
    // Eyes: an eyeball in the socket, the upper lid over its top and the lower lid under it,
    // leaving an open almond of eyeball between them (about 6 mm high at its middle; an
    // adult's palpebral fissure is 8-10 mm; lids that meet read as closed eyes).
    const Vec3 eye(sx * 0.031, 1.5985, 0.0848);
    landmarks_.eye_centres[sx > 0 ? 0 : 1] = eye;
    landmarks_.eye_radius = 0.0122;
    // The lids meet the eyeball in a crease (small blend radii): blended smoothly, lids and
    // eyeball read as one closed bulge.
    head_details_.push_back({ellipsoid(eye, Y, X, 0.0122, 0.0122, 0.0122), 0.0015});
    head_details_.push_back(
        {ellipsoid(eye + Vec3(0, 0.0116, 0.0002), Y, X, 0.0094, 0.0128, 0.0130), 0.0012});
    head_details_.push_back(
        {ellipsoid(eye + Vec3(0, -0.0112, 0.0), Y, X, 0.0072, 0.0124, 0.0127), 0.0012});
    // Brows: a low ridge arching over each eye, fullest towards the nose.
    head_details_.push_back(
        {capsule(Vec3(sx * 0.014, 1.6165, 0.0975), Vec3(sx * 0.050, 1.6155, 0.0865), Y, 0.0042,
                 0.0045, 0.0032, 0.0035, 0.004, 0.004),
         0.004});
  }
  for (double sx : {1.0, -1.0}) {
    head_parts_.push_back(
        {ellipsoid(Vec3(sx * 0.076, 1.588, -0.005), Y, X, 0.03, 0.012, 0.02), 0.012});
    // The ear's bowl (concha) hollowed out of its outer face, leaving the rim (helix) round
    // it; and the nostrils under the tip of the nose.
    head_cuts_.push_back(
        {ellipsoid(Vec3(sx * 0.0875, 1.584, -0.001), Y, X, 0.016, 0.0055, 0.0095), 0.003});
    head_cuts_.push_back(
        {ellipsoid(Vec3(sx * 0.0072, 1.5555, 0.1085), Y, X, 0.0026, 0.0036, 0.0042), 0.0015});
  }

  std::tie(head_centre_, head_radius_) = bounding_sphere(head_parts_, 0);

  for (int s = 0; s < 2; ++s) {
    auto M = [&](const Vec3& p) { return s == 0 ? p : mirror(p); };
    const int o = s;
    Side& side = sides_[s];
    const Vec3 du = s == 0 ? d_upper : mirror(d_upper);
    const Vec3 df = s == 0 ? d_fore : mirror(d_fore);
    const Vec3 n = s == 0 ? n_arm : mirror(n_arm);
    const Vec3 sh = J[kLeftShoulder + o], el = J[kLeftElbow + o], wr = J[kLeftWrist + o];
    side.shoulder = sh;
    // Arm: upper arm, deltoid, forearm with its muscle belly, palm, fingers, thumb.
    side.arm.push_back(
        {capsule(sh + 0.01 * du, el, n, 0.050, 0.054, 0.037, 0.041, 0.04, 0.03), 0.0});
    side.arm.push_back({ellipsoid(sh + 0.035 * du + 0.012 * n, du, n, 0.075, 0.05, 0.056), 0.03});
    side.arm.push_back({capsule(el, wr, n, 0.037, 0.041, 0.019, 0.028, 0.03, 0.02), 0.025});
    side.arm.push_back({ellipsoid(el + 0.08 * df + 0.004 * n, df, n, 0.09, 0.035, 0.042), 0.03});
    side.arm.push_back(
        {capsule(wr + 0.012 * df, wr + 0.075 * df, n, 0.0165, 0.038, 0.0145, 0.042, 0.015, 0.012),
         0.03});
    const Vec3 zf = M(Vec3(0, 0, 1));
    // Four fingers, fanned slightly so that they part beyond the knuckles: index (on the
    // thumb's side, +w) to little finger. Each has three phalanges curling a little towards the
    // palm (-n), knuckles that stand out on the back (+n) at the base and middle joints, and a
    // nail on the last phalanx.
    side.hand_begin = side.arm.size();
    auto nail = [&](const Vec3& tip, const Vec3& dir, const Vec3& back, double len, double width,
                    double thickness) {
      const Vec3 c = tip - 0.45 * len * dir + 0.9 * thickness * back;
      side.arm.push_back({ellipsoid(c, dir, back, 0.42 * len, 0.0018, width), 0.0008});
      fine_spots_.push_back({c, 0.009});
    };
    {
      const Vec3 w = (zf - df * df.dot(zf) - n * n.dot(zf)).normalized();
      const double offset[4] = {0.0285, 0.0095, -0.0095, -0.0275};
      const double angle[4] = {0.20, 0.07, -0.07, -0.20};
      const double length[4] = {0.072, 0.080, 0.074, 0.060};
      const double radius[4] = {0.0085, 0.0088, 0.0083, 0.0074};
      for (int f = 0; f < 4; ++f) {
        const Vec3 base = wr + 0.078 * df + offset[f] * w;
        Vec3 dir = (std::cos(angle[f]) * df + std::sin(angle[f]) * w).normalized();
        const double r = radius[f];
        // Knuckle at the back of the hand.
        side.arm.push_back(
            {ellipsoid(base - 0.006 * dir + 0.008 * n, dir, n, 0.008, 0.0065, 0.85 * r), 0.006});
        const double part[3] = {0.45, 0.31, 0.24};
        // SMPL-X's slot of this finger (index, middle, pinky, ring).
        FingerChain& chain = landmarks_.fingers[s][f == 0 ? 0 : f == 1 ? 1 : f == 2 ? 3 : 2];
        chain.points[0] = base;
        const double thick[4] = {0.0079, 0.0071, 0.0064, 0.0058};
        const double wide[4] = {1.0, 0.9, 0.82, 0.74};
        Vec3 a = base;
        for (int ph = 0; ph < 3; ++ph) {
          const Vec3 b = a + part[ph] * length[f] * dir;
          side.arm.push_back({capsule(a, b, n, thick[ph], wide[ph] * r, 0.97 * thick[ph + 1],
                                      0.97 * wide[ph + 1] * r, ph == 0 ? 0.008 : 0.5 * thick[ph],
                                      ph == 2 ? 0.8 * thick[3] : 0.5 * thick[ph + 1]),
                              0.0025});
          chain.points[ph + 1] = ph < 2 ? b : Vec3(b + 0.8 * thick[3] * dir);
          if (ph < 2)  // the joint: as wide as the phalanx there, and proud on the back
            side.arm.push_back({ellipsoid(b + 0.0016 * n, dir, n, 0.0055, thick[ph + 1] * 0.98,
                                          wide[ph + 1] * r * 1.0),
                                0.003});
          else
            nail(b + 0.8 * thick[3] * dir, dir, n, part[2] * length[f], 0.62 * r, thick[3]);
          a = b;
          // Curl: each phalanx turns 8 degrees further towards the palm.
          dir = (std::cos(0.14) * dir - std::sin(0.14) * n).normalized();
        }
      }
    }
    {
      // Thumb: two segments with a knuckle between them and a nail.
      const Vec3 t0 = wr + 0.03 * df + 0.03 * zf - 0.004 * n;
      const Vec3 t1 = wr + 0.058 * df + 0.052 * zf - 0.007 * n;
      const Vec3 t2 = wr + 0.08 * df + 0.07 * zf - 0.01 * n;
      const Vec3 dir = (t2 - t1).normalized();
      const Vec3 back = (n - dir * dir.dot(n)).normalized();
      side.arm.push_back({capsule(t0, t1, n, 0.012, 0.012, 0.0098, 0.0105, 0.01, 0.007), 0.012});
      side.arm.push_back({ellipsoid(t1 + 0.0012 * back, dir, n, 0.006, 0.0102, 0.0108), 0.003});
      side.arm.push_back(
          {capsule(t1, t2, n, 0.0096, 0.0102, 0.0085, 0.0088, 0.007, 0.0085), 0.003});
      nail(t2 + 0.006 * dir, dir, back, 0.03, 0.0068, 0.0085);
      // The thumb's three joints: its base by the wrist, the knuckle, and the joint between
      // the last two phalanges (the template draws those as one segment).
      landmarks_.fingers[s][4].points = {t0, t1, Vec3(t1 + 0.5 * (t2 - t1)),
                                         Vec3(t2 + 0.008 * dir)};
    }
    std::tie(side.hand_centre, side.hand_radius) = bounding_sphere(side.arm, side.hand_begin);
    // Upper arm and deltoid, forearm and its muscle, palm, then the fingers (the hand's).
    side.arm_bone.clear();
    for (std::size_t i = 0; i < side.arm.size(); ++i)
      side.arm_bone.push_back(i < 2                 ? kLeftShoulder + o
                              : i < 4               ? kLeftElbow + o
                              : i < side.hand_begin ? kLeftWrist + o
                                                    : kLeftHand + o);
    (void)M;
    // Leg: thigh, calf with muscle, ankle, foot.
    const Vec3 hp = J[kLeftHip + o], kn = J[kLeftKnee + o], an = J[kLeftAnkle + o];
    // The thigh's axis starts well above the hip joint, inside the trunk, so that its rounded
    // top end lies above the morph (kMorphTop) and the thigh is a plain cone wherever the trunk
    // morphs into it (a rounded end there left a corner round the hips).
    side.leg.push_back(
        {capsule(hp + Vec3(0, 0.10, 0), kn, X, 0.090, 0.087, 0.047, 0.052, 0.05, 0.045), 0.0});
    // The shank starts at the knee with the thigh's radii there, so the two meet without the
    // ring that an overlap of their rounded ends made.
    side.leg.push_back({capsule(kn, an, X, 0.047, 0.052, 0.029, 0.033, 0.045, 0.03), 0.02});
    side.leg.push_back(
        {ellipsoid(kn + 0.28 * (an - kn) + Vec3(0, 0, -0.018), Y, X, 0.11, 0.046, 0.049), 0.04});
    // Foot: heel, instep, the ball of the foot and five toes, the arch carved out of the
    // inner sole. The toes sit side by side and blend into the ball but barely into each other,
    // so grooves part them; the big toe is on the inner side (towards x = 0).
    const double sx = s == 0 ? 1.0 : -1.0;
    const double fx = an.x();
    auto F = [&](double dx, double y, double z) { return Vec3(fx + sx * dx, y, z); };
    side.leg.push_back(
        {capsule(an, F(0.0, 0.04, 0.04), X, 0.031, 0.033, 0.036, 0.03, 0.03, 0.03), 0.03});
    side.leg.push_back({ellipsoid(F(0.0, 0.036, -0.052), Y, X, 0.036, 0.031, 0.036), 0.02});
    side.leg.push_back({capsule(F(0.0, 0.034, -0.03), F(0.004, 0.026, 0.105), X, 0.031, 0.032,
                                0.042, 0.022, 0.03, 0.02),
                        0.025});
    side.leg.push_back({ellipsoid(F(0.004, 0.021, 0.118), Y, X, 0.02, 0.042, 0.03), 0.02});
    side.leg_cuts.push_back({ellipsoid(F(-0.036, -0.004, 0.035), Y, X, 0.02, 0.022, 0.06), 0.015});
    // Thigh; shank and calf; the foot's parts (the toes follow the foot joint).
    for (std::size_t i = 0; i < side.leg.size(); ++i)
      side.leg_bone.push_back(i == 0 ? kLeftHip + o : i < 3 ? kLeftKnee + o : kLeftAnkle + o);
    {
      // Big toe to little toe: base and tip (inner-outer offset, height, forward), radius.
      const double dx[5] = {-0.026, -0.0075, 0.0055, 0.0175, 0.028};
      const double base_z[5] = {0.128, 0.135, 0.132, 0.127, 0.120};
      const double tip_z[5] = {0.186, 0.178, 0.170, 0.160, 0.148};
      const double r[5] = {0.0125, 0.0083, 0.0078, 0.0074, 0.0068};
      for (int t = 0; t < 5; ++t) {
        const double y0 = t == 0 ? 0.019 : 0.017, y1 = t == 0 ? 0.013 : 0.0095;
        const double tip_dx = dx[t] + 0.002 * t;
        side.toes.push_back(capsule(F(dx[t], y0, base_z[t]), F(tip_dx, y1, tip_z[t]), X, r[t],
                                    0.92 * r[t], 0.95 * r[t], 0.85 * r[t], 0.01, 0.8 * r[t]));
      }
    }
  }
}

double Mannequin::torso_loft(const Vec3& p) const {
  const auto& L = levels_;
  const double y0 = L.front().y, y1 = L.back().y;
  const double yc = std::clamp(p.y(), y0, y1);
  // Find the interval and interpolate with Catmull-Rom (finite difference tangents).
  std::size_t i = 0;
  while (i + 2 < L.size() && L[i + 1].y < yc) ++i;
  const double t = (yc - L[i].y) / (L[i + 1].y - L[i].y);
  auto tangent = [&](std::size_t k, auto get) {
    const std::size_t a = k == 0 ? 0 : k - 1;
    const std::size_t b = std::min(k + 1, L.size() - 1);
    return (get(L[b]) - get(L[a])) / (L[b].y - L[a].y);
  };
  auto interp = [&](auto get) {
    const double h = L[i + 1].y - L[i].y;
    const double p0 = get(L[i]), p1 = get(L[i + 1]);
    const double m0 = tangent(i, get) * h, m1 = tangent(i + 1, get) * h;
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * p1 +
           (t3 - t2) * m1;
  };
  const double a = interp([](const TorsoLevel& l) { return l.half_width; });
  const double b = interp([](const TorsoLevel& l) { return l.half_depth; });
  const double c = interp([](const TorsoLevel& l) { return l.z_center; });
  const double e = 2.4;
  const double qx = std::abs(p.x()) / a, qz = std::abs(p.z() - c) / b;
  const double n = std::pow(std::pow(qx, e) + std::pow(qz, e), 1.0 / e);
  const double cap = p.y() < y0 ? 0.045 : 0.03;
  const double qy = (p.y() - yc) / cap;
  const double r = std::min(a, b);
  return (std::sqrt(n * n + qy * qy) - 1.0) * r;
}

JointPose joint_pose(int joint, const Eigen::Matrix3d& rotation, const Skeleton& skeleton) {
  JointPose pose;
  for (int j = 0; j < kJointCount; ++j)
    for (int k = j; k >= 0; k = joint_parents()[k])
      if (k == joint) pose.moved[j] = 1;
  pose.centre = skeleton.joints[joint];
  pose.rotation = rotation;
  return pose;
}

double Mannequin::arm_field(const Side& s, const Vec3& p, const JointPose* pose) const {
  // Each primitive is evaluated where the query point was before its bone turned.
  const auto at = [&](std::size_t i) {
    return pose && pose->moved[s.arm_bone[i]] ? pose->to_rest(p) : p;
  };
  double d = 1e9;
  for (std::size_t i = 0; i < s.hand_begin; ++i)
    d = smooth_min(d, s.arm[i].first.distance(at(i)), s.arm[i].second);
  // The fingers (most of the primitives) only where they can change the result: farther from
  // their sphere than d plus any blend radius they cannot.
  if ((at(s.hand_begin) - s.hand_centre).norm() - s.hand_radius > d + 0.02) return d;
  for (std::size_t i = s.hand_begin; i < s.arm.size(); ++i)
    d = smooth_min(d, s.arm[i].first.distance(at(i)), s.arm[i].second);
  return d;
}

Dist Mannequin::leg_field(const Side& s, const Vec3& p, const JointPose* pose) const {
  const auto moved = [&](int bone) { return pose && pose->moved[bone]; };
  Dist d;
  for (std::size_t i = 0; i < s.leg.size(); ++i) {
    const auto& [c, k] = s.leg[i];
    const bool turned = moved(s.leg_bone[i]);
    Dist e;
    e.d = c.distance(turned ? pose->to_rest(p) : p, &e.n);
    if (turned) e.n = pose->rotation * e.n;
    d = smooth_union(d, e, k);
  }
  const int ankle = s.leg_bone.back(), foot = ankle + 3;  // SMPL's order: foot = ankle + 3
  const Vec3 pa = moved(ankle) ? pose->to_rest(p) : p;
  const Vec3 pf = moved(foot) ? pose->to_rest(p) : p;
  if (pa.y() < 0.1) {  // the foot
    for (const auto& [c, k] : s.leg_cuts) d.d = -smooth_min(-d.d, c.distance(pa), k);
    Dist toes;
    double closest = 1e9;
    for (const Capsule& c : s.toes) {
      Dist e;
      e.d = c.distance(pf, &e.n);
      if (moved(foot)) e.n = pose->rotation * e.n;
      toes.d = smooth_min(toes.d, e.d, 0.004);
      if (e.d < closest) {
        closest = e.d;
        toes.n = e.n;
      }
    }
    d = smooth_union(d, toes, 0.012);
  }
  return d;
}

double Mannequin::trunk_field(const Vec3& p) const {
  double d = torso_loft(p);
  for (const auto& [c, k] : torso_parts_) d = smooth_min(d, c.distance(p), k);
  return d;
}

double Mannequin::field(const Vec3& p, const JointPose* pose) const {
  double d = trunk_and_legs(p, pose);
  // The head only where it can change the result (it blends in with radius 0.03).
  if ((p - head_centre_).norm() - head_radius_ <= d + 0.04) {
    double head = 1e9;
    for (const auto& [c, k] : head_parts_) head = smooth_min(head, c.distance(p), k);
    for (const auto& [c, k] : head_cuts_) head = -smooth_min(-head, c.distance(p), k);
    for (const auto& [c, k] : head_details_) head = smooth_min(head, c.distance(p), k);
    d = smooth_min(d, head, 0.03);
  }
  for (const Side& s : sides_) {
    const double k = 0.045 * (1.0 - smoothstep(0.10, 0.22, (p - s.shoulder).norm()));
    d = smooth_min(d, arm_field(s, p, pose), k);
  }
  return d;
}

double Mannequin::trunk_and_legs(const Vec3& p, const JointPose* pose) const {
  // Between the crotch and the hip the field morphs from the two legs (below) into the trunk
  // (above): a convex combination of the two distance estimates, so the pelvis narrows into
  // the thighs without a seam. (Any union of the two, plain or smooth, left a band like a
  // pair of shorts where the thighs run alongside the hips and a step where they leave them.)
  // At the back the buttocks stay the trunk's down to their fold, so the morph is shorter.
  const double top = kMorphTop - 0.11 * smoothstep(0.0, -0.08, p.z());
  // C2 weight (6t^5 - 15t^4 + 10t^3): with a C1 one the surface's curvature jumps at the ends
  // of the morph, a line that the soft-tissue fields of heavy bodies turned into a band.
  const double t = std::clamp((p.y() - kMorphBottom) / (top - kMorphBottom), 0.0, 1.0);
  const double w = t * t * t * (t * (6 * t - 15) + 10);
  if (w >= 1.0) return trunk_field(p);
  const Dist l0 = leg_field(sides_[0], p, pose), l1 = leg_field(sides_[1], p, pose);
  const double legs = std::min(l0.d, l1.d);
  if (w <= 0.0) return legs;
  return w * trunk_field(p) + (1.0 - w) * legs;
}

Vec3 Mannequin::gradient(const Vec3& p, const JointPose* pose) const {
  const double e = 1e-5;
  Vec3 g;
  for (int i = 0; i < 3; ++i) {
    Vec3 a = p, b = p;
    a[i] += e;
    b[i] -= e;
    g[i] = (field(a, pose) - field(b, pose)) / (2 * e);
  }
  return g;
}

Vec3 Mannequin::project(const Vec3& p, int iterations, const JointPose* pose) const {
  Vec3 q = p;
  for (int it = 0; it < iterations; ++it) {
    const double f = field(q, pose);
    if (std::abs(f) < 1e-7) break;
    const Vec3 g = gradient(q, pose);
    const double g2 = g.squaredNorm();
    if (g2 < 1e-12) break;
    Vec3 step = f * g / g2;
    if (step.norm() > 0.01) step *= 0.01 / step.norm();
    q -= step;
  }
  return q;
}

double Mannequin::target_edge(const Vec3& p) const {
  double L = 0.0175;
  // Hands: near the wrists and beyond.
  for (int s = 0; s < 2; ++s) {
    const Vec3& w = skeleton_.joints[kLeftWrist + s];
    L = std::min(
        L, 0.007 + 0.0105 * smoothstep(0.09, 0.14, (p - skeleton_.joints[kLeftHand + s]).norm()));
    (void)w;
  }
  // Nails.
  for (const auto& [c, r] : fine_spots_)
    L = std::min(L, 0.0036 + 0.0139 * smoothstep(r, 1.6 * r, (p - c).norm()));
  // Head and face.
  L = std::min(L, 0.011 + 0.0065 * smoothstep(0.10, 0.16, (p - Vec3(0, 1.59, 0.02)).norm()));
  // The face (brow, eyes, nose, lips, chin) finer still, and eyes and mouth finest.
  L = std::min(L, 0.0075 + 0.0035 * smoothstep(0.035, 0.07, (p - Vec3(0, 1.56, 0.095)).norm()));
  for (const Vec3& c : {Vec3(0.031, 1.5985, 0.095), Vec3(-0.031, 1.5985, 0.095)})
    L = std::min(L, 0.003 + 0.0145 * smoothstep(0.014, 0.026, (p - c).norm()));
  // Nostrils, and the ears' bowls.
  L = std::min(L, 0.0025 + 0.015 * smoothstep(0.012, 0.02, (p - Vec3(0, 1.556, 0.108)).norm()));
  for (const Vec3& c : {Vec3(0.085, 1.585, -0.003), Vec3(-0.085, 1.585, -0.003)})
    L = std::min(L, 0.004 + 0.0135 * smoothstep(0.02, 0.035, (p - c).norm()));
  L = std::min(
      L,
      0.003 + 0.0145 *
                  smoothstep(0.016, 0.03,
                             (p - Vec3(0, 1.532, 0.097)).cwiseProduct(Vec3(0.7, 1.3, 1.0)).norm()));
  // Feet, and the toes finer.
  if (p.y() < 0.12) {
    L = std::min(L, 0.012 + 0.0055 * smoothstep(0.06, 0.12, p.y()));
    const Vec3 toes(std::abs(p.x()) - skeleton_.joints[kLeftAnkle].x(), 0.6 * p.y(), p.z() - 0.155);
    L = std::min(L, 0.005 + 0.007 * smoothstep(0.035, 0.06, toes.norm()));
  }
  return L;
}

Eigen::AlignedBox3d Mannequin::bounds() const {
  return Eigen::AlignedBox3d(Vec3(-0.78, -0.04, -0.22), Vec3(0.78, 1.76, 0.26));
}

}  // namespace default_model
