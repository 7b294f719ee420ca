#include "smplx_rig.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "body/joint_names.hpp"
#include "rig.hpp"

namespace default_model {

namespace {

constexpr int kBodyJoints = 22;  // SMPL's and SMPL-X's common first joints
constexpr int kJaw = 22, kLeftEye = 23, kRightEye = 24;
constexpr double kTrunkRadius = 0.14;

}  // namespace

SmplxRig smplx_rig(const Mannequin& mannequin) {
  const Skeleton& sk = mannequin.skeleton();
  const RigLandmarks& lm = mannequin.landmarks();
  const std::vector<std::string>* names = body::builtin_joint_names(55);
  if (names == nullptr || names->at(kJaw) != "jaw")
    throw std::logic_error("smplx_rig: SMPL-X's joint names are not as expected");
  SmplxRig rig;
  rig.names = *names;
  rig.landmarks = lm;
  const int J = rig.size();
  rig.parents.assign(J, -1);
  rig.joints.assign(J, Vec3::Zero());
  rig.segments.assign(J, {});
  for (int j = 0; j < kBodyJoints; ++j) {
    rig.parents[j] = joint_parents()[j];
    rig.joints[j] = sk.joints[j];
    // The trunk, neck and head compare plain distances among themselves (one radius): their
    // own radii differ so much that the thin neck and the spine's middle lost every vertex.
    const bool trunk =
        j == kPelvis || j == kSpine1 || j == kSpine2 || j == kSpine3 || j == kNeck || j == kHead;
    rig.segments[j].push_back(
        {sk.bone_start[j], sk.bone_end[j], trunk ? kTrunkRadius : sk.bone_radius[j]});
  }
  rig.head = kHead;
  rig.jaw = kJaw;
  rig.eyes = {kLeftEye, kRightEye};
  // The head also drives the face above the mouth (the skull's bone alone runs up its middle,
  // farther from the cheeks and nose than the jaw's).
  rig.segments[kHead].push_back({sk.joints[kHead], lm.face, kTrunkRadius});
  rig.parents[kJaw] = kHead;
  rig.joints[kJaw] = lm.jaw;
  rig.segments[kJaw].push_back({lm.jaw, lm.chin, kTrunkRadius});
  for (int s = 0; s < 2; ++s) {
    rig.parents[kLeftEye + s] = kHead;
    rig.joints[kLeftEye + s] = lm.eye_centres[s];
    const int wrist = kLeftWrist + s;
    // The palm: from the wrist to the knuckles of the four fingers (not the thumb, whose base
    // joint sits by the wrist).
    rig.segments[wrist].clear();
    for (int f = 0; f < 5; ++f) {
      const FingerChain& chain = lm.fingers[s][f];
      if (f < 4) rig.segments[wrist].push_back({sk.joints[wrist], chain.points[0], 0.018});
      for (int k = 0; k < 3; ++k) {
        const int j = kSmplxHandsBegin + 15 * s + 3 * f + k;
        rig.parents[j] = k == 0 ? wrist : j - 1;
        rig.joints[j] = chain.points[k];
        rig.segments[j].push_back({chain.points[k], chain.points[k + 1], f == 4 ? 0.011 : 0.008});
      }
    }
  }
  return rig;
}

Eigen::MatrixXd heat_weights(const TriMesh& mesh, const SmplxRig& rig,
                             const std::function<double(const Vec3&)>& inside, int max_influences,
                             HeatWeightReport* report) {
  const int V = static_cast<int>(mesh.vertices.size());
  const int J = rig.size();
  const auto& P = mesh.vertices;

  // Cotangent Laplacian (positive semi-definite) and lumped vertex areas.
  std::map<std::pair<int, int>, double> edge;
  Eigen::VectorXd area = Eigen::VectorXd::Zero(V);
  for (const auto& f : mesh.faces) {
    const double a = 0.5 * (P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]).norm();
    for (int c = 0; c < 3; ++c) {
      area[f[c]] += a / 3.0;
      const int i = f[(c + 1) % 3], k = f[(c + 2) % 3];
      const Vec3 e1 = P[i] - P[f[c]], e2 = P[k] - P[f[c]];
      const double cross = e1.cross(e2).norm();
      const double cot = cross > 1e-14 ? e1.dot(e2) / cross : 0.0;
      edge[{std::min(i, k), std::max(i, k)}] += 0.5 * cot;
    }
  }
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(V);
  for (const auto& [ik, w0] : edge) {
    // Obtuse triangles give negative weights, which break the maximum principle (weights
    // outside [0, 1]); dropping them keeps an M-matrix at little cost in accuracy.
    const double w = std::max(w0, 0.0);
    if (w == 0) continue;
    t.emplace_back(ik.first, ik.second, -w);
    t.emplace_back(ik.second, ik.first, -w);
    diagonal[ik.first] += w;
    diagonal[ik.second] += w;
  }

