// The pose benchmark (`bench-pose`): every pose of the pose library on a model's mean body and
// on its +-3 SD bodies of the first components, the three figures of pose_quality per body, the
// worst and the mean over the bodies, judged against fixed targets, and a markdown report that
// puts several models (e.g. today's weights and new ones) side by side. No GL here.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "body/body_model.hpp"
#include "body/pose_library.hpp"
#include "body/pose_quality.hpp"

namespace body {

// The targets: |volume change| <= 8 %, no fold beyond 60 degrees, no new
// self-intersection (for the fist: none outside the hands' own contact).
struct PoseTargets {
  double volume_percent = 8.0;
  double fold_degrees = 60.0;
  int intersections = 0;
};

struct BenchBody {
  std::string label;  // "mean", "c1-3", "c1+3", ...
  Eigen::VectorXf betas;
};

// The mean body, then component k at -3 and at +3 for k = 1..components (1-based as in the
// docs), the others at 0. `components` must not exceed the model's.
std::vector<BenchBody> benchmark_bodies(const Model& model, int components);

struct PoseResult {
  const PoseDefinition* pose = nullptr;
  bool available = false;
  bool asked = true;                  // false: left out by run_pose_benchmark's `only`
  std::string reason;                 // when not available
  std::vector<PoseFigures> per_body;  // in benchmark_bodies' order
  // Over the bodies: the volume change with the largest magnitude (sign kept) and the mean
  // signed change; the sharpest fold and the mean; the most intersecting pairs and the mean.
  double volume_worst = 0.0, volume_mean = 0.0;
  double fold_worst = 0.0, fold_mean = 0.0;
  int intersections_worst = 0;
  double intersections_mean = 0.0;
  int exempt_worst = 0;  // the fist's own contacts (not judged)
  bool pass = false;
  std::string failed;  // "volume, fold" ...; empty when it passes or is not available
};

struct ModelBenchmark {
  std::string label;  // as given on the command line (a built-in name or a file path)
  std::string model_name;
  int vertices = 0, faces = 0, joints = 0;
  bool correctives = false;  // SMPL-layout pose correctives were applied
  std::vector<BenchBody> bodies;
  std::vector<PoseResult> poses;  // in pose_library() order
  double seconds = 0.0;           // wall time of the run
};

// Throws ModelError naming the first of `names` that is no pose of the library (and listing
// its poses).
void require_known_poses(const std::vector<std::string>& names);

// Runs the poses of the library named in `only` (every pose when it is empty) on the bodies;
// the others are reported as not available ("not asked for"), so `poses` stays in library
// order. Throws ModelError if the model has no joint names, `components` is out of range or a
// name in `only` is no pose of the library.
ModelBenchmark run_pose_benchmark(const Model& model, const std::string& label, int components,
                                  const PoseTargets& targets = {},
                                  const std::vector<std::string>& only = {});

// The figures of one posed body (used by the benchmark and the contact sheet's labels).
PoseFigures measure_posed_body(const Model& model, const PosedBody& posed,
                               const PoseDefinition& pose);

// The report: the summary table (one group of columns per model, side by side), how each
// figure is defined, and per model the figures of every body. `command` is quoted as the way to
// make it again; `sheet` (may be empty) is linked as the contact sheet.
std::string pose_benchmark_markdown(const std::vector<ModelBenchmark>& models,
                                    const PoseTargets& targets, const std::string& command,
                                    const std::string& sheet);

}  // namespace body
