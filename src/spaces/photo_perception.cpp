#include "spaces/photo_perception.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "spaces/photo_enhancement.hpp"

namespace spaces {

namespace {

constexpr double kPi = 3.14159265358979323846;

double degrees(double radians) {
  return radians * 180.0 / kPi;
}
double radians(double degrees) {
  return degrees * kPi / 180.0;
}

double srgb_to_linear(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double lab_f(double t) {
  constexpr double delta = 6.0 / 29.0;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0;
}

// Hue angle in degrees in [0, 360); 0 for a neutral colour (as Sharma et al. define it).
double hue_degrees(double b, double a) {
  if (a == 0.0 && b == 0.0) return 0.0;
  const double h = degrees(std::atan2(b, a));
  return h < 0.0 ? h + 360.0 : h;
}

double pow7(double v) {
  const double v2 = v * v;
  return v2 * v2 * v2 * v;
}

}  // namespace

app::ZoomPolicy photo_zoom_policy(double distinct) {
  app::ZoomPolicy policy;
  policy.distinct_mm = distinct;
  policy.look_alike_mm = distinct;
  policy.compare_mm = 2.0 * distinct;
  return policy;
}

sps::Population photo_population() {
  sps::Population population{Eigen::VectorXd::Constant(kPhotoParameters, 0.5),
                             Eigen::VectorXd::Constant(kPhotoParameters, 0.2), Eigen::MatrixXd()};
  // Each colour-balance parameter (tone band b: shadows, midtones, highlights; axis a:
  // cyan-red, magenta-green, yellow-blue) as the sum of shared factors and its own part, each
  // of unit variance: a global white-balance temperature T (red with yellow: +cyan-red and
  // -yellow-blue), a shift of the axis in every band A_a, and the band's own U_ba:
  //   x_ba = l_T s_a T + l_A A_a + l_U U_ba,   s = (+1, 0, -1),   l_T^2 + l_A^2 + l_U^2 = 1.
  // So the bands of one axis correlate by l_T^2 s_a^2 + l_A^2 and red with yellow by -l_T^2.
  // The weights are modelling choices, not measurements; brightness, contrast and saturation
  // stay independent.
  Eigen::MatrixXd loadings = Eigen::MatrixXd::Zero(kPhotoParameters, 4);  // T, A_cr, A_mg, A_yb
  Eigen::VectorXd own = Eigen::VectorXd::Ones(kPhotoParameters);
  constexpr double kTemperature2 = 0.5, kAxis2 = 0.15, kTint2 = 0.5;
  for (int band = 0; band < 3; ++band) {
    for (int axis = 0; axis < 3; ++axis) {
      const int i = 3 + 3 * band + axis;
      const double sign = axis == 0 ? 1.0 : (axis == 2 ? -1.0 : 0.0);
      const double axis2 = axis == 1 ? kTint2 : kAxis2;
      loadings(i, 0) = sign * std::sqrt(kTemperature2);
      loadings(i, 1 + axis) = std::sqrt(axis2);
      own(i) = 1.0 - axis2 - sign * sign * kTemperature2;
    }
  }
  population.correlation = loadings * loadings.transpose();
  population.correlation.diagonal() += own;
  return population;
}

Lab srgb_to_lab(const std::array<float, 3>& rgb) {
  const double r = srgb_to_linear(rgb[0]);
  const double g = srgb_to_linear(rgb[1]);
  const double b = srgb_to_linear(rgb[2]);
  // IEC 61966-2-1 primaries to XYZ, relative to the D65 white (Xn, Yn, Zn).
  const double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
  const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
  const double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
  const double fx = lab_f(x);
  const double fy = lab_f(y);
  const double fz = lab_f(z);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double ciede2000(const Lab& x, const Lab& y) {
  const double c1 = std::hypot(x.a, x.b);
  const double c2 = std::hypot(y.a, y.b);
  const double c_mean7 = pow7(0.5 * (c1 + c2));
  const double g = 0.5 * (1.0 - std::sqrt(c_mean7 / (c_mean7 + pow7(25.0))));
  const double a1 = (1.0 + g) * x.a;
  const double a2 = (1.0 + g) * y.a;
  const double c1p = std::hypot(a1, x.b);
  const double c2p = std::hypot(a2, y.b);
  const double h1p = hue_degrees(x.b, a1);
  const double h2p = hue_degrees(y.b, a2);

  const double dl = y.l - x.l;
  const double dc = c2p - c1p;
  double dh = 0.0;
  if (c1p * c2p != 0.0) {
    dh = h2p - h1p;
    if (dh > 180.0) dh -= 360.0;
    if (dh < -180.0) dh += 360.0;
  }
  const double dhh = 2.0 * std::sqrt(c1p * c2p) * std::sin(radians(0.5 * dh));

  const double l_mean = 0.5 * (x.l + y.l);
  const double c_mean = 0.5 * (c1p + c2p);
  double h_mean = h1p + h2p;
  if (c1p * c2p != 0.0) {
    if (std::abs(h1p - h2p) <= 180.0) {
      h_mean *= 0.5;
    } else {
      h_mean = h_mean < 360.0 ? 0.5 * (h_mean + 360.0) : 0.5 * (h_mean - 360.0);
    }
  }
  const double t =
      1.0 - 0.17 * std::cos(radians(h_mean - 30.0)) + 0.24 * std::cos(radians(2.0 * h_mean)) +
      0.32 * std::cos(radians(3.0 * h_mean + 6.0)) - 0.20 * std::cos(radians(4.0 * h_mean - 63.0));
  const double d_theta = 30.0 * std::exp(-std::pow((h_mean - 275.0) / 25.0, 2.0));
  const double c_mean_p7 = pow7(c_mean);
  const double rc = 2.0 * std::sqrt(c_mean_p7 / (c_mean_p7 + pow7(25.0)));
  const double l50 = (l_mean - 50.0) * (l_mean - 50.0);
  const double sl = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double sc = 1.0 + 0.045 * c_mean;
  const double sh = 1.0 + 0.015 * c_mean * t;
  const double rt = -std::sin(radians(2.0 * d_theta)) * rc;
  const double tl = dl / sl;
  const double tc = dc / sc;
  const double th = dhh / sh;
  return std::sqrt(std::max(0.0, tl * tl + tc * tc + th * th + rt * tc * th));
}

PhotoDistance::PhotoDistance(const Image& image, int max_edge) {
  if (max_edge < 1) throw std::invalid_argument("PhotoDistance: max_edge must be >= 1");
  if (image.width < 1 || image.height < 1 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
    throw std::invalid_argument("PhotoDistance: the pixels do not match the image size");
  }
  // Box-average blocks of block x block pixels (the last row and column of blocks may be
  // partial): the small copy keeps the picture's colours in their proportions.
  const int block = std::max(1, (std::max(image.width, image.height) + max_edge - 1) / max_edge);
  const int w = (image.width + block - 1) / block;
  const int h = (image.height + block - 1) / block;
  rgb_.reserve(static_cast<std::size_t>(w) * h);
  for (int by = 0; by < h; ++by) {
    for (int bx = 0; bx < w; ++bx) {
      std::array<double, 3> sum{};
      int count = 0;
      for (int y = by * block; y < std::min(image.height, (by + 1) * block); ++y) {
        for (int x = bx * block; x < std::min(image.width, (bx + 1) * block); ++x) {
          const std::size_t i = (static_cast<std::size_t>(y) * image.width + x) * 4;
          for (int k = 0; k < 3; ++k) sum[static_cast<std::size_t>(k)] += image.rgba[i + k];
          ++count;
        }
      }
      rgb_.push_back({static_cast<float>(sum[0] / (255.0 * count)),
                      static_cast<float>(sum[1] / (255.0 * count)),
                      static_cast<float>(sum[2] / (255.0 * count))});
    }
  }
}

std::vector<Lab> PhotoDistance::lab_of(const Eigen::VectorXd& x) const {
  const std::array<float, 12> p = photo_parameters(x);
  std::vector<Lab> out;
  out.reserve(rgb_.size());
  for (const auto& c : rgb_) out.push_back(srgb_to_lab(enhance_pixel(c, p)));
  return out;
}

double PhotoDistance::mean_difference(const std::vector<Lab>& p, const std::vector<Lab>& q) {
  if (p.size() != q.size() || p.empty()) {
    throw std::invalid_argument("PhotoDistance: pictures of " + std::to_string(p.size()) + " and " +
                                std::to_string(q.size()) + " pixels");
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += ciede2000(p[i], q[i]);
  return sum / static_cast<double>(p.size());
}

double PhotoDistance::visible_difference(const std::vector<Lab>& p, const std::vector<Lab>& q) {
  if (p.size() != q.size() || p.empty()) {
    throw std::invalid_argument("PhotoDistance: pictures of " + std::to_string(p.size()) + " and " +
                                std::to_string(q.size()) + " pixels");
  }
  std::vector<double> d(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) d[i] = ciede2000(p[i], q[i]);
  const auto count = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::ceil(kVisibleShare * static_cast<double>(d.size()))));
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(count - 1), d.end(),
                   std::greater<double>());
  double sum = 0.0;
  for (std::size_t i = 0; i < count; ++i) sum += d[i];
  return sum / static_cast<double>(count);
}

Eigen::MatrixXd PhotoDistance::pairwise(const std::vector<Eigen::VectorXd>& xs) const {
  std::vector<std::vector<Lab>> labs;
  labs.reserve(xs.size());
  for (const auto& x : xs) labs.push_back(lab_of(x));
  const auto n = static_cast<Eigen::Index>(xs.size());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = i + 1; j < n; ++j) {
      d(i, j) = d(j, i) =
          visible_difference(labs[static_cast<std::size_t>(i)], labs[static_cast<std::size_t>(j)]);
    }
  }
  return d;
}

std::vector<double> PhotoDistance::to_target(const std::vector<Eigen::VectorXd>& xs,
                                             const Eigen::VectorXd& target) const {
  const std::vector<Lab> goal = lab_of(target);
  std::vector<double> out;
  out.reserve(xs.size());
  for (const auto& x : xs) out.push_back(mean_difference(lab_of(x), goal));
  return out;
}

Eigen::VectorXd PhotoDistance::direction_scale() const {
  Eigen::VectorXd scale(kPhotoParameters);
  for (int i = 0; i < kPhotoParameters; ++i) {
    Eigen::VectorXd low = Eigen::VectorXd::Constant(kPhotoParameters, 0.5);
    Eigen::VectorXd high = low;
    low[i] = 0.0;
    high[i] = 1.0;
    scale[i] = visible_difference(lab_of(low), lab_of(high));
  }
  return scale;
}

}  // namespace spaces
