#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include "sps/btl_likelihood.hpp"
#include "sps/matern_kernel.hpp"
#include "sps/preference_model.hpp"
#include "test_support.hpp"

using sps_test::numeric_gradient;
using sps_test::random_point;

namespace {

sps::KernelParams params_for(int d, std::mt19937_64& rng) {
  sps::KernelParams p;
  p.amplitude = 0.3;
  p.length_scales = random_point(d, rng, 0.3, 0.9);
  return p;
}

}  // namespace

TEST_CASE("Matern 5/2 kernel has the textbook values", "[kernel]") {
  sps::KernelParams p;
  p.amplitude = 0.5;
  p.length_scales = Eigen::Vector2d(1.0, 2.0);
  const sps::MaternKernel k(p);
  const Eigen::Vector2d x(0.1, 0.2);
  CHECK(k(x, x) == Approx(0.25));
  // r = sqrt(0.3^2 / 1 + 0.4^2 / 4) = sqrt(0.13)
  const double r = std::sqrt(0.13);
  const double expected =
      0.25 * (1 + std::sqrt(5.0) * r + 5.0 / 3.0 * r * r) * std::exp(-std::sqrt(5.0) * r);
  CHECK(k(x, Eigen::Vector2d(0.4, 0.6)) == Approx(expected).epsilon(1e-12));
}

TEST_CASE("batched kernel values and x-gradients match the definition and finite differences",
          "[kernel][gradient]") {
  std::mt19937_64 rng(7);
  for (int d : {1, 3, 12}) {
    const sps::MaternKernel k(params_for(d, rng));
    Eigen::MatrixXd pts(d, 3);
    for (int i = 0; i < 3; ++i) pts.col(i) = random_point(d, rng);
    Eigen::MatrixXd xs(d, 2);
    xs.col(0) = random_point(d, rng);
    xs.col(1) = pts.col(1);  // r = 0: the gradient factor must stay finite
    Eigen::MatrixXd kv;
    Eigen::MatrixXd q;
    k.cross_batch(pts, xs, kv, q);
    REQUIRE(q.allFinite());
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 3; ++i) {
        const Eigen::VectorXd x = xs.col(j);
        const Eigen::VectorXd y = pts.col(i);
        CHECK(kv(i, j) == Approx(k(x, y)).epsilon(1e-10).margin(1e-14));
        const Eigen::VectorXd analytic =
            q(i, j) * ((x - y).array() * k.inverse_squared_lengths().array()).matrix();
        const Eigen::VectorXd numeric =
            numeric_gradient([&](const Eigen::VectorXd& z) { return k(z, y); }, x);
        CHECK((analytic - numeric).norm() < 1e-7);
      }
    }
  }
}

TEST_CASE("hyperparameter gradient contraction matches finite differences of the Gram matrix",
          "[kernel][gradient]") {
  std::mt19937_64 rng(11);
  const int d = 4;
  const int n = 6;
  Eigen::MatrixXd pts(d, n);
  for (int i = 0; i < n; ++i) pts.col(i) = random_point(d, rng);
  Eigen::MatrixXd m = Eigen::MatrixXd::Random(n, n);
  m = (m + m.transpose()).eval();
  const Eigen::VectorXd theta = params_for(d, rng).to_log();
  const auto contracted = [&](const Eigen::VectorXd& t) {
    return (sps::MaternKernel(sps::KernelParams::from_log(t)).gram(pts).array() * m.array()).sum();
  };
  const Eigen::VectorXd analytic =
      sps::MaternKernel(sps::KernelParams::from_log(theta)).contract_log_gradients(pts, m);
  CHECK((analytic - numeric_gradient(contracted, theta)).norm() < 1e-6 * (1.0 + analytic.norm()));
}

