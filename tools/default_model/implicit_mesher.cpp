#include "implicit_mesher.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <queue>
#include <thread>
#include <tuple>
#include <unordered_map>

namespace default_model {

using Vec3 = Eigen::Vector3d;

TriMesh marching_tetrahedra(const ScalarField& field, const Eigen::AlignedBox3d& box,
                            double spacing, int threads) {
  const Vec3 lo = box.min();
  const Vec3 ext = box.max() - box.min();
  const int nx = static_cast<int>(std::ceil(ext.x() / spacing)) + 1;
  const int ny = static_cast<int>(std::ceil(ext.y() / spacing)) + 1;
  const int nz = static_cast<int>(std::ceil(ext.z() / spacing)) + 1;
  auto index = [&](int i, int j, int k) {
    return static_cast<std::int64_t>(i) + nx * (static_cast<std::int64_t>(j) + ny * k);
  };
  auto point = [&](int i, int j, int k) {
    return Vec3(lo.x() + i * spacing, lo.y() + j * spacing, lo.z() + k * spacing);
  };
  std::vector<double> values(static_cast<std::size_t>(nx) * ny * nz);
  threads = std::max(1, threads);
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      for (int k = t; k < nz; k += threads)
        for (int j = 0; j < ny; ++j)
          for (int i = 0; i < nx; ++i) {
            double v = field(point(i, j, k));
            // Grid points exactly on the surface would make degenerate triangles.
            if (v == 0.0) v = 1e-12;
            // The box boundary is always outside, so the surface is closed.
            if (i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1)
              v = std::max(v, 1e-6);
            values[index(i, j, k)] = v;
          }
    });
  }
  for (auto& th : pool) th.join();

  TriMesh mesh;
  std::unordered_map<std::uint64_t, int> edge_vertex;
  edge_vertex.reserve(1 << 20);
  const std::uint64_t total = static_cast<std::uint64_t>(nx) * ny * nz;
  auto vertex_on_edge = [&](std::int64_t ga, std::int64_t gb, const Vec3& pa, const Vec3& pb) {
    if (ga > gb) return -1;  // never: callers order the pair
    const std::uint64_t key = static_cast<std::uint64_t>(ga) * total + gb;
    auto it = edge_vertex.find(key);
    if (it != edge_vertex.end()) return it->second;
    const double fa = values[ga], fb = values[gb];
    const double t = fa / (fa - fb);
    const int id = static_cast<int>(mesh.vertices.size());
    mesh.vertices.push_back(pa + t * (pb - pa));
    edge_vertex.emplace(key, id);
    return id;
  };

  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i) {
        std::int64_t g[8];
        Vec3 p[8];
        bool any_in = false, any_out = false;
        for (int b = 0; b < 8; ++b) {
          const int di = b & 1, dj = (b >> 1) & 1, dk = (b >> 2) & 1;
          g[b] = index(i + di, j + dj, k + dk);
          p[b] = point(i + di, j + dj, k + dk);
          (values[g[b]] < 0 ? any_in : any_out) = true;
        }
        if (!any_in || !any_out) continue;
        for (const auto& perm : perms) {
          const int c0 = 0, c1 = 1 << perm[0], c2 = c1 | (1 << perm[1]), c3 = 7;
          const int tet[4] = {c0, c1, c2, c3};
          int in[4], out[4], ni = 0, no = 0;
          for (int q = 0; q < 4; ++q) {
            if (values[g[tet[q]]] < 0)
              in[ni++] = tet[q];
            else
              out[no++] = tet[q];
          }
          if (ni == 0 || no == 0) continue;
          auto ev = [&](int a, int b) {
            return g[a] < g[b] ? vertex_on_edge(g[a], g[b], p[a], p[b])
                               : vertex_on_edge(g[b], g[a], p[b], p[a]);
          };
          Vec3 cin = Vec3::Zero(), cout = Vec3::Zero();
          for (int q = 0; q < ni; ++q) cin += p[in[q]];
          for (int q = 0; q < no; ++q) cout += p[out[q]];
          const Vec3 outward = cout / no - cin / ni;
          auto emit = [&](int a, int b, int c) {
            const Vec3 n =
                (mesh.vertices[b] - mesh.vertices[a]).cross(mesh.vertices[c] - mesh.vertices[a]);
            if (n.dot(outward) < 0) std::swap(b, c);
            mesh.faces.push_back({a, b, c});
          };
          if (ni == 1) {
            emit(ev(in[0], out[0]), ev(in[0], out[1]), ev(in[0], out[2]));
          } else if (no == 1) {
            emit(ev(out[0], in[0]), ev(out[0], in[1]), ev(out[0], in[2]));
          } else {
            const int a = ev(in[0], out[0]), b = ev(in[0], out[1]);
            const int c = ev(in[1], out[1]), d = ev(in[1], out[0]);
            emit(a, b, c);
            emit(a, c, d);
          }
        }
      }
  return mesh;
}

