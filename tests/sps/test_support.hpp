// Helpers shared by the sps tests: finite differences and small random data sets.
#pragma once

#include <functional>
#include <random>

#include <Eigen/Core>

#include "sps/preference_data.hpp"

namespace sps_test {

// A perceptual metric M = A^T A (mm^2 per unit^2) in which coordinates 0 and 1 move much of
// the same (as the built-in body models' turned components 1 and 2 do) and coordinate 2 moves
// on its own.
inline Eigen::Matrix3d overlapping_metric() {
  Eigen::Matrix3d a;
  a << 90.0, 70.0, 0.0,  //
      20.0, 45.0, 0.0,   //
      0.0, 0.0, 40.0;
  return a.transpose() * a;
}

// Central finite-difference gradient of f at x.
inline Eigen::VectorXd numeric_gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                                        const Eigen::VectorXd& x, double h = 1e-6) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd a = x;
    Eigen::VectorXd b = x;
    a(i) += h;
    b(i) -= h;
    g(i) = (f(a) - f(b)) / (2.0 * h);
  }
  return g;
}

inline Eigen::VectorXd random_point(int d, std::mt19937_64& rng, double lo = 0.05,
                                    double hi = 0.95) {
  std::uniform_real_distribution<double> u(lo, hi);
  Eigen::VectorXd x(d);
  for (int k = 0; k < d; ++k) x(k) = u(rng);
  return x;
}

// A few "chosen > others" preferences among random points.
inline sps::PreferenceData random_data(int d, int preferences, std::mt19937_64& rng) {
  sps::PreferenceData data(d);
  for (int p = 0; p < preferences; ++p) {
    std::vector<Eigen::VectorXd> others;
    for (int o = 0; o < 3; ++o) others.push_back(random_point(d, rng));
    data.add_preference(random_point(d, rng), others);
  }
  return data;
}

}  // namespace sps_test
