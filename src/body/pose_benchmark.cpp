#include "body/pose_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace body {

namespace {

std::string format(const char* fmt, double value) {
  if (!std::isfinite(value)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, value);
  return buf;
}

// "worst (mean)" for a table cell.
std::string pair_cell(const char* fmt, double worst, double mean) {
  return format(fmt, worst) + " (" + format(fmt, mean) + ")";
}

std::string verdict(const PoseResult& r) {
  if (!r.available) return "n/a";
  return r.pass ? "pass" : "**fail** (" + r.failed + ")";
}

}  // namespace

std::vector<BenchBody> benchmark_bodies(const Model& model, int components) {
  if (components < 0 || components > model.component_count()) {
    throw ModelError(model.name + ": the pose benchmark asks for " + std::to_string(components) +
                     " components but the model keeps " + std::to_string(model.component_count()));
  }
  std::vector<BenchBody> out;
  out.push_back({"mean", Eigen::VectorXf::Zero(model.component_count())});
  for (int k = 0; k < components; ++k) {
    for (const float beta : {-3.0f, 3.0f}) {
      Eigen::VectorXf b = Eigen::VectorXf::Zero(model.component_count());
      b[k] = beta;
      out.push_back({"c" + std::to_string(k + 1) + (beta < 0 ? "-3" : "+3"), b});
    }
  }
  return out;
}

PoseFigures measure_posed_body(const Model& model, const PosedBody& posed,
                               const PoseDefinition& pose) {
  const std::vector<JointRegion> regions = measured_joints(model, posed.rest_joints, pose);
  const RestAndPosed mesh{posed.rest_vertices, posed.posed_vertices, posed.rest_joints,
                          posed.posed_joints, model.faces};
  return measure_pose(mesh, model.weights, model.parents, regions,
                      pose.hand_contact ? hand_joints(model) : std::vector<int>{});
}

void require_known_poses(const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    if (find_pose(name) == nullptr) {
      throw ModelError("'" + name + "' is not a pose of the benchmark (its poses: " + pose_names() +
                       ")");
    }
  }
}

