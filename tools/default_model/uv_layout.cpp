#include "uv_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <unordered_map>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "uv_packing.hpp"

namespace default_model {

namespace {

// Body parts before the splits that make charts of them (the charts' parts, 0..19: torso front
// and back, face, back of the head, eyes, arms, hands' backs and palms, legs, feet's tops and
// soles, the head's sides).
enum Group { kGroupTorso, kGroupHead, kGroupEye, kGroupArm, kGroupHand, kGroupLeg, kGroupFoot };

struct JointGroup {
  Group group;
  int side;  // 0 left, 1 right, -1 the middle
};

JointGroup group_of_joint(int j) {
  // SMPL-X's order (smplx_rig.hpp): 0..21 SMPL's body, 22 jaw, 23/24 eyes, 25..39 the left
  // hand's fingers, 40..54 the right hand's.
  if (j >= 25) return {kGroupHand, j < 40 ? 0 : 1};
  switch (j) {
    case 12:
    case 15:
    case 22:
      return {kGroupHead, -1};
    case 23:
    case 24:
      return {kGroupEye, j - 23};
    case 16:
    case 18:
    case 17:
    case 19:
      return {kGroupArm, (j % 2 == 0) ? 0 : 1};
    case 20:
    case 21:
      return {kGroupHand, j - 20};
    case 1:
    case 4:
    case 2:
    case 5:
      return {kGroupLeg, (j % 3 == 1) ? 0 : 1};
    case 7:
    case 10:
    case 8:
    case 11:
      return {kGroupFoot, (j % 3 == 1) ? 0 : 1};
    default:
      return {kGroupTorso, -1};
  }
}

using Edge = std::uint64_t;
Edge edge_key(int a, int b) {
  return (static_cast<Edge>(std::min(a, b)) << 32) | static_cast<Edge>(std::max(a, b));
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

Vec3 face_normal(const TriMesh& m, int f) {
  const auto& t = m.faces[f];
  return (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
}

// Least squares conformal map of one chart (its faces, corners as chart-local ids).
std::vector<Eigen::Vector2d> lscm(const TriMesh& mesh, const std::vector<int>& faces,
                                  const std::vector<std::array<int, 3>>& corners, int n,
                                  const std::vector<Vec3>& position) {
  // Pins: two far-apart vertices (a double sweep of the farthest point).
  int p0 = 0, p1 = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const Vec3 from = position[pass == 0 ? 0 : p0];
    double best = -1;
    int arg = 0;
    for (int i = 0; i < n; ++i)
      if (const double d = (position[i] - from).squaredNorm(); d > best) best = d, arg = i;
    (pass == 0 ? p0 : p1) = arg;
  }
  if (p0 == p1) p1 = (p0 + 1) % n;
  // Unknowns: (u, v) of every non-pinned vertex.
  std::vector<int> column(n, -1);
  int free = 0;
  for (int i = 0; i < n; ++i)
    if (i != p0 && i != p1) column[i] = free++;
  const Eigen::Vector2d pinned[2] = {{0, 0}, {1, 0}};
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> rhs;
  int row = 0;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const auto& f = mesh.faces[faces[k]];
    const Vec3 e1 = mesh.vertices[f[1]] - mesh.vertices[f[0]];
    const Vec3 e2 = mesh.vertices[f[2]] - mesh.vertices[f[0]];
    const Vec3 normal = e1.cross(e2);
    const double twice_area = normal.norm();
    if (twice_area < 1e-14) continue;
    const Vec3 x = e1.normalized(), y = normal.normalized().cross(x);
    const Eigen::Vector2d q[3] = {{0, 0}, {e1.norm(), 0}, {e2.dot(x), e2.dot(y)}};
    const double scale = 1.0 / std::sqrt(twice_area);
    double b_re = 0, b_im = 0;
    for (int j = 0; j < 3; ++j) {
      // W_j = q_{j+2} - q_{j+1}: sum_j W_j U_j vanishes exactly for similarities.
      const Eigen::Vector2d w = (q[(j + 2) % 3] - q[(j + 1) % 3]) * scale;
      const int c = corners[k][j];
      const int col = column[c];
      if (col < 0) {
        const Eigen::Vector2d& u = pinned[c == p0 ? 0 : 1];
        b_re -= w.x() * u.x() - w.y() * u.y();
        b_im -= w.y() * u.x() + w.x() * u.y();
        continue;
      }
      t.emplace_back(row, 2 * col, w.x());
      t.emplace_back(row, 2 * col + 1, -w.y());
      t.emplace_back(row + 1, 2 * col, w.y());
      t.emplace_back(row + 1, 2 * col + 1, w.x());
    }
    rhs.push_back(b_re);
    rhs.push_back(b_im);
    row += 2;
  }
  Eigen::SparseMatrix<double> A(row, 2 * free);
  A.setFromTriplets(t.begin(), t.end());
  const Eigen::Map<const Eigen::VectorXd> b(rhs.data(), row);
  const Eigen::SparseMatrix<double> AtA = A.transpose() * A;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(AtA);
  if (solver.info() != Eigen::Success)
    throw std::runtime_error("uv_layout: a chart's conformal map could not be solved");
  const Eigen::VectorXd x = solver.solve(A.transpose() * b);
  std::vector<Eigen::Vector2d> uv(n);
  for (int i = 0; i < n; ++i)
    uv[i] = column[i] < 0 ? pinned[i == p0 ? 0 : 1]
                          : Eigen::Vector2d(x[2 * column[i]], x[2 * column[i] + 1]);
  return uv;
}

}  // namespace

UvLayout uv_layout(const TriMesh& mesh, const SmplxRig& rig, const Eigen::MatrixXd& weights) {
  const int V = static_cast<int>(mesh.vertices.size());
  const int F = static_cast<int>(mesh.faces.size());
  const int J = rig.size();
  if (weights.rows() != V || weights.cols() != J)
    throw std::invalid_argument("uv_layout: weights do not match the mesh and rig");

  // Neighbouring faces across each edge.
  std::unordered_map<Edge, std::array<int, 2>> edge_faces;
  for (int f = 0; f < F; ++f)
    for (int c = 0; c < 3; ++c) {
      auto [it, fresh] = edge_faces.try_emplace(
          edge_key(mesh.faces[f][c], mesh.faces[f][(c + 1) % 3]), std::array<int, 2>{f, -1});
      if (!fresh) it->second[1] = f;
    }
  auto neighbours = [&](int f) {
    std::array<int, 3> out;
    for (int c = 0; c < 3; ++c) {
      const auto& e = edge_faces.at(edge_key(mesh.faces[f][c], mesh.faces[f][(c + 1) % 3]));
      out[c] = e[0] == f ? e[1] : e[0];
    }
    return out;
  };

  // 1. Each face's body part, then the splits into charts.
  std::vector<int> label(F);
  const Vec3 up(0, 1, 0);
  for (int f = 0; f < F; ++f) {
    Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(J);
    Vec3 centre = Vec3::Zero();
    for (int c = 0; c < 3; ++c) {
      sum += weights.row(mesh.faces[f][c]);
      centre += mesh.vertices[mesh.faces[f][c]] / 3.0;
    }
    Eigen::Index joint;
    sum.maxCoeff(&joint);
    const JointGroup g = group_of_joint(static_cast<int>(joint));
    const Vec3 n = face_normal(mesh, f).normalized();
    const int side = std::max(g.side, 0);
    int part = 0;
    switch (g.group) {
      case kGroupTorso:  // front and back, parted down the sides
        part = centre.z() > -0.012 ? 0 : 1;
        break;
      case kGroupHead:
        // The face (in front of the cheekbones, above the chin), the back of the head behind
        // the ears, and each side between them with its ear and the side of the neck: as one
        // chart the head's front half shrank the face to a fraction of its share of texture.
        if (centre.z() < -0.035)
          part = 3;
        else if (centre.z() > 0.035 && centre.y() > 1.47)
          part = 2;
        else
          part = centre.x() > 0 ? 18 : 19;
        break;
      case kGroupEye:
        part = 4 + side;
        break;
      case kGroupArm:
        part = 6 + side;
        break;
      case kGroupHand: {  // the back (+n, the knuckles' side) and the palm
        const Vec3 d = (rig.joints[18 + side] - rig.joints[16 + side]).normalized();
        const double sx = side == 0 ? 1.0 : -1.0;
        const Vec3 back = sx * Vec3(-d.y(), d.x(), 0.0);
        part = 8 + 2 * side + (n.dot(back) > 0 ? 0 : 1);
        break;
      }
      case kGroupLeg:
        part = 12 + side;
        break;
      case kGroupFoot:  // the top and the sole
        part = 14 + 2 * side + (n.dot(up) < -0.5 && centre.y() < 0.04 ? 1 : 0);
        break;
    }
    label[f] = part;
  }
  // Smooth the parts' borders: a face goes with two neighbours that agree on another part.
  for (int it = 0; it < 6; ++it) {
    std::vector<int> next = label;
    for (int f = 0; f < F; ++f) {
      const auto nb = neighbours(f);
      for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b)
          if (nb[a] >= 0 && nb[b] >= 0 && label[nb[a]] == label[nb[b]] && label[nb[a]] != label[f])
            next[f] = label[nb[a]];
    }
    label.swap(next);
  }
  // Connected pieces of each part are charts; pieces of fewer than 40 faces join the chart
  // they share most edges with.
  std::vector<int> chart(F, -1);
  int charts = 0;
  for (int round = 0; round < 4; ++round) {
    std::fill(chart.begin(), chart.end(), -1);
    charts = 0;
    std::vector<int> size;
    for (int f = 0; f < F; ++f) {
      if (chart[f] >= 0) continue;
      std::vector<int> stack = {f};
      chart[f] = charts;
      int count = 0;
      while (!stack.empty()) {
        const int g = stack.back();
        stack.pop_back();
        ++count;
        for (int h : neighbours(g))
          if (h >= 0 && chart[h] < 0 && label[h] == label[g]) {
            chart[h] = charts;
            stack.push_back(h);
          }
      }
      size.push_back(count);
      ++charts;
    }
    bool merged = false;
    for (int c = 0; c < charts; ++c) {
      if (size[c] >= 40) continue;
      std::unordered_map<int, int> shared;
      for (int f = 0; f < F; ++f)
        if (chart[f] == c)
          for (int h : neighbours(f))
            if (h >= 0 && chart[h] != c) ++shared[label[h]];
      int best = -1, most = 0;
      for (const auto& [l, k] : shared)
        if (k > most) most = k, best = l;
      if (best < 0) continue;
      for (int f = 0; f < F; ++f)
        if (chart[f] == c) label[f] = best;
      merged = true;
    }
    if (!merged) break;
  }

