#include "body/mesh_slice.hpp"

#include <cstdint>
#include <numeric>
#include <unordered_map>

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

}  // namespace

std::vector<SlicePiece> slice_mesh(const Vertices& vertices, const Faces& faces, double h) {
  // A vertex exactly on the plane is nudged up (treated as above) so every crossing lies
  // strictly inside an edge and is identified by that edge.
  auto above = [&](std::uint32_t v) { return static_cast<double>(vertices(v, 1)) >= h; };
  std::unordered_map<std::uint64_t, int> edge_point;  // edge key -> point id
  std::vector<Eigen::Vector2d> points;
  UnionFind uf;
  auto point_on = [&](std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key = (static_cast<std::uint64_t>(a) << 32) | b;
    const auto it = edge_point.find(key);
    if (it != edge_point.end()) return it->second;
    const double ya = vertices(a, 1), yb = vertices(b, 1);
    const double t = (h - ya) / (yb - ya);
    points.emplace_back(vertices(a, 0) + t * (vertices(b, 0) - vertices(a, 0)),
                        vertices(a, 2) + t * (vertices(b, 2) - vertices(a, 2)));
    const int id = uf.add();
    edge_point.emplace(key, id);
    return id;
  };
  for (Eigen::Index i = 0; i < faces.rows(); ++i) {
    const std::uint32_t v[3] = {faces(i, 0), faces(i, 1), faces(i, 2)};
    const bool up[3] = {above(v[0]), above(v[1]), above(v[2])};
    if (up[0] == up[1] && up[1] == up[2]) continue;
    int ids[2];
    int n = 0;
    for (int e = 0; e < 3; ++e) {
      const int a = e, b = (e + 1) % 3;
      if (up[a] != up[b]) ids[n++] = point_on(v[a], v[b]);
    }
    if (n == 2) uf.unite(ids[0], ids[1]);
  }
  std::unordered_map<int, std::size_t> piece_of_root;
  std::vector<SlicePiece> pieces;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const int root = uf.find(static_cast<int>(p));
    auto it = piece_of_root.find(root);
    if (it == piece_of_root.end()) {
      it = piece_of_root.emplace(root, pieces.size()).first;
      pieces.emplace_back();
    }
    pieces[it->second].points.push_back(points[p]);
  }
  return pieces;
}

}  // namespace body
