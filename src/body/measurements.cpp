// Tape-measure girths from horizontal slices.
//
// Landmark choice. SMPL-family meshes carry no landmark labels that are shared across models,
// so the landmarks are relative heights of the standing body. Classic anthropometric
// proportions (Drillis & Contini 1966, as tabulated in Winter, "Biomechanics and Motor Control
// of Human Movement": shoulder 0.818 H, chest/nipple ~0.72 H, navel/waist ~0.60 H, greater
// trochanter/hip ~0.53 H, crotch ~0.47 H) put each landmark inside a band; within the band the
// tailoring definitions pick the slice (chest = maximum girth, waist = minimum girth of the
// torso, hip = maximum girth below the waist). Bands stop below the armpit (0.75 H) so
// T-posed arms stay out, and the hip band starts at 0.45 H where the legs split. Arms that
// hang beside the body are separate slice pieces and are dropped; where they merge with the
// torso at the armpit (short bodies in A-pose reach that below 0.75 H) the girth jumps by
// more than 15% between neighbouring slices and the chest search stops there.
#include "body/measurements.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

#include "body/convex_hull.hpp"
#include "body/mesh_slice.hpp"

namespace body {

namespace {

// False when `p` lies clearly (a micrometre) outside the piece's bounding box, so that its
// convex hull cannot hold it either: the arms' pieces of a torso slice skip their hulls.
bool may_surround(const SlicePiece& piece, const Eigen::Vector2d& p) {
  if (piece.points.empty()) return false;
  Eigen::Vector2d lo = piece.points.front(), hi = lo;
  for (const auto& q : piece.points) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  constexpr double kMargin = 1e-6;
  return p.x() >= lo.x() - kMargin && p.x() <= hi.x() + kMargin && p.y() >= lo.y() - kMargin &&
         p.y() <= hi.y() + kMargin;
}

// The girth of the slice piece that surrounds the axis (0 if none).
double piece_girth(const std::vector<SlicePiece>& pieces, const Eigen::Vector2d& axis) {
  double best = 0.0;
  for (const auto& piece : pieces) {
    if (!may_surround(piece, axis)) continue;
    const auto hull = convex_hull(piece.points);
    if (!hull_contains(hull, axis)) continue;
    best = std::max(best, polygon_perimeter(hull));
  }
  return best;
}

}  // namespace

double torso_girth(const BodyMesh& mesh, const Faces& faces, double y, double axis_x,
                   double axis_z) {
  return piece_girth(slice_mesh(mesh.vertices, faces, y), Eigen::Vector2d(axis_x, axis_z));
}

namespace {

// Calls visit(a, b, c) with the corners in double precision of each triangle whose vertex
// indices i, j, k pass keep(i, j, k); faces that name a vertex beyond the mesh are skipped (a
// loaded model's faces are validated, this keeps a measurement from reading out of bounds on
// a mismatched mesh all the same).
template <class Keep, class Visit>
void for_each_triangle_where(const Vertices& vertices, const Faces& faces, Keep&& keep,
                             Visit&& visit) {
  const Eigen::Index V = vertices.rows();
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const std::uint32_t i = faces(f, 0), j = faces(f, 1), k = faces(f, 2);
    if (i >= V || j >= V || k >= V || !keep(i, j, k)) continue;
    const Eigen::Vector3d a = vertices.row(i).cast<double>().transpose();
    const Eigen::Vector3d b = vertices.row(j).cast<double>().transpose();
    const Eigen::Vector3d c = vertices.row(k).cast<double>().transpose();
    visit(a, b, c);
  }
}

// Every triangle.
template <class Visit>
void for_each_triangle(const Vertices& vertices, const Faces& faces, Visit&& visit) {
  for_each_triangle_where(
      vertices, faces, [](std::uint32_t, std::uint32_t, std::uint32_t) { return true; }, visit);
}

// The triangles whose bounding box meets the box [lo, hi]: a ray or a vertical line tests the
// few faces near it instead of all. Callers widen the box by far more than rounding (a
// micrometre), so no face the full pass would count is left out.
template <class Visit>
void for_each_triangle_in_box(const Vertices& vertices, const Faces& faces,
                              const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Visit&& visit) {
  // The box in single precision, rounded outwards (the vertices are floats).
  float flo[3], fhi[3];
  for (int axis = 0; axis < 3; ++axis) {
    flo[axis] =
        std::nextafter(static_cast<float>(lo[axis]), -std::numeric_limits<float>::infinity());
    fhi[axis] =
        std::nextafter(static_cast<float>(hi[axis]), std::numeric_limits<float>::infinity());
  }
  const auto meets = [&](std::uint32_t i, std::uint32_t j, std::uint32_t k) {
    for (int axis = 0; axis < 3; ++axis) {
      const float p = vertices(i, axis), q = vertices(j, axis), r = vertices(k, axis);
      if ((p < flo[axis] && q < flo[axis] && r < flo[axis]) ||
          (p > fhi[axis] && q > fhi[axis] && r > fhi[axis]))
        return false;
    }
    return true;
  };
  for_each_triangle_where(vertices, faces, meets, visit);
}

constexpr double kBoxMargin = 1e-6;

// Six times the signed enclosed volume: positive when the faces turn counter-clockwise seen
// from outside.
double signed_six_volume(const Vertices& vertices, const Faces& faces) {
  double six_volume = 0.0;
  for_each_triangle(vertices, faces,
                    [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c) { six_volume += a.dot(b.cross(c)); });
  return six_volume;
}

}  // namespace