  // The nearest visible bone of each vertex and its heat.
  struct Source {
    int joint;
    const Segment* segment;
  };
  std::vector<Source> sources;
  for (int j = 0; j < J; ++j)
    for (const Segment& s : rig.segments[j]) sources.push_back({j, &s});
  // Past the thigh's end at the knee and the upper arm's at the elbow, distances are compared in
  // the radius of the segment that begins there (the shin's, the forearm's). In the thick
  // thigh's own radius its end reached 6-7 cm down the back of the calf, and the knee's blend
  // zone with it (the calf 10 cm below the knee still moved 20 % with the thigh), so that the
  // calf and thigh crossed each other when the knee bent. The other joints keep theirs (their
  // correctives are tuned to them).
  std::vector<double> past_end_radius(sources.size());
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const Segment& seg = *sources[i].segment;
    past_end_radius[i] = seg.radius;
    const int j = sources[i].joint;
    const bool hinge_parent =
        j == kLeftHip || j == kRightHip || j == kLeftShoulder || j == kRightShoulder;
    if (!hinge_parent) continue;
    const int hinge = limb_child(j);  // the knee, the elbow
    for (const Segment& next : rig.segments[hinge])
      if ((next.a - seg.b).norm() < 1e-3) past_end_radius[i] = std::min(seg.radius, next.radius);
  }
  Eigen::VectorXd heat = Eigen::VectorXd::Zero(V);
  std::vector<int> nearest(V, -1);
  int blind = 0;
  for (int v = 0; v < V; ++v) {
    std::vector<std::pair<double, int>> order;
    std::vector<Vec3> closest(sources.size());
    for (std::size_t i = 0; i < sources.size(); ++i) {
      const Segment& seg = *sources[i].segment;
      const double d = segment_distance(P[v], seg.a, seg.b, &closest[i]);
      const double radius = (closest[i] - seg.b).norm() < 1e-9 ? past_end_radius[i] : seg.radius;
      order.push_back({d / radius, int(i)});
    }
    std::sort(order.begin(), order.end());
    for (std::size_t r = 0; r < std::min<std::size_t>(order.size(), 8); ++r) {
      const Vec3& q = closest[order[r].second];
      bool visible = true;
      for (int k = 1; k <= 12 && visible; ++k) {
        const double s = k / 12.0;
        // A millimetre of tolerance: the vertex itself lies on the surface.
        visible = inside(P[v] + s * (q - P[v])) < 1e-3;
      }
      if (visible) {
        nearest[v] = sources[order[r].second].joint;
        const double d = std::max((P[v] - q).norm(), 0.004);
        // Baran & Popovic's c = 1: larger c narrows the blend zones, which keeps more volume
        // when a joint bends but folds more sharply (the pose benchmark at c = 4 and 16).
        heat[v] = 1.0 / (d * d);
        break;
      }
    }
    if (nearest[v] < 0) ++blind;
  }
  for (int v = 0; v < V; ++v) t.emplace_back(v, v, diagonal[v] + area[v] * heat[v]);
  Eigen::SparseMatrix<double> S(V, V);
  S.setFromTriplets(t.begin(), t.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(S);
  if (solver.info() != Eigen::Success)
    throw std::runtime_error("heat_weights: the heat system could not be factored");

  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(V, J);
  for (int j = 0; j < J; ++j) {
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(V);
    bool any = false;
    for (int v = 0; v < V; ++v)
      if (nearest[v] == j) {
        rhs[v] = area[v] * heat[v];
        any = true;
      }
    if (any) W.col(j) = solver.solve(rhs);
  }

  const RigLandmarks& lm = rig.landmarks;
  int eyeball = 0;
  for (int v = 0; v < V; ++v) {
    auto row = W.row(v);
    for (int j = 0; j < J; ++j) row[j] = std::max(row[j], 0.0);
    // The mandible: only what lies below the mouth line opens with the jaw.
    const double up = smoothstep(lm.mouth_y - 0.002, lm.mouth_y + 0.004, P[v].y());
    row[rig.head] += up * row[rig.jaw];
    row[rig.jaw] *= 1.0 - up;
    for (int s = 0; s < 2; ++s)
      if ((P[v] - lm.eye_centres[s]).norm() < lm.eye_radius + 5e-4) {
        row.setZero();
        row[rig.eyes[s]] = 1.0;
        ++eyeball;
      }
    if (max_influences > 0 && max_influences < J) {
      std::vector<int> idx(J);
      std::iota(idx.begin(), idx.end(), 0);
      std::partial_sort(
          idx.begin(), idx.begin() + max_influences + 1, idx.end(),
          [&](int a, int b) { return row[a] > row[b] || (row[a] == row[b] && a < b); });
      // Less the first weight left out, so that a weight reaches 0 where it drops out of the
      // largest four: cut off at its value, it left a step in the skin (a crack once posed).
      const double cut = row[idx[max_influences]];
      for (std::size_t k = 0; k < idx.size(); ++k)
        row[idx[k]] = k < static_cast<std::size_t>(max_influences) ? row[idx[k]] - cut : 0.0;
    }
    for (int j = 0; j < J; ++j)
      if (row[j] < 1e-4) row[j] = 0.0;
    const double sum = row.sum();
    if (sum <= 0) throw std::runtime_error("heat_weights: a vertex has no weight");
    row /= sum;
  }
  if (report) {
    report->vertices_without_visible_bone = blind;
    report->eyeball_vertices = eyeball;
  }
  return W;
}