namespace {

Vec3 face_normal(const std::vector<Vec3>& P, const std::array<int, 3>& f) {
  return (P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]);
}

struct Adjacency {
  std::vector<std::vector<int>> vf;  // vertex -> faces (alive ones after compaction)
  void build(const TriMesh& m) {
    vf.assign(m.vertices.size(), {});
    for (int f = 0; f < static_cast<int>(m.faces.size()); ++f)
      for (int v : m.faces[f]) vf[v].push_back(f);
  }
};

void compact(TriMesh& mesh, const std::vector<char>& face_alive) {
  std::vector<std::array<int, 3>> faces;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (face_alive[f]) faces.push_back(mesh.faces[f]);
  std::vector<int> remap(mesh.vertices.size(), -1);
  std::vector<Vec3> verts;
  for (auto& f : faces)
    for (int& v : f) {
      if (remap[v] < 0) {
        remap[v] = static_cast<int>(verts.size());
        verts.push_back(mesh.vertices[v]);
      }
      v = remap[v];
    }
  mesh.vertices = std::move(verts);
  mesh.faces = std::move(faces);
}

std::vector<std::vector<int>> vertex_neighbours(const TriMesh& mesh) {
  std::vector<std::vector<int>> nb(mesh.vertices.size());
  for (const auto& f : mesh.faces)
    for (int e = 0; e < 3; ++e) {
      nb[f[e]].push_back(f[(e + 1) % 3]);
      nb[f[e]].push_back(f[(e + 2) % 3]);
    }
  for (auto& n : nb) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return nb;
}

void collapse_short_edges(TriMesh& mesh, const RemeshOptions& opt) {
  auto& P = mesh.vertices;
  auto& F = mesh.faces;
  std::vector<char> face_alive(F.size(), 1), vert_alive(P.size(), 1);
  Adjacency adj;
  adj.build(mesh);
  auto alive_faces = [&](int v) {
    auto& list = adj.vf[v];
    list.erase(std::remove_if(list.begin(), list.end(), [&](int f) { return !face_alive[f]; }),
               list.end());
    return list;
  };
  auto neighbours = [&](int v) {
    std::vector<int> n;
    for (int f : alive_faces(v))
      for (int w : F[f])
        if (w != v) n.push_back(w);
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
    return n;
  };
  auto ratio = [&](int a, int b) {
    return (P[a] - P[b]).norm() / opt.target_edge(0.5 * (P[a] + P[b]));
  };
  using Item = std::tuple<double, int, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (const auto& f : F)
    for (int e = 0; e < 3; ++e) {
      const int a = f[e], b = f[(e + 1) % 3];
      if (a < b) queue.emplace(ratio(a, b), a, b);
    }
  while (!queue.empty()) {
    const auto [r, a, b] = queue.top();
    queue.pop();
    if (r >= 0.8) break;
    if (!vert_alive[a] || !vert_alive[b]) continue;
    if (ratio(a, b) != r) continue;  // stale entry; a fresh one was queued
    std::vector<int> fa = alive_faces(a), fb = alive_faces(b);
    std::vector<int> shared;
    for (int f : fa)
      if (F[f][0] == b || F[f][1] == b || F[f][2] == b) shared.push_back(f);
    if (shared.size() != 2) continue;
    int opp[2] = {-1, -1};
    for (int s = 0; s < 2; ++s)
      for (int w : F[shared[s]])
        if (w != a && w != b) opp[s] = w;
    const auto na = neighbours(a), nb = neighbours(b);
    std::vector<int> common;
    std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
    if (common.size() != 2) continue;
    if (neighbours(opp[0]).size() <= 3 || neighbours(opp[1]).size() <= 3) continue;
    const Vec3 target = opt.project(0.5 * (P[a] + P[b]));
    const double limit = 1.35 * opt.target_edge(target);
    bool ok = true;
    for (int w : na)
      if (w != b && (P[w] - target).norm() > limit) ok = false;
    for (int w : nb)
      if (w != a && (P[w] - target).norm() > limit) ok = false;
    if (!ok) continue;
    for (const auto* list : {&fa, &fb}) {
      for (int f : *list) {
        if (f == shared[0] || f == shared[1]) continue;
        const Vec3 before = face_normal(P, F[f]);
        std::array<Vec3, 3> q;
        for (int c = 0; c < 3; ++c) q[c] = (F[f][c] == a || F[f][c] == b) ? target : P[F[f][c]];
        const Vec3 after = (q[1] - q[0]).cross(q[2] - q[0]);
        if (after.dot(before) <= 0.4 * after.norm() * before.norm() || after.norm() < 1e-14)
          ok = false;
      }
      if (!ok) break;
    }
    if (!ok) continue;
    face_alive[shared[0]] = face_alive[shared[1]] = 0;
    for (int f : fb) {
      if (!face_alive[f]) continue;
      for (int& w : F[f])
        if (w == b) w = a;
      adj.vf[a].push_back(f);
    }
    adj.vf[b].clear();
    vert_alive[b] = 0;
    P[a] = target;
    for (int w : neighbours(a))
      queue.emplace(ratio(std::min(a, w), std::max(a, w)), std::min(a, w), std::max(a, w));
  }
  compact(mesh, face_alive);
}