double enclosed_volume(const Vertices& vertices, const Faces& faces) {
  return std::abs(signed_six_volume(vertices, faces)) / 6.0;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int joint_index(const Model& model, const BodyMesh& mesh, const char* name) {
  for (std::size_t j = 0; j < model.joint_names.size(); ++j) {
    if (model.joint_names[j] == name && static_cast<Eigen::Index>(j) < mesh.joints.rows()) {
      return static_cast<int>(j);
    }
  }
  return -1;
}

Eigen::Vector3d joint(const BodyMesh& mesh, int j) {
  return mesh.joints.row(j).cast<double>().transpose();
}

// The horizontal distance of the shoulder joint centres (NaN without them): the bideltoid
// breadth adds the deltoids' reach to it.
double shoulder_joint_distance(const Model& model, const BodyMesh& mesh) {
  const int l = joint_index(model, mesh, "left_shoulder");
  const int r = joint_index(model, mesh, "right_shoulder");
  if (l < 0 || r < 0) return kNaN;
  const Eigen::Vector3d d = joint(mesh, l) - joint(mesh, r);
  return std::hypot(d.x(), d.z());
}

// For each ray (from origins[i] along the unit directions[i]) the nearest point (t > 0,
// t <= reach) where it crosses a face, whichever way the face turns; NaN coordinates when none
// does. Both rays in one pass over the faces: measure() runs this for every body a hold or a
// target solve looks at.
std::array<Eigen::Vector3d, 2> first_crossings(const Vertices& vertices, const Faces& faces,
                                               const std::array<Eigen::Vector3d, 2>& origins,
                                               const std::array<Eigen::Vector3d, 2>& directions,
                                               double reach) {
  std::array<double, 2> best = {std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::infinity()};
  // Only faces near the two rays' segments can be crossed within `reach`.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector3d end = origins[i] + reach * directions[i];
    lo = lo.cwiseMin(origins[i]).cwiseMin(end);
    hi = hi.cwiseMax(origins[i]).cwiseMax(end);
  }
  if (!lo.allFinite() || !hi.allFinite()) {
    lo.setConstant(-std::numeric_limits<double>::infinity());
    hi.setConstant(std::numeric_limits<double>::infinity());
  }
  lo.array() -= kBoxMargin;
  hi.array() += kBoxMargin;
  for_each_triangle_in_box(
      vertices, faces, lo, hi,
      [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
        // Moller and Trumbore 1997 (J. Graphics Tools 2(1):21).
        const Eigen::Vector3d e1 = b - a, e2 = c - a;
        for (int i = 0; i < 2; ++i) {
          const Eigen::Vector3d p = directions[i].cross(e2);
          const double det = e1.dot(p);
          if (std::abs(det) < 1e-14) continue;
          const Eigen::Vector3d s = origins[i] - a;
          const double u = s.dot(p) / det;
          if (u < 0.0 || u > 1.0) continue;
          const Eigen::Vector3d q = s.cross(e1);
          const double v = directions[i].dot(q) / det;
          if (v < 0.0 || u + v > 1.0) continue;
          const double t = e2.dot(q) / det;
          if (t > 0.0 && t <= reach && t < best[i]) best[i] = t;
        }
      });
  std::array<Eigen::Vector3d, 2> out;
  for (int i = 0; i < 2; ++i)
    out[i] = std::isfinite(best[i]) ? Eigen::Vector3d(origins[i] + best[i] * directions[i])
                                    : Eigen::Vector3d::Constant(kNaN);
  return out;
}