ModelBenchmark run_pose_benchmark(const Model& model, const std::string& label, int components,
                                  const PoseTargets& targets,
                                  const std::vector<std::string>& only) {
  const auto start = std::chrono::steady_clock::now();
  if (static_cast<int>(model.joint_names.size()) != model.joint_count()) {
    throw ModelError(model.name + ": the pose benchmark finds joints by name, and this model's " +
                     std::to_string(model.joint_count()) + " joints have none");
  }
  const auto asked = [&only](const std::string& name) {
    return only.empty() || std::find(only.begin(), only.end(), name) != only.end();
  };
  require_known_poses(only);
  ModelBenchmark out;
  out.label = label;
  out.model_name = model.name;
  out.vertices = model.vertex_count();
  out.faces = static_cast<int>(model.faces.rows());
  out.joints = model.joint_count();
  out.bodies = benchmark_bodies(model, components);
  std::vector<BodyMesh> shaped;
  for (const auto& b : out.bodies) shaped.push_back(evaluate(model, b.betas));
  for (const PoseDefinition& pose : pose_library()) {
    PoseResult r;
    r.pose = &pose;
    r.asked = r.available = asked(pose.name);
    if (!r.asked) r.reason = "not asked for";
    for (std::size_t b = 0; r.available && b < shaped.size(); ++b) {
      const BodyMesh& mesh = shaped[b];
      const PosedBody posed = pose_body(model, mesh, pose);
      if (!posed.available) {
        r.available = false;
        r.reason = posed.reason;
        r.per_body.clear();
        break;
      }
      out.correctives = out.correctives || posed.correctives_applied;
      if (measured_joints(model, posed.rest_joints, pose).empty()) {
        r.available = false;
        r.reason = "the skeleton lacks the joints this pose is measured at";
        break;
      }
      r.per_body.push_back(measure_posed_body(model, posed, pose));
    }
    if (r.available) {
      double volume_sum = 0.0, fold_sum = 0.0, crossing_sum = 0.0;
      int volume_count = 0;
      r.volume_worst = std::numeric_limits<double>::quiet_NaN();
      for (const PoseFigures& f : r.per_body) {
        if (std::isfinite(f.volume_change_percent)) {
          if (!(std::abs(f.volume_change_percent) <= std::abs(r.volume_worst))) {
            r.volume_worst = f.volume_change_percent;
          }
          volume_sum += f.volume_change_percent;
          ++volume_count;
        }
        r.fold_worst = std::max(r.fold_worst, f.sharpest_fold_degrees);
        fold_sum += f.sharpest_fold_degrees;
        r.intersections_worst = std::max(r.intersections_worst, f.intersections.pairs);
        r.exempt_worst = std::max(r.exempt_worst, f.intersections.exempt_pairs);
        crossing_sum += f.intersections.pairs;
      }
      const double n = static_cast<double>(r.per_body.size());
      r.volume_mean =
          volume_count ? volume_sum / volume_count : std::numeric_limits<double>::quiet_NaN();
      r.fold_mean = fold_sum / n;
      r.intersections_mean = crossing_sum / n;
      // A region that measured nothing (no faces near the joint) cannot pass.
      const bool volume_ok =
          std::isfinite(r.volume_worst) && std::abs(r.volume_worst) <= targets.volume_percent;
      const bool fold_ok = r.fold_worst <= targets.fold_degrees;
      const bool crossings_ok = r.intersections_worst <= targets.intersections;
      for (const auto& [ok, name] : {std::pair<bool, const char*>{volume_ok, "volume"},
                                     {fold_ok, "fold"},
                                     {crossings_ok, "intersections"}}) {
        if (!ok) r.failed += (r.failed.empty() ? "" : ", ") + std::string(name);
      }
      r.pass = r.failed.empty();
    }
    out.poses.push_back(std::move(r));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::string pose_benchmark_markdown(const std::vector<ModelBenchmark>& models,
                                    const PoseTargets& targets, const std::string& command,
                                    const std::string& sheet) {
  std::string md;
  md += "# Pose benchmark\n\n";
  md += "Made by `" + command + "`";
  md += " (`tools/pose_benchmark.sh` runs it on the built-in models).\n\n";
  md += "Each pose on each model's mean body and on its +-3 SD bodies of the first components; ";
  md += "each figure is the worst body's, the mean over the bodies in brackets. Targets: ";
  md += "|volume change| <= " + format("%.0f", targets.volume_percent) + " %, ";
  md += "no fold beyond " + format("%.0f", targets.fold_degrees) + " degrees, ";
  md += std::to_string(targets.intersections) +
        " self-intersections (for the fist: outside the hands' own contact).\n\n";

  // Summary: one row per pose, four columns per model.
  md += "| pose |";
  std::string rule = "|---|";
  for (const auto& m : models) {
    md += " " + m.label + ": volume % | fold deg | self-int. | |";
    rule += "---:|---:|---:|---|";
  }
  md += "\n" + rule + "\n";
  for (std::size_t p = 0; p < pose_library().size(); ++p) {
    md += "| " + pose_library()[p].name + " |";
    for (const auto& m : models) {
      const PoseResult& r = m.poses[p];
      if (!r.available) {
        md += " - | - | - | n/a |";
        continue;
      }
      md += " " + pair_cell("%+.1f", r.volume_worst, r.volume_mean) + " |";
      md += " " + pair_cell("%.0f", r.fold_worst, r.fold_mean) + " |";
      std::string crossings =
          std::to_string(r.intersections_worst) + " (" + format("%.1f", r.intersections_mean) + ")";
      if (r.pose->hand_contact) crossings += "; hands " + std::to_string(r.exempt_worst);
      md += " " + crossings + " |";
      md += " " + verdict(r) + " |";
    }
    md += "\n";
  }
  md += "| **passing** |";
  for (const auto& m : models) {
    int pass = 0, available = 0;
    for (const auto& r : m.poses) {
      available += r.available;
      pass += r.available && r.pass;
    }
    md += " | | | " + std::to_string(pass) + " of " + std::to_string(available) + " |";
  }
  md += "\n\n";
  for (const auto& m : models) {
    for (const auto& r : m.poses) {
      if (!r.available && r.asked) {
        md += "- " + m.label + ", " + r.pose->name + ": not available (" + r.reason + ")\n";
      }
    }
  }

  md += "\n## Models\n\n";
  for (const auto& m : models) {
    md += "- **" + m.label + "**: " + m.model_name + ", " + std::to_string(m.vertices) +
          " vertices, " + std::to_string(m.faces) + " faces, " + std::to_string(m.joints) +
          " joints" + (m.correctives ? ", with its pose correctives" : ", no pose correctives") +
          "; bodies:";
    for (const auto& b : m.bodies) md += " " + b.label;
    md += "; " + format("%.0f", m.seconds) + " s.\n";
  }
  if (!sheet.empty()) {
    md +=
        "\n![Every pose on the mean body, framed on the measured (left) joint; labels give the "
        "mean body's figures](" +
        sheet + ")\n";
  }

  md += "\n## What is measured\n\n";
  md +=
      "- **Poses** (both sides alike; the figures are the left side's; the rest pose is the "
      "model's own, A for the built-in models, or the T-pose for the `-from-t` rows: the "
      "T-posed mesh and joints with the same weights, as a T-pose glTF export gives an "
      "engine):\n";
  for (const auto& p : pose_library()) md += "  - `" + p.name + "`: " + p.description + "\n";
  md +=
      "- **Region**: the faces around the measured joint, chosen in the rest pose: centroid "
      "within a radius of the joint (half the upper arm for the shoulder, half the forearm "
      "for the elbow and wrist, half the thigh for the hip, half the shin for the knee, the "
      "neck's length for the head, one finger segment for each finger joint of the fist) and "
      "the face's dominant bone (largest summed weight) the joint, its parent or a child.\n";
  md +=
      "- **Volume change**: of the signed volume of the cones from the joint to the region's "
      "faces, rest to posed (apex at the rest and the posed joint). A rigid motion of the "
      "region about its joint leaves it unchanged; a limb that collapses or bulges at the "
      "joint changes it. The fist: the finger joint whose region changes most.\n";
  md +=
      "- **Sharpest fold**: the largest change, rest to posed, of the signed dihedral angle "
      "across the region's interior edges.\n";
  md +=
      "- **Self-intersections**: pairs of faces without a common vertex that intersect in the "
      "posed mesh (whole mesh, both sides) and did not at rest (Moller's triangle test on a "
      "uniform grid). For the fist, pairs of two hand faces (mostly weighted to a wrist or "
      "finger joint) are the fist's own contact and listed apart (\"hands\").\n";

  md += "\n## Per body\n\nvolume % / fold deg / self-intersections of each body.\n";
  for (const auto& m : models) {
    md += "\n### " + m.label + "\n\n| pose |";
    std::string body_rule = "|---|";
    for (const auto& b : m.bodies) {
      md += " " + b.label + " |";
      body_rule += "---|";
    }
    md += "\n" + body_rule + "\n";
    for (const auto& r : m.poses) {
      md += "| " + r.pose->name + " |";
      for (std::size_t b = 0; b < m.bodies.size(); ++b) {
        if (!r.available || b >= r.per_body.size()) {
          md += " n/a |";
          continue;
        }
        const PoseFigures& f = r.per_body[b];
        md += " " + format("%+.1f", f.volume_change_percent) + " / " +
              format("%.0f", f.sharpest_fold_degrees) + " / " +
              std::to_string(f.intersections.pairs) + " |";
      }
      md += "\n";
    }
  }
  return md;
}

}  // namespace body