  // 2. Seams: the charts' borders, and a cut along the inner side of each arm and leg (they
  //    are tubes: open at both ends, they need one cut to unroll).
  const std::vector<Vec3> vertex_normal = vertex_normals(mesh);
  std::unordered_map<Edge, bool> cut;
  for (int c = 0; c < charts; ++c) {
    int any = -1;
    for (int f = 0; f < F && any < 0; ++f)
      if (chart[f] == c) any = f;
    const int part = label[any];
    const bool arm = part == 6 || part == 7, leg = part == 12 || part == 13;
    if (!arm && !leg) continue;
    const int side = arm ? part - 6 : part - 12;
    const double sx = side == 0 ? 1.0 : -1.0;
    const Vec3 axis = arm ? (rig.joints[18 + side] - rig.joints[16 + side]).normalized()
                          : (rig.joints[4 + side] - rig.joints[1 + side]).normalized();
    const Vec3 medial = (Vec3(-sx, 0, 0) - axis * axis.dot(Vec3(-sx, 0, 0))).normalized();
    // Boundary loops of the chart.
    std::unordered_map<int, std::vector<int>> boundary;  // vertex -> boundary neighbours
    std::unordered_map<int, std::vector<std::pair<int, double>>> graph;
    for (int f = 0; f < F; ++f) {
      if (chart[f] != c) continue;
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
        const auto& e = edge_faces.at(edge_key(a, b));
        const int other = e[0] == f ? e[1] : e[0];
        if (other < 0 || chart[other] != c) {
          boundary[a].push_back(b);
          boundary[b].push_back(a);
        } else if (a < b) {
          const double facing =
              std::max(0.0, 0.5 * (vertex_normal[a] + vertex_normal[b]).dot(medial));
          const double cost = (mesh.vertices[a] - mesh.vertices[b]).norm() *
                              (1.0 + 40.0 * (1.0 - facing) * (1.0 - facing));
          graph[a].push_back({b, cost});
          graph[b].push_back({a, cost});
        }
      }
    }
    std::unordered_map<int, int> loop;
    int loops = 0;
    for (const auto& [v, nb] : boundary) {
      if (loop.count(v)) continue;
      std::vector<int> stack = {v};
      loop[v] = loops;
      while (!stack.empty()) {
        const int u = stack.back();
        stack.pop_back();
        for (int w : boundary[u])
          if (!loop.count(w)) loop[w] = loops, stack.push_back(w);
      }
      ++loops;
    }
    if (loops < 2) continue;
    // The two largest loops are the tube's ends.
    std::vector<int> loop_size(loops, 0);
    for (const auto& [v, l] : loop) ++loop_size[l];
    std::vector<int> order(loops);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return loop_size[a] > loop_size[b]; });
    // Dijkstra from one end to the other through the chart's inside, cheapest on the inner side.
    std::unordered_map<int, double> dist;
    std::unordered_map<int, int> prev;
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (const auto& [v, l] : loop)
      if (l == order[0]) {
        const double facing = std::max(0.0, vertex_normal[v].dot(medial));
        dist[v] = 0.05 * (1.0 - facing);  // start where the end loop faces inwards
        queue.push({dist[v], v});
      }
    int reached = -1;
    while (!queue.empty()) {
      const auto [d, u] = queue.top();
      queue.pop();
      if (d > dist[u]) continue;
      if (loop.count(u) && loop[u] == order[1]) {
        reached = u;
        break;
      }
      for (const auto& [w, cost] : graph[u])
        if (!dist.count(w) || d + cost < dist[w]) {
          dist[w] = d + cost;
          prev[w] = u;
          queue.push({dist[w], w});
        }
    }
    for (int u = reached; u >= 0 && prev.count(u); u = prev[u]) cut[edge_key(u, prev[u])] = true;
  }

  // 3. Texture vertices: the corners round each vertex that are joined by edges inside one
  //    chart and not on a cut share one.
  UnionFind corners(3 * F);
  for (const auto& [key, e] : edge_faces) {
    if (e[1] < 0 || chart[e[0]] != chart[e[1]] || cut.count(key)) continue;
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    for (int v : {a, b}) {
      int ca = -1, cb = -1;
      for (int k = 0; k < 3; ++k) {
        if (mesh.faces[e[0]][k] == v) ca = 3 * e[0] + k;
        if (mesh.faces[e[1]][k] == v) cb = 3 * e[1] + k;
      }
      corners.unite(ca, cb);
    }
  }
  UvLayout out;
  out.charts = charts;
  out.chart_of_face = chart;
  out.faces.assign(F, {0, 0, 0});
  std::unordered_map<int, int> texture_vertex;  // corner root -> uv id
  std::vector<int> texture_source;              // uv id -> mesh vertex
  for (int f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k) {
      const int root = corners.find(3 * f + k);
      auto [it, fresh] = texture_vertex.try_emplace(root, static_cast<int>(texture_source.size()));
      if (fresh) texture_source.push_back(mesh.faces[f][k]);
      out.faces[f][k] = it->second;
    }
  const int T = static_cast<int>(texture_source.size());
  out.uv.assign(T, Eigen::Vector2d::Zero());

  // 4. Flatten each chart and scale it to its area.
  std::vector<std::vector<int>> chart_faces(charts);
  for (int f = 0; f < F; ++f) chart_faces[chart[f]].push_back(f);
  std::vector<int> local(T, -1);
  std::vector<PackChart> flat(charts);
  std::vector<std::vector<int>> chart_ids(charts);
  for (int c = 0; c < charts; ++c) {
    std::vector<int>& ids = chart_ids[c];
    std::vector<std::array<int, 3>>& lc = flat[c].triangles;
    for (int f : chart_faces[c]) {
      std::array<int, 3> a;
      for (int k = 0; k < 3; ++k) {
        const int t = out.faces[f][k];
        if (local[t] < 0) {
          local[t] = static_cast<int>(ids.size());
          ids.push_back(t);
        }
        a[k] = local[t];
      }
      lc.push_back(a);
    }
    std::vector<Vec3> position;
    for (int t : ids) position.push_back(mesh.vertices[texture_source[t]]);
    std::vector<Eigen::Vector2d> uv =
        lscm(mesh, chart_faces[c], lc, static_cast<int>(ids.size()), position);
    double area3 = 0, area2 = 0;
    for (std::size_t k = 0; k < lc.size(); ++k) {
      area3 += 0.5 * face_normal(mesh, chart_faces[c][k]).norm();
      const Eigen::Vector2d a = uv[lc[k][1]] - uv[lc[k][0]], b = uv[lc[k][2]] - uv[lc[k][0]];
      area2 += 0.5 * (a.x() * b.y() - a.y() * b.x());
    }
    const double s = area2 > 0 ? std::sqrt(area3 / area2) : 1.0;
    for (auto& p : uv) p *= s;
    flat[c].points = std::move(uv);
    for (int t : ids) local[t] = -1;
  }

  // 5. Pack the charts into [0, 1]^2 (uv_packing.hpp).
  // 384 cells across the charts' area: about 460 across the square, so the two-cell gutter
  // between charts is 4 texels of a 1024 texture (mipmaps of a baked texture do not bleed).
  const ChartPacking packing = pack_charts(flat, 384);
  for (int c = 0; c < charts; ++c)
    for (std::size_t i = 0; i < chart_ids[c].size(); ++i)
      out.uv[chart_ids[c][i]] =
          packing.scale * (packing.rotation[c] * flat[c].points[i] + packing.offset[c]);
  return out;
}