TEST_CASE("BTL likelihood gradient and Hessian match finite differences",
          "[likelihood][gradient]") {
  std::mt19937_64 rng(3);
  const sps::PreferenceData data = sps_test::random_data(3, 5, rng);
  const Eigen::VectorXd f = 0.05 * Eigen::VectorXd::Random(data.point_count());
  const double scale = 0.05;
  Eigen::VectorXd grad;
  Eigen::MatrixXd neg_hess;
  const double value = sps::btl_log_likelihood(data.preferences(), f, scale, &grad, &neg_hess);
  CHECK(value < 0.0);  // a log-probability
  const auto fn = [&](const Eigen::VectorXd& z) {
    return sps::btl_log_likelihood(data.preferences(), z, scale);
  };
  CHECK((grad - numeric_gradient(fn, f, 1e-7)).norm() < 1e-5 * (1.0 + grad.norm()));
  for (Eigen::Index i = 0; i < f.size(); ++i) {
    const auto gi = [&](const Eigen::VectorXd& z) {
      Eigen::VectorXd g;
      sps::btl_log_likelihood(data.preferences(), z, scale, &g);
      return g(i);
    };
    const Eigen::VectorXd row = numeric_gradient(gi, f, 1e-7);
    CHECK((-neg_hess.row(i).transpose() - row).norm() < 1e-3 * (1.0 + row.norm()));
  }
  // Negated Hessian is positive semi-definite (log-concave likelihood).
  const Eigen::VectorXd eig =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(neg_hess).eigenvalues();
  CHECK(eig.minCoeff() > -1e-9);
}

TEST_CASE("MAP profile objective: gradient w.r.t. log hyperparameters matches finite differences",
          "[likelihood][gradient]") {
  std::mt19937_64 rng(5);
  const int d = 3;
  const sps::PreferenceData data = sps_test::random_data(d, 6, rng);
  const sps::ModelSettings settings;
  const sps::MapObjective objective(data, settings);
  const Eigen::VectorXd theta = settings.prior_log_mean(d) + 0.05 * Eigen::VectorXd::Random(d + 1);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(data.point_count());
  Eigen::VectorXd grad;
  objective.evaluate(theta, f, grad);
  const auto profile = [&](const Eigen::VectorXd& t) {
    Eigen::VectorXd latent = f;
    Eigen::VectorXd g;
    return objective.evaluate(t, latent, g);
  };
  const Eigen::VectorXd numeric = numeric_gradient(profile, theta, 1e-5);
  CHECK((grad - numeric).norm() < 1e-4 * (1.0 + grad.norm()));
  // The inner solution is a maximum of the joint objective in f.
  const double at_optimum = objective.joint(theta, f);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd nudged = f + 1e-3 * Eigen::VectorXd::Random(f.size());
    CHECK(objective.joint(theta, nudged) < at_optimum);
  }
}

TEST_CASE("posterior mean and variance gradients match finite differences", "[model][gradient]") {
  std::mt19937_64 rng(9);
  const int d = 4;
  const sps::PreferenceData data = sps_test::random_data(d, 5, rng);
  const sps::ModelSettings settings;
  const sps::PreferenceModel model =
      sps::PreferenceModel::fit(data, settings, sps::PreferenceModel(d, settings));
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd x = random_point(d, rng);
    double mean = 0.0;
    double var = 0.0;
    Eigen::VectorXd dm;
    Eigen::VectorXd dv;
    model.predict(x, mean, var, &dm, &dv);
    CHECK(mean == Approx(model.mean(x)));
    CHECK(var == Approx(model.variance(x)));
    const auto fm = [&](const Eigen::VectorXd& z) { return model.mean(z); };
    const auto fv = [&](const Eigen::VectorXd& z) { return model.variance(z); };
    CHECK((dm - numeric_gradient(fm, x)).norm() < 1e-6 * (1.0 + dm.norm()));
    CHECK((dv - numeric_gradient(fv, x)).norm() < 1e-6 * (1.0 + dv.norm()));
  }
}

TEST_CASE("the fitted model ranks chosen points above the rejected ones", "[model]") {
  const int d = 2;
  sps::PreferenceData data(d);
  const Eigen::Vector2d good(0.3, 0.3);
  for (int i = 0; i < 4; ++i) {
    data.add_preference(good,
                        {Eigen::Vector2d(0.8, 0.1 + 0.2 * i), Eigen::Vector2d(0.1 + 0.2 * i, 0.9)});
  }
  const sps::ModelSettings settings;
  const auto model = sps::PreferenceModel::fit(data, settings, sps::PreferenceModel(d, settings));
  REQUIRE(model.best_observed_index() == 0);
  CHECK(model.mean(good) > model.mean(Eigen::Vector2d(0.8, 0.5)));
  // Far from data the variance returns to the prior; at data it is small.
  CHECK(model.variance(good) < 0.2 * model.variance(Eigen::Vector2d(0.99, 0.01)));
}
