// `bench-survey`: the built-in body models' populations against the ANSUR II survey they are
// meant to reproduce. Prints, per model, the tool's measurements of bodies drawn with
// betas ~ N(0, 1) beside the same measurements of the surveyed people (mean, SD, 5th, 50th
// and 95th percentiles) and the gap of the means in survey SDs.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "body/model_loader.hpp"
#include "body/survey_comparison.hpp"
#include "body/survey_table.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery bench-survey [--female FEMALE.csv] [--male MALE.csv]\n"
    "                                       [--samples N] [--seed S] [--components K]\n"
    "                                       [--models-dir DIR]\n"
    "Compares the built-in body models with the ANSUR II public survey files\n"
    "(ANSUR_II_FEMALE_Public.csv, ANSUR_II_MALE_Public.csv): the female model with the women,\n"
    "the male model with the men and, when both files are given, the neutral model with\n"
    "everyone, each sex weighing the same (the neutral model is built from equal numbers of\n"
    "women and men). N bodies per model (default 300) with betas ~ N(0, 1) on K components\n"
    "(default 10). Lengths in cm, mass in kg. --models-dir reads DIR/body_{female,male,\n"
    "neutral}.npz (as written by generate-default-model --output-dir) instead of the built-in\n"
    "models.\n";

void print(const body::PopulationComparison& c, const std::string& against) {
  std::printf("\nmodel %s (%d bodies) against %s (%d people)\n", c.model_name.c_str(), c.bodies,
              against.c_str(), c.people);
  std::printf("%-15s %8s %7s %7s %7s %7s | %8s %7s %7s %7s %7s | %8s\n", "measure", "survey", "sd",
              "p5", "p50", "p95", "model", "sd", "p5", "p50", "p95", "gap (SD)");
  for (const auto& r : c.rows) {
    // Lengths in cm, mass in kg, BMI and ratios as they are.
    const bool ratio = r.name.find('/') != std::string::npos;
    const double k = (r.name == "mass" || r.name == "bmi" || ratio) ? 1.0 : 100.0;
    const char* f = ratio ? "%8.3f %7.3f %7.3f %7.3f %7.3f" : "%8.1f %7.1f %7.1f %7.1f %7.1f";
    std::printf("%-15s ", r.name.c_str());
    std::printf(f, k * r.survey.mean, k * r.survey.sd, k * r.survey.p5, k * r.survey.p50,
                k * r.survey.p95);
    std::printf(" | ");
    std::printf(f, k * r.model.mean, k * r.model.sd, k * r.model.p5, k * r.model.p50,
                k * r.model.p95);
    std::printf(" | %+8.2f\n", r.mean_gap_sd);
  }
  double worst = 0.0;
  std::string worst_name;
  for (const auto& r : c.rows) {
    if (std::isfinite(r.mean_gap_sd) && std::abs(r.mean_gap_sd) > std::abs(worst)) {
      worst = r.mean_gap_sd;
      worst_name = r.name;
    }
  }
  std::printf("largest gap of the means: %s %+.2f survey SDs\n", worst_name.c_str(), worst);
  // The population targets: every mean within 2% of the survey's, every SD within 15%, every
  // correlation within 0.15.
  int means_off = 0, sds_off = 0;
  for (const auto& r : c.rows) {
    if (!(std::abs(r.model.mean / r.survey.mean - 1.0) <= 0.02)) ++means_off;
    if (!(std::abs(r.model.sd / r.survey.sd - 1.0) <= 0.15)) ++sds_off;
  }
  int correlations_off = 0;
  for (const auto& g : c.correlations) {
    if (!(std::abs(g.model - g.survey) <= 0.15)) ++correlations_off;
  }
  std::printf(
      "means within 2%%: %zu of %zu; SDs within 15%%: %zu of %zu; correlations within "
      "0.15: %zu of %zu\n",
      c.rows.size() - static_cast<std::size_t>(means_off), c.rows.size(),
      c.rows.size() - static_cast<std::size_t>(sds_off), c.rows.size(),
      c.correlations.size() - static_cast<std::size_t>(correlations_off), c.correlations.size());
  std::printf("largest correlation gaps (survey -> model):");
  for (std::size_t i = 0; i < c.correlations.size() && i < 5; ++i) {
    const auto& g = c.correlations[i];
    std::printf("%s %s-%s %.2f -> %.2f", i ? "," : "", g.a.c_str(), g.b.c_str(), g.survey, g.model);
  }
  std::printf("\n");
}

int run(int argc, char** argv) {
  const cli::ArgParser args(argc, argv, {"help"});
  if (args.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  args.reject_unknown({"help", "female", "male", "samples", "seed", "components", "models-dir"});
  const auto female_path = args.get("female");
  const auto male_path = args.get("male");
  if (!female_path && !male_path) {
    throw cli::ArgError("bench-survey needs --female, --male or both\n" + std::string(kUsage));
  }
  const int samples = args.get_int("samples", 300);
  if (samples < 2 || samples > 100000) throw cli::ArgError("--samples must be 2..100000");
  const int components = args.get_int("components", 10);
  if (components < 1 || components > 300) throw cli::ArgError("--components must be 1..300");
  const auto seed = static_cast<unsigned>(args.get_int("seed", 1));
  // Models freshly written by generate-default-model --output-dir, before they are embedded.
  const auto models_dir = args.get("models-dir");
  auto model = [&](const std::string& name) {
    return models_dir
               ? body::load_model(std::filesystem::path(*models_dir) / ("body_" + name + ".npz"),
                                  components)
               : body::load_builtin_model(name, components);
  };
  // Both files are read (and checked) before any body is measured.
  const auto columns = body::survey_columns();
  std::optional<body::SurveyTable> women, men;
  if (female_path) women = body::read_survey_csv(*female_path, columns);
  if (male_path) men = body::read_survey_csv(*male_path, columns);
  if (women) {
    print(body::compare_with_survey(model("female"), {&*women}, samples, seed),
          "ANSUR II women, " + women->source.filename().string());
  }
  if (men) {
    print(body::compare_with_survey(model("male"), {&*men}, samples, seed),
          "ANSUR II men, " + men->source.filename().string());
  }
  if (women && men) {
    print(body::compare_with_survey(model("neutral"), {&*women, &*men}, samples, seed),
          "ANSUR II women and men pooled, each sex weighing the same");
  }
  return 0;
}

const cli::CommandRegistration reg{
    "bench-survey", "the built-in body models' measurements against the ANSUR II survey", &run};

}  // namespace