// Splits every edge longer than 1.5 target lengths at its midpoint, projected onto the surface,
// until none is left (a few rounds): the marching grid is as coarse as the body needs, and
// this refines it where the target asks for finer detail (face, toes, fingers). Each split
// keeps the mesh a consistently wound 2-manifold (the two faces of an edge become four).
void split_long_edges(TriMesh& mesh, const RemeshOptions& opt) {
  auto& P = mesh.vertices;
  auto& F = mesh.faces;
  for (int round = 0; round < 8; ++round) {
    const std::uint64_t V = P.size();
    std::unordered_map<std::uint64_t, std::array<int, 2>> edge_faces;
    edge_faces.reserve(F.size() * 2);
    for (int f = 0; f < static_cast<int>(F.size()); ++f)
      for (int e = 0; e < 3; ++e) {
        int a = F[f][e], b = F[f][(e + 1) % 3];
        const bool forward = a < b;
        if (!forward) std::swap(a, b);
        edge_faces[static_cast<std::uint64_t>(a) * V + b][forward ? 0 : 1] = f;
      }
    const std::size_t faces_before = F.size();
    std::vector<char> touched(faces_before, 0);
    int splits = 0;
    for (std::size_t f0 = 0; f0 < faces_before; ++f0) {
      for (int e = 0; e < 3; ++e) {
        if (touched[f0]) break;
        const int a = F[f0][e], b = F[f0][(e + 1) % 3];
        if (a > b) continue;  // each edge once, from the face where it runs a -> b, a < b
        const auto it = edge_faces.find(static_cast<std::uint64_t>(a) * V + b);
        if (it == edge_faces.end()) continue;
        const int f1 = it->second[0], f2 = it->second[1];
        if (f1 != static_cast<int>(f0) || touched[f2]) continue;
        const Vec3 mid = 0.5 * (P[a] + P[b]);
        if ((P[a] - P[b]).norm() <= 1.5 * opt.target_edge(mid)) continue;
        int c = -1, d = -1;
        for (int w : F[f1])
          if (w != a && w != b) c = w;
        for (int w : F[f2])
          if (w != a && w != b) d = w;
        const int m = static_cast<int>(P.size());
        P.push_back(opt.project(mid));
        // f1 = (a, b, c) and f2 = (b, a, d) up to rotation.
        F[f1] = {a, m, c};
        F[f2] = {b, m, d};
        F.push_back({m, b, c});
        F.push_back({m, a, d});
        touched[f1] = touched[f2] = 1;
        ++splits;
      }
    }
    if (splits == 0) break;
  }
}

