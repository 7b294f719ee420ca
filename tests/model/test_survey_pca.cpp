// The built-in models' components (survey_pca): checked on small synthetic populations where
// every property can be computed exactly.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <Eigen/Core>
#include <Eigen/Dense>

#include "default_model/pca.hpp"

namespace {

using default_model::PcaResult;
using default_model::SurveyPcaOptions;

struct Synthetic {
  Eigen::MatrixXd theta, basis, measures;
  // Two leads linear in the vertices x = basis theta: lead j = lead_rows.col(j) . x.
  Eigen::MatrixXd lead_rows, leads;
};

// n bodies of p parameters, a 3V x p basis, m measures linear in the parameters (plus a
// little noise) and a stature linear in the vertices.
Synthetic make_population(int n, int p, int coords, int m, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  auto random = [&](int rows, int cols) {
    Eigen::MatrixXd a(rows, cols);
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < rows; ++i) a(i, j) = normal(rng);
    return a;
  };
  Synthetic s;
  // Parameters with very different spreads, so that a plain PCA would favour a few.
  s.theta = random(n, p);
  for (int j = 0; j < p; ++j) s.theta.col(j) *= std::pow(0.6, j);
  s.basis = random(coords, p);
  s.measures = s.theta * random(p, m) + 0.01 * random(n, m);
  s.lead_rows = random(coords, 2);
  s.leads = s.theta * (s.basis.transpose() * s.lead_rows);
  return s;
}

// The population's vertex covariance and the one the components represent (betas ~ N(0, I)).
Eigen::MatrixXd vertex_covariance(const Synthetic& s) {
  const Eigen::MatrixXd x = s.theta * s.basis.transpose();
  const Eigen::MatrixXd c = x.rowwise() - x.colwise().mean();
  return c.transpose() * c / double(x.rows() - 1);
}
Eigen::MatrixXd represented(const PcaResult& r, int count) {
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(r.directions.rows(), r.directions.rows());
  for (int k = 0; k < count; ++k)
    sum += r.variances[k] * r.directions.col(k) * r.directions.col(k).transpose();
  return sum;
}

}  // namespace

TEST_CASE("survey_pca: all components together are the population's vertex covariance", "[pca]") {
  const Synthetic s = make_population(300, 8, 24, 4, 1);
  const PcaResult r = default_model::survey_pca(s.theta, s.basis, s.measures, s.leads, 12,
                                                SurveyPcaOptions{1.0, 5, 0.05});
  REQUIRE(r.variances.size() == 12);
  const Eigen::MatrixXd cov = vertex_covariance(s);
  CHECK(r.total_variance == Approx(cov.trace()).epsilon(1e-9));
  CHECK((represented(r, 12) - cov).norm() < 1e-8 * cov.norm());
  CHECK((r.mean - s.basis * s.theta.colwise().mean().transpose()).norm() < 1e-9);
}

TEST_CASE("survey_pca: without the measures, the searched block spans the vertex PCA's", "[pca]") {
  const Synthetic s = make_population(300, 8, 24, 4, 2);
  const int searched = 4;
  const PcaResult r = default_model::survey_pca(s.theta, s.basis, s.measures, s.leads, 8,
                                                SurveyPcaOptions{0.0, searched, 0.05});
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(vertex_covariance(s));
  const Eigen::Index d = eig.eigenvalues().size();
  double top = 0;
  for (int k = 0; k < searched; ++k) top += eig.eigenvalues()[d - 1 - k];
  // A turn within the block keeps its total and its span.
  CHECK(represented(r, searched).trace() == Approx(top).epsilon(1e-9));
  const Eigen::MatrixXd pcs = eig.eigenvectors().rightCols(searched);
  for (int k = 0; k < searched; ++k) {
    const Eigen::VectorXd u = r.directions.col(k);
    CHECK((pcs * (pcs.transpose() * u) - u).norm() < 1e-8);
  }
}

