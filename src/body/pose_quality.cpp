#include "body/pose_quality.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace body {

namespace {

using V3 = Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

V3 vertex(const Vertices& v, std::uint32_t i) {
  return v.row(i).transpose().cast<double>();
}

// Area-scaled normal of face f.
V3 face_normal(const Vertices& v, const Faces& faces, int f) {
  const V3 a = vertex(v, faces(f, 0)), b = vertex(v, faces(f, 1)), c = vertex(v, faces(f, 2));
  return (b - a).cross(c - a);
}

// Signed dihedral angle (radians) across the edge x -> y (as face f1 runs it) between faces f1
// and f2: 0 where they are coplanar, its sign saying which way the edge bends.
double signed_dihedral(const Vertices& v, const Faces& faces, int f1, int f2, std::uint32_t x,
                       std::uint32_t y, bool* degenerate) {
  const V3 n1 = face_normal(v, faces, f1), n2 = face_normal(v, faces, f2);
  const V3 e = vertex(v, y) - vertex(v, x);
  const double l1 = n1.norm(), l2 = n2.norm(), le = e.norm();
  if (!(l1 > 1e-18) || !(l2 > 1e-18) || !(le > 1e-12)) {
    *degenerate = true;
    return 0.0;
  }
  const V3 a = n1 / l1, b = n2 / l2;
  return std::atan2(a.cross(b).dot(e / le), a.dot(b));
}

// --- Moller's triangle-triangle test -----------------------------------------------------

// Signed distances of p0..p2 to the plane through q0..q2 (unit normal n), with values within
// `eps` of the plane snapped to 0 so that near-touching vertices are treated as on it.
std::array<double, 3> plane_distances(const V3& n, const V3& q0, const V3& p0, const V3& p1,
                                      const V3& p2, double eps) {
  std::array<double, 3> d = {n.dot(p0 - q0), n.dot(p1 - q0), n.dot(p2 - q0)};
  for (double& x : d) {
    if (std::abs(x) < eps) x = 0.0;
  }
  return d;
}

// The interval a triangle cuts on the line where the two planes meet, in the projection of the
// line onto its dominant axis: `v` the vertices' projections, `d` their plane distances. The
// vertex alone on its side (or on the plane) gives the two crossing points of its two edges.
// Returns false if every distance is 0 (coplanar).
bool line_interval(const std::array<double, 3>& v, const std::array<double, 3>& d, double* lo,
                   double* hi) {
  int alone;
  if (d[0] * d[1] > 0.0) {
    alone = 2;
  } else if (d[0] * d[2] > 0.0) {
    alone = 1;
  } else if (d[1] * d[2] > 0.0 || d[0] != 0.0) {
    alone = 0;
  } else if (d[1] != 0.0) {
    alone = 1;
  } else if (d[2] != 0.0) {
    alone = 2;
  } else {
    return false;
  }
  const int b = (alone + 1) % 3, c = (alone + 2) % 3;
  // d[alone] differs from d[b] and d[c] here (opposite signs or one of them zero and the other
  // not), so neither division is by zero.
  const double t0 = v[alone] + (v[b] - v[alone]) * d[alone] / (d[alone] - d[b]);
  const double t1 = v[alone] + (v[c] - v[alone]) * d[alone] / (d[alone] - d[c]);
  *lo = std::min(t0, t1);
  *hi = std::max(t0, t1);
  return true;
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Closed 2D segments ab and cd share a point.
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double d1 = cross2(b - a, c - a), d2 = cross2(b - a, d - a);
  const double d3 = cross2(d - c, a - c), d4 = cross2(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;
  }
  auto on = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r,
               double cr) {  // r on segment pq, given it is collinear (cr == 0)
    return cr == 0.0 && std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4);
}

bool inside_triangle_2d(const Eigen::Vector2d& p, const std::array<Eigen::Vector2d, 3>& t) {
  const double a = cross2(t[1] - t[0], p - t[0]);
  const double b = cross2(t[2] - t[1], p - t[1]);
  const double c = cross2(t[0] - t[2], p - t[2]);
  return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
}