// The acromia, left then right (see measurements.hpp); NaN coordinates without shoulder
// joints or where the ray leaves no skin within 25 cm.
std::array<Eigen::Vector3d, 2> acromia(const Model& model, const BodyMesh& mesh) {
  const Eigen::Vector3d none = Eigen::Vector3d::Constant(kNaN);
  const int l = joint_index(model, mesh, "left_shoulder");
  const int r = joint_index(model, mesh, "right_shoulder");
  if (l < 0 || r < 0) return {none, none};
  Eigen::Vector3d across = joint(mesh, l) - joint(mesh, r);
  across.y() = 0.0;
  if (!(across.norm() > 1e-6)) return {none, none};
  across.normalize();
  const double angle = kAcromionAngleDegrees * M_PI / 180.0;
  const Eigen::Vector3d up = std::cos(angle) * Eigen::Vector3d::UnitY();
  return first_crossings(mesh.vertices, model.faces, {joint(mesh, l), joint(mesh, r)},
                         {up + std::sin(angle) * across, up - std::sin(angle) * across}, 0.25);
}

double shoulder_width(const std::array<Eigen::Vector3d, 2>& acromion) {
  const Eigen::Vector3d d = acromion[0] - acromion[1];
  return std::hypot(d.x(), d.z());
}

double arm_length(const Model& model, const BodyMesh& mesh,
                  const std::array<Eigen::Vector3d, 2>& acromion) {
  double sum = 0.0;
  for (int side = 0; side < 2; ++side) {
    const std::string s(side == 0 ? "left" : "right");
    const int b = joint_index(model, mesh, (s + "_elbow").c_str());
    const int c = joint_index(model, mesh, (s + "_wrist").c_str());
    if (b < 0 || c < 0) return kNaN;
    sum += (acromion[side] - joint(mesh, b)).norm() + (joint(mesh, b) - joint(mesh, c)).norm();
  }
  return 0.5 * sum;
}

// Slices across a limb or the neck look this far from the bone: farther than any limb's
// surface (a thigh of 80 cm girth has a radius under 13 cm), nearer than most of the torso.
constexpr double kLimbRadius = 0.25;

// The slices across the limbs and the neck that one body's measurements take, cut in one call
// (the levels across one bone share its direction, so they cost about one pass over the
// faces): add() each plane, cut(), then read each plane's girth or reach.
class LimbSlices {
 public:
  int add(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
    planes_.push_back(plane_across(origin, direction));
    return static_cast<int>(planes_.size()) - 1;
  }
  void cut(const BodyMesh& mesh, const Faces& faces) {
    pieces_ = slice_mesh(mesh.vertices, faces, planes_, kLimbRadius);
  }
  // The girth of the slice piece around the plane's origin; 0 when the plane misses the body.
  double girth(int i) const {
    return piece_girth(pieces_[static_cast<std::size_t>(i)], Eigen::Vector2d::Zero());
  }
  // How far that piece reaches along `outward` (a unit vector in the plane).
  double reach(int i, const Eigen::Vector3d& outward) const {
    const SlicePlane& plane = planes_[static_cast<std::size_t>(i)];
    const Eigen::Vector2d out(outward.dot(plane.u), outward.dot(plane.v));
    double best = 0.0;
    for (const auto& piece : pieces_[static_cast<std::size_t>(i)]) {
      if (!may_surround(piece, Eigen::Vector2d::Zero())) continue;
      const auto hull = convex_hull(piece.points);
      if (!hull_contains(hull, Eigen::Vector2d::Zero())) continue;
      for (const auto& p : hull) best = std::max(best, p.dot(out));
    }
    return best;
  }

 private:
  std::vector<SlicePlane> planes_;
  std::vector<std::vector<SlicePiece>> pieces_;
};

// A bone: the segment from joint `from` to joint `to` ("left_knee" -> "left_ankle").
struct Bone {
  Eigen::Vector3d a, b;
  bool found = false;
  Eigen::Vector3d at(double t) const { return a + t * (b - a); }
};