TEST_CASE("survey_pca: each lead on its own component, every free one visible", "[pca]") {
  const Synthetic s = make_population(400, 10, 30, 5, 3);
  const SurveyPcaOptions options{1.0, 6, 0.06};
  const PcaResult r = default_model::survey_pca(s.theta, s.basis, s.measures, s.leads, 9, options);
  REQUIRE(r.variances.size() == 9);
  // A lead's rise per unit of component k: cov(lead, beta_k) = row . cov(x, beta_k), and
  // the component's axis is cov(x, beta_k) (betas with unit variance).
  const double n1 = double(s.theta.rows() - 1);
  for (int j = 0; j < 2; ++j) {
    const Eigen::VectorXd c = s.leads.col(j).array() - s.leads.col(j).mean();
    const double sd = std::sqrt(c.squaredNorm() / n1);
    Eigen::VectorXd rise(r.variances.size());
    for (int k = 0; k < r.variances.size(); ++k)
      rise[k] = s.lead_rows.col(j).dot(std::sqrt(r.variances[k]) * r.directions.col(k));
    INFO("lead " << j << ": rise per unit " << rise.transpose() << ", SD " << sd);
    for (int k = j + 1; k < options.searched; ++k) CHECK(std::abs(rise[k]) < 1e-9 * sd);
    CHECK(std::abs(rise[j]) > 0.3 * sd);
  }
  // Visible: each free searched component carries at least the floor (or 0.9 of the free
  // ones' average when that is lower), largest first.
  double rest = 0;
  for (int k = 2; k < options.searched; ++k) rest += r.variances[k];
  const double floor =
      std::min(options.visible_share * r.total_variance, 0.9 * rest / double(options.searched - 2));
  for (int k = 2; k < options.searched; ++k) {
    CHECK(r.variances[k] >= floor * (1 - 1e-9));
    if (k > 2) CHECK(r.variances[k] <= r.variances[k - 1] * (1 + 1e-9));
  }
  // Beyond the searched block: the vertices' principal axes, largest first, orthogonal.
  for (int k = options.searched + 1; k < r.variances.size(); ++k) {
    CHECK(r.variances[k] <= r.variances[k - 1] * (1 + 1e-9));
    CHECK(std::abs(r.directions.col(k).dot(r.directions.col(k - 1))) < 1e-8);
  }
}

TEST_CASE("survey_pca: weighing the measures in keeps more of their variance in the block",
          "[pca]") {
  Synthetic s = make_population(400, 10, 30, 5, 4);
  // Measures that follow the parameters moving the vertices least (a neck girth, say).
  s.measures = s.theta.rightCols(5) * Eigen::MatrixXd::Identity(5, 5) * 100.0;
  const int searched = 4;
  // Each measure's share of its variance that the searched block's scores explain: the
  // measures are linear in theta, so the regression of theta on the scores shows it through
  // the vertices. Simpler and exact: compare the block's fit of the measures by least squares
  // on the represented vertices' coordinates.
  auto kept = [&](double weight) {
    const PcaResult r = default_model::survey_pca(s.theta, s.basis, s.measures, s.leads, 10,
                                                  SurveyPcaOptions{weight, searched, 0.0});
    const Eigen::MatrixXd x = s.theta * s.basis.transpose();
    const Eigen::MatrixXd xc = x.rowwise() - x.colwise().mean();
    // Projection of each body onto the block's span, then the measures regressed on all
    // coordinates of the projected bodies.
    Eigen::MatrixXd span = r.directions.leftCols(searched);
    const Eigen::MatrixXd projected =
        xc * span * (span.transpose() * span).inverse() * span.transpose();
    const Eigen::MatrixXd mc = s.measures.rowwise() - s.measures.colwise().mean();
    const Eigen::MatrixXd fit = projected * projected.completeOrthogonalDecomposition().solve(mc);
    return 1.0 - (mc - fit).squaredNorm() / mc.squaredNorm();
  };
  const double plain = kept(0.0), weighed = kept(4.0);
  INFO("measures' variance kept: plain " << plain << ", weighed " << weighed);
  CHECK(weighed > plain + 0.01);
}
