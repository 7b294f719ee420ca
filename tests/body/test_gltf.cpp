// glTF export: round trip through tinygltf, atomic writes, and the Khronos validator.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <tuple>

#include <Eigen/Geometry>

#include "body/atomic_file.hpp"
#include "body/bone_frames.hpp"
#include "body/export_presets.hpp"
#include "body/gltf_export.hpp"
#include "body/model_loader.hpp"
#include "body/posing.hpp"
#include "npz_fixtures.hpp"

using Catch::Contains;

namespace {

body::Model cylinder(int joints = 24, int components = 10) {
  fixtures::Cylinder c;
  c.joints = joints;
  c.components = components;
  c.base_y = -0.9;
  const auto path = fixtures::scratch_dir("gltf-model-" + std::to_string(joints)) / "cyl.npz";
  fixtures::write_npz(path, fixtures::encode_model(fixtures::cylinder_model(c)));
  return body::load_model(path, components);
}

// A fixture model with SMPL-family look-alike arrays, loaded with `components` shape and
// `expressions` expression components.
body::Model family_model(const fixtures::Cylinder& c, const std::string& tag, int components = 0,
                         int expressions = 0) {
  const auto path = fixtures::scratch_dir("family-" + tag) / (tag + ".npz");
  fixtures::write_npz(path, fixtures::encode_model(fixtures::cylinder_model(c)));
  return body::load_model(path, components, expressions);
}

Eigen::VectorXf some_betas(int k) {
  Eigen::VectorXf b(k);
  for (int i = 0; i < k; ++i) b[i] = 0.3f * static_cast<float>(i % 3) - 0.25f;
  return b;
}

tinygltf::Model read_back(const std::filesystem::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model doc;
  std::string err, warn;
  const bool ok = path.extension() == ".glb"
                      ? loader.LoadBinaryFromFile(&doc, &err, &warn, path.string())
                      : loader.LoadASCIIFromFile(&doc, &err, &warn, path.string());
  INFO("tinygltf: " << err << warn);
  REQUIRE(ok);
  return doc;
}

template <typename T>
std::vector<T> accessor_data(const tinygltf::Model& doc, int index, int comps) {
  const auto& acc = doc.accessors.at(static_cast<std::size_t>(index));
  const auto& view = doc.bufferViews.at(static_cast<std::size_t>(acc.bufferView));
  const auto& buf = doc.buffers.at(static_cast<std::size_t>(view.buffer));
  std::vector<T> out(acc.count * static_cast<std::size_t>(comps));
  std::memcpy(out.data(), buf.data.data() + view.byteOffset + acc.byteOffset,
              out.size() * sizeof(T));
  return out;
}

// Runs a command, returns its exit status and output.
int run_command(const std::string& cmd, std::string& output) {
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, p)) output += buf;
  const int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// World matrix of every node (glTF: parent * T * R * S), by walking down from the roots.
std::vector<Eigen::Matrix4d> world_matrices(const tinygltf::Model& doc) {
  std::vector<Eigen::Matrix4d> world(doc.nodes.size(), Eigen::Matrix4d::Identity());
  std::vector<int> parent(doc.nodes.size(), -1);
  for (std::size_t i = 0; i < doc.nodes.size(); ++i) {
    for (int c : doc.nodes[i].children) parent[static_cast<std::size_t>(c)] = static_cast<int>(i);
  }
  std::function<Eigen::Matrix4d(int)> get = [&](int i) -> Eigen::Matrix4d {
    const auto& n = doc.nodes[static_cast<std::size_t>(i)];
    Eigen::Matrix4d local = Eigen::Matrix4d::Identity();
    if (n.rotation.size() == 4) {
      local.topLeftCorner<3, 3>() =
          Eigen::Quaterniond(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2])
              .toRotationMatrix();
    }
    if (n.translation.size() == 3) {
      local.topRightCorner<3, 1>() =
          Eigen::Vector3d(n.translation[0], n.translation[1], n.translation[2]);
    }
    const int p = parent[static_cast<std::size_t>(i)];
    return p < 0 ? local : Eigen::Matrix4d(get(p) * local);
  };
  for (std::size_t i = 0; i < doc.nodes.size(); ++i) world[i] = get(static_cast<int>(i));
  return world;
}