// Coplanar triangles (normal n): projected onto the coordinate plane where n is largest, they
// meet if an edge of one crosses an edge of the other or one holds a vertex of the other.
bool coplanar_intersect(const V3& n, const std::array<V3, 3>& p, const std::array<V3, 3>& q) {
  int drop = 0;
  n.cwiseAbs().maxCoeff(&drop);
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  std::array<Eigen::Vector2d, 3> a, b;
  for (int k = 0; k < 3; ++k) {
    a[k] = Eigen::Vector2d(p[k][i], p[k][j]);
    b[k] = Eigen::Vector2d(q[k][i], q[k][j]);
  }
  for (int e = 0; e < 3; ++e) {
    for (int g = 0; g < 3; ++g) {
      if (segments_meet(a[e], a[(e + 1) % 3], b[g], b[(g + 1) % 3])) return true;
    }
  }
  return inside_triangle_2d(a[0], b) || inside_triangle_2d(b[0], a);
}

// --- Uniform grid over face bounding boxes -----------------------------------------------

struct Box {
  V3 lo, hi;
};

}  // namespace

std::vector<int> dominant_bones(const Faces& faces, const Eigen::MatrixXf& weights) {
  std::vector<int> out(static_cast<std::size_t>(faces.rows()), -1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::VectorXf sum =
        (weights.row(faces(f, 0)) + weights.row(faces(f, 1)) + weights.row(faces(f, 2)))
            .transpose();
    Eigen::Index best = 0;
    sum.maxCoeff(&best);
    out[static_cast<std::size_t>(f)] = static_cast<int>(best);
  }
  return out;
}

std::vector<int> joint_region(const Vertices& rest_vertices, const Faces& faces,
                              const std::vector<int>& face_bones, const std::vector<int>& parents,
                              const Vertices& rest_joints, const JointRegion& region) {
  const int j = region.joint;
  std::vector<char> bone_ok(parents.size(), 0);
  if (j < 0 || j >= static_cast<int>(parents.size())) return {};
  bone_ok[static_cast<std::size_t>(j)] = 1;
  if (parents[static_cast<std::size_t>(j)] >= 0) {
    bone_ok[static_cast<std::size_t>(parents[static_cast<std::size_t>(j)])] = 1;
  }
  for (std::size_t c = 0; c < parents.size(); ++c) {
    if (parents[c] == j) bone_ok[c] = 1;
  }
  const V3 centre = rest_joints.row(j).transpose().cast<double>();
  std::vector<int> out;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const int bone = face_bones[static_cast<std::size_t>(f)];
    if (bone < 0 || bone >= static_cast<int>(bone_ok.size()) ||
        !bone_ok[static_cast<std::size_t>(bone)]) {
      continue;
    }
    const V3 centroid = (vertex(rest_vertices, faces(f, 0)) + vertex(rest_vertices, faces(f, 1)) +
                         vertex(rest_vertices, faces(f, 2))) /
                        3.0;
    if ((centroid - centre).norm() <= region.radius) out.push_back(static_cast<int>(f));
  }
  return out;
}

double cone_volume(const Vertices& vertices, const Faces& faces, const std::vector<int>& region,
                   const Eigen::Vector3d& apex) {
  double sum = 0.0;
  for (int f : region) {
    const V3 a = vertex(vertices, faces(f, 0)) - apex;
    const V3 b = vertex(vertices, faces(f, 1)) - apex;
    const V3 c = vertex(vertices, faces(f, 2)) - apex;
    sum += a.dot(b.cross(c));
  }
  return sum / 6.0;
}