void flip_edges(TriMesh& mesh) {
  auto& P = mesh.vertices;
  auto& F = mesh.faces;
  const int V = static_cast<int>(P.size());
  Adjacency adj;
  adj.build(mesh);
  std::vector<int> valence(V, 0);
  {
    const auto nb = vertex_neighbours(mesh);
    for (int v = 0; v < V; ++v) valence[v] = static_cast<int>(nb[v].size());
  }
  std::unordered_map<std::uint64_t, std::array<int, 2>> edge_faces;
  for (int f = 0; f < static_cast<int>(F.size()); ++f)
    for (int e = 0; e < 3; ++e) {
      int a = F[f][e], b = F[f][(e + 1) % 3];
      if (a > b) std::swap(a, b);
      auto& slot = edge_faces[static_cast<std::uint64_t>(a) * V + b];
      if (a == F[f][e])
        slot[0] = f;
      else
        slot[1] = f;
    }
  std::vector<char> touched(F.size(), 0);
  auto has_edge = [&](int c, int d) {
    for (int f : adj.vf[c])
      if (F[f][0] == d || F[f][1] == d || F[f][2] == d) return true;
    return false;
  };
  auto third = [&](int f, int a, int b) {
    for (int w : F[f])
      if (w != a && w != b) return w;
    return -1;
  };
  for (int f0 = 0; f0 < static_cast<int>(F.size()); ++f0) {
    for (int e = 0; e < 3; ++e) {
      if (touched[f0]) break;
      int a = F[f0][e], b = F[f0][(e + 1) % 3];
      if (a > b) continue;  // visit each edge once, from the face where it runs a -> b, a < b
      const auto it = edge_faces.find(static_cast<std::uint64_t>(a) * V + b);
      if (it == edge_faces.end()) continue;
      const int f1 = it->second[0], f2 = it->second[1];
      if (f1 != f0 || touched[f2]) continue;
      const int c = third(f1, a, b), d = third(f2, a, b);
      if (c == d || has_edge(c, d)) continue;
      auto dev = [](int x) { return std::abs(x - 6); };
      const int before = dev(valence[a]) + dev(valence[b]) + dev(valence[c]) + dev(valence[d]);
      const int after =
          dev(valence[a] - 1) + dev(valence[b] - 1) + dev(valence[c] + 1) + dev(valence[d] + 1);
      if (after >= before || valence[a] <= 4 || valence[b] <= 4) continue;
      const Vec3 n1 = face_normal(P, F[f1]).normalized(), n2 = face_normal(P, F[f2]).normalized();
      if (n1.dot(n2) < 0.8) continue;
      const std::array<int, 3> g1{a, d, c}, g2{d, b, c};
      const Vec3 m1 = face_normal(P, g1), m2 = face_normal(P, g2);
      const Vec3 avg = n1 + n2;
      if (m1.dot(avg) <= 0.5 * m1.norm() * avg.norm() ||
          m2.dot(avg) <= 0.5 * m2.norm() * avg.norm())
        continue;
      F[f1] = g1;
      F[f2] = g2;
      auto erase = [&](int v, int f) {
        auto& l = adj.vf[v];
        l.erase(std::remove(l.begin(), l.end(), f), l.end());
      };
      erase(b, f1);
      adj.vf[d].push_back(f1);
      erase(a, f2);
      adj.vf[c].push_back(f2);
      --valence[a];
      --valence[b];
      ++valence[c];
      ++valence[d];
      touched[f1] = touched[f2] = 1;
    }
  }
}

void relax(TriMesh& mesh, const RemeshOptions& opt) {
  const auto nb = vertex_neighbours(mesh);
  const auto normals = vertex_normals(mesh);
  std::vector<Vec3> next(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    Vec3 c = Vec3::Zero();
    for (int w : nb[v]) c += mesh.vertices[w];
    c /= static_cast<double>(nb[v].size());
    Vec3 delta = c - mesh.vertices[v];
    delta -= normals[v] * normals[v].dot(delta);
    next[v] = opt.project(mesh.vertices[v] + 0.7 * delta);
  }
  mesh.vertices = std::move(next);
}

}  // namespace

std::vector<std::vector<int>> neighbours_by_face(std::size_t vertex_count,
                                                 const std::vector<std::array<int, 3>>& faces) {
  std::vector<std::vector<int>> neighbours(vertex_count);
  for (const auto& f : faces)
    for (int a = 0; a < 3; ++a) neighbours[f[a]].push_back(f[(a + 1) % 3]);
  return neighbours;
}

void remesh(TriMesh& mesh, const RemeshOptions& options) {
  split_long_edges(mesh, options);
  // Two rounds: the first collapse leaves edges that its checks refused next to slivers; after
  // flips and relaxation most of them can go.
  for (int round = 0; round < 2; ++round) {
    collapse_short_edges(mesh, options);
    for (int it = 0; it < options.relax_iterations; ++it) {
      flip_edges(mesh);
      relax(mesh, options);
    }
  }
}

void keep_largest_component(TriMesh& mesh) {
  std::vector<int> parent(mesh.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& f : mesh.faces) {
    parent[find(f[1])] = find(f[0]);
    parent[find(f[2])] = find(f[0]);
  }
  std::vector<int> count(mesh.vertices.size(), 0);
  for (const auto& f : mesh.faces) ++count[find(f[0])];
  const int best = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
  std::vector<char> alive(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) alive[f] = find(mesh.faces[f][0]) == best;
  compact(mesh, alive);
}

double signed_volume(const TriMesh& mesh) {
  double v = 0;
  for (const auto& f : mesh.faces)
    v += mesh.vertices[f[0]].dot(mesh.vertices[f[1]].cross(mesh.vertices[f[2]]));
  return v / 6.0;
}

std::vector<Vec3> vertex_normals(const TriMesh& mesh) {
  std::vector<Vec3> n(mesh.vertices.size(), Vec3::Zero());
  for (const auto& f : mesh.faces) {
    const Vec3 fn = face_normal(mesh.vertices, f);
    for (int v : f) n[v] += fn;
  }
  for (auto& x : n) {
    const double l = x.norm();
    if (l > 0) x /= l;
  }
  return n;
}

}  // namespace default_model