// Largest |a - b| over the vertices (a: output order, 3 floats each; b: model order).
float max_vertex_error(const std::vector<float>& a, const body::Vertices& b) {
  float e = 0.0f;
  for (Eigen::Index v = 0; v < b.rows(); ++v) {
    for (int k = 0; k < 3; ++k) {
      e = std::max(e, std::abs(a[static_cast<std::size_t>(3 * v + k)] - b(v, k)));
    }
  }
  return e;
}

const tinygltf::Node& joint_node(const tinygltf::Model& doc, int j) {
  return doc.nodes.at(
      static_cast<std::size_t>(doc.skins.at(0).joints.at(static_cast<std::size_t>(j))));
}

}  // namespace

TEST_CASE("gltf: the base mesh is the design; one morph target per component edits it", "[gltf]") {
  const auto model = cylinder();
  const auto betas = some_betas(10);
  const auto path = fixtures::scratch_dir("gltf-rt") / "body.glb";
  body::ExportOptions options;
  options.morph_encoding = body::MorphEncoding::betas;
  body::export_gltf(model, betas, path, options);
  const auto doc = read_back(path);

  auto mesh = body::evaluate(model, betas);
  const float offset = body::place_on_ground(mesh);
  REQUIRE(doc.meshes.size() == 1);
  const auto& prim = doc.meshes[0].primitives.at(0);
  const int V = model.vertex_count();

  // At zero weights (the default) the mesh is the evaluated, grounded design.
  const auto base = accessor_data<float>(doc, prim.attributes.at("POSITION"), 3);
  REQUIRE(base.size() == static_cast<std::size_t>(3 * V));
  CHECK(max_vertex_error(base, mesh.vertices) < 1e-5f);
  REQUIRE(prim.targets.size() == 10);
  REQUIRE(doc.meshes[0].weights.size() == 10);
  for (double w : doc.meshes[0].weights) CHECK(w == 0.0);
  // Weight w on target k moves the body to beta_k + w (same ground offset).
  for (int k : {0, 1, 4}) {
    const auto t =
        accessor_data<float>(doc, prim.targets[static_cast<std::size_t>(k)].at("POSITION"), 3);
    auto moved = base;
    for (std::size_t i = 0; i < moved.size(); ++i) moved[i] += 0.7f * t[i];
    Eigen::VectorXf b = betas;
    b[k] += 0.7f;
    auto expect = body::evaluate(model, b);
    expect.vertices.col(1).array() += offset;
    CHECK(max_vertex_error(moved, expect.vertices) < 1e-5f);
  }
  CHECK(offset == Approx(-body::evaluate(model, betas).vertices.col(1).minCoeff()));

  const auto normals = accessor_data<float>(doc, prim.attributes.at("NORMAL"), 3);
  CHECK(normals[30] == Approx(mesh.normals(10, 0)).margin(1e-6));
  const auto idx = accessor_data<std::uint32_t>(doc, prim.indices, 1);
  REQUIRE(idx.size() == static_cast<std::size_t>(model.faces.size()));
  CHECK(std::equal(idx.begin(), idx.end(), model.faces.data()));
  CHECK(prim.attributes.count("TEXCOORD_0") == 0);  // the fixture has no vt/ft

  // Skin: 24 joints named after SMPL, hierarchy from kintree_table, weights normalised top 4.
  REQUIRE(doc.skins.size() == 1);
  const auto& skin = doc.skins[0];
  REQUIRE(skin.joints.size() == 24);
  CHECK(joint_node(doc, 0).name == "pelvis");
  CHECK(joint_node(doc, 16).name == "left_shoulder");
  for (int j = 1; j < 24; ++j) {
    const int parent_node =
        skin.joints[static_cast<std::size_t>(model.parents[static_cast<std::size_t>(j)])];
    const auto& ch = doc.nodes.at(static_cast<std::size_t>(parent_node)).children;
    CHECK(std::find(ch.begin(), ch.end(), skin.joints[static_cast<std::size_t>(j)]) != ch.end());
  }
  // Each joint's world position is the design's joint; world * inverse bind = identity.
  const auto world = world_matrices(doc);
  const auto ibm = accessor_data<float>(doc, skin.inverseBindMatrices, 16);
  for (int j = 0; j < 24; ++j) {
    const Eigen::Matrix4d& w =
        world[static_cast<std::size_t>(skin.joints[static_cast<std::size_t>(j)])];
    CHECK(w.topRightCorner<3, 1>().cast<float>().isApprox(mesh.joints.row(j).transpose(), 1e-5f));
    const Eigen::Matrix4d inv =
        Eigen::Map<const Eigen::Matrix4f>(ibm.data() + 16 * j).cast<double>();
    CHECK((w * inv - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff() < 1e-5);
  }

  const auto w = accessor_data<float>(doc, prim.attributes.at("WEIGHTS_0"), 4);
  const auto jj = accessor_data<std::uint8_t>(doc, prim.attributes.at("JOINTS_0"), 4);
  for (int v = 0; v < V; ++v) {
    const float* wv = &w[static_cast<std::size_t>(4 * v)];
    CHECK(wv[0] + wv[1] + wv[2] + wv[3] == Approx(1.0f).epsilon(1e-6));
    CHECK(wv[0] >= wv[1]);
    for (int k = 0; k < 4; ++k) {
      if (wv[k] == 0.0f) CHECK(jj[static_cast<std::size_t>(4 * v + k)] == 0);
    }
  }
  // Vertex 4 of the fixture has five influences 0.4, 0.25, 0.15, 0.12, 0.08 on joints
  // 4, 7, 10, 13, 16: the top four are kept and renormalised by 0.92.
  CHECK(jj[16] == 4);
  CHECK(jj[17] == 7);
  CHECK(jj[19] == 13);
  CHECK(w[16] == Approx(0.4 / 0.92).epsilon(1e-5));
  CHECK(w[19] == Approx(0.12 / 0.92).epsilon(1e-5));

  // extras: betas, model name, component count.
  const auto& extras = doc.nodes.at(0).extras;
  REQUIRE(extras.IsObject());
  CHECK(extras.Get("model").Get<std::string>() == "cyl");
  CHECK(extras.Get("components").GetNumberAsInt() == 10);
  REQUIRE(extras.Get("betas").ArrayLen() == 10);
  CHECK(extras.Get("betas").Get(2).GetNumberAsDouble() == Approx(betas[2]));
  CHECK(doc.asset.extras.Get("components").GetNumberAsInt() == 10);
  CHECK(doc.meshes[0].extras.Get("targetNames").Get(3).Get<std::string>() == "shape_03");
}

TEST_CASE("gltf: default morph targets split +-3 sigma, all default weights 0", "[gltf]") {
  const auto model = cylinder();
  Eigen::VectorXf betas(10);
  betas << 1.5f, -3.0f, 0.0f, 0.3f, -0.6f, 2.0f, -1.0f, 0.0f, 3.0f, -0.1f;
  const auto path = fixtures::scratch_dir("gltf-split") / "split.gltf";
  body::export_gltf(model, betas, path);  // default options
  const auto doc = read_back(path);
  const auto& gm = doc.meshes.at(0);
  const auto& prim = gm.primitives.at(0);
  REQUIRE(prim.targets.size() == 20);
  REQUIRE(gm.weights.size() == 20);
  for (double w : gm.weights) CHECK(w == 0.0);
  CHECK(gm.extras.Get("targetNames").Get(2).Get<std::string>() == "shape_01_pos");
  CHECK(gm.extras.Get("targetNames").Get(3).Get<std::string>() == "shape_01_neg");
  // shape_01_neg at weight 0.5 takes beta 1 from -3 to -4.5; shape_00_pos at 1 from 1.5 to 4.5.
  auto mesh = body::evaluate(model, betas);
  const float offset = body::place_on_ground(mesh);
  const auto base = accessor_data<float>(doc, prim.attributes.at("POSITION"), 3);
  CHECK(max_vertex_error(base, mesh.vertices) < 1e-5f);
  for (const auto& [target, weight, component, change] :
       std::vector<std::tuple<int, float, int, float>>{{3, 0.5f, 1, -1.5f}, {0, 1.0f, 0, 3.0f}}) {
    auto pos = base;
    const auto d =
        accessor_data<float>(doc, prim.targets[static_cast<std::size_t>(target)].at("POSITION"), 3);
    for (std::size_t i = 0; i < pos.size(); ++i) pos[i] += weight * d[i];
    Eigen::VectorXf b = betas;
    b[component] += change;
    auto expect = body::evaluate(model, b);
    expect.vertices.col(1).array() += offset;
    CHECK(max_vertex_error(pos, expect.vertices) < 1e-5f);
  }
  CHECK(doc.nodes.at(0).extras.Get("betas").Get(1).GetNumberAsDouble() == Approx(-3.0));
}

TEST_CASE("gltf: .gltf without morph targets holds the shaped body", "[gltf]") {
  const auto model = cylinder(5, 4);
  Eigen::VectorXf betas(4);
  betas << 0.5f, -0.2f, 1.0f, 0.0f;
  const auto path = fixtures::scratch_dir("gltf-text") / "body.gltf";
  body::ExportOptions opt;
  opt.morph_targets = false;
  body::export_gltf(model, betas, path, opt);
  CHECK(fixtures::read_file(path).find("\"asset\"") != std::string::npos);
  const auto doc = read_back(path);
  const auto& prim = doc.meshes.at(0).primitives.at(0);
  CHECK(prim.targets.empty());
  auto mesh = body::evaluate(model, betas);
  body::place_on_ground(mesh);
  const auto pos = accessor_data<float>(doc, prim.attributes.at("POSITION"), 3);
  for (int v = 0; v < model.vertex_count(); v += 50) {
    CHECK(pos[static_cast<std::size_t>(3 * v + 1)] == Approx(mesh.vertices(v, 1)));
  }
  const auto& acc = doc.accessors.at(static_cast<std::size_t>(prim.attributes.at("POSITION")));
  CHECK(acc.minValues.at(1) == Approx(0.0).margin(1e-7));  // feet on the ground
  CHECK(doc.nodes.at(static_cast<std::size_t>(doc.skins.at(0).joints.at(3))).name == "joint_3");
}

TEST_CASE("gltf: failures never replace a good file", "[gltf][atomic]") {
  const auto model = cylinder();
  const auto dir = fixtures::scratch_dir("gltf-atomic");
  const auto path = dir / "keep.glb";
  body::export_gltf(model, some_betas(10), path);
  const std::string before = fixtures::read_file(path);
  REQUIRE(before.size() > 1000);

  Eigen::VectorXf too_many = Eigen::VectorXf::Zero(11);
  CHECK_THROWS_WITH(body::export_gltf(model, too_many, path),
                    Contains(path.string()) && Contains("11 betas"));
  CHECK(fixtures::read_file(path) == before);

  CHECK_THROWS_WITH(body::export_gltf(model, some_betas(10), dir / "missing" / "x.glb"),
                    Contains("does not exist"));
  CHECK_THROWS_WITH(body::export_gltf(model, some_betas(10), dir / "x.obj"),
                    Contains("unknown extension"));
  std::filesystem::create_directories(dir / "taken.glb");
  CHECK_THROWS_WITH(body::export_gltf(model, some_betas(10), dir / "taken.glb"),
                    Contains("taken.glb"));
  // No temporary files left behind.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    (void)e;
    ++files;
  }
  CHECK(files == 2);  // keep.glb and the taken.glb folder
}