Bone bone(const Model& model, const BodyMesh& mesh, const std::string& from,
          const std::string& to) {
  Bone result;
  const int i = joint_index(model, mesh, from.c_str());
  const int j = joint_index(model, mesh, to.c_str());
  if (i < 0 || j < 0) return result;
  result.a = joint(mesh, i);
  result.b = joint(mesh, j);
  result.found = (result.b - result.a).norm() > 1e-6;
  return result;
}

// The limb girths and the bideltoid breadth (see measurements.hpp); `crotch` is the crotch's
// absolute height (NaN if none).
void measure_limbs(const Model& model, const BodyMesh& mesh, const Faces& faces, double H,
                   double crotch, unsigned bands, Measurements& m) {
  LimbSlices slices;
  // The narrowest girth along the middle of the neck: below it the trapezius widens the
  // slice, above it the jaw; where the SMPL-family joints put the neck's middle varies.
  std::vector<int> neck_levels;
  const Bone neck = bone(model, mesh, "neck", "head");
  if ((bands & kNeckBand) != 0 && neck.found)
    for (const double t : {0.3, 0.4, 0.5, 0.6, 0.7})
      neck_levels.push_back(slices.add(neck.at(t), neck.b - neck.a));
  // Per side (left, right): the upper arm's levels (its largest girth), the deltoid's (its
  // farthest reach outward), the thigh's level and the calf's levels (its largest girth).
  struct Side {
    std::vector<int> upper_arm, deltoid, calf;
    int thigh = -1;
    Eigen::Vector3d outward = Eigen::Vector3d::Zero();
  };
  std::array<Side, 2> sides;
  const double centre_x = mesh.vertices.col(0).cast<double>().mean();
  bool arms = true, legs = true;
  for (int i = 0; i < 2; ++i) {
    const std::string s(i == 0 ? "left" : "right");
    Side& side = sides[static_cast<std::size_t>(i)];
    if ((bands & kArmBand) != 0) {
      const Bone arm = bone(model, mesh, s + "_shoulder", s + "_elbow");
      if (!arm.found) {
        arms = false;
      } else {
        for (const double t : {0.4, 0.5, 0.6})
          side.upper_arm.push_back(slices.add(arm.at(t), arm.b - arm.a));
        // Outward: the body's side direction (+x for the left side of an SMPL-family body
        // facing +z) made perpendicular to the humerus.
        const Eigen::Vector3d axis = (arm.b - arm.a).normalized();
        const Eigen::Vector3d side_x(arm.a.x() >= centre_x ? 1.0 : -1.0, 0.0, 0.0);
        side.outward = (side_x - side_x.dot(axis) * axis).normalized();
        for (const double t : {0.1, 0.2, 0.3}) side.deltoid.push_back(slices.add(arm.at(t), axis));
      }
    }
    if ((bands & kLegBand) != 0) {
      const Bone femur = bone(model, mesh, s + "_hip", s + "_knee");
      const Bone shin = bone(model, mesh, s + "_knee", s + "_ankle");
      if (!femur.found || !shin.found) {
        legs = false;
      } else {
        // The point of the femur 1% of H below the crotch (a quarter of the way down without
        // one), kept in the thigh's upper half.
        double t = 0.25;
        const double drop = femur.a.y() - femur.b.y();
        if (std::isfinite(crotch) && drop > 1e-6) t = (femur.a.y() - (crotch - 0.01 * H)) / drop;
        t = std::clamp(t, 0.05, 0.5);
        side.thigh = slices.add(femur.at(t), femur.b - femur.a);
        for (const double u : {0.2, 0.3, 0.4, 0.5})
          side.calf.push_back(slices.add(shin.at(u), shin.b - shin.a));
      }
    }
  }
  slices.cut(mesh, faces);
  const auto largest = [&](const std::vector<int>& levels) {
    double best = 0.0;
    for (const int level : levels) best = std::max(best, slices.girth(level));
    return best;
  };
  if ((bands & kNeckBand) != 0) {
    m.neck = kNaN;
    double narrowest = std::numeric_limits<double>::infinity();
    for (const int level : neck_levels) {
      const double g = slices.girth(level);
      if (g > 0.0) narrowest = std::min(narrowest, g);
    }
    if (std::isfinite(narrowest)) m.neck = narrowest;
  }
  if ((bands & kArmBand) != 0) {
    double upper_arm = 0.0, deltoids = 0.0;
    for (const Side& side : sides) {
      if (!arms) break;
      upper_arm += largest(side.upper_arm);
      double reach = 0.0;
      for (const int level : side.deltoid)
        reach = std::max(reach, slices.reach(level, side.outward));
      deltoids += reach;
    }
    m.upper_arm = arms ? 0.5 * upper_arm : kNaN;
    const double joints = shoulder_joint_distance(model, mesh);
    m.bideltoid = arms && std::isfinite(joints) ? joints + deltoids : kNaN;
  }
  if ((bands & kLegBand) != 0) {
    double thigh = 0.0, calf = 0.0;
    for (const Side& side : sides) {
      if (!legs) break;
      thigh += slices.girth(side.thigh);
      calf += largest(side.calf);
    }
    m.thigh = legs ? 0.5 * thigh : kNaN;
    m.calf = legs ? 0.5 * calf : kNaN;
  }
}

