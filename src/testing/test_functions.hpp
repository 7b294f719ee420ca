// Synthetic goodness functions on [0,1]^n for simulated users (to be maximized), each with a
// known optimum value: the paper's isotropic Gaussian and scaled negative Rosenbrock plus
// standard test functions mapped into the unit box.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sps {

class TestFunction {
 public:
  virtual ~TestFunction() = default;
  virtual double operator()(const Eigen::Ref<const Eigen::VectorXd>& x) const = 0;
  virtual double optimum_value() const = 0;
  virtual Eigen::VectorXd optimum_location() const = 0;
  virtual std::string name() const = 0;
};

struct FunctionInfo {
  std::string name;
  std::string description;
  bool movable_optimum;  // accepts --optimum
};

const std::vector<FunctionInfo>& available_functions();

// `optimum` (one value for every coordinate) moves the optimum where the function allows;
// NaN keeps the default. Throws std::invalid_argument for unknown names or bad values.
std::unique_ptr<TestFunction> make_test_function(
    const std::string& name, int dims, double optimum = std::numeric_limits<double>::quiet_NaN());

}  // namespace sps
