#include "model_checks.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include <Eigen/Geometry>

namespace model_checks {

Topology topology(int vertex_count, const Tris& faces) {
  Topology t;
  t.vertices = vertex_count;
  t.faces = static_cast<int>(faces.size());
  std::map<std::pair<int, int>, int> directed;
  for (const auto& f : faces)
    for (int e = 0; e < 3; ++e) ++directed[{f[e], f[(e + 1) % 3]}];
  std::map<std::pair<int, int>, int> undirected;
  for (const auto& [e, n] : directed) {
    if (n > 1) ++t.inconsistent_edges;
    undirected[{std::min(e.first, e.second), std::max(e.first, e.second)}] += n;
  }
  t.edges = static_cast<int>(undirected.size());
  for (const auto& [e, n] : undirected)
    if (n != 2) ++t.non_manifold_edges;
  // One closed fan per vertex: around v, each face (v, b, c) links b -> c; following the links
  // from any start must visit every face of v once and return.
  std::vector<std::vector<std::pair<int, int>>> fan(vertex_count);
  for (const auto& f : faces)
    for (int e = 0; e < 3; ++e) fan[f[e]].push_back({f[(e + 1) % 3], f[(e + 2) % 3]});
  for (int v = 0; v < vertex_count; ++v) {
    if (fan[v].empty()) {
      ++t.unused_vertices;
      continue;
    }
    std::unordered_map<int, int> next;
    for (const auto& [b, c] : fan[v]) next[b] = c;
    int steps = 0, cur = fan[v][0].first;
    do {
      auto it = next.find(cur);
      if (it == next.end()) break;
      cur = it->second;
      ++steps;
    } while (cur != fan[v][0].first && steps <= static_cast<int>(fan[v].size()));
    if (steps != static_cast<int>(fan[v].size()) || cur != fan[v][0].first)
      ++t.non_manifold_vertices;
  }
  return t;
}

double signed_volume(const Points& v, const Tris& faces) {
  double s = 0;
  for (const auto& f : faces) s += v[f[0]].dot(v[f[1]].cross(v[f[2]]));
  return s / 6.0;
}

int inverted_triangles(const Points& base, const Points& deformed, const Tris& faces) {
  int bad = 0;
  for (const auto& f : faces) {
    const Eigen::Vector3d n0 = (base[f[1]] - base[f[0]]).cross(base[f[2]] - base[f[0]]);
    const Eigen::Vector3d n =
        (deformed[f[1]] - deformed[f[0]]).cross(deformed[f[2]] - deformed[f[0]]);
    if (n.dot(n0) <= 0 || 0.5 * n.norm() < 1e-12) ++bad;
  }
  return bad;
}

double stature(const Points& v) {
  double lo = 1e9, hi = -1e9;
  for (const auto& p : v) {
    lo = std::min(lo, p.y());
    hi = std::max(hi, p.y());
  }
  return hi - lo;
}

double breast_projection(const Points& v, double window) {
  double lo = 1e9, hi = -1e9, mid_x = 0.0;
  for (const auto& p : v) {
    lo = std::min(lo, p.y());
    hi = std::max(hi, p.y());
    mid_x += p.x();
  }
  mid_x /= static_cast<double>(v.size());
  const double H = hi - lo;
  // The forward profile of the nipple line in bins of 0.5% of the stature, 60-80% from the
  // soles.
  const double bin = 0.005 * H, base = lo + 0.60 * H;
  constexpr int kBins = 40;
  std::vector<double> profile(kBins, -1e9);
  for (const auto& p : v) {
    const double side = std::abs(p.x() - mid_x);
    if (side < 0.035 * H || side > 0.075 * H) continue;
    const int b = static_cast<int>(std::floor((p.y() - base) / bin));
    if (b >= 0 && b < kBins) profile[b] = std::max(profile[b], p.z());
  }
  const int below = static_cast<int>(std::lround(window * H / bin));
  double projection = 0.0;
  for (int b = 20; b < 36; ++b) {  // the chest band, 70-78% of the stature
    if (profile[b] < -1e8) continue;
    double fold = profile[b];
    for (int c = std::max(0, b - below); c < b; ++c)
      if (profile[c] > -1e8) fold = std::min(fold, profile[c]);
    projection = std::max(projection, profile[b] - fold);
  }
  return projection;
}

namespace {

// Segment p-q against triangle (a, b, c), Moller-Trumbore.
bool segment_hits(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                  const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d d = q - p, e1 = b - a, e2 = c - a;
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-18) return false;
  const double inv = 1.0 / det;
  const Eigen::Vector3d s = p - a;
  const double u = inv * s.dot(h);
  if (u < 0 || u > 1) return false;
  const Eigen::Vector3d qq = s.cross(e1);
  const double w = inv * d.dot(qq);
  if (w < 0 || u + w > 1) return false;
  const double t = inv * e2.dot(qq);
  return t >= 0 && t <= 1;
}

bool triangles_intersect(const Points& v, const std::array<int, 3>& A,
                         const std::array<int, 3>& B) {
  for (int e = 0; e < 3; ++e) {
    if (segment_hits(v[A[e]], v[A[(e + 1) % 3]], v[B[0]], v[B[1]], v[B[2]])) return true;
    if (segment_hits(v[B[e]], v[B[(e + 1) % 3]], v[A[0]], v[A[1]], v[A[2]])) return true;
  }
  return false;
}

}  // namespace

int intersecting_pairs(const Points& v, const Tris& faces, const std::vector<int>& a,
                       const std::vector<int>& b) {
  const double cell = 0.03;
  auto key = [&](int x, int y, int z) {
    return (static_cast<std::int64_t>(x + 1000) * 4096 + (y + 1000)) * 4096 + (z + 1000);
  };
  auto cell_of = [&](double x) { return static_cast<int>(std::floor(x / cell)); };
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  for (int f : b) {
    Eigen::Vector3d lo = v[faces[f][0]], hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = lo.cwiseMin(v[faces[f][k]]);
      hi = hi.cwiseMax(v[faces[f][k]]);
    }
    for (int x = cell_of(lo.x()); x <= cell_of(hi.x()); ++x)
      for (int y = cell_of(lo.y()); y <= cell_of(hi.y()); ++y)
        for (int z = cell_of(lo.z()); z <= cell_of(hi.z()); ++z) grid[key(x, y, z)].push_back(f);
  }
  int hits = 0;
  std::vector<int> seen;
  for (int f : a) {
    Eigen::Vector3d lo = v[faces[f][0]], hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = lo.cwiseMin(v[faces[f][k]]);
      hi = hi.cwiseMax(v[faces[f][k]]);
    }
    seen.clear();
    for (int x = cell_of(lo.x()); x <= cell_of(hi.x()); ++x)
      for (int y = cell_of(lo.y()); y <= cell_of(hi.y()); ++y)
        for (int z = cell_of(lo.z()); z <= cell_of(hi.z()); ++z) {
          auto it = grid.find(key(x, y, z));
          if (it == grid.end()) continue;
          seen.insert(seen.end(), it->second.begin(), it->second.end());
        }
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    for (int g : seen) {
      bool shares = false;
      for (int i : faces[f])
        for (int j : faces[g])
          if (i == j) shares = true;
      if (shares) continue;
      if (triangles_intersect(v, faces[f], faces[g])) ++hits;
    }
  }
  return hits;
}

}  // namespace model_checks
