#include "body/mesh_slice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

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

  // The points grouped by the pieces they were joined into (pieces in the order of their
  // first point, points in the order they were made).
  std::vector<SlicePiece> pieces() {
    std::vector<int> piece_of_root(points_.size(), -1);
    std::vector<SlicePiece> pieces;
    for (std::size_t p = 0; p < points_.size(); ++p) {
      int& piece = piece_of_root[static_cast<std::size_t>(uf_.find(static_cast<int>(p)))];
      if (piece < 0) {
        piece = static_cast<int>(pieces.size());
        pieces.emplace_back();
      }
      pieces[static_cast<std::size_t>(piece)].points.push_back(points_[p]);
    }
    return pieces;
  }

 private:
  template <class MakePoint>
  int point_on(std::uint32_t a, std::uint32_t b, MakePoint& make_point) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key = (static_cast<std::uint64_t>(a) << 32) | b;
    int& id = edge_point_.find_or_add(key);
    if (id < 0) {
      points_.push_back(make_point(a, b));
      id = uf_.add();
    }
    return id;
  }

  // Edge key -> point id, open addressing (a slice crosses a few hundred edges; a node-based
  // map's allocations cost more than the cutting).
  class EdgeTable {
   public:
    int& find_or_add(std::uint64_t key) {
      if (2 * (count_ + 1) > keys_.size()) grow();
      std::size_t i = slot(key);
      while (keys_[i] != kEmpty && keys_[i] != key) i = (i + 1) & (keys_.size() - 1);
      if (keys_[i] == kEmpty) {
        keys_[i] = key;
        ids_[i] = -1;
        ++count_;
      }
      return ids_[i];
    }

   private:
    // No edge has this key: its two vertex indices would both be 2^32 - 1.
    static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
    std::size_t slot(std::uint64_t key) const {
      return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
    }
    void grow() {
      std::vector<std::uint64_t> keys = std::move(keys_);
      std::vector<int> ids = std::move(ids_);
      const std::size_t size = keys.empty() ? 256 : 2 * keys.size();
      keys_.assign(size, kEmpty);
      ids_.assign(size, -1);
      shift_ = 64;
      for (std::size_t s = size; s > 1; s >>= 1) --shift_;
      for (std::size_t k = 0; k < keys.size(); ++k) {
        if (keys[k] == kEmpty) continue;
        std::size_t i = slot(keys[k]);
        while (keys_[i] != kEmpty) i = (i + 1) & (size - 1);
        keys_[i] = keys[k];
        ids_[i] = ids[k];
      }
    }
    std::vector<std::uint64_t> keys_;
    std::vector<int> ids_;
    std::size_t count_ = 0;
    int shift_ = 64;
  };

  EdgeTable edge_point_;
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
  return std::move(slice_mesh(vertices, faces, std::vector<SlicePlane>{plane}, radius).front());
}

