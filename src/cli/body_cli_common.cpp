#include "cli/body_cli_common.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "body/measurement_solve.hpp"
#include "body/model_loader.hpp"

namespace cli {

namespace {

std::string plain(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

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
  const int expressions = args.get_int("expressions", 0);
  if (expressions < 0) throw ArgError("--expressions must be >= 0");
  const auto path = args.get("model");
  // female, male, neutral (built in) or a file; no --model = the built-in neutral model.
  const body::Model model = path ? body::load_model(*path, components, expressions)
                                 : body::load_default_model(components);
  // The loader keeps what the file has; asking for more is a mistake worth saying.
  check_component_count(args, model);
  if (expressions > model.total_expressions) {
    const std::string what = path ? "'" + *path + "'" : std::string("the default model");
    throw ArgError(
        "--expressions " + std::to_string(expressions) + ": " + what + " has " +
        (model.total_expressions == 0
             ? std::string("no expression components (only SMPL-X has them)")
             : "only " + std::to_string(model.total_expressions) + " expression components"));
  }
  return model;
}

void check_component_count(const ArgParser& args, const body::Model& model) {
  if (!args.has("components")) return;
  const int asked = args.get_int("components", 0);
  if (asked > model.total_components) {
    throw ArgError("--components " + std::to_string(asked) + ": the model '" + model.name +
                   "' has only " + std::to_string(model.total_components) +
                   " shape components (0 = all of them)");
  }
}

Eigen::VectorXf read_betas(const ArgParser& args, const body::Model& model) {
  if (args.has("betas") && args.has("x")) throw ArgError("give either --betas or --x, not both");
  Eigen::VectorXf betas;
  if (args.has("x")) {
    const auto x = args.get_doubles("x");
    Eigen::VectorXd xv(static_cast<Eigen::Index>(x.size()));
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (x[i] < 0.0 || x[i] > 1.0) {
        throw ArgError("--x: value number " + std::to_string(i + 1) + " is " + plain(x[i]) +
                       ", which is outside [0, 1]");
      }
      xv[static_cast<Eigen::Index>(i)] = x[i];
    }
    betas = body::betas_from_unit(xv);
  } else {
    const auto b = args.get_doubles("betas");
    betas.resize(static_cast<Eigen::Index>(b.size()));
    for (std::size_t i = 0; i < b.size(); ++i) {
      // Betas are in standard deviations; far beyond +-10 the body collapses or explodes.
      if (std::abs(b[i]) > kMaxAbsBeta) {
        throw ArgError("--betas: value number " + std::to_string(i + 1) + " is " + plain(b[i]) +
                       ", which is outside [-10, 10] (betas are in standard deviations)");
      }
      betas[static_cast<Eigen::Index>(i)] = static_cast<float>(b[i]);
    }
  }
  if (betas.size() > model.component_count()) {
    throw ArgError(std::to_string(betas.size()) + " shape values given but the model '" +
                   model.name + "' has " + std::to_string(model.component_count()) + " components");
  }
  return betas;
}

Eigen::VectorXf apply_targets(const ArgParser& args, const body::Model& model,
                              const Eigen::VectorXf& start) {
  const auto texts = args.get_all("target");
  if (texts.empty()) return start;
  std::vector<body::MeasurementTarget> targets;
  for (const auto& text : texts) {
    try {
      targets.push_back(body::parse_target(text));
    } catch (const std::invalid_argument& e) {
      throw ArgError(std::string("--target: ") + e.what());
    }
  }
  const int K = model.component_count();
  Eigen::VectorXf full = Eigen::VectorXf::Zero(K);
  full.head(std::min<Eigen::Index>(K, start.size())) =
      start.head(std::min<Eigen::Index>(K, start.size()));
  // The solve shares the model without copying it (the caller keeps it alive).
  const std::shared_ptr<const body::Model> shared(&model, [](const body::Model*) {});
  std::unique_ptr<body::MeasurementConstraints> constraints;
  try {
    constraints = std::make_unique<body::MeasurementConstraints>(shared, targets);
  } catch (const std::invalid_argument& e) {
    throw ArgError(std::string("--target: ") + e.what());
  }
  const auto result = constraints->solve(body::unit_from_betas(full));
  if (!result.reached) {
    // The nearest reachable body itself, so that it can be looked at (`measure --betas ...`)
    // or solved on from (a solve from the mean body can end at another least-squares point).
    std::ostringstream nearest;
    nearest << std::setprecision(6);
    const Eigen::VectorXf b = body::betas_from_unit(result.x);
    for (Eigen::Index i = 0; i < b.size(); ++i) nearest << (i == 0 ? "" : " ") << b[i];
    throw std::runtime_error("--target: " + result.message + "; that body: --betas " +
                             nearest.str());
  }
  std::cerr << "target: " << result.message << " (" << result.iterations << " steps, "
            << result.evaluations << " bodies measured)\n";
  return body::betas_from_unit(result.x);
}

void require_output_file(const std::string& path) {
  std::error_code ec;
  if (path.empty()) throw ArgError("-o needs a file name");
  if (path.back() == '/' || std::filesystem::is_directory(path, ec)) {
    throw ArgError("-o " + path + " is a folder; give a file name, e.g. " +
                   (std::filesystem::path(path) / "body.glb").string());
  }
}

std::string format_betas(const Eigen::VectorXf& betas) {
  std::ostringstream out;
  for (Eigen::Index i = 0; i < betas.size(); ++i) out << (i ? ", " : "") << betas[i];
  return out.str();
}

}  // namespace cli
