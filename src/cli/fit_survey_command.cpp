// `fit-survey`: are real people in the body model's space? For a seeded sample of the ANSUR II
// people, the body of the model nearest to each person's measurements (the measurement solve)
// and, per measurement, the median and 95th-percentile absolute error of that body.
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "body/model_loader.hpp"
#include "body/survey_comparison.hpp"
#include "body/survey_fit.hpp"
#include "body/survey_table.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"
#include "util/atomic_file.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery fit-survey --model female|male|neutral|FILE.npz --csv PATH\n"
    "                                     [--sample N] [--seed S] [--components K|all]\n"
    "                                     [--threads T] [--out FILE.csv]\n"
    "                                     [--measurements NAME,NAME,...]\n"
    "For N people of an ANSUR II CSV file (default 1000, drawn with seed S, default 1), solves\n"
    "for the body of the model nearest to each person's height, mass, chest, waist, hips,\n"
    "neck, bideltoid breadth, biceps, thigh and calf girths, crotch height and arm length\n"
    "(inside the +-3 SD box, from the mean body, on the first K components: default 10, 'all'\n"
    "for every component of the model) and prints, per measurement, the median and the 95th\n"
    "percentile of the absolute error (cm; kg for mass). --out also writes them as CSV\n"
    "(measurement,unit,median_abs_error,p95_abs_error). The survey's biceps is flexed, the\n"
    "tool's upper arm relaxed. --measurements fits only those named.\n";

int run(int argc, char** argv) {
  const cli::ArgParser args(argc, argv, {"help"});
  if (args.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  args.reject_unknown(
      {"help", "model", "csv", "sample", "seed", "components", "threads", "out", "measurements"});
  const auto model_name = args.get("model");
  const auto csv = args.get("csv");
  if (!model_name || !csv) {
    throw cli::ArgError("fit-survey needs --model and --csv\n" + std::string(kUsage));
  }
  const int sample = args.get_int("sample", 1000);
  if (sample < 1 || sample > 100000) throw cli::ArgError("--sample must be 1..100000");
  const auto seed = static_cast<unsigned>(args.get_int("seed", 1));
  const int threads =
      args.get_int("threads", static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  if (threads < 1 || threads > 64) throw cli::ArgError("--threads must be 1..64");
  const std::string components_text = args.get("components").value_or("10");
  int components = 0;
  if (components_text != "all") {
    components = args.get_int("components", 10);
    if (components < 1 || components > 300)
      throw cli::ArgError("--components must be 1..300 or all");
  }
  std::vector<std::string> names;
  if (const auto list = args.get("measurements")) {
    std::stringstream in(*list);
    for (std::string n; std::getline(in, n, ',');) {
      if (!n.empty()) names.push_back(n);
    }
    if (names.empty()) throw cli::ArgError("--measurements needs at least one name");
  }
  const auto out_path = args.get("out");
  if (out_path && out_path->empty()) throw cli::ArgError("--out needs a file name");
  // The file is read and checked before any body is solved for.
  const body::SurveyTable table = body::read_survey_csv(*csv, body::survey_columns());
  auto model = std::make_shared<const body::Model>(body::resolve_model(*model_name, components));
  body::SurveyFit fit;
  try {
    fit = body::fit_survey(model, {&table}, sample, seed, threads, names);
  } catch (const std::invalid_argument& e) {
    throw cli::ArgError(e.what());  // a name, or a sample larger than the file
  }

  std::printf(
      "model %s (%d components) against %d people of %s (seed %u); %d of them met on "
      "every measurement within the solve's tolerance\n",
      fit.model_name.c_str(), fit.components, fit.people, table.source.filename().string().c_str(),
      seed, fit.reached);
  std::printf("%-12s %4s %10s %10s\n", "measurement", "unit", "median", "p95");
  std::ostringstream rows;
  rows << "measurement,unit,median_abs_error,p95_abs_error\n";
  for (const auto& r : fit.rows) {
    std::printf("%-12s %4s %10.2f %10.2f\n", r.name.c_str(), r.unit.c_str(), r.median_abs_error,
                r.p95_abs_error);
    char line[160];
    std::snprintf(line, sizeof line, "%s,%s,%.3f,%.3f\n", r.name.c_str(), r.unit.c_str(),
                  r.median_abs_error, r.p95_abs_error);
    rows << line;
  }
  if (out_path) {
    util::write_file_atomically(*out_path, rows.str());
    std::printf("wrote %s\n", out_path->c_str());
  }
  return 0;
}

const cli::CommandRegistration reg{
    "fit-survey", "benchmark: how near the body model comes to real people's measurements", &run};

}  // namespace