namespace {

// A vertex's signed distance from the plane; the one expression every cut uses, so that a
// plane cut alone and among others gives the same points to the last bit.
double signed_distance(const Vertices& vertices, Eigen::Index i, const SlicePlane& plane) {
  return (vertices.row(i).cast<double>().transpose() - plane.origin).dot(plane.normal);
}

// The pieces of one plane's slice through the faces listed (ascending), each face tested as a
// pass over all of them would: it is cut when its corners lie on both sides (a corner on the
// plane counts as above) and, with a finite radius, one corner is within it of the origin.
std::vector<SlicePiece> cut_faces(const Vertices& vertices, const Faces& faces,
                                  const SlicePlane& plane, double radius,
                                  const std::vector<Eigen::Index>& face_ids) {
  auto make_point = [&](std::uint32_t a, std::uint32_t b) {
    const double da = signed_distance(vertices, a, plane);
    const double db = signed_distance(vertices, b, plane);
    const double t = da / (da - db);
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
  for (const Eigen::Index i : face_ids) {
    const std::uint32_t v[3] = {faces(i, 0), faces(i, 1), faces(i, 2)};
    const bool up[3] = {signed_distance(vertices, v[0], plane) >= 0.0,
                        signed_distance(vertices, v[1], plane) >= 0.0,
                        signed_distance(vertices, v[2], plane) >= 0.0};
    if (up[0] == up[1] && up[1] == up[2]) continue;
    if (std::isfinite(radius) && !near(v[0]) && !near(v[1]) && !near(v[2])) continue;
    builder.cut(v, up, make_point);
  }
  return builder.pieces();
}

}  // namespace

std::vector<std::vector<SlicePiece>> slice_mesh(const Vertices& vertices, const Faces& faces,
                                                const std::vector<SlicePlane>& planes,
                                                double radius) {
  std::vector<std::vector<SlicePiece>> out(planes.size());
  const Eigen::Index V = vertices.rows();
  if (planes.empty() || V == 0) return out;
  // The mesh's extent bounds how far a vertex's distance from a plane can differ from its
  // projection on a nearly parallel normal less the plane's offset (the candidates' margin).
  double extent = 0.0;
  for (Eigen::Index i = 0; i < V; ++i)
    extent = std::max(extent, vertices.row(i).cast<double>().cwiseAbs().maxCoeff());
  std::vector<bool> done(planes.size(), false);
  std::vector<std::vector<Eigen::Index>> candidates(planes.size());
  Eigen::VectorXd projection(V);
  for (std::size_t first = 0; first < planes.size(); ++first) {
    if (done[first]) continue;
    // The planes whose normals are (nearly) this one's: one projection of the vertices finds
    // the faces that may cross each (a limb's levels share their bone's direction).
    const Eigen::Vector3d n = planes[first].normal;
    std::vector<std::size_t> group;
    double tilt = 0.0, origin_extent = 0.0;
    for (std::size_t k = first; k < planes.size(); ++k) {
      const double d = (planes[k].normal - n).norm();
      if (done[k] || !(d <= 1e-9)) continue;
      done[k] = true;
      group.push_back(k);
      tilt = std::max(tilt, d);
      origin_extent = std::max(origin_extent, planes[k].origin.cwiseAbs().maxCoeff());
    }
    // |signed_distance - (projection - offset)| is rounding (a few ulps of the coordinates)
    // plus the normals' difference times the distance from the origin.
    const double reach = std::sqrt(3.0) * (extent + origin_extent);
    const double margin = 1e-9 * (1.0 + reach) + 2.0 * tilt * reach;
    for (Eigen::Index i = 0; i < V; ++i) projection[i] = vertices.row(i).cast<double>().dot(n);
    std::vector<double> offset;
    double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
    for (const std::size_t k : group) {
      offset.push_back(planes[k].origin.dot(n));
      lowest = std::min(lowest, offset.back() - margin);
      highest = std::max(highest, offset.back() + margin);
    }
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      const std::uint32_t v[3] = {faces(f, 0), faces(f, 1), faces(f, 2)};
      if (v[0] >= V || v[1] >= V || v[2] >= V) continue;
      const double p0 = projection[v[0]], p1 = projection[v[1]], p2 = projection[v[2]];
      const double lo = std::min({p0, p1, p2}), hi = std::max({p0, p1, p2});
      if (hi < lowest || lo > highest) continue;
      for (std::size_t g = 0; g < group.size(); ++g)
        if (lo <= offset[g] + margin && hi >= offset[g] - margin) candidates[group[g]].push_back(f);
    }
  }
  for (std::size_t k = 0; k < planes.size(); ++k)
    out[k] = cut_faces(vertices, faces, planes[k], radius, candidates[k]);
  return out;
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
  if (heights.empty()) return crossing;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    double lo = vertices(faces(f, 0), 1), hi = lo;
    for (int c = 1; c < 3; ++c) {
      const double y = vertices(faces(f, c), 1);
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    if (hi < sorted.front() || lo >= sorted.back()) continue;  // crosses none of them
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
