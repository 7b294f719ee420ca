#include "uv_packing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

#include <Eigen/Geometry>

namespace default_model {

namespace {

using Vec2 = Eigen::Vector2d;

Eigen::Matrix2d turn(double radians) {
  return Eigen::Rotation2Dd(radians).toRotationMatrix();
}

// The turn in [0, 90) degrees, in 3-degree steps, that gives the points the smallest bounding
// box (quarter turns are tried when placing).
double smallest_box_angle(const std::vector<Vec2>& points) {
  double best = 0, best_area = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 30; ++step) {
    const double a = step * M_PI / 60.0;
    const Eigen::Matrix2d R = turn(a);
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec2& p : points) {
      const Vec2 q = R * p;
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const double area = (hi - lo).prod();
    if (area < best_area) best_area = area, best = a;
  }
  return best;
}

double cross(const Vec2& u, const Vec2& v) {
  return u.x() * v.y() - u.y() * v.x();
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double distance_to_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
  const bool negative = d1 < 0 || d2 < 0 || d3<0, positive = d1> 0 || d2 > 0 || d3 > 0;
  if (!(negative && positive)) return 0.0;
  return std::min(
      {distance_to_segment(p, a, b), distance_to_segment(p, b, c), distance_to_segment(p, c, a)});
}

// A chart's cells in one orientation: every cell a triangle touches, dilated by one cell, as
// runs [x0, x1) per row.
struct Mask {
  Eigen::Matrix2d rotation;
  Vec2 origin;  // the turned chart's coordinates at the corner of cell (0, 0)
  int width = 0, height = 0;
  long cells = 0;
  std::vector<std::vector<std::pair<int, int>>> runs;
};

Mask rasterise(const PackChart& chart, const Eigen::Matrix2d& rotation, double h) {
  std::vector<Vec2> q(chart.points.size());
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < q.size(); ++i) {
    q[i] = rotation * chart.points[i];
    lo = lo.cwiseMin(q[i]);
    hi = hi.cwiseMax(q[i]);
  }
  constexpr int pad = 2;  // a cell for the cover's reach, a cell for the dilation
  Mask m;
  m.rotation = rotation;
  m.origin = lo - Vec2::Constant(pad * h);
  m.width = static_cast<int>(std::ceil((hi.x() - lo.x()) / h)) + 2 * pad + 1;
  m.height = static_cast<int>(std::ceil((hi.y() - lo.y()) / h)) + 2 * pad + 1;
  std::vector<char> touched(static_cast<std::size_t>(m.width) * m.height, 0);
  // Half a cell's diagonal: a cell whose centre is that close to a triangle may overlap it.
  const double reach = 0.7072 * h;
  for (const auto& t : chart.triangles) {
    const Vec2 &a = q[t[0]], &b = q[t[1]], &c = q[t[2]];
    const Vec2 tlo = a.cwiseMin(b).cwiseMin(c), thi = a.cwiseMax(b).cwiseMax(c);
    const int x0 = std::max(0, static_cast<int>(std::floor((tlo.x() - m.origin.x()) / h)) - 1);
    const int y0 = std::max(0, static_cast<int>(std::floor((tlo.y() - m.origin.y()) / h)) - 1);
    const int x1 = std::min(m.width - 1, static_cast<int>((thi.x() - m.origin.x()) / h) + 1);
    const int y1 = std::min(m.height - 1, static_cast<int>((thi.y() - m.origin.y()) / h) + 1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        char& cell = touched[static_cast<std::size_t>(y) * m.width + x];
        if (cell) continue;
        const Vec2 centre = m.origin + Vec2(x + 0.5, y + 0.5) * h;
        if (distance_to_triangle(centre, a, b, c) <= reach) cell = 1;
      }
  }
  m.runs.resize(m.height);
  for (int y = 0; y < m.height; ++y) {
    int start = -1;
    for (int x = 0; x <= m.width; ++x) {
      bool on = false;
      for (int dy = -1; dy <= 1 && !on && x < m.width; ++dy)
        for (int dx = -1; dx <= 1 && !on; ++dx) {
          const int xx = x + dx, yy = y + dy;
          on = xx >= 0 && yy >= 0 && xx < m.width && yy < m.height &&
               touched[static_cast<std::size_t>(yy) * m.width + xx];
        }
      if (on && start < 0) start = x;
      if (!on && start >= 0) {
        m.runs[y].emplace_back(start, x);
        m.cells += x - start;
        start = -1;
      }
    }
  }
  return m;
}

