#include "testing/test_functions.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace sps {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Functions whose optimum sits at a single point x* (same value in every coordinate).
class CentredFunction : public TestFunction {
 public:
  CentredFunction(std::string name, int dims, double centre)
      : name_(std::move(name)), centre_(Eigen::VectorXd::Constant(dims, centre)) {}
  Eigen::VectorXd optimum_location() const override { return centre_; }
  std::string name() const override { return name_; }

 protected:
  std::string name_;
  Eigen::VectorXd centre_;
};

// The paper's g1: exp(-|x - x*|^2), x* = 0.3 by default.
class IsotropicGaussian : public CentredFunction {
 public:
  using CentredFunction::CentredFunction;
  double operator()(const Eigen::Ref<const Eigen::VectorXd>& x) const override {
    return std::exp(-(x - centre_).squaredNorm());
  }
  double optimum_value() const override { return 1.0; }
};

// The paper's g2: -sum 100 (4x_{i+1} - 16x_i^2)^2 + (1 - 4x_i)^2, optimum 0 at 0.25.
class ScaledRosenbrock : public CentredFunction {
 public:
  ScaledRosenbrock(int dims) : CentredFunction("rosenbrock", dims, 0.25) {}
  double operator()(const Eigen::Ref<const Eigen::VectorXd>& x) const override {
    double sum = 0.0;
    for (Eigen::Index i = 0; i + 1 < x.size(); ++i) {
      const double a = 4.0 * x(i + 1) - 16.0 * x(i) * x(i);
      const double b = 1.0 - 4.0 * x(i);
      sum += 100.0 * a * a + b * b;
    }
    return -sum;
  }
  double optimum_value() const override { return 0.0; }
};

class Sphere : public CentredFunction {
 public:
  using CentredFunction::CentredFunction;
  double operator()(const Eigen::Ref<const Eigen::VectorXd>& x) const override {
    return -(x - centre_).squaredNorm();
  }
  double optimum_value() const override { return 0.0; }
};

// Rastrigin on [-5.12, 5.12]^n centred on x*: z = 10.24 (x - x*).
class Rastrigin : public CentredFunction {
 public:
  using CentredFunction::CentredFunction;
  double operator()(const Eigen::Ref<const Eigen::VectorXd>& x) const override {
    double sum = 10.0 * static_cast<double>(x.size());
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double z = 10.24 * (x(i) - centre_(i));
      sum += z * z - 10.0 * std::cos(2.0 * kPi * z);
    }
    return -sum;
  }
  double optimum_value() const override { return 0.0; }
};

// Ackley on [-32.768, 32.768]^n centred on x*: z = 65.536 (x - x*).
class Ackley : public CentredFunction {
 public:
  using CentredFunction::CentredFunction;
  double operator()(const Eigen::Ref<const Eigen::VectorXd>& x) const override {
    const double n = static_cast<double>(x.size());
    double sq = 0.0;
    double cs = 0.0;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double z = 65.536 * (x(i) - centre_(i));
      sq += z * z;
      cs += std::cos(2.0 * kPi * z);
    }
    return -(-20.0 * std::exp(-0.2 * std::sqrt(sq / n)) - std::exp(cs / n) + 20.0 + std::exp(1.0));
  }
  double optimum_value() const override { return 0.0; }
};

// Styblinski-Tang on [-5, 5]^n (z = 10x - 5); optimum at z = -2.903534 in every coordinate,
// value -39.16617 n, so g = -f has optimum 39.16617 n (fixed location).
class StyblinskiTang : public CentredFunction {
 public:
  explicit StyblinskiTang(int dims)
      : CentredFunction("styblinski-tang", dims, (5.0 - 2.903534027771177) / 10.0) {}
  double operator()(const Eigen::Ref<const Eigen::VectorXd>& x) const override {
    double f = 0.0;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double z = 10.0 * x(i) - 5.0;
      f += 0.5 * (z * z * z * z - 16.0 * z * z + 5.0 * z);
    }
    return -f;
  }
  double optimum_value() const override {
    const double z = -2.903534027771177;
    return -0.5 * (z * z * z * z - 16.0 * z * z + 5.0 * z) * static_cast<double>(centre_.size());
  }
};

