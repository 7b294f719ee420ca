#include "default_model.hpp"

#include <algorithm>
#include <cmath>

#include "implicit_mesher.hpp"
#include "mannequin_shape.hpp"
#include "npz_writer.hpp"
#include "pca.hpp"
#include "population.hpp"
#include "pose_correctives.hpp"
#include "rig.hpp"
#include "smplx_rig.hpp"
#include "survey_calibration.hpp"
#include "uv_layout.hpp"

namespace default_model {

namespace {

struct Template {
  const Mannequin* mannequin = nullptr;  // the shape the template was meshed from
  TriMesh mesh;
  SmplxRig rig;                   // the exported skeleton (55 joints)
  Eigen::MatrixXd rig_weights;    // V x 55, 4 influences, for glTF
  Eigen::MatrixXd rig_regressor;  // 55 x V
  Eigen::MatrixXd regressor;      // 24 x V: the shape model's joints (the calibration's too)
  HeatWeightReport heat;
  UvLayout uv;
  Eigen::MatrixXf posedirs;  // 3V x 9 (J - 1)
  PoseCorrectiveReport correctives;
  double joint_fit_error = 0;
};

// The shape deformation's broad weights give the skin round the shoulder joint a large share
// of spine3, whose scale widens the chest about the midline: that skin followed the chest's
// breadth rather than the shoulders' spread drawn from the survey's biacromial breadth, and
// the shoulder joint the model regresses from it with it (600 bodies: 4 cm RMS from the placed
// joint, r 0.5 across people). Above the armpit and out from the neck, the chest's share
// (spine2, spine3) goes to the collar bone of its side, which the shoulders' spread moves (r
// 0.7; with the fields off 0.94). A transition narrower than 5-17 cm from the midline folded
// the skin there on far bodies.
void shoulder_girdle_weights(const std::vector<Vec3>& vertices, Eigen::MatrixXd& weights) {
  for (int v = 0; v < weights.rows(); ++v) {
    const Vec3& p = vertices[static_cast<std::size_t>(v)];
    const double share = smoothstep(0.05, 0.17, std::abs(p.x())) * smoothstep(1.27, 1.35, p.y());
    if (share <= 0.0) continue;
    const int collar = p.x() > 0 ? kLeftCollar : kRightCollar;
    for (const int j : {static_cast<int>(kSpine3), static_cast<int>(kSpine2)}) {
      const double moved = share * weights(v, j);
      weights(v, j) -= moved;
      weights(v, collar) += moved;
    }
  }
}

// The shoulder joints' regressor rows, refitted to the generator's own bodies. The convex
// rows (joint_regressor) average the skin round the joint, which lies on its outer side only:
// fat and muscle grown there moved the regressed joint outwards (r 0.73 with the joint placed
// from the survey's biacromial breadth, over 600 bodies). These rows are least squares over
// 400 bodies of each sex (knobs at 0) of the joint the generator placed, on the vertices within
// 10 cm of the joint on its side, held to the template's joint and to weights summing to 1 (a
// strong penalty) and shrunk towards the convex row: r about 0.93 / 0.88 (women / men).
void fit_shoulder_rows(const DeformationModel& deformation, const TriMesh& mesh,
                       const Skeleton& skeleton, std::uint64_t seed, Template& tpl) {
  constexpr double kRadius = 0.10, kShrink = 1e-3;
  std::vector<Eigen::VectorXd> thetas;
  for (const bool female : {true, false})
    for (const Anthropometry& a : sample_population(female, 400, seed + 2 + (female ? 1 : 0)))
      thetas.push_back(deformation.parameters(a));
  const int N = static_cast<int>(thetas.size());
  const int V = static_cast<int>(mesh.vertices.size());
  for (const int j : {static_cast<int>(kLeftShoulder), static_cast<int>(kRightShoulder)}) {
    const Vec3& c = skeleton.joints[j];
    std::vector<int> near;
    for (int v = 0; v < V; ++v)
      if ((mesh.vertices[v] - c).norm() < kRadius && mesh.vertices[v].x() * c.x() > 0)
        near.push_back(v);
    const int n = static_cast<int>(near.size());
    // Rows: each body's three coordinates, then the template's joint and the sum, weighted.
    Eigen::MatrixXd A(3 * N + 4, n);
    Eigen::VectorXd b(3 * N + 4);
    for (int i = 0; i < N; ++i) {
      const Eigen::VectorXd& theta = thetas[i];
      for (int k = 0; k < n; ++k)
        for (int a = 0; a < 3; ++a)
          A(3 * i + a, k) = deformation.basis().row(3 * near[k] + a).dot(theta);
      b.segment<3>(3 * i) = deformation.bone_start(theta, j);  // the placed joint
    }
    const double strong = 1e3 * std::sqrt(static_cast<double>(N));
    for (int k = 0; k < n; ++k) {
      for (int a = 0; a < 3; ++a) A(3 * N + a, k) = strong * mesh.vertices[near[k]][a];
      A(3 * N + 3, k) = strong;
    }
    for (int a = 0; a < 3; ++a) b[3 * N + a] = strong * c[a];
    b[3 * N + 3] = strong;
    Eigen::VectorXd convex(n);
    for (int k = 0; k < n; ++k) convex[k] = tpl.regressor(j, near[k]);
    convex /= convex.sum();
    Eigen::MatrixXd normal = A.transpose() * A;
    normal.diagonal().array() += kShrink * N;
    const Eigen::VectorXd w = normal.ldlt().solve(A.transpose() * b + kShrink * N * convex);
    tpl.regressor.row(j).setZero();
    for (int k = 0; k < n; ++k) tpl.regressor(j, near[k]) = w[k];
    // The exported rig's body joints are the shape model's.
    tpl.rig_regressor.row(j) = tpl.regressor.row(j);
    Vec3 fit = Vec3::Zero();
    for (int k = 0; k < n; ++k) fit += w[k] * mesh.vertices[near[k]];
    tpl.joint_fit_error = std::max(tpl.joint_fit_error, (fit - c).norm());
  }
}

std::vector<int> vertices_where(const TriMesh& mesh, bool top) {
  std::vector<int> ids;
  for (int v = 0; v < static_cast<int>(mesh.vertices.size()); ++v)
    if (top ? mesh.vertices[v].y() > 1.55 : mesh.vertices[v].y() < 0.05) ids.push_back(v);
  return ids;
}

// Vertex normals averaged over the mesh neighbourhood (a few centimetres): the bump fields
// (belly, hips) push along them, and raw normals turn quickly in creases, where pushing along
// them folds the surface.
std::vector<Vec3> smoothed_normals(const TriMesh& mesh, int iterations) {
  std::vector<Vec3> n = vertex_normals(mesh);
  const std::vector<std::vector<int>> neighbours =
      neighbours_by_face(mesh.vertices.size(), mesh.faces);
  for (int it = 0; it < iterations; ++it) {
    std::vector<Vec3> next(n.size());
    for (std::size_t v = 0; v < n.size(); ++v) {
      Vec3 sum = n[v];
      for (int u : neighbours[v]) sum += 0.5 * n[u];
      next[v] = sum.normalized();
    }
    n.swap(next);
  }
  return n;
}

GeneratedModel build_model(const std::string& name, const Template& tpl,
                           const DeformationModel& deformation, const Eigen::MatrixXd& theta,
                           const Eigen::MatrixXd& measures, int components, double measure_weight,
                           int threads);

}  // namespace

const std::vector<std::string>& default_model_names() {
  static const std::vector<std::string> names = {"female", "male", "neutral"};
  return names;
}

std::string default_model_asset(const std::string& name) {
  return "assets/body_" + name + ".npz";
}

std::vector<GeneratedModel> generate_default_models(const GeneratorOptions& options) {
  const Mannequin mannequin;
  Template tpl;
  tpl.mannequin = &mannequin;
  TriMesh& mesh = tpl.mesh;
  mesh = marching_tetrahedra([&](const Vec3& p) { return mannequin.field(p); }, mannequin.bounds(),
                             options.grid_spacing, options.threads);
  keep_largest_component(mesh);
  RemeshOptions remesh_options;
  remesh_options.target_edge = [&](const Vec3& p) { return mannequin.target_edge(p); };
  remesh_options.project = [&](const Vec3& p) { return mannequin.project(p); };
  remesh(mesh, remesh_options);
  if (signed_volume(mesh) < 0)
    for (auto& f : mesh.faces) std::swap(f[1], f[2]);

  const Skeleton& skeleton = mannequin.skeleton();
  // Broad weights for the shape deformation (its 24 bones), and the exported rig's.
  Eigen::MatrixXd deform_weights = skin_weights(mesh.vertices, skeleton, 1.0, 0);
  shoulder_girdle_weights(mesh.vertices, deform_weights);
  tpl.regressor = joint_regressor(mesh.vertices, skeleton);
  tpl.rig = smplx_rig(mannequin);
  tpl.rig_weights = heat_weights(
      mesh, tpl.rig, [&](const Vec3& p) { return mannequin.field(p); }, 4, &tpl.heat);
  tpl.rig_regressor =
      smplx_regressor(mesh, tpl.rig, tpl.regressor, tpl.rig_weights, &tpl.joint_fit_error);
  tpl.uv = uv_layout(mesh, tpl.rig, tpl.rig_weights);
  tpl.posedirs = fit_pose_correctives(mannequin, mesh, tpl.rig, tpl.rig_weights, options.threads,
                                      &tpl.correctives);

  DeformationModel deformation(mesh.vertices, smoothed_normals(mesh, 8), skeleton, deform_weights);
  deformation.smooth_fields(neighbours_by_face(mesh.vertices.size(), mesh.faces), 36);
  const int P = deformation.parameter_count();
  fit_shoulder_rows(deformation, mesh, skeleton, options.seed, tpl);
  std::vector<CalibrationReport> calibration;
  struct Population {
    Eigen::MatrixXd theta, measures;
  };
  auto population = [&](bool female) {
    std::vector<Anthropometry> people =
        sample_population(female, options.population, options.seed + (female ? 0 : 1));
    calibration.push_back(calibrate_population(people, deformation, mesh.faces, tpl.regressor,
                                               options.calibration_sample,
                                               options.calibration_rounds, options.threads));
    Population pop{Eigen::MatrixXd(options.population, P),
                   Eigen::MatrixXd(options.population, kSurveyMeasures)};
    for (int i = 0; i < options.population; ++i) {
      pop.theta.row(i) = deformation.parameters(people[i]).transpose();
      for (int k = 0; k < kSurveyMeasures; ++k) pop.measures(i, k) = people[i].m[k];
    }
    return pop;
  };
  const Population female = population(true), male = population(false);
  Population both{Eigen::MatrixXd(female.theta.rows() + male.theta.rows(), P),
                  Eigen::MatrixXd(female.theta.rows() + male.theta.rows(), kSurveyMeasures)};
  both.theta << female.theta, male.theta;
  both.measures << female.measures, male.measures;
  // The survey measures' weight in the components (survey_pca): 0.8 for each sex. Since each
  // body's mass is calibrated to its draw, the draws are what the bodies measure, and the
  // weight buys survey spread that the vertices' own axes leave to the dropped components
  // (bench-survey, all 18 components: at 0.4 the women's neck SD was 16% short, the men's
  // waist-to-hip ratio's 17%, and 75 of the women's 78 correlations were met; at 0.8 every
  // mean, SD and correlation target is met). The neutral model meets every target with all
  // 18 at 0.4 and keeps that weight.
  auto model = [&](const std::string& name, const Population& pop, double measure_weight) {
    return build_model(name, tpl, deformation, pop.theta, pop.measures, options.components,
                       measure_weight, options.threads);
  };
  std::vector<GeneratedModel> out;
  out.push_back(model("female", female, 0.8));
  out.push_back(model("male", male, 0.8));
  out.push_back(model("neutral", both, 0.4));
  out[0].calibration_reports = {calibration[0]};
  out[1].calibration_reports = {calibration[1]};
  out[2].calibration_reports = calibration;
  return out;
}

namespace {

GeneratedModel build_model(const std::string& name, const Template& tpl,
                           const DeformationModel& deformation, const Eigen::MatrixXd& theta,
                           const Eigen::MatrixXd& measures, int components, double measure_weight,
                           int threads) {
  const TriMesh& mesh = tpl.mesh;
  const int V = static_cast<int>(mesh.vertices.size());
  GeneratedModel out;
  out.name = name;
  {
    // Statures of the population from the y rows of the highest and lowest template vertices.
    auto rows = [&](const std::vector<int>& ids) {
      Eigen::MatrixXd b(ids.size(), deformation.parameter_count());
      for (std::size_t i = 0; i < ids.size(); ++i)
        b.row(i) = deformation.basis().row(3 * ids[i] + 1);
      return Eigen::MatrixXd(b * theta.transpose());
    };
    const Eigen::MatrixXd yt = rows(vertices_where(mesh, true));
    const Eigen::MatrixXd yb = rows(vertices_where(mesh, false));
    for (Eigen::Index i = 0; i < theta.rows(); ++i)
      out.population_statures.push_back(yt.col(i).maxCoeff() - yb.col(i).minCoeff());
  }

  // Component 1 carries the searched components' stature, component 2 their mass beyond
  // it: a person's first words about a body ("tall", "heavy") are one axis each, and no
  // corner of the box is taller or shorter than component 1 alone at +-3.
  Eigen::MatrixXd leads(theta.rows(), 2);
  for (Eigen::Index i = 0; i < theta.rows(); ++i)
    leads.row(i) << out.population_statures[i], measures(i, k_weight);
  SurveyPcaOptions survey_options;
  survey_options.measure_weight = measure_weight;
  const PcaResult pca =
      survey_pca(theta, deformation.basis(), measures, leads, components, survey_options);
  const int K = static_cast<int>(pca.variances.size());
  out.v_template.resize(V, 3);
  for (int v = 0; v < V; ++v)
    for (int a = 0; a < 3; ++a) out.v_template(v, a) = static_cast<float>(pca.mean[3 * v + a]);
  Eigen::VectorXd centroid = Eigen::VectorXd::Zero(3 * V);
  {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v = 0; v < V; ++v) c += pca.mean.segment<3>(3 * v);
    c /= V;
    for (int v = 0; v < V; ++v) centroid.segment<3>(3 * v) = pca.mean.segment<3>(3 * v) - c;
  }
  out.shapedirs.resize(3 * V, K);
  out.variance_share.resize(K);
  for (int k = 0; k < K; ++k) {
    Eigen::VectorXd dir = pca.directions.col(k);
    // Sign convention: +beta makes the body larger (direction along the body's own extent).
    if (dir.dot(centroid) < 0) dir = -dir;
    // Rounded to 2^-20 m (a micrometre): 18 components at 3 SD move a vertex by under 0.03 mm,
    // and the rounded floats deflate to about two thirds, which keeps each file under 5 MB.
    out.shapedirs.col(k) = (std::sqrt(pca.variances[k]) * dir)
                               .unaryExpr([](double c) { return rounded_to_binary_step(c, 20); })
                               .cast<float>();
    out.variance_share[k] = static_cast<float>(pca.variances[k] / pca.total_variance);
  }
  out.faces.resize(static_cast<Eigen::Index>(mesh.faces.size()), 3);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int a = 0; a < 3; ++a) out.faces(f, a) = static_cast<std::uint32_t>(mesh.faces[f][a]);
  out.j_regressor = tpl.rig_regressor.cast<float>();
  out.weights = tpl.rig_weights.cast<float>();
  out.joints = (out.j_regressor * out.v_template);
  out.joint_fit_error = tpl.joint_fit_error;
  out.vertices_without_visible_bone = tpl.heat.vertices_without_visible_bone;
  out.uv_distortion = uv_distortion(mesh, tpl.uv);
  out.uv = tpl.uv;
  out.pose_correctives = tpl.correctives;
  // The .npz, in SMPL's layout.
  std::vector<NpyArray> arrays;
  {
    std::vector<float> v(out.v_template.data(), out.v_template.data() + out.v_template.size());
    arrays.push_back(make_array("v_template", "<f4", {std::size_t(V), 3}, v));
  }
  {
    std::vector<std::uint32_t> f(out.faces.data(), out.faces.data() + out.faces.size());
    arrays.push_back(make_array("f", "<u4", {mesh.faces.size(), 3}, f));
  }
  {
    // (V, 3, K) in C order: element [v][a][k] = shapedirs(3v + a, k).
    std::vector<float> s(static_cast<std::size_t>(3) * V * K);
    for (int r = 0; r < 3 * V; ++r)
      for (int k = 0; k < K; ++k) s[static_cast<std::size_t>(r) * K + k] = out.shapedirs(r, k);
    arrays.push_back(make_array("shapedirs", "<f4", {std::size_t(V), 3, std::size_t(K)}, s));
  }
  const int J = tpl.rig.size();
  {
    std::vector<float> r(static_cast<std::size_t>(J) * V);
    for (int j = 0; j < J; ++j)
      for (int v = 0; v < V; ++v) r[static_cast<std::size_t>(j) * V + v] = out.j_regressor(j, v);
    arrays.push_back(make_array("J_regressor", "<f4", {std::size_t(J), std::size_t(V)}, r));
  }
  {
    std::vector<float> w(static_cast<std::size_t>(V) * J);
    for (int v = 0; v < V; ++v)
      for (int j = 0; j < J; ++j) w[static_cast<std::size_t>(v) * J + j] = out.weights(v, j);
    arrays.push_back(make_array("weights", "<f4", {std::size_t(V), std::size_t(J)}, w));
  }
  {
    std::vector<std::uint32_t> k(2 * J);
    for (int j = 0; j < J; ++j) {
      const int p = tpl.rig.parents[j];
      k[j] = p < 0 ? 4294967295u : static_cast<std::uint32_t>(p);
      k[J + j] = static_cast<std::uint32_t>(j);
    }
    arrays.push_back(make_array("kintree_table", "<u4", {2, std::size_t(J)}, k));
  }
  {
    std::vector<float> j(out.joints.data(), out.joints.data() + out.joints.size());
    arrays.push_back(make_array("J", "<f4", {std::size_t(J), 3}, j));
  }
  {
    // The limbs' correctives are the template's; the shoulders', hips', head's and fingers' are
    // fitted on this model's mean body, whose arms, neck and hands are not the template's, and
    // so is where the elbows' and knees' flesh meets in a deep bend.
    Eigen::MatrixXf posedirs = tpl.posedirs;
    {
      std::vector<Vec3> rest(V);
      for (int v = 0; v < V; ++v) rest[v] = out.v_template.row(v).transpose().cast<double>();
      SmplxRig rig = tpl.rig;
      for (int j = 0; j < rig.size(); ++j)
        rig.joints[j] = out.joints.row(j).transpose().cast<double>();
      // Where the elbows' and knees' flesh meets is found on the mean body made 14 mm thicker
      // all over: the correctives are the same for every body of the model, and pressed only
      // as far as the mean body needs, the thick bodies' calves and thighs (a component at +3)
      // still went through each other at 130 degrees (hundreds of triangle pairs; 24 with this,
      // 0-13 on the mean bodies); the mean body's limbs then meet a few millimetres apart.
      constexpr double kContactThickness = 0.014;
      TriMesh mean_mesh = tpl.mesh;
      mean_mesh.vertices = rest;
      const std::vector<Vec3> normals = smoothed_normals(mean_mesh, 2);
      std::vector<Vec3> thick(V);
      for (int v = 0; v < V; ++v) thick[v] = rest[v] + kContactThickness * normals[v];
      fit_hinge_contact_correctives(*tpl.mannequin, tpl.mesh, tpl.rig, tpl.rig_weights, thick, rig,
                                    threads, posedirs);
      // Where the arm meets the trunk is found on the mean body and its +-3 SD bodies of the
      // first components (the bodies the pose benchmark poses).
      const int shown = std::min<int>(3, static_cast<int>(out.shapedirs.cols()));
      std::vector<std::vector<Vec3>> bodies(1, rest);
      std::vector<SmplxRig> rigs(1, rig);
      for (int k = 0; k < shown; ++k)
        for (double sd : {-3.0, 3.0}) {
          std::vector<Vec3> b(V);
          for (int v = 0; v < V; ++v)
            b[v] = rest[v] + sd * out.shapedirs.block<3, 1>(3 * v, k).cast<double>();
          SmplxRig r = rig;
          for (int j = 0; j < r.size(); ++j) {
            Vec3 x = Vec3::Zero();
            for (int v = 0; v < V; ++v) x += tpl.rig_regressor(j, v) * b[v];
            r.joints[j] = x;
          }
          bodies.push_back(std::move(b));
          rigs.push_back(std::move(r));
        }
      std::vector<ContactBody> contact_bodies;
      for (std::size_t b = 0; b < bodies.size(); ++b)
        contact_bodies.push_back({&bodies[b], &rigs[b]});
      fit_rotation_share_correctives(rest, tpl.mesh.faces, contact_bodies, rig, tpl.rig_weights,
                                     threads, posedirs, &out.pose_correctives);
    }
    // (V, 3, P) in C order, as SMPL stores posedirs: element [v][a][p] = posedirs(3v + a, p).
    const Eigen::Index Pc = posedirs.cols();
    std::vector<float> p(static_cast<std::size_t>(3) * V * Pc);
    for (int r = 0; r < 3 * V; ++r)
      for (Eigen::Index c = 0; c < Pc; ++c)
        p[static_cast<std::size_t>(r) * Pc + c] = posedirs(r, c);
    arrays.push_back(
        make_array("posedirs", "<f4", {std::size_t(V), 3, static_cast<std::size_t>(Pc)}, p));
  }
  {
    // Texture coordinates as SMPL-X stores them: vt (T, 2), origin bottom left; ft (F, 3).
    std::vector<float> vt;
    for (const auto& p : tpl.uv.uv) {
      vt.push_back(static_cast<float>(p.x()));
      vt.push_back(static_cast<float>(p.y()));
    }
    arrays.push_back(make_array("vt", "<f4", {tpl.uv.uv.size(), 2}, vt));
    std::vector<std::uint32_t> ft;
    for (const auto& f : tpl.uv.faces)
      for (int a = 0; a < 3; ++a) ft.push_back(static_cast<std::uint32_t>(f[a]));
    arrays.push_back(make_array("ft", "<u4", {tpl.uv.faces.size(), 3}, ft));
  }
  {
    std::vector<float> s(out.variance_share.data(), out.variance_share.data() + K);
    arrays.push_back(make_array("variance_share", "<f4", {std::size_t(K)}, s));
  }
  out.npz = npz_bytes(arrays);
  return out;
}

}  // namespace

}  // namespace default_model
