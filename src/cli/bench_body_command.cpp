// `bench-body`: time of evaluating the nine bodies of a 3x3 grid (vertices, joints, normals)
// on a synthetic SMPL-X-sized model, with 10 and 300 shape components.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <random>
#include <vector>

#include "body/body_model.hpp"
#include "body/mesh_normals.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"

namespace {

// SMPL-X v1.1 sizes: 10,475 vertices, 20,908 faces, 55 joints. Faces form a strip over
// consecutive vertices (neighbouring indices, as in a real mesh); values are random.
body::Model synthetic_model(int components) {
  const int V = 10475, F = 20908, J = 55;
  std::mt19937 rng(7);
  std::normal_distribution<float> n01(0.0f, 1.0f);
  body::Model m;
  m.name = "synthetic SMPL-X size";
  m.v_template.resize(V, 3);
  for (int v = 0; v < V; ++v) {
    const float t = static_cast<float>(v) / V;
    m.v_template.row(v) << 0.2f * std::cos(97.0f * t), 1.7f * t, 0.2f * std::sin(97.0f * t);
  }
  m.shapedirs.resize(3 * V, components);
  for (Eigen::Index i = 0; i < m.shapedirs.size(); ++i) m.shapedirs.data()[i] = 0.01f * n01(rng);
  m.faces.resize(F, 3);
  for (int f = 0; f < F; ++f) {
    const int a = (f / 2) % (V - 2);
    m.faces.row(f) << static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(a + 1 + f % 2),
        static_cast<std::uint32_t>(a + 2 - f % 2);
  }
  m.j_regressor = Eigen::MatrixXf::Zero(J, V);
  for (int j = 0; j < J; ++j) {
    for (int k = 0; k < 20; ++k) m.j_regressor(j, (j * 190 + k * 7) % V) = 0.05f;
  }
  m.weights = Eigen::MatrixXf::Zero(V, J);
  for (int v = 0; v < V; ++v) m.weights(v, v % J) = 1.0f;
  m.parents.assign(J, 0);
  m.parents[0] = -1;
  for (int j = 0; j < J; ++j) m.joint_names.push_back("joint_" + std::to_string(j));
  m.total_components = components;
  m.prepare();
  return m;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

template <typename Fn>
std::vector<double> time_runs(int runs, Fn fn) {
  std::vector<double> ms;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    const auto t1 = std::chrono::steady_clock::now();
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  return ms;
}

int run(int argc, char** argv) {
  const cli::ArgParser args(argc, argv, {});
  if (args.has("help")) {
    std::cout << "usage: sequential-gallery bench-body [--runs N]\n\n"
                 "Prints the median (and minimum) time in ms to evaluate the nine bodies of a 3x3\n"
                 "grid (vertices, joints, normals) for a synthetic SMPL-X-sized model with 10\n"
                 "and 300 shape components: with evaluate_batch_into (reused meshes; one matrix\n"
                 "product for many components) and with nine evaluate() calls; and the time of the "
                 "vertex normals of one body.\n";
    return 0;
  }
  args.reject_unknown({"runs"});
  const int runs = std::max(5, args.get_int("runs", 200));
  std::mt19937 rng(1);
  std::normal_distribution<float> n01(0.0f, 1.0f);
  std::printf("bench-body: synthetic model 10475 vertices, 20908 faces, 55 joints; %d runs\n",
              runs);
  std::printf("%-11s %15s %9s %15s %9s %14s\n", "K  betas", "batch_into", "(min)", "9 x evaluate",
              "(min)", "normals/body");
  for (int K : {10, 300}) {
    const body::Model model = synthetic_model(K);
    for (const bool plane : {true, false}) {
      // The gallery's nine bodies: c + s u + t v for s, t in {-1, 0, 1} (a plane in shape
      // space, as the paper builds them); or nine unrelated random bodies.
      std::vector<Eigen::VectorXf> betas(9);
      Eigen::VectorXf c(K), u(K), v(K);
      for (Eigen::Index i = 0; i < K; ++i) c[i] = n01(rng), u[i] = n01(rng), v[i] = n01(rng);
      for (int cell = 0; cell < 9; ++cell) {
        if (plane) {
          betas[static_cast<std::size_t>(cell)] =
              c + static_cast<float>(cell % 3 - 1) * u + static_cast<float>(cell / 3 - 1) * v;
        } else {
          betas[static_cast<std::size_t>(cell)].resize(K);
          for (Eigen::Index i = 0; i < K; ++i) betas[static_cast<std::size_t>(cell)][i] = n01(rng);
        }
      }
      float sink = 0.0f;
      auto nine = [&] {
        for (const auto& b : betas) sink += body::evaluate(model, b).vertices(0, 0);
      };
      nine();  // warm-up
      const auto ms = time_runs(runs, nine);
      std::vector<body::BodyMesh> meshes;  // reused, as the gallery reuses its nine meshes
      auto batch = [&] {
        body::evaluate_batch_into(model, betas, meshes);
        sink += meshes[8].vertices(0, 0);
      };
      batch();
      const auto bms = time_runs(runs, batch);
      const auto mesh = body::evaluate(model, betas[0]);
      body::Vertices normals;
      const auto nms = time_runs(
          runs, [&] { body::compute_vertex_normals(mesh.vertices, model.faces, normals); });
      std::printf("%-4d %-6s %12.3f ms %9.3f %12.3f ms %9.3f %11.3f ms\n", K,
                  plane ? "plane" : "random", median(bms),
                  *std::min_element(bms.begin(), bms.end()), median(ms),
                  *std::min_element(ms.begin(), ms.end()), median(nms));
      if (sink == 12345.0f) std::printf(" ");
    }
  }
  return 0;
}

const cli::CommandRegistration reg{"bench-body", "benchmark: ms to evaluate 9 bodies (SMPL-X size)",
                                   &run};

}  // namespace