// The square being filled: occupied cells, with a prefix count per row so that a run is
// tested in constant time.
class Raster {
 public:
  explicit Raster(int side)
      : side_(side),
        occupied_(side, std::vector<char>(side, 0)),
        prefix_(side, std::vector<int>(side + 1, 0)) {}

  bool fits(const Mask& m, int X, int Y) const {
    if (X + m.width > side_ || Y + m.height > side_) return false;
    for (int r = 0; r < m.height; ++r) {
      const std::vector<int>& row = prefix_[Y + r];
      for (const auto& [x0, x1] : m.runs[r])
        if (row[X + x1] != row[X + x0]) return false;
    }
    return true;
  }

  // The lowest, then leftmost, place the mask fits; false if none.
  bool first_fit(const Mask& m, int* X, int* Y) const {
    for (int y = 0; y + m.height <= side_; ++y)
      for (int x = 0; x + m.width <= side_; ++x)
        if (fits(m, x, y)) {
          *X = x;
          *Y = y;
          return true;
        }
    return false;
  }

  void place(const Mask& m, int X, int Y) {
    for (int r = 0; r < m.height; ++r) {
      std::vector<char>& row = occupied_[Y + r];
      for (const auto& [x0, x1] : m.runs[r])
        std::fill(row.begin() + X + x0, row.begin() + X + x1, 1);
      std::vector<int>& p = prefix_[Y + r];
      for (int x = 0; x < side_; ++x) p[x + 1] = p[x] + row[x];
    }
  }

 private:
  int side_;
  std::vector<std::vector<char>> occupied_;
  std::vector<std::vector<int>> prefix_;
};

}  // namespace

ChartPacking pack_charts(const std::vector<PackChart>& charts, int resolution) {
  const int C = static_cast<int>(charts.size());
  ChartPacking out;
  out.rotation.assign(C, Eigen::Matrix2d::Identity());
  out.offset.assign(C, Vec2::Zero());
  if (C == 0) return out;
  double area = 0;
  for (const PackChart& c : charts)
    for (const auto& t : c.triangles)
      area +=
          0.5 * std::abs(cross(c.points[t[1]] - c.points[t[0]], c.points[t[2]] - c.points[t[0]]));
  if (!(area > 0) || resolution < 8)
    throw std::invalid_argument("pack_charts: the charts have no area to pack");
  const double h = std::sqrt(area) / resolution;

  // Each chart in its four quarter turns of the smallest-box orientation.
  std::vector<std::array<Mask, 4>> masks(C);
  long total_cells = 0;
  int least_side = 0;
  for (int c = 0; c < C; ++c) {
    const double a = smallest_box_angle(charts[c].points);
    int side = std::numeric_limits<int>::max();
    for (int r = 0; r < 4; ++r) {
      masks[c][r] = rasterise(charts[c], turn(a + r * M_PI / 2), h);
      side = std::min(side, std::max(masks[c][r].width, masks[c][r].height));
    }
    least_side = std::max(least_side, side);
    total_cells += masks[c][0].cells;
  }
  // Largest first: the small charts then fill what is left round them.
  std::vector<int> order(C);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return masks[a][0].cells > masks[b][0].cells; });

  int side = std::max(least_side, static_cast<int>(std::ceil(std::sqrt(double(total_cells)))));
  for (;; side += std::max(1, side / 100)) {
    Raster raster(side);
    std::vector<std::pair<int, Vec2>> placed(C);  // quarter turn, cell
    bool all = true;
    for (int c : order) {
      int best_r = -1, best_x = 0, best_y = 0;
      for (int r = 0; r < 4; ++r) {
        int x = 0, y = 0;
        if (!raster.first_fit(masks[c][r], &x, &y)) continue;
        const int top = y + masks[c][r].height,
                  best_top = best_y + masks[c][best_r < 0 ? 0 : best_r].height;
        if (best_r < 0 || top < best_top || (top == best_top && x < best_x))
          best_r = r, best_x = x, best_y = y;
      }
      if (best_r < 0) {
        all = false;
        break;
      }
      raster.place(masks[c][best_r], best_x, best_y);
      placed[c] = {best_r, Vec2(best_x, best_y)};
    }
    if (!all) continue;
    out.cells = side;
    out.scale = 1.0 / (side * h);
    for (int c = 0; c < C; ++c) {
      const Mask& m = masks[c][placed[c].first];
      out.rotation[c] = m.rotation;
      out.offset[c] = placed[c].second * h - m.origin;
    }
    return out;
  }
}

}  // namespace default_model
