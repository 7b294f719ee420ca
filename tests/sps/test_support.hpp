// Helpers shared by the sps tests: finite differences and small random data sets.
#pragma once

#include <functional>
#include <random>

#include <Eigen/Core>

#include "sps/preference_data.hpp"

namespace sps_test {

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