// Levy on [-10, 10]^n centred on x*: z = 1 + 20 (x - x*) so that the optimum z = 1 sits at x*.
class Levy : public CentredFunction {
 public:
  using CentredFunction::CentredFunction;
  double operator()(const Eigen::Ref<const Eigen::VectorXd>& x) const override {
    const Eigen::Index n = x.size();
    auto w = [&](Eigen::Index i) { return 1.0 + (20.0 * (x(i) - centre_(i))) / 4.0; };
    const double w0 = w(0);
    const double wn = w(n - 1);
    double f = std::pow(std::sin(kPi * w0), 2.0);
    for (Eigen::Index i = 0; i + 1 < n; ++i) {
      const double wi = w(i);
      f += (wi - 1.0) * (wi - 1.0) * (1.0 + 10.0 * std::pow(std::sin(kPi * wi + 1.0), 2.0));
    }
    f += (wn - 1.0) * (wn - 1.0) * (1.0 + std::pow(std::sin(2.0 * kPi * wn), 2.0));
    return -f;
  }
  double optimum_value() const override { return 0.0; }
};

}  // namespace

const std::vector<FunctionInfo>& available_functions() {
  static const std::vector<FunctionInfo> functions{
      {"gaussian", "isotropic Gaussian exp(-|x-x*|^2), optimum 1 at x* (default 0.3; paper)", true},
      {"rosenbrock", "-Rosenbrock(4x), optimum 0 at 0.25 (paper)", false},
      {"sphere", "-|x-x*|^2, optimum 0 at x* (default 0.5)", true},
      {"rastrigin", "-Rastrigin(10.24 (x-x*)), optimum 0 at x* (default 0.5); multimodal", true},
      {"ackley", "-Ackley(65.536 (x-x*)), optimum 0 at x* (default 0.5); multimodal", true},
      {"styblinski-tang", "-Styblinski-Tang(10x-5), optimum 39.166 n at 0.2097", false},
      {"levy", "-Levy(1 + 20 (x-x*)), optimum 0 at x* (default 0.5); multimodal", true},
  };
  return functions;
}

std::unique_ptr<TestFunction> make_test_function(const std::string& name, int dims,
                                                 double optimum) {
  if (dims < 1) throw std::invalid_argument("the number of dimensions must be at least 1");
  const bool moved = !std::isnan(optimum);
  if (moved && !(optimum >= 0.0 && optimum <= 1.0)) {
    throw std::invalid_argument("the optimum location must lie in [0, 1]");
  }
  const auto centre = [&](double fallback) { return moved ? optimum : fallback; };
  const auto fixed = [&](std::unique_ptr<TestFunction> f) {
    if (moved) {
      throw std::invalid_argument("function '" + name + "' has a fixed optimum; drop --optimum");
    }
    return f;
  };
  if (name == "gaussian") return std::make_unique<IsotropicGaussian>(name, dims, centre(0.3));
  if (name == "rosenbrock") {
    if (dims < 2) throw std::invalid_argument("rosenbrock needs at least 2 dimensions");
    return fixed(std::make_unique<ScaledRosenbrock>(dims));
  }
  if (name == "sphere") return std::make_unique<Sphere>(name, dims, centre(0.5));
  if (name == "rastrigin") return std::make_unique<Rastrigin>(name, dims, centre(0.5));
  if (name == "ackley") return std::make_unique<Ackley>(name, dims, centre(0.5));
  if (name == "styblinski-tang") return fixed(std::make_unique<StyblinskiTang>(dims));
  if (name == "levy") return std::make_unique<Levy>(name, dims, centre(0.5));
  std::string known;
  for (const auto& f : available_functions()) known += (known.empty() ? "" : ", ") + f.name;
  throw std::invalid_argument("unknown function '" + name + "' (known: " + known + ")");
}

}  // namespace sps
