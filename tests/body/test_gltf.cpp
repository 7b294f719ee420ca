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
#include <map>
#include <tuple>

#include <Eigen/Geometry>

#include "body/atomic_file.hpp"
#include "body/bone_frames.hpp"
#include "body/export_presets.hpp"
#include "body/gltf_export.hpp"
#include "body/joint_names.hpp"
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
  body::Model m = body::load_model(path, components, expressions);
  CHECK(m.posedirs.size() == 0);  // read on demand only
  body::load_pose_correctives(m);
  return m;
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

TEST_CASE("gltf: the base mesh is the design, and one morph target per component edits it",
          "[gltf]") {
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

TEST_CASE("gltf: every bone points at its child (local +Y), leaves continue their parent",
          "[gltf][rig]") {
  const body::Model model = body::load_default_model(10);
  const auto betas = some_betas(10);
  for (const auto pose : {body::RestPose::model, body::RestPose::t}) {
    body::ExportOptions opt;
    opt.rest_pose = pose;
    const auto bytes = body::export_gltf_bytes(model, betas, true, opt);
    tinygltf::TinyGLTF loader;
    tinygltf::Model doc;
    std::string err, warn;
    REQUIRE(loader.LoadBinaryFromMemory(&doc, &err, &warn,
                                        reinterpret_cast<const unsigned char*>(bytes.data()),
                                        static_cast<unsigned>(bytes.size())));
    const auto world = world_matrices(doc);
    const auto targets = body::bone_targets(model.parents, model.joint_names);
    double worst = 0.0;
    for (int j = 0; j < model.joint_count(); ++j) {
      const auto& wj =
          world[static_cast<std::size_t>(doc.skins[0].joints[static_cast<std::size_t>(j)])];
      const Eigen::Vector3d axis = wj.topLeftCorner<3, 3>() * Eigen::Vector3d::UnitY();
      CHECK(std::abs(wj.topLeftCorner<3, 3>().determinant() - 1.0) < 1e-5);
      const int c = targets[static_cast<std::size_t>(j)];
      if (c < 0) continue;
      const auto& wc =
          world[static_cast<std::size_t>(doc.skins[0].joints[static_cast<std::size_t>(c)])];
      const Eigen::Vector3d bone =
          (wc.topRightCorner<3, 1>() - wj.topRightCorner<3, 1>()).normalized();
      worst = std::max(worst, std::acos(std::min(1.0, axis.dot(bone))) * 180.0 / 3.14159265358979);
    }
    INFO("rest pose " << (pose == body::RestPose::t ? "T" : "model") << ": worst bone-to-child "
                      << worst << " degrees");
    // The matrices are float32: acos of a dot product within ~1e-7 of 1 reads up to ~0.03
    // degrees, so the bound sits above that noise (0.01 failed on the built-in neutral model
    // at 0.012).
    CHECK(worst < 0.05);
    // The main chains: pelvis -> spine1, spine3 -> neck, left_elbow -> left_wrist.
    CHECK(model.joint_names[static_cast<std::size_t>(targets[0])] == "spine1");
    CHECK(model.joint_names[static_cast<std::size_t>(targets[9])] == "neck");
    CHECK(model.joint_names[static_cast<std::size_t>(targets[18])] == "left_wrist");
    CHECK(targets[22] == -1);  // left_hand: a leaf
  }
}

// The model vertex behind each exported vertex: a vertex on a texture seam is written once per
// texture coordinate, in first-use order of (vertex, texture vertex) over the faces.
body::Vertices as_exported(const body::Model& model, const body::Vertices& v) {
  if (model.uvs.rows() == 0) return v;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> seen;
  std::vector<int> source;
  for (Eigen::Index f = 0; f < model.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (seen.emplace(std::make_pair(model.faces(f, c), model.uv_faces(f, c)), 0).second)
        source.push_back(static_cast<int>(model.faces(f, c)));
  body::Vertices out(static_cast<Eigen::Index>(source.size()), 3);
  for (std::size_t i = 0; i < source.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = v.row(source[i]);
  return out;
}

TEST_CASE("gltf: T-pose puts the arms horizontal, with the model's skinning", "[gltf][rig]") {
  const body::Model model = body::load_default_model(10);
  const auto betas = some_betas(10);
  auto shaped = body::evaluate(model, betas);
  const auto posed = body::t_posed(model, shaped);
  for (const std::string side : {"left", "right"}) {
    auto index = [&](const std::string& n) {
      return static_cast<int>(
          std::find(model.joint_names.begin(), model.joint_names.end(), side + n) -
          model.joint_names.begin());
    };
    const int s = index("_shoulder"), e = index("_elbow"), w = index("_wrist");
    const Eigen::Vector3f upper = (posed.joints.row(e) - posed.joints.row(s)).transpose();
    const Eigen::Vector3f fore = (posed.joints.row(w) - posed.joints.row(e)).transpose();
    INFO(side << " upper arm " << upper.transpose() << ", forearm " << fore.transpose());
    CHECK(std::abs(upper.normalized().x()) > 0.9999f);
    CHECK(std::abs(fore.normalized().x()) > 0.9999f);
    CHECK(upper.x() * fore.x() > 0.0f);
    CHECK((side == "left") == (upper.x() > 0.0f));  // SMPL's left is +x
    // Bone lengths are kept (rigid rotations).
    CHECK(upper.norm() ==
          Approx((shaped.joints.row(e) - shaped.joints.row(s)).norm()).epsilon(1e-5));
  }
  // The legs and spine do not move (only the arms turn); feet stay on the ground.
  CHECK(posed.vertices.col(1).minCoeff() == Approx(0.0).margin(1e-6));
  body::place_on_ground(shaped);
  CHECK((posed.joints.row(4) - shaped.joints.row(4)).norm() < 1e-5f);
  // The export in T-pose holds that mesh; its morph targets are the posed shape changes.
  body::ExportOptions opt;
  opt.rest_pose = body::RestPose::t;
  opt.morph_encoding = body::MorphEncoding::betas;
  const auto path = fixtures::scratch_dir("gltf-tpose") / "t.glb";
  body::export_gltf(model, betas, path, opt);
  const auto doc = read_back(path);
  const auto& prim = doc.meshes.at(0).primitives.at(0);
  const auto base = accessor_data<float>(doc, prim.attributes.at("POSITION"), 3);
  CHECK(max_vertex_error(base, as_exported(model, posed.vertices)) < 1e-5f);
  // Target 2 = the same rotations applied to the body with beta_2 + 1, minus the design.
  const body::Rotations local = body::t_pose_rotations(model, body::evaluate(model, betas).joints);
  const body::Skinning skin(model, local);
  Eigen::VectorXf b2 = betas;
  b2[2] += 1.0f;
  const auto s1 = body::evaluate(model, betas), s2 = body::evaluate(model, b2);
  const body::Vertices expect =
      skin.vertices(s2.vertices, s2.joints) - skin.vertices(s1.vertices, s1.joints);
  const auto t2 = accessor_data<float>(doc, prim.targets.at(2).at("POSITION"), 3);
  CHECK(max_vertex_error(t2, as_exported(model, expect)) < 1e-5f);
  CHECK_THAT(doc.nodes.at(0).extras.Get("rest_pose").Get<std::string>(), Contains("T"));
  // The skinning of the rest pose itself: identity rotations change nothing.
  const body::Skinning rest(model, body::Rotations(static_cast<std::size_t>(model.joint_count()),
                                                   Eigen::Matrix3f::Identity()));
  CHECK((rest.vertices(s1.vertices, s1.joints) - s1.vertices).cwiseAbs().maxCoeff() < 1e-6f);
}

TEST_CASE("gltf: T-pose applies SMPL-layout pose correctives, skips other layouts", "[gltf][rig]") {
  fixtures::Cylinder c;
  c.pose_columns = 9 * 23;  // SMPL: 207
  const auto with = family_model(c, "smpl-posedirs", 10);
  c.pose_columns = 0;
  const auto without = family_model(c, "smpl-plain", 10);
  c.pose_columns = 93;  // STAR's quaternion layout: not applied
  const auto star = family_model(c, "star", 10);
  REQUIRE(with.posedirs.cols() == 207);
  REQUIRE(star.posedirs.cols() == 93);
  const auto betas = some_betas(10);
  bool used = false;
  const auto shaped = body::evaluate(with, betas);
  const auto a = body::t_posed(with, shaped, &used);
  CHECK(used);
  const auto b = body::t_posed(without, body::evaluate(without, betas), &used);
  CHECK_FALSE(used);
  const auto s = body::t_posed(star, body::evaluate(star, betas), &used);
  CHECK_FALSE(used);
  CHECK((s.vertices - b.vertices).cwiseAbs().maxCoeff() < 1e-6f);
  // The fixture's corrective column 135 is R(0,0) - 1 of the left shoulder, times 0.05 m on y
  // for every vertex: the posed difference is the skinning of exactly that offset.
  const body::Rotations local = body::t_pose_rotations(with, shaped.joints);
  const float feature = local[16](0, 0) - 1.0f;
  REQUIRE(std::abs(feature) > 0.1f);
  body::Vertices offset = body::Vertices::Zero(with.vertex_count(), 3);
  offset.col(1).setConstant(0.05f * feature);
  const body::Skinning skin(with, local);
  const body::Vertices zero_joints = body::Vertices::Zero(with.joint_count(), 3);
  body::Vertices expect = b.vertices + skin.vertices(offset, zero_joints);
  expect.col(1).array() -= expect.col(1).minCoeff();  // both are grounded
  CHECK((a.vertices - expect).cwiseAbs().maxCoeff() < 1e-5f);
  CHECK((a.vertices - b.vertices).cwiseAbs().maxCoeff() > 1e-3f);
  CHECK(star.joint_names[16] == "left_shoulder");  // STAR uses SMPL's names
}

TEST_CASE("loader: SMPL+H and SMPL-X joint names built in, and SMPL-X shape and expressions apart",
          "[gltf][family]") {
  fixtures::Cylinder c;
  c.joints = 52;
  c.components = 16;
  const auto smplh = family_model(c, "smplh");
  REQUIRE(smplh.joint_count() == 52);
  CHECK(smplh.joint_names[21] == "right_wrist");
  CHECK(smplh.joint_names[22] == "left_index1");
  CHECK(smplh.joint_names[36] == "left_thumb3");
  CHECK(smplh.joint_names[37] == "right_index1");
  CHECK(smplh.joint_names[51] == "right_thumb3");
  CHECK(smplh.parents[22] == 20);  // the fixture's hierarchy: fingers on the wrists
  CHECK(smplh.total_components == 16);
  CHECK(smplh.total_expressions == 0);

  c.joints = 55;
  c.components = 20;  // SMPL-X v1.0 layout: 10 shape + 10 expression
  const auto smplx = family_model(c, "smplx", 0, 4);
  REQUIRE(smplx.joint_count() == 55);
  CHECK(smplx.joint_names[22] == "jaw");
  CHECK(smplx.joint_names[23] == "left_eye_smplhf");
  CHECK(smplx.joint_names[24] == "right_eye_smplhf");
  CHECK(smplx.joint_names[25] == "left_index1");
  CHECK(smplx.joint_names[54] == "right_thumb3");
  CHECK(smplx.total_components == 10);
  CHECK(smplx.component_count() == 10);  // "all" = all shape components, no expressions
  CHECK(smplx.total_expressions == 10);
  REQUIRE(smplx.expression_dirs.cols() == 4);
  // Expression e is column 10 + e of the file's shapedirs (fixture: 0.002 sin(0.7 k (v+1) + a)).
  CHECK(smplx.expression_dirs(3 * 7 + 1, 2) ==
        Approx(0.002 * std::sin(0.7 * 12 * 8 + 1)).margin(1e-7));
  CHECK(smplx.shapedirs(3 * 7 + 1, 9) == Approx(0.002 * std::sin(0.7 * 9 * 8 + 1)).margin(1e-7));
  CHECK(body::load_model(smplx.source, 0, 0).expression_dirs.cols() == 0);
  // A file with 400 columns and 55 joints is SMPL-X v1.1: 300 shape, 100 expressions.
  c.components = 400;
  c.rings = 5;
  c.segments = 4;
  const auto v11 = family_model(c, "smplx-v11", 0, 100);
  CHECK(v11.total_components == 300);
  CHECK(v11.total_expressions == 100);
  CHECK(v11.expression_dirs.cols() == 100);

  body::ExportOptions opt;
  opt.morph_encoding = body::MorphEncoding::betas;
  const auto path = fixtures::scratch_dir("gltf-smplx") / "x.gltf";
  body::export_gltf(smplx, some_betas(10), path, opt);
  const auto doc = read_back(path);
  const auto& gm = doc.meshes.at(0);
  REQUIRE(gm.primitives.at(0).targets.size() == 14);
  CHECK(gm.extras.Get("targetNames").Get(9).Get<std::string>() == "shape_09");
  CHECK(gm.extras.Get("targetNames").Get(13).Get<std::string>() == "expr_03");
  CHECK(joint_node(doc, 22).name == "jaw");
  CHECK(joint_node(doc, 54).name == "right_thumb3");
  // expr_01 at weight 1 is the body with expression 1 added.
  const auto& prim = gm.primitives.at(0);
  auto pos = accessor_data<float>(doc, prim.attributes.at("POSITION"), 3);
  const auto d = accessor_data<float>(doc, prim.targets.at(11).at("POSITION"), 3);
  for (std::size_t i = 0; i < pos.size(); ++i) pos[i] += d[i];
  auto mesh = body::evaluate(smplx, some_betas(10));
  body::place_on_ground(mesh);
  Eigen::Map<Eigen::VectorXf>(mesh.vertices.data(), mesh.vertices.size()) +=
      smplx.expression_dirs.col(1);
  CHECK(max_vertex_error(pos, mesh.vertices) < 1e-5f);
}

TEST_CASE("gltf: UVs from vt/ft, vertices split along the seam", "[gltf][family]") {
  fixtures::Cylinder c;
  c.uvs = true;
  const auto model = family_model(c, "uv", 10);
  REQUIRE(model.uvs.rows() == (c.segments + 1) * c.rings + 2);
  const auto path = fixtures::scratch_dir("gltf-uv") / "uv.glb";
  body::export_gltf(model, some_betas(10), path);
  const auto doc = read_back(path);
  const auto& prim = doc.meshes.at(0).primitives.at(0);
  REQUIRE(prim.attributes.count("TEXCOORD_0") == 1);
  const auto uv = accessor_data<float>(doc, prim.attributes.at("TEXCOORD_0"), 2);
  const auto pos = accessor_data<float>(doc, prim.attributes.at("POSITION"), 3);
  const std::size_t n = uv.size() / 2;
  // One extra vertex per ring on the seam (u = 0 and u = 1 at the same place).
  CHECK(n == static_cast<std::size_t>(model.vertex_count() + c.rings));
  const auto idx = accessor_data<std::uint32_t>(doc, prim.indices, 1);
  REQUIRE(idx.size() == static_cast<std::size_t>(model.faces.size()));
  // Every corner: same position as the model's vertex, the file's (u, 1 - v).
  auto mesh = body::evaluate(model, some_betas(10));
  body::place_on_ground(mesh);
  float worst_pos = 0.0f, worst_uv = 0.0f;
  for (Eigen::Index f = 0; f < model.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::size_t o = idx[static_cast<std::size_t>(3 * f + k)];
      const auto v = model.faces(f, k);
      const auto t = model.uv_faces(f, k);
      for (int a = 0; a < 3; ++a) {
        worst_pos = std::max(
            worst_pos, std::abs(pos[3 * o + static_cast<std::size_t>(a)] - mesh.vertices(v, a)));
      }
      worst_uv = std::max(worst_uv, std::abs(uv[2 * o] - model.uvs(t, 0)));
      worst_uv = std::max(worst_uv, std::abs(uv[2 * o + 1] - (1.0f - model.uvs(t, 1))));
    }
  }
  CHECK(worst_pos < 1e-5f);
  CHECK(worst_uv < 1e-7f);
  // Morph targets and skin attributes have the same (split) vertex count.
  CHECK(doc.accessors.at(static_cast<std::size_t>(prim.targets.at(0).at("POSITION"))).count == n);
  CHECK(doc.accessors.at(static_cast<std::size_t>(prim.attributes.at("WEIGHTS_0"))).count == n);
}

TEST_CASE("gltf: .vrm holds VRMC_vrm with meta and the humanoid bone map", "[gltf][vrm]") {
  const body::Model model = body::load_default_model(10);
  const auto path = fixtures::scratch_dir("gltf-vrm") / "avatar.vrm";
  body::ExportOptions opt;
  opt.vrm.authors = {"A. Designer"};
  opt.vrm.name = "Test avatar";
  body::export_gltf(model, some_betas(10), path, opt);
  tinygltf::TinyGLTF loader;
  tinygltf::Model doc;
  std::string err, warn;
  REQUIRE(loader.LoadBinaryFromFile(&doc, &err, &warn, path.string()));
  REQUIRE(std::find(doc.extensionsUsed.begin(), doc.extensionsUsed.end(), "VRMC_vrm") !=
          doc.extensionsUsed.end());
  const auto& vrm = doc.extensions.at("VRMC_vrm");
  CHECK(vrm.Get("specVersion").Get<std::string>() == "1.0");
  CHECK(vrm.Get("meta").Get("name").Get<std::string>() == "Test avatar");
  CHECK(vrm.Get("meta").Get("authors").Get(0).Get<std::string>() == "A. Designer");
  CHECK(vrm.Get("meta").Get("licenseUrl").Get<std::string>() == "https://vrm.dev/licenses/1.0/");
  const auto& bones = vrm.Get("humanoid").Get("humanBones");
  const std::vector<std::pair<std::string, std::string>> expect = {
      {"hips", "pelvis"},
      {"spine", "spine1"},
      {"chest", "spine2"},
      {"upperChest", "spine3"},
      {"neck", "neck"},
      {"head", "head"},
      {"leftShoulder", "left_collar"},
      {"leftUpperArm", "left_shoulder"},
      {"leftLowerArm", "left_elbow"},
      {"leftHand", "left_wrist"},
      {"rightUpperLeg", "right_hip"},
      {"rightLowerLeg", "right_knee"},
      {"rightFoot", "right_ankle"},
      {"rightToes", "right_foot"}};
  for (const auto& [role, joint] : expect) {
    INFO(role);
    REQUIRE(bones.Has(role));
    CHECK(
        doc.nodes.at(static_cast<std::size_t>(bones.Get(role).Get("node").GetNumberAsInt())).name ==
        joint);
  }
  // The built-in models have SMPL-X's skeleton: fingers, jaw and eyes in the humanoid map,
  // and a lookAt on the eye bones.
  CHECK(bones.Has("leftThumbProximal"));
  CHECK(bones.Has("rightLittleDistal"));
  CHECK(bones.Has("jaw"));
  CHECK(bones.Has("leftEye"));
  REQUIRE(vrm.Has("lookAt"));
  CHECK(vrm.Get("lookAt").Get("type").Get<std::string>() == "bone");

  // T-pose: the left hand lies level with the left shoulder, out on +x.
  const auto world = world_matrices(doc);
  const auto node_of = [&](const char* role) {
    return static_cast<std::size_t>(bones.Get(role).Get("node").GetNumberAsInt());
  };
  const auto& sh = world.at(node_of("leftUpperArm"));
  const auto& hand = world.at(node_of("leftHand"));
  CHECK(hand(1, 3) == Approx(sh(1, 3)).margin(1e-4));
  CHECK(hand(0, 3) > sh(0, 3) + 0.3);

  // A skeleton without the humanoid joints cannot be a VRM; a .vrm cannot be A-posed.
  const auto other = cylinder(5, 4);
  CHECK_THROWS_WITH(body::export_gltf(other, some_betas(4), path.parent_path() / "x.vrm"),
                    Contains("x.vrm") && Contains("T-pose needs"));
  opt.rest_pose = body::RestPose::model;
  CHECK_THROWS_WITH(body::export_gltf(model, some_betas(10), path, opt), Contains("T-pose"));
  opt.rest_pose = body::RestPose::automatic;
  opt.vrm.commercial_usage = "free";
  CHECK_THROWS_WITH(body::export_gltf(model, some_betas(10), path, opt),
                    Contains("commercialUsage") && Contains("'free'"));
  opt.vrm.commercial_usage = "corporation";
  opt.vrm.authors = {"ok", "bad \xff byte"};
  CHECK_THROWS_WITH(body::export_gltf(model, some_betas(10), path, opt),
                    Contains("avatar.vrm") && Contains("'authors'") && Contains("UTF-8"));
}

TEST_CASE("gltf: presets and humanoid joint names", "[gltf][presets]") {
  REQUIRE(body::export_presets().size() == 5);
  for (const char* name : {"blender", "unity", "unreal", "threejs", "vrm"}) {
    INFO(name);
    CHECK(body::find_export_preset(name).has_value());
  }
  CHECK_FALSE(body::find_export_preset("maya").has_value());
  CHECK(body::find_export_preset("vrm")->extension == ".vrm");
  CHECK(body::find_export_preset("threejs")->options.morph_encoding == body::MorphEncoding::betas);
  CHECK(body::find_export_preset("unity")->options.rest_pose == body::RestPose::t);
  CHECK(body::find_export_preset("blender")->options.rest_pose == body::RestPose::model);
  const body::Model model = body::load_default_model(10);
  const auto path = fixtures::scratch_dir("gltf-presets") / "unity.glb";
  body::export_gltf(model, some_betas(10), path, body::find_export_preset("unity")->options);
  const auto doc = read_back(path);
  CHECK(joint_node(doc, 0).name == "hips");
  CHECK(joint_node(doc, 16).name == "leftUpperArm");
  // The built-in models have SMPL-X's skeleton: jaw, eyes and fingers have humanoid roles too,
  // and no SMPL name is left among the humanoid ones.
  CHECK(joint_node(doc, 22).name == "jaw");
  CHECK(joint_node(doc, 23).name == "leftEye");
  CHECK(joint_node(doc, 25).name == "leftIndexProximal");
  CHECK(joint_node(doc, 54).name == "rightThumbDistal");
  for (int j = 0; j < 55; ++j) {
    INFO("joint " << j << ": " << joint_node(doc, j).name);
    CHECK(joint_node(doc, j).name.find('_') == std::string::npos);
  }
  // Unreal: the UE5 mannequin's names, one style throughout.
  CHECK(body::find_export_preset("unreal")->options.joint_naming == body::JointNaming::unreal);
  const auto unreal_path = fixtures::scratch_dir("gltf-presets") / "unreal.glb";
  body::export_gltf(model, some_betas(10), unreal_path,
                    body::find_export_preset("unreal")->options);
  const auto ue = read_back(unreal_path);
  const std::pair<int, const char*> expected[] = {
      {0, "pelvis"},      {1, "thigh_l"},     {2, "thigh_r"},  {3, "spine_01"},    {4, "calf_l"},
      {7, "foot_l"},      {10, "ball_l"},     {12, "neck_01"}, {13, "clavicle_l"}, {15, "head"},
      {16, "upperarm_l"}, {19, "lowerarm_r"}, {20, "hand_l"},  {22, "jaw"},        {23, "eye_l"},
      {25, "index_01_l"}, {54, "thumb_03_r"}};
  for (const auto& [j, name] : expected) CHECK(joint_node(ue, j).name == name);
  // Every SMPL-family joint has a name in each engine style, the fingers, jaw and eyes too.
  for (const auto* names : {body::builtin_joint_names(24), body::builtin_joint_names(55)}) {
    REQUIRE(names != nullptr);
    for (const auto& n : *names) {
      INFO(n);
      CHECK_FALSE(body::humanoid_bone_name(n).empty());
      CHECK_FALSE(body::unreal_bone_name(n).empty());
    }
  }
  CHECK(body::unreal_bone_name("left_index1") == "index_01_l");
  CHECK(body::unreal_bone_name("right_thumb3") == "thumb_03_r");
}