Eigen::MatrixXd smplx_regressor(const TriMesh& mesh, const SmplxRig& rig,
                                const Eigen::MatrixXd& body_rows, const Eigen::MatrixXd& weights,
                                double* fit_error) {
  const int V = static_cast<int>(mesh.vertices.size());
  const int J = rig.size();
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(J, V);
  R.topRows(kBodyJoints) = body_rows.topRows(kBodyJoints);
  std::vector<int> dominant(V);
  for (int v = 0; v < V; ++v) weights.row(v).maxCoeff(&dominant[v]);
  double worst = 0;
  for (int j = 0; j < kBodyJoints; ++j) {
    Vec3 fit = Vec3::Zero();
    for (int v = 0; v < V; ++v) fit += R(j, v) * mesh.vertices[v];
    worst = std::max(worst, (fit - rig.joints[j]).norm());
  }
  std::vector<std::pair<int, double>> row;
  for (int j = kBodyJoints; j < J; ++j) {
    // Only the vertices of the joint's own part and its parent's: a finger's joint must not
    // follow the finger beside it.
    std::vector<int> candidates;
    for (int v = 0; v < V; ++v)
      if (dominant[v] == j || dominant[v] == rig.parents[j]) candidates.push_back(v);
    const Vec3& c = rig.joints[j];
    double nearest = 1e9;
    for (int v : candidates) nearest = std::min(nearest, (mesh.vertices[v] - c).norm());
    double radius = 1.8 * nearest + 0.015;
    double error = convex_joint_weights(mesh.vertices, c, candidates, radius, &row);
    // A joint that lies outside the hull of the nearby vertices (the eyes' centres behind
    // their visible caps) takes a wider neighbourhood.
    for (int grow = 0; grow < 8 && error > 1e-4; ++grow) {
      radius *= 1.3;
      error = convex_joint_weights(mesh.vertices, c, candidates, radius, &row);
    }
    if (error > 1e-3)
      throw std::runtime_error("smplx_regressor: joint '" + rig.names[j] +
                               "' cannot be regressed from the vertices round it");
    worst = std::max(worst, error);
    for (const auto& [v, w] : row) R(j, v) = w;
  }
  if (fit_error) *fit_error = worst;
  return R;
}

}  // namespace default_model