TEST_CASE("atomic write: a full disk gives a clear error", "[gltf][atomic]") {
  const int fd = ::open("/dev/full", O_WRONLY);
  REQUIRE(fd >= 0);
  const std::string data(1 << 16, 'x');
  CHECK_THROWS_WITH(body::write_all(fd, data.data(), data.size(), "out.glb"),
                    Contains("out.glb") && Contains("disk full"));
  ::close(fd);
}

TEST_CASE("gltf: exported files pass the Khronos glTF validator", "[gltf][validator]") {
  std::string out;
  const int node = run_command("command -v node", out);
  INFO(out);
  if (node != 0) FAIL("node (Node.js) is not on PATH: run bash tools/setup.sh --test");
  const std::string script = SG_VALIDATOR_SCRIPT;
  if (!std::filesystem::exists(std::filesystem::path(script).parent_path() / "node_modules" /
                               "gltf-validator")) {
    FAIL("the glTF validator is not installed in tests/validator: run bash tools/setup.sh --test");
  }

  const auto dir = fixtures::scratch_dir("gltf-validate");
  const auto smpl = cylinder(24, 10);
  const auto other = cylinder(5, 16);
  std::vector<std::filesystem::path> files;
  for (int variant = 0; variant < 3; ++variant) {  // split morphs, beta morphs, baked
    for (const char* ext : {".glb", ".gltf"}) {
      body::ExportOptions opt;
      opt.morph_targets = variant < 2;
      opt.morph_encoding =
          variant == 1 ? body::MorphEncoding::betas : body::MorphEncoding::split_signed;
      const std::string name[] = {"split", "betas", "plain"};
      const auto p = dir / (name[variant] + ext);
      body::export_gltf(smpl, some_betas(10), p, opt);
      files.push_back(p);
      const auto q = dir / ("j5_" + name[variant] + ext);
      body::export_gltf(other, some_betas(16), q, opt);
      files.push_back(q);
    }
  }
  REQUIRE(files.size() == 12);
  // Every rest pose and preset, on the default model and on SMPL+H / SMPL-X / STAR look-alikes
  // with UVs, pose correctives and expressions.
  const body::Model def = body::load_default_model(10);
  for (const auto& preset : body::export_presets()) {
    const auto p = dir / ("preset_" + preset.name + preset.extension);
    body::export_gltf(def, some_betas(10), p, preset.options);
    files.push_back(p);
  }
  fixtures::Cylinder c;
  c.uvs = true;
  c.joints = 52;
  c.components = 16;
  c.pose_columns = 9 * 51;
  const auto smplh = family_model(c, "v-smplh", 0);
  c.joints = 55;
  c.components = 20;
  c.pose_columns = 9 * 54;
  const auto smplx = family_model(c, "v-smplx", 0, 5);
  c.joints = 24;
  c.components = 10;
  c.pose_columns = 93;
  const auto star = family_model(c, "v-star", 0);
  for (const auto* m : {&smplh, &smplx, &star}) {
    for (const char* ext : {".glb", ".gltf", ".vrm"}) {
      body::ExportOptions opt;
      opt.rest_pose = body::RestPose::t;
      const auto p = dir / (m->name + ext);
      body::export_gltf(*m, some_betas(m->component_count()), p, opt);
      files.push_back(p);
    }
  }
  REQUIRE(files.size() == 26);
  for (const auto& f : files) {
    std::string report;
    const int rc = run_command("node '" + script + "' '" + f.string() + "'", report);
    INFO(report);
    CHECK(rc == 0);
    CHECK_THAT(report, Contains(": 0 errors, 0 warnings"));
  }
}

TEST_CASE("gltf: morph target count (the CLI warns above 200)", "[gltf][presets]") {
  fixtures::Cylinder c;
  c.joints = 55;
  c.components = 20;
  const auto smplx = family_model(c, "count", 0, 7);
  body::ExportOptions opt;
  CHECK(body::morph_target_count(smplx, opt) == 2 * 10 + 7);
  opt.morph_encoding = body::MorphEncoding::betas;
  CHECK(body::morph_target_count(smplx, opt) == 10 + 7);
  opt.morph_targets = false;
  CHECK(body::morph_target_count(smplx, opt) == 7);
  c.joints = 24;
  c.components = 120;
  const auto many = family_model(c, "many", 0);
  CHECK(body::morph_target_count(many, body::ExportOptions{}) == 240);
  CHECK(body::morph_target_count(many, body::ExportOptions{}) > body::kManyMorphTargets);
}
