#include "body/mesh_slice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include <Eigen/Geometry>

namespace body {

namespace {

struct UnionFind {
  std::vector<int> parent;
  int add() {
    parent.push_back(static_cast<int>(parent.size()));
    return parent.back();
  }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  void unite(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

// Joins a plane's crossings of the faces' edges into connected pieces. Each crossed edge gets
// one point, made by `make_point(a, b)` (a < b) the first time a face crossing it is cut, and
// shared with the other face on that edge; the two points of one face belong together.
class SliceBuilder {
 public:
  // `up`: which corners lie on the plane's positive side (a corner on the plane counts as
  // positive, so every crossing lies strictly inside an edge).
  template <class MakePoint>
  void cut(const std::uint32_t (&v)[3], const bool (&up)[3], MakePoint&& make_point) {
    if (up[0] == up[1] && up[1] == up[2]) return;
    int ids[2];
    int n = 0;
    for (int e = 0; e < 3; ++e) {
      const int a = e, b = (e + 1) % 3;
      if (up[a] != up[b]) ids[n++] = point_on(v[a], v[b], make_point);
    }
    if (n == 2) uf_.unite(ids[0], ids[1]);
  }

  // The points grouped by the pieces they were joined into.
  std::vector<SlicePiece> pieces() {
    std::unordered_map<int, std::size_t> piece_of_root;
    std::vector<SlicePiece> pieces;
    for (std::size_t p = 0; p < points_.size(); ++p) {
      const int root = uf_.find(static_cast<int>(p));
      auto it = piece_of_root.find(root);
      if (it == piece_of_root.end()) {
        it = piece_of_root.emplace(root, pieces.size()).first;
        pieces.emplace_back();
      }
      pieces[it->second].points.push_back(points_[p]);
    }
    return pieces;
  }

 private:
  template <class MakePoint>
  int point_on(std::uint32_t a, std::uint32_t b, MakePoint& make_point) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key = (static_cast<std::uint64_t>(a) << 32) | b;
    const auto it = edge_point_.find(key);
    if (it != edge_point_.end()) return it->second;
    points_.push_back(make_point(a, b));
    const int id = uf_.add();
    edge_point_.emplace(key, id);
    return id;
  }

  std::unordered_map<std::uint64_t, int> edge_point_;  // edge key -> point id
  std::vector<Eigen::Vector2d> points_;
  UnionFind uf_;
};

// The slice through the faces listed (ascending face order, as a pass over all faces visits
// them), or through every face when `face_ids` is null.
std::vector<SlicePiece> slice_faces(const Vertices& vertices, const Faces& faces, double h,
                                    const std::vector<Eigen::Index>* face_ids) {
  auto above = [&](std::uint32_t v) { return static_cast<double>(vertices(v, 1)) >= h; };
  auto make_point = [&](std::uint32_t a, std::uint32_t b) {
    const double ya = vertices(a, 1), yb = vertices(b, 1);
    const double t = (h - ya) / (yb - ya);
    return Eigen::Vector2d(vertices(a, 0) + t * (vertices(b, 0) - vertices(a, 0)),
                           vertices(a, 2) + t * (vertices(b, 2) - vertices(a, 2)));
  };
  SliceBuilder builder;
  const Eigen::Index count =
      face_ids != nullptr ? static_cast<Eigen::Index>(face_ids->size()) : faces.rows();
  for (Eigen::Index k = 0; k < count; ++k) {
    const Eigen::Index i = face_ids != nullptr ? (*face_ids)[static_cast<std::size_t>(k)] : k;
    const std::uint32_t v[3] = {faces(i, 0), faces(i, 1), faces(i, 2)};
    const bool up[3] = {above(v[0]), above(v[1]), above(v[2])};
    builder.cut(v, up, make_point);
  }
  return builder.pieces();
}

}  // namespace

SlicePlane plane_across(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
  SlicePlane p;
  p.origin = origin;
  p.normal = direction.normalized();
  // u from the world axis least aligned with the normal, so the basis never degenerates.
  Eigen::Index axis = 0;
  p.normal.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d seed = Eigen::Vector3d::Unit(axis);
  p.u = (seed - seed.dot(p.normal) * p.normal).normalized();
  p.v = p.normal.cross(p.u);
  return p;
}

std::vector<SlicePiece> slice_mesh(const Vertices& vertices, const Faces& faces,
                                   const SlicePlane& plane, double radius) {
  // Signed distances once per vertex; a vertex exactly on the plane counts as above (as in
  // slice_faces), so every crossing lies strictly inside an edge.
  Eigen::VectorXd distance(vertices.rows());
  for (Eigen::Index i = 0; i < vertices.rows(); ++i) {
    distance[i] = (vertices.row(i).cast<double>().transpose() - plane.origin).dot(plane.normal);
  }
  auto make_point = [&](std::uint32_t a, std::uint32_t b) {
    const double t = distance[a] / (distance[a] - distance[b]);
    const Eigen::Vector3d pa = vertices.row(a).cast<double>().transpose();
    const Eigen::Vector3d pb = vertices.row(b).cast<double>().transpose();
    const Eigen::Vector3d q = pa + t * (pb - pa) - plane.origin;
    return Eigen::Vector2d(q.dot(plane.u), q.dot(plane.v));
  };
  const auto near = [&](std::uint32_t corner) {
    return (vertices.row(corner).cast<double>().transpose() - plane.origin).squaredNorm() <=
           radius * radius;
  };
  SliceBuilder builder;
  for (Eigen::Index i = 0; i < faces.rows(); ++i) {
    const std::uint32_t v[3] = {faces(i, 0), faces(i, 1), faces(i, 2)};
    if (v[0] >= vertices.rows() || v[1] >= vertices.rows() || v[2] >= vertices.rows()) continue;
    const bool up[3] = {distance[v[0]] >= 0.0, distance[v[1]] >= 0.0, distance[v[2]] >= 0.0};
    if (up[0] == up[1] && up[1] == up[2]) continue;
    if (std::isfinite(radius) && !near(v[0]) && !near(v[1]) && !near(v[2])) continue;
    builder.cut(v, up, make_point);
  }
  return builder.pieces();
}

std::vector<SlicePiece> slice_mesh(const Vertices& vertices, const Faces& faces, double h) {
  return slice_faces(vertices, faces, h, nullptr);
}

std::vector<SlicePiece> slice_mesh(const Vertices& vertices, const Faces& faces, double h,
                                   const std::vector<Eigen::Index>& face_ids) {
  return slice_faces(vertices, faces, h, &face_ids);
}

std::vector<std::vector<Eigen::Index>> faces_crossing(const Vertices& vertices, const Faces& faces,
                                                      const std::vector<double>& heights) {
  // Heights in ascending order (with their original index): a face crosses the plane y = h
  // when one vertex is below and one at or above it, i.e. exactly the heights in
  // (min y, max y] of its vertices, as slice_faces decides.
  std::vector<std::size_t> order(heights.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return heights[a] < heights[b]; });
  std::vector<double> sorted;
  for (const std::size_t i : order) sorted.push_back(heights[i]);
  std::vector<std::vector<Eigen::Index>> crossing(heights.size());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    double lo = vertices(faces(f, 0), 1), hi = lo;
    for (int c = 1; c < 3; ++c) {
      const double y = vertices(faces(f, c), 1);
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    const auto first = std::upper_bound(sorted.begin(), sorted.end(), lo);
    const auto last = std::upper_bound(first, sorted.end(), hi);
    for (auto it = first; it != last; ++it) {
      crossing[order[static_cast<std::size_t>(it - sorted.begin())]].push_back(f);
    }
  }
  return crossing;
}

std::vector<std::vector<SlicePiece>> slice_mesh(const Vertices& vertices, const Faces& faces,
                                                const std::vector<double>& heights) {
  const auto crossing = faces_crossing(vertices, faces, heights);
  std::vector<std::vector<SlicePiece>> slices;
  slices.reserve(heights.size());
  for (std::size_t i = 0; i < heights.size(); ++i) {
    slices.push_back(slice_faces(vertices, faces, heights[i], &crossing[i]));
  }
  return slices;
}

}  // namespace body