double volume_change_percent(const Vertices& rest_vertices, const Vertices& posed_vertices,
                             const Faces& faces, const std::vector<int>& region,
                             const Eigen::Vector3d& rest_apex, const Eigen::Vector3d& posed_apex) {
  const double rest = cone_volume(rest_vertices, faces, region, rest_apex);
  const double posed = cone_volume(posed_vertices, faces, region, posed_apex);
  if (region.empty() || !(std::abs(rest) > 1e-12)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return 100.0 * (posed - rest) / std::abs(rest);
}

Fold sharpest_fold(const Vertices& rest_vertices, const Vertices& posed_vertices,
                   const Faces& faces, const std::vector<int>& region) {
  // Directed edges (from, to, face) of the region's faces, sorted by their undirected key, so
  // the two faces of an interior edge sit next to each other.
  struct Edge {
    std::uint64_t key;
    std::uint32_t from, to;
    int face;
  };
  std::vector<Edge> edges;
  edges.reserve(region.size() * 3);
  for (int f : region) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = faces(f, k), b = faces(f, (k + 1) % 3);
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      edges.push_back({key, a, b, f});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    return x.key != y.key ? x.key < y.key : x.face < y.face;
  });
  Fold out;
  for (std::size_t i = 0; i + 1 < edges.size();) {
    std::size_t n = 1;
    while (i + n < edges.size() && edges[i + n].key == edges[i].key) ++n;
    if (n == 2) {  // an interior, manifold edge: exactly two region faces share it
      const Edge& e = edges[i];
      const int g = edges[i + 1].face;
      bool degenerate = false;
      const double rest =
          signed_dihedral(rest_vertices, faces, e.face, g, e.from, e.to, &degenerate);
      const double posed =
          signed_dihedral(posed_vertices, faces, e.face, g, e.from, e.to, &degenerate);
      if (!degenerate) {
        // The change wrapped into [0, pi]: a fold that passes through flat and over counts in
        // full, whichever way the angles' branches lie.
        double change = std::abs(std::remainder(posed - rest, 2.0 * kPi));
        change = change * 180.0 / kPi;
        if (change > out.degrees) {
          out.degrees = change;
          out.face_a = e.face;
          out.face_b = g;
        }
      }
    }
    i += n;
  }
  return out;
}

bool triangles_intersect(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                         const Eigen::Vector3d& p2, const Eigen::Vector3d& q0,
                         const Eigen::Vector3d& q1, const Eigen::Vector3d& q2) {
  const std::array<V3, 3> p = {p0, p1, p2}, q = {q0, q1, q2};
  V3 n1 = (p1 - p0).cross(p2 - p0), n2 = (q1 - q0).cross(q2 - q0);
  const double l1 = n1.norm(), l2 = n2.norm();
  if (!(l1 > 0.0) || !(l2 > 0.0)) return false;
  n1 /= l1;
  n2 /= l2;
  // Distances below a relative epsilon of the triangles' size count as on the plane: floats
  // posed through a skinning carry ~1e-7 relative noise, far above double rounding.
  double size = 0.0;
  for (int k = 0; k < 3; ++k) {
    size = std::max({size, (p[k] - p[(k + 1) % 3]).norm(), (q[k] - q[(k + 1) % 3]).norm()});
  }
  const double eps = 1e-9 * size;
  const auto dq = plane_distances(n1, p0, q0, q1, q2, eps);
  if ((dq[0] > 0 && dq[1] > 0 && dq[2] > 0) || (dq[0] < 0 && dq[1] < 0 && dq[2] < 0)) {
    return false;
  }
  const auto dp = plane_distances(n2, q0, p0, p1, p2, eps);
  if ((dp[0] > 0 && dp[1] > 0 && dp[2] > 0) || (dp[0] < 0 && dp[1] < 0 && dp[2] < 0)) {
    return false;
  }
  if (dq[0] == 0.0 && dq[1] == 0.0 && dq[2] == 0.0) return coplanar_intersect(n1, p, q);
  // Both triangles cross the other's plane: each cuts an interval out of the line where the
  // planes meet; they intersect if the intervals overlap. Projecting onto the line's largest
  // axis keeps the order along it and is cheaper than the true parameter.
  const V3 dir = n1.cross(n2);
  int axis = 0;
  dir.cwiseAbs().maxCoeff(&axis);
  const std::array<double, 3> vp = {p0[axis], p1[axis], p2[axis]};
  const std::array<double, 3> vq = {q0[axis], q1[axis], q2[axis]};
  double a0, a1, b0, b1;
  if (!line_interval(vp, dp, &a0, &a1) || !line_interval(vq, dq, &b0, &b1)) {
    return coplanar_intersect(n1, p, q);
  }
  return !(a1 < b0 || b1 < a0);
}

