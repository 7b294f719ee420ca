#include "cli/body_cli_common.hpp"

#include <algorithm>
#include <sstream>

#include "body/model_loader.hpp"

namespace cli {

std::vector<char*> normalize_output_flag(int argc, char** argv, std::vector<std::string>& store) {
  store.assign(argv, argv + argc);
  for (auto& a : store) {
    if (a == "-o") a = "--output";
  }
  std::vector<char*> out;
  for (auto& a : store) out.push_back(a.data());
  out.push_back(nullptr);
  return out;
}

std::size_t shape_value_count(const ArgParser& args) {
  return std::max(args.get_doubles("betas").size(), args.get_doubles("x").size());
}

body::Model load_body_model(const ArgParser& args) {
  const int given = static_cast<int>(shape_value_count(args));
  int components = args.get_int("components", std::max(10, given));
  if (components < 0) throw ArgError("--components must be >= 0 (0 = all the file has)");
  if (components != 0 && components < given) {
    throw ArgError("--components " + std::to_string(components) + " but " + std::to_string(given) +
                   " shape values were given");
  }
  return body::resolve_model(args.get_or("model", ""), components);
}

Eigen::VectorXf read_betas(const ArgParser& args, const body::Model& model) {
  if (args.has("betas") && args.has("x")) throw ArgError("give either --betas or --x, not both");
  Eigen::VectorXf betas;
  if (args.has("x")) {
    const auto x = args.get_doubles("x");
    Eigen::VectorXd xv(static_cast<Eigen::Index>(x.size()));
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (x[i] < 0.0 || x[i] > 1.0) {
        throw ArgError("--x: value " + std::to_string(i + 1) + " (" + std::to_string(x[i]) +
                       ") is outside [0, 1]");
      }
      xv[static_cast<Eigen::Index>(i)] = x[i];
    }
    betas = body::betas_from_unit(xv);
  } else {
    const auto b = args.get_doubles("betas");
    betas.resize(static_cast<Eigen::Index>(b.size()));
    for (std::size_t i = 0; i < b.size(); ++i)
      betas[static_cast<Eigen::Index>(i)] = static_cast<float>(b[i]);
  }
  if (betas.size() > model.component_count()) {
    throw ArgError(std::to_string(betas.size()) + " shape values given but the model '" +
                   model.name + "' has " + std::to_string(model.component_count()) + " components");
  }
  return betas;
}

std::string format_betas(const Eigen::VectorXf& betas) {
  std::ostringstream out;
  for (Eigen::Index i = 0; i < betas.size(); ++i) out << (i ? ", " : "") << betas[i];
  return out.str();
}

}  // namespace cli