// The crotch: the highest downward-facing triangle that the vertical line (x, z) crosses
// below `ceiling` (absolute y); NaN if none.
double crotch_y(const Vertices& vertices, const Faces& faces, double x, double z, double ceiling) {
  double best = -std::numeric_limits<double>::infinity();
  // Only faces whose footprint holds (x, z) can be crossed by the vertical line.
  const double inf = std::numeric_limits<double>::infinity();
  for_each_triangle_in_box(
      vertices, faces, Eigen::Vector3d(x - kBoxMargin, -inf, z - kBoxMargin),
      Eigen::Vector3d(x + kBoxMargin, inf, z + kBoxMargin),
      [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
        // Barycentric coordinates of (x, z) in the triangle's projection on the floor.
        const double area = (b.x() - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (b.z() - a.z());
        if (std::abs(area) < 1e-14) return;
        const double wb = ((x - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (z - a.z())) / area;
        const double wc = ((b.x() - a.x()) * (z - a.z()) - (x - a.x()) * (b.z() - a.z())) / area;
        const double wa = 1.0 - wb - wc;
        if (wa < 0.0 || wb < 0.0 || wc < 0.0) return;
        // The normal (b - a) x (c - a) has y = -area: it faces down when area > 0 (faces turning
        // counter-clockwise seen from outside; measure() flips a mesh wound the other way).
        if (!(area > 0.0)) return;
        const double y = wa * a.y() + wb * b.y() + wc * c.y();
        if (y < ceiling && y > best) best = y;
      });
  return std::isfinite(best) ? best : kNaN;
}

}  // namespace

Measurements measure(const Model& model, const BodyMesh& mesh, bool girths, unsigned bands) {
  Measurements m;
  const Eigen::Index V = mesh.vertices.rows();
  if (V == 0) return m;
  const double six_volume = signed_six_volume(mesh.vertices, model.faces);
  m.volume = std::abs(six_volume) / 6.0;
  m.mass = kBodyDensity * m.volume;
  const double ymin = mesh.vertices.col(1).minCoeff();
  const double ymax = mesh.vertices.col(1).maxCoeff();
  const double H = ymax - ymin;
  m.height = H;
  const std::array<Eigen::Vector3d, 2> acromion = acromia(model, mesh);
  m.shoulder_width = shoulder_width(acromion);
  m.arm_length = arm_length(model, mesh, acromion);
  m.inseam = kNaN;
  if (!(H > 0.0)) return m;
  m.bmi = m.mass / (H * H);
  {
    const int l = joint_index(model, mesh, "left_hip");
    const int r = joint_index(model, mesh, "right_hip");
    double x = mesh.vertices.col(0).cast<double>().mean();
    double z = mesh.vertices.col(2).cast<double>().mean();
    double ceiling = ymin + 0.6 * H;
    if (l >= 0 && r >= 0) {
      const Eigen::Vector3d mid = 0.5 * (joint(mesh, l) + joint(mesh, r));
      x = mid.x(), z = mid.z(), ceiling = mid.y();
    }
    // The winding decides which side is "down" (the signed volume says which way it turns).
    double y = kNaN;
    if (six_volume >= 0.0) {
      y = crotch_y(mesh.vertices, model.faces, x, z, ceiling);
    } else {
      Faces flipped = model.faces;
      flipped.col(1).swap(flipped.col(2));
      y = crotch_y(mesh.vertices, flipped, x, z, ceiling);
    }
    if (y - ymin > 0.2 * H) m.inseam = y - ymin;
  }
  if (!girths) return m;
  measure_limbs(model, mesh, model.faces, H, ymin + m.inseam, bands, m);
  const double ax = mesh.vertices.col(0).cast<double>().mean();
  const double az = mesh.vertices.col(2).cast<double>().mean();
  // Each girth's band of horizontal slices, in 1/200ths of the stature above the soles (the
  // landmarks of measurements.hpp): the chest the largest girth in 0.65-0.75 H, the waist the
  // smallest in 0.56-0.67 H, the hips the largest in 0.45-0.55 H.
  struct SliceBand {
    int lowest, highest;
  };
  constexpr int steps = 200;
  constexpr SliceBand kChestSlices{130, 150}, kWaistSlices{112, 134}, kHipsSlices{90, 110};
  // Every slice the bands may use (0.45 H to 0.75 H) in one pass over the faces; each girth
  // (its convex hulls) only when a band asks for it, once.
  constexpr int kLowest = kHipsSlices.lowest, kHighest = kChestSlices.highest;
  std::vector<double> heights;
  for (int i = kLowest; i <= kHighest; ++i) heights.push_back(ymin + H * i / steps);
  const auto crossing = faces_crossing(mesh.vertices, model.faces, heights);
  std::vector<double> girths_at(heights.size(), -1.0);
  const Eigen::Vector2d axis(ax, az);
  auto girth_at = [&](int i) {
    const auto k = static_cast<std::size_t>(i - kLowest);
    double& g = girths_at[k];
    if (g < 0.0)
      g = piece_girth(slice_mesh(mesh.vertices, model.faces, heights[k], crossing[k]), axis);
    return g;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  m.chest_height = m.waist_height = m.hips_height = nan;

  double previous = 0.0;
  for (int i = kChestSlices.lowest; i <= kChestSlices.highest && (bands & kChestBand) != 0;
       ++i) {  // below the armpits
    const double g = girth_at(i);
    // Arms that hang close (A-pose) join the torso slice at the armpit: the girth jumps from
    // one slice to the next (0.5% of H apart) by far more than a chest ever grows. Stop there.
    if (previous > 0.0 && g > 1.15 * previous) break;
    previous = g;
    if (g > m.chest) m.chest = g, m.chest_height = H * i / steps;
  }
  int waist_i = -1;
  double waist = std::numeric_limits<double>::infinity();
  for (int i = kWaistSlices.lowest; i <= kWaistSlices.highest && (bands & kWaistBand) != 0; ++i) {
    const double g = girth_at(i);
    if (g > 0.0 && g < waist) waist = g, waist_i = i;
  }
  if (waist_i >= 0) m.waist = waist, m.waist_height = H * waist_i / steps;
  for (int i = kHipsSlices.lowest; i <= kHipsSlices.highest && (bands & kHipsBand) != 0; ++i) {
    const double g = girth_at(i);
    if (g > m.hips) m.hips = g, m.hips_height = H * i / steps;
  }
  return m;
}

Measurements measure(const Model& model, const Eigen::VectorXf& betas, bool girths,
                     unsigned bands) {
  return measure(model, evaluate_shape(model, betas), girths, bands);
}

const std::vector<MeasurementKind>& measurement_kinds() {
  // Examples: about the middle of ANSUR II's adults (stature ~175 cm, chest ~100 cm, waist
  // ~88 cm, hips ~100 cm); the joint-based lengths read a few cm under the callipers' values.
  static const std::vector<MeasurementKind> kinds{
      {"height", "Height", Quantity::kLength, &Measurements::height, false, 0.01, "e.g. 175cm",
       "e.g. 69in"},
      {"mass", "Mass", Quantity::kMass, &Measurements::mass, false, 1.5, "e.g. 75kg", "e.g. 165lb"},
      {"bmi", "BMI", Quantity::kBmi, &Measurements::bmi, false, 0.5, "e.g. 24", "e.g. 24"},
      {"chest", "Chest", Quantity::kLength, &Measurements::chest, true, 0.01, "e.g. 100cm",
       "e.g. 39in"},
      {"waist", "Waist", Quantity::kLength, &Measurements::waist, true, 0.01, "e.g. 85cm",
       "e.g. 33in"},
      {"hips", "Hips", Quantity::kLength, &Measurements::hips, true, 0.01, "e.g. 100cm",
       "e.g. 39in"},
      {"shoulder_width", "Shoulder width", Quantity::kLength, &Measurements::shoulder_width, false,
       0.01, "e.g. 36cm", "e.g. 14in"},
      {"inseam", "Inseam", Quantity::kLength, &Measurements::inseam, false, 0.01, "e.g. 80cm",
       "e.g. 31in"},
      {"arm_length", "Arm length", Quantity::kLength, &Measurements::arm_length, false, 0.01,
       "e.g. 55cm", "e.g. 22in"},
      {"neck", "Neck", Quantity::kLength, &Measurements::neck, true, 0.01, "e.g. 37cm",
       "e.g. 15in"},
      {"bideltoid", "Deltoid breadth", Quantity::kLength, &Measurements::bideltoid, true, 0.01,
       "e.g. 47cm", "e.g. 18in"},
      {"upper_arm", "Upper arm", Quantity::kLength, &Measurements::upper_arm, true, 0.01,
       "e.g. 31cm", "e.g. 12in"},
      {"thigh", "Thigh", Quantity::kLength, &Measurements::thigh, true, 0.01, "e.g. 58cm",
       "e.g. 23in"},
      {"calf", "Calf", Quantity::kLength, &Measurements::calf, true, 0.01, "e.g. 37cm",
       "e.g. 15in"},
  };
  return kinds;
}

const MeasurementKind* find_measurement(const std::string& name) {
  for (const auto& k : measurement_kinds()) {
    if (name == k.name) return &k;
  }
  return nullptr;
}

unsigned girth_band(const MeasurementKind& kind) {
  const std::string name = kind.name;
  if (name == "chest") return kChestBand;
  if (name == "waist") return kWaistBand;
  if (name == "hips") return kHipsBand;
  if (name == "neck") return kNeckBand;
  if (name == "bideltoid" || name == "upper_arm") return kArmBand;
  if (name == "thigh" || name == "calf") return kLegBand;
  return 0;
}

std::string measurement_names() {
  std::string names;
  for (const auto& k : measurement_kinds())
    names += (names.empty() ? "" : ", ") + std::string(k.name);
  return names;
}

namespace {

constexpr double kMetresPerInch = 0.0254;
constexpr double kKgPerPound = 0.45359237;

// The unit a quantity is shown in: the factor from SI and the suffix.
struct DisplayUnit {
  double per_si;
  const char* suffix;
};

DisplayUnit display_unit(Quantity quantity, Units units) {
  const bool metric = units == Units::kMetric;
  switch (quantity) {
    case Quantity::kLength:
      return metric ? DisplayUnit{100.0, " cm"} : DisplayUnit{1.0 / kMetresPerInch, " in"};
    case Quantity::kMass:
      return metric ? DisplayUnit{1.0, " kg"} : DisplayUnit{1.0 / kKgPerPound, " lb"};
    case Quantity::kBmi:
      break;
  }
  return {1.0, ""};  // BMI has one unit (kg/m^2), shown bare as people quote it
}

std::string printed(const char* format, int decimals, double a, const char* suffix) {
  char text[64];
  std::snprintf(text, sizeof text, format, decimals, a, suffix);
  return text;
}

}  // namespace

std::string format_measurement(Quantity quantity, double value, Units units) {
  if (!std::isfinite(value)) return "n/a";
  const DisplayUnit unit = display_unit(quantity, units);
  const double shown = value * unit.per_si;
  // Statures read in feet and inches; girths and breadths in inches. Rounded to a tenth of an
  // inch before splitting, so 71.96 in reads "6 ft 0.0 in", never "5 ft 12.0 in".
  if (quantity == Quantity::kLength && units == Units::kImperial && shown >= 48.0) {
    const double tenths = std::round(shown * 10.0) / 10.0;
    const int feet = static_cast<int>(std::floor(tenths / 12.0));
    char text[64];
    std::snprintf(text, sizeof text, "%d ft %.1f in", feet, tenths - 12.0 * feet);
    return text;
  }
  return printed("%.*f%s", 1, shown, unit.suffix);
}

std::string format_difference(Quantity quantity, double difference, Units units) {
  if (!std::isfinite(difference)) return "n/a";
  const DisplayUnit unit = display_unit(quantity, units);
  // Inch differences get two decimals: a tenth of an inch is 2.5 mm, too coarse for a hold.
  const int decimals = quantity == Quantity::kLength && units == Units::kImperial ? 2 : 1;
  return printed("%+.*f%s", decimals, difference * unit.per_si, unit.suffix);
}

double parse_measurement_value(const MeasurementKind& kind, const std::string& text) {
  const std::string what = std::string(kind.name) + " '" + text + "'";
  std::size_t i = 0;
  while (i < text.size() &&
         (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.' || text[i] == '+' ||
          text[i] == '-' || text[i] == 'e' || text[i] == 'E')) {
    // An 'e' only counts as an exponent when a digit or sign follows ("1e2", not "1em").
    if ((text[i] == 'e' || text[i] == 'E') &&
        !(i + 1 < text.size() && (std::isdigit(static_cast<unsigned char>(text[i + 1])) ||
                                  text[i + 1] == '+' || text[i + 1] == '-'))) {
      break;
    }
    ++i;
  }
  const std::string number = text.substr(0, i);
  std::string unit = text.substr(i);
  unit.erase(std::remove(unit.begin(), unit.end(), ' '), unit.end());
  char* end = nullptr;
  double raw = number.empty() ? kNaN : std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(raw)) {
    throw std::invalid_argument(
        what + " is not a number (write e.g. " +
        (kind.quantity == Quantity::kMass ? "85 or 85kg" : "1.80 or 180cm") + ")");
  }
  // Feet and inches together, as people say heights and as format_measurement writes them:
  // "5ft11in", "5 ft 10.9 in", 5'11" or 5'11. The inches are folded into the feet.
  if (kind.quantity == Quantity::kLength) {
    for (const char* feet : {"ft", "'"}) {
      const std::size_t n = std::string(feet).size();
      if (unit.size() <= n || unit.compare(0, n, feet) != 0) continue;
      std::string inches = unit.substr(n);
      for (const char* mark : {"in", "\"", "''"}) {
        const std::size_t m = std::string(mark).size();
        if (inches.size() > m && inches.compare(inches.size() - m, m, mark) == 0) {
          inches.erase(inches.size() - m);
          break;
        }
      }
      char* inches_end = nullptr;
      const double in = std::strtod(inches.c_str(), &inches_end);
      if (inches.empty() || inches_end != inches.c_str() + inches.size() || !std::isfinite(in) ||
          in < 0.0 || in >= 12.0 || raw < 0.0) {
        throw std::invalid_argument(what +
                                    ": feet and inches are written like 5ft11in or 5'11\" "
                                    "(inches from 0 to under 12)");
      }
      raw += in / 12.0;
      unit = "ft";
    }
    if (unit == "'") unit = "ft";
    if (unit == "\"" || unit == "''") unit = "in";
  }
  double factor = 1.0;
  bool unit_ok = unit.empty();
  if (kind.quantity == Quantity::kLength) {
    const struct {
      const char* name;
      double factor;
    } lengths[] = {{"m", 1.0},
                   {"cm", 0.01},
                   {"mm", 0.001},
                   {"in", kMetresPerInch},
                   {"ft", 12 * kMetresPerInch}};
    for (const auto& u : lengths) {
      if (unit == u.name) factor = u.factor, unit_ok = true;
    }
  } else if (kind.quantity == Quantity::kMass) {
    if (unit == "kg") unit_ok = true;
    if (unit == "lb" || unit == "lbs") factor = kKgPerPound, unit_ok = true;
  }
  if (!unit_ok) {
    throw std::invalid_argument(what + ": unknown unit '" + unit + "' for " + kind.name +
                                (kind.quantity == Quantity::kLength ? " (m, cm, mm, in, ft)"
                                 : kind.quantity == Quantity::kMass ? " (kg, lb)"
                                                                    : " (BMI has no unit)"));
  }
  const double value = raw * factor;
  const double limit = kind.quantity == Quantity::kLength ? 3.0
                       : kind.quantity == Quantity::kMass ? 500.0
                                                          : 100.0;
  if (!(value > 0.0) || value > limit) {
    throw std::invalid_argument(what + " is out of range: a body's " + kind.name + " lies in (0, " +
                                format_measurement(kind.quantity, limit, Units::kMetric) + "]");
  }
  return value;
}

}  // namespace body