std::vector<std::pair<int, int>> intersecting_face_pairs(const Vertices& vertices,
                                                         const Faces& faces) {
  const int F = static_cast<int>(faces.rows());
  std::vector<std::pair<int, int>> out;
  if (F < 2) return out;
  std::vector<Box> boxes(static_cast<std::size_t>(F));
  Box all{V3::Constant(std::numeric_limits<double>::max()),
          V3::Constant(-std::numeric_limits<double>::max())};
  double extent_sum = 0.0;
  for (int f = 0; f < F; ++f) {
    Box& b = boxes[static_cast<std::size_t>(f)];
    b.lo = b.hi = vertex(vertices, faces(f, 0));
    for (int k = 1; k < 3; ++k) {
      const V3 p = vertex(vertices, faces(f, k));
      b.lo = b.lo.cwiseMin(p);
      b.hi = b.hi.cwiseMax(p);
    }
    all.lo = all.lo.cwiseMin(b.lo);
    all.hi = all.hi.cwiseMax(b.hi);
    extent_sum += (b.hi - b.lo).maxCoeff();
  }
  if (!all.lo.allFinite() || !all.hi.allFinite()) return out;
  // Cells twice the mean face size: a face covers a few cells and a cell holds a few dozen
  // faces; at most 128 cells along an axis so the grid stays small for a stray far vertex.
  const V3 span = (all.hi - all.lo).cwiseMax(1e-9);
  double cell = std::max(2.0 * extent_sum / F, 1e-9);
  cell = std::max(cell, span.maxCoeff() / 128.0);
  Eigen::Vector3i dims;
  for (int a = 0; a < 3; ++a) dims[a] = std::max(0, static_cast<int>(span[a] / cell)) + 1;
  auto cell_of = [&](const V3& p) {
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a) {
      c[a] = std::clamp(static_cast<int>(std::floor((p[a] - all.lo[a]) / cell)), 0, dims[a] - 1);
    }
    return c;
  };
  const std::size_t cells = std::size_t(dims.x()) * dims.y() * dims.z();
  auto index = [&](int x, int y, int z) { return (std::size_t(z) * dims.y() + y) * dims.x() + x; };
  std::vector<Eigen::Vector3i> first(static_cast<std::size_t>(F)),
      last(static_cast<std::size_t>(F));
  // Compressed rows: the faces of cell c are members[start[c] .. start[c + 1]).
  std::vector<std::uint32_t> start(cells + 1, 0);
  for (int f = 0; f < F; ++f) {
    first[f] = cell_of(boxes[f].lo);
    last[f] = cell_of(boxes[f].hi);
    for (int z = first[f].z(); z <= last[f].z(); ++z)
      for (int y = first[f].y(); y <= last[f].y(); ++y)
        for (int x = first[f].x(); x <= last[f].x(); ++x) ++start[index(x, y, z) + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  std::vector<int> members(start[cells]);
  for (int f = 0; f < F; ++f) {
    for (int z = first[f].z(); z <= last[f].z(); ++z)
      for (int y = first[f].y(); y <= last[f].y(); ++y)
        for (int x = first[f].x(); x <= last[f].x(); ++x) members[fill[index(x, y, z)]++] = f;
  }
  for (int z = 0; z < dims.z(); ++z) {
    for (int y = 0; y < dims.y(); ++y) {
      for (int x = 0; x < dims.x(); ++x) {
        const std::size_t c = index(x, y, z);
        for (std::uint32_t i = start[c]; i < start[c + 1]; ++i) {
          const int f = members[i];
          for (std::uint32_t k = i + 1; k < start[c + 1]; ++k) {
            const int g = members[k];
            // Test each pair once: in the first cell both boxes cover.
            const Eigen::Vector3i common = first[f].cwiseMax(first[g]);
            if (common != Eigen::Vector3i(x, y, z)) continue;
            const Box &a = boxes[f], &b = boxes[g];
            if ((a.hi.array() < b.lo.array()).any() || (b.hi.array() < a.lo.array()).any()) {
              continue;
            }
            bool shared = false;
            for (int s = 0; s < 3 && !shared; ++s) {
              for (int t = 0; t < 3; ++t) shared = shared || faces(f, s) == faces(g, t);
            }
            if (shared) continue;
            if (triangles_intersect(vertex(vertices, faces(f, 0)), vertex(vertices, faces(f, 1)),
                                    vertex(vertices, faces(f, 2)), vertex(vertices, faces(g, 0)),
                                    vertex(vertices, faces(g, 1)), vertex(vertices, faces(g, 2)))) {
              out.emplace_back(std::min(f, g), std::max(f, g));
            }
          }
        }
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

Intersections new_self_intersections(const Vertices& rest_vertices, const Vertices& posed_vertices,
                                     const Faces& faces, const std::vector<char>& exempt_faces) {
  Intersections out;
  for (const auto& [f, g] : intersecting_face_pairs(posed_vertices, faces)) {
    // A pair that already crossed at rest is the mesh's own defect, not the pose's.
    if (triangles_intersect(vertex(rest_vertices, faces(f, 0)), vertex(rest_vertices, faces(f, 1)),
                            vertex(rest_vertices, faces(f, 2)), vertex(rest_vertices, faces(g, 0)),
                            vertex(rest_vertices, faces(g, 1)),
                            vertex(rest_vertices, faces(g, 2)))) {
      continue;
    }
    const bool exempt = !exempt_faces.empty() && exempt_faces[static_cast<std::size_t>(f)] &&
                        exempt_faces[static_cast<std::size_t>(g)];
    ++(exempt ? out.exempt_pairs : out.pairs);
  }
  return out;
}

PoseFigures measure_pose(const RestAndPosed& mesh, const Eigen::MatrixXf& weights,
                         const std::vector<int>& parents, const std::vector<JointRegion>& regions,
                         const std::vector<int>& exempt_bones) {
  PoseFigures out;
  const std::vector<int> bones = dominant_bones(mesh.faces, weights);
  double worst_volume = std::numeric_limits<double>::quiet_NaN();
  for (const JointRegion& r : regions) {
    const std::vector<int> region =
        joint_region(mesh.rest_vertices, mesh.faces, bones, parents, mesh.rest_joints, r);
    out.region_faces += static_cast<int>(region.size());
    const double change =
        volume_change_percent(mesh.rest_vertices, mesh.posed_vertices, mesh.faces, region,
                              mesh.rest_joints.row(r.joint).transpose().cast<double>(),
                              mesh.posed_joints.row(r.joint).transpose().cast<double>());
    if (std::isfinite(change) && !(std::abs(change) <= std::abs(worst_volume))) {
      worst_volume = change;
    }
    out.sharpest_fold_degrees = std::max(
        out.sharpest_fold_degrees,
        sharpest_fold(mesh.rest_vertices, mesh.posed_vertices, mesh.faces, region).degrees);
  }
  out.volume_change_percent = worst_volume;
  std::vector<char> exempt;
  if (!exempt_bones.empty()) {
    exempt.assign(static_cast<std::size_t>(mesh.faces.rows()), 0);
    for (std::size_t f = 0; f < bones.size(); ++f) {
      exempt[f] =
          std::find(exempt_bones.begin(), exempt_bones.end(), bones[f]) != exempt_bones.end();
    }
  }
  out.intersections =
      new_self_intersections(mesh.rest_vertices, mesh.posed_vertices, mesh.faces, exempt);
  return out;
}

}  // namespace body