UvDistortion uv_distortion(const TriMesh& mesh, const UvLayout& layout) {
  UvDistortion d;
  d.charts = layout.charts;
  const int F = static_cast<int>(mesh.faces.size());
  double total3 = 0, total2 = 0;
  std::vector<double> a3(F), a2(F);
  for (int f = 0; f < F; ++f) {
    const auto& t = mesh.faces[f];
    a3[f] = 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                      .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]])
                      .norm();
    const Eigen::Vector2d p = layout.uv[layout.faces[f][1]] - layout.uv[layout.faces[f][0]];
    const Eigen::Vector2d q = layout.uv[layout.faces[f][2]] - layout.uv[layout.faces[f][0]];
    a2[f] = 0.5 * (p.x() * q.y() - p.y() * q.x());
    if (a2[f] <= 0) ++d.flipped_faces;
    total3 += a3[f];
    total2 += std::abs(a2[f]);
  }
  d.packing = total2;
  std::vector<std::pair<double, double>> area_err, angle_err;  // value, weight
  for (int f = 0; f < F; ++f) {
    const double r = (std::abs(a2[f]) / total2) / std::max(a3[f] / total3, 1e-30);
    area_err.push_back({std::abs(std::log2(std::max(r, 1e-12))), a3[f]});
    for (int k = 0; k < 3; ++k) {
      const auto& t = mesh.faces[f];
      const Vec3 e1 = mesh.vertices[t[(k + 1) % 3]] - mesh.vertices[t[k]];
      const Vec3 e2 = mesh.vertices[t[(k + 2) % 3]] - mesh.vertices[t[k]];
      const Eigen::Vector2d u1 =
          layout.uv[layout.faces[f][(k + 1) % 3]] - layout.uv[layout.faces[f][k]];
      const Eigen::Vector2d u2 =
          layout.uv[layout.faces[f][(k + 2) % 3]] - layout.uv[layout.faces[f][k]];
      const double g3 = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      const double g2 = std::atan2(std::abs(u1.x() * u2.y() - u1.y() * u2.x()), u1.dot(u2));
      angle_err.push_back({std::abs(g3 - g2) * 180.0 / M_PI, a3[f]});
    }
  }
  auto stats = [](std::vector<std::pair<double, double>> v, double* mean, double* p95) {
    double sw = 0, s = 0;
    for (const auto& [x, w] : v) s += x * w, sw += w;
    *mean = s / sw;
    std::sort(v.begin(), v.end());
    double acc = 0;
    for (const auto& [x, w] : v) {
      acc += w;
      if (acc >= 0.95 * sw) {
        *p95 = x;
        break;
      }
    }
  };
  stats(area_err, &d.area_log2_mean, &d.area_log2_p95);
  stats(angle_err, &d.angle_mean_deg, &d.angle_p95_deg);
  // Disks have Euler characteristic 1 (in texture space: vertices - edges + faces).
  std::vector<std::vector<int>> faces_of(layout.charts);
  for (int f = 0; f < F; ++f) faces_of[layout.chart_of_face[f]].push_back(f);
  for (const auto& fs : faces_of) {
    std::unordered_map<Edge, int> edges;
    std::unordered_map<int, int> verts;
    for (int f : fs)
      for (int k = 0; k < 3; ++k) {
        verts[layout.faces[f][k]] = 1;
        edges[edge_key(layout.faces[f][k], layout.faces[f][(k + 1) % 3])] = 1;
      }
    if (static_cast<long>(verts.size()) - static_cast<long>(edges.size()) +
            static_cast<long>(fs.size()) !=
        1)
      ++d.non_disk_charts;
  }
  return d;
}

std::string UvDistortion::describe() const {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%d charts (%d not disks), %d flipped faces; area distortion |log2| mean %.3f, "
                "p95 %.3f; angle distortion mean %.2f deg, p95 %.2f deg; %.0f%% of the square used",
                charts, non_disk_charts, flipped_faces, area_log2_mean, area_log2_p95,
                angle_mean_deg, angle_p95_deg, 100.0 * packing);
  return buf;
}

}  // namespace default_model
