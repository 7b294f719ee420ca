// glTF 2.0 / VRM 1.0 writer for one body: a skinned mesh with the model's skeleton (bones
// along the limbs), optional morph targets relative to the design, metres, +Y up, facing +Z,
// feet on y = 0.
#include "body/gltf_export.hpp"

#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>

#include "body/atomic_file.hpp"
#include "body/bone_frames.hpp"
#include "body/eye_parts.hpp"
#include "body/joint_names.hpp"
#include "body/mesh_normals.hpp"
#include "body/posing.hpp"
#include "util/utf8.hpp"

namespace body {

namespace {

// Appends typed arrays to one buffer, each view starting 4-byte aligned.
class BufferBuilder {
 public:
  explicit BufferBuilder(tinygltf::Model& doc) : doc_(doc) { doc_.buffers.emplace_back(); }

  int add_view(const void* data, std::size_t bytes, int target) {
    auto& buf = doc_.buffers[0].data;
    while (buf.size() % 4 != 0) buf.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buf.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + bytes);
    doc_.bufferViews.push_back(view);
    return static_cast<int>(doc_.bufferViews.size()) - 1;
  }

  int add_accessor(int view, int component_type, int type, std::size_t count,
                   std::vector<double> min = {}, std::vector<double> max = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.byteOffset = 0;
    a.componentType = component_type;
    a.type = type;
    a.count = count;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    doc_.accessors.push_back(a);
    return static_cast<int>(doc_.accessors.size()) - 1;
  }

  // Float VEC3 data (n rows of x, y, z) with the min/max glTF requires for positions.
  int add_vec3(const float* xyz, std::size_t n, int target, bool with_bounds) {
    std::vector<double> lo, hi;
    if (with_bounds) {
      lo.assign(3, 0.0);
      hi.assign(3, 0.0);
      for (int c = 0; c < 3; ++c) {
        float mn = n ? xyz[c] : 0.0f, mx = mn;
        for (std::size_t i = 0; i < n; ++i) {
          mn = std::min(mn, xyz[3 * i + c]);
          mx = std::max(mx, xyz[3 * i + c]);
        }
        lo[static_cast<std::size_t>(c)] = mn;
        hi[static_cast<std::size_t>(c)] = mx;
      }
    }
    const int view = add_view(xyz, n * 3 * sizeof(float), target);
    return add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n, lo, hi);
  }

 private:
  tinygltf::Model& doc_;
};

// Top four skinning influences of one vertex, renormalised to sum to exactly 1 in float;
// unused slots carry joint 0 with weight 0 (as the validator wants).
void top4(const Eigen::MatrixXf& weights, Eigen::Index v, int root, std::array<int, 4>& joints,
          std::array<float, 4>& w) {
  const Eigen::Index J = weights.cols();
  std::array<std::pair<float, int>, 4> best;
  best.fill({0.0f, -1});
  for (Eigen::Index j = 0; j < J; ++j) {
    const float x = weights(v, j);
    if (!(x > 0.0f)) continue;
    if (x > best[3].first) {
      best[3] = {x, static_cast<int>(j)};
      for (int k = 3; k > 0 && best[static_cast<std::size_t>(k)].first >
                                   best[static_cast<std::size_t>(k - 1)].first;
           --k) {
        std::swap(best[static_cast<std::size_t>(k)], best[static_cast<std::size_t>(k - 1)]);
      }
    }
  }
  double sum = 0.0;
  for (const auto& b : best) sum += b.second >= 0 ? b.first : 0.0f;
  if (!(sum > 0.0)) {  // no influence at all: bind to the root
    joints = {root, 0, 0, 0};
    w = {1.0f, 0.0f, 0.0f, 0.0f};
    return;
  }
  float rest = 0.0f;
  for (std::size_t k = 0; k < 4; ++k) {
    if (best[k].second >= 0) {
      joints[k] = best[k].second;
      w[k] = static_cast<float>(best[k].first / sum);
    } else {
      joints[k] = 0;
      w[k] = 0.0f;
    }
    if (k > 0) rest += w[k];
  }
  w[0] = 1.0f - rest;  // the largest absorbs the rounding
  for (std::size_t k = 1; k < 4; ++k) {
    if (w[k] == 0.0f) joints[k] = 0;
  }
}

tinygltf::Value number_array(const Eigen::VectorXf& v) {
  tinygltf::Value::Array a;
  for (Eigen::Index i = 0; i < v.size(); ++i) a.emplace_back(static_cast<double>(v[i]));
  return tinygltf::Value(a);
}

tinygltf::Value str(const std::string& s) {
  return tinygltf::Value(s);
}

// glTF has one index per vertex for every attribute, so a vertex that sits on a texture seam
// (two texture coordinates) becomes two glTF vertices. `source` maps each output vertex to the
// model's vertex; without UVs the map is the identity.
struct SplitMesh {
  std::vector<std::uint32_t> source;
  std::vector<float> uv;  // 2 per output vertex, glTF convention (origin top left)
  Faces faces;
};

SplitMesh split_along_seams(const Model& model) {
  SplitMesh out;
  const auto V = static_cast<std::size_t>(model.vertex_count());
  const bool with_uv = model.uvs.rows() > 0 && model.uv_faces.rows() == model.faces.rows();
  if (!with_uv) {
    out.source.resize(V);
    std::iota(out.source.begin(), out.source.end(), 0u);
    out.faces = model.faces;
    return out;
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> index;
  out.faces.resize(model.faces.rows(), 3);
  // Vertices in first-use order of (vertex, uv) pairs; unused vertices are dropped.
  for (Eigen::Index f = 0; f < model.faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const std::pair<std::uint32_t, std::uint32_t> key{model.faces(f, c), model.uv_faces(f, c)};
      auto [it, added] = index.emplace(key, static_cast<std::uint32_t>(out.source.size()));
      if (added) {
        out.source.push_back(key.first);
        out.uv.push_back(model.uvs(key.second, 0));
        out.uv.push_back(1.0f - model.uvs(key.second, 1));  // glTF's v runs downwards
      }
      out.faces(f, c) = it->second;
    }
  }
  return out;
}

// Rows of `m` (V x 3, model vertices) in output order.
std::vector<float> gather(const Vertices& m, const std::vector<std::uint32_t>& source) {
  std::vector<float> out(3 * source.size());
  for (std::size_t i = 0; i < source.size(); ++i) {
    for (int a = 0; a < 3; ++a) out[3 * i + static_cast<std::size_t>(a)] = m(source[i], a);
  }
  return out;
}

std::array<float, 4> quaternion_of(const Eigen::Matrix3f& r) {
  Eigen::Quaternionf q(r);
  q.normalize();
  if (q.w() < 0.0f) q.coeffs() = -q.coeffs();
  return {q.x(), q.y(), q.z(), q.w()};
}

tinygltf::Value vrm_extension(const Model& model, const std::vector<std::string>& names,
                              const ExportOptions& options,
                              const std::optional<tinygltf::Value>& look_at,
                              const std::vector<std::pair<std::string, int>>& expression_targets) {
  const VrmMeta& m = options.vrm;
  // The schema's enumerations: a wrong value would make a file VRM readers reject.
  const auto require_one_of = [](const std::string& field, const std::string& value,
                                 std::initializer_list<const char*> allowed) {
    std::string list;
    for (const char* a : allowed) {
      if (value == a) return;
      list += (list.empty() ? "" : "|") + std::string(a);
    }
    throw ExportError("VRM meta '" + field + "' must be one of " + list + ", got '" + value + "'");
  };
  require_one_of("avatarPermission", m.avatar_permission,
                 {"onlyAuthor", "onlySeparatelyLicensedPerson", "everyone"});
  require_one_of("commercialUsage", m.commercial_usage,
                 {"personalNonProfit", "personalProfit", "corporation"});
  require_one_of("creditNotation", m.credit_notation, {"required", "unnecessary"});
  require_one_of("modification", m.modification,
                 {"prohibited", "allowModification", "allowModificationRedistribution"});
  if (m.license_url.empty()) throw ExportError("VRM meta 'licenseUrl' must not be empty");
  // JSON text must be UTF-8 (the window passes what the user typed).
  std::vector<std::pair<const char*, const std::string*>> texts = {
      {"name", &m.name}, {"version", &m.version}, {"licenseUrl", &m.license_url}};
  for (const auto& a : m.authors) texts.emplace_back("authors", &a);
  for (const auto& [field, text] : texts) {
    if (!util::is_valid_utf8(*text)) {
      throw ExportError("VRM meta '" + std::string(field) + "' is not valid UTF-8 text");
    }
  }
  tinygltf::Value::Object meta;
  meta["name"] = str(m.name.empty() ? (model.name.empty() ? "body" : model.name) : m.name);
  meta["version"] = str(m.version);
  tinygltf::Value::Array authors;
  for (const auto& a : m.authors) authors.emplace_back(a);
  if (authors.empty()) authors.emplace_back(std::string("unknown"));
  meta["authors"] = tinygltf::Value(authors);
  meta["licenseUrl"] = str(m.license_url);
  meta["avatarPermission"] = str(m.avatar_permission);
  meta["allowExcessivelyViolentUsage"] = tinygltf::Value(false);
  meta["allowExcessivelySexualUsage"] = tinygltf::Value(false);
  meta["commercialUsage"] = str(m.commercial_usage);
  meta["allowPoliticalOrReligiousUsage"] = tinygltf::Value(false);
  meta["allowAntisocialOrHateUsage"] = tinygltf::Value(false);
  meta["creditNotation"] = str(m.credit_notation);
  meta["allowRedistribution"] = tinygltf::Value(m.allow_redistribution);
  meta["modification"] = str(m.modification);
  tinygltf::Value::Object bones;
  for (std::size_t j = 0; j < names.size(); ++j) {
    const std::string role = vrm_humanoid_bone(names[j]);
    if (role.empty()) continue;
    tinygltf::Value::Object bone;
    bone["node"] = tinygltf::Value(static_cast<int>(1 + j));
    bones[role] = tinygltf::Value(bone);
  }
  for (const char* required :
       {"hips", "spine", "head", "leftUpperLeg", "leftLowerLeg", "leftFoot", "rightUpperLeg",
        "rightLowerLeg", "rightFoot", "leftUpperArm", "leftLowerArm", "leftHand", "rightUpperArm",
        "rightLowerArm", "rightHand"}) {
    if (bones.count(required) == 0) {
      throw ExportError("model '" + model.name + "' has no joint for the VRM humanoid bone '" +
                        required + "' (VRM needs an SMPL-family skeleton)");
    }
  }
  tinygltf::Value::Object humanoid;
  humanoid["humanBones"] = tinygltf::Value(bones);
  tinygltf::Value::Object vrm;
  vrm["specVersion"] = str("1.0");
  vrm["meta"] = tinygltf::Value(meta);
  vrm["humanoid"] = tinygltf::Value(humanoid);
  if (look_at) vrm["lookAt"] = *look_at;
  // Expressions: the model's own expression components (SMPL-X's), one custom expression each
  // on its morph target; readers such as three-vrm also need the block present for lookAt.
  tinygltf::Value::Object custom;
  for (const auto& [name, index] : expression_targets) {
    tinygltf::Value::Object bind;
    bind["node"] = tinygltf::Value(0);
    bind["index"] = tinygltf::Value(index);
    bind["weight"] = tinygltf::Value(1.0);
    tinygltf::Value::Object expression;
    expression["morphTargetBinds"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(bind)});
    expression["isBinary"] = tinygltf::Value(false);
    custom[name] = tinygltf::Value(expression);
  }
  tinygltf::Value::Object expressions;
  expressions["preset"] = tinygltf::Value(tinygltf::Value::Object{});
  if (!custom.empty()) expressions["custom"] = tinygltf::Value(custom);
  vrm["expressions"] = tinygltf::Value(expressions);
  return tinygltf::Value(vrm);
}

// VRM 1.0 `lookAt` of type "bone" when the skeleton has both eyes: its origin between the
// eyes, in the head bone's local frame (three-vrm and UniVRM apply it to the head node), and
// the eyes turning at most 10 degrees for a target 90 degrees off (UniVRM's defaults).
std::optional<tinygltf::Value> vrm_look_at(const std::vector<std::string>& names,
                                           const Vertices& joints,
                                           const std::vector<Eigen::Matrix3f>& frames) {
  const auto find = [&](const char* name) {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
  };
  const int head = find("head"), left = find("left_eye_smplhf"), right = find("right_eye_smplhf");
  if (head < 0 || left < 0 || right < 0) return std::nullopt;
  const Eigen::Vector3f between =
      0.5f * (joints.row(left) + joints.row(right)).transpose() - joints.row(head).transpose();
  const Eigen::Vector3f local = frames[static_cast<std::size_t>(head)].transpose() * between;
  tinygltf::Value::Object range;
  range["inputMaxValue"] = tinygltf::Value(90.0);
  range["outputScale"] = tinygltf::Value(10.0);
  tinygltf::Value::Object look;
  look["type"] = str("bone");
  look["offsetFromHeadBone"] = tinygltf::Value(
      tinygltf::Value::Array{tinygltf::Value(double(local.x())), tinygltf::Value(double(local.y())),
                             tinygltf::Value(double(local.z()))});
  for (const char* m : {"rangeMapHorizontalInner", "rangeMapHorizontalOuter",
                        "rangeMapVerticalDown", "rangeMapVerticalUp"})
    look[m] = tinygltf::Value(range);
  return tinygltf::Value(look);
}

// The body's primitives, one per material, sharing the vertices and morph targets: skin on
// the body; the eyeballs white, with a dark iris where they face forward (body/eye_parts.hpp).
// Metallic-roughness PBR factors, no textures.
void add_primitives(tinygltf::Model& doc, BufferBuilder& bb, const Model& model,
                    const SplitMesh& split, const tinygltf::Primitive& shared,
                    tinygltf::Mesh& gmesh) {
  const std::vector<EyePart> parts = eye_parts(model);
  std::array<std::vector<std::uint32_t>, 3> groups;  // skin, eye white, iris
  for (Eigen::Index f = 0; f < split.faces.rows(); ++f) {
    // A face of the eyeball (all three corners): the iris where most of its corners are.
    int eye = 0, iris = 0;
    for (int c = 0; c < 3; ++c) {
      const EyePart p = parts[split.source[split.faces(f, c)]];
      eye += p != EyePart::kSkin;
      iris += p == EyePart::kIris;
    }
    const int group = eye < 3 ? 0 : iris >= 2 ? 2 : 1;
    for (int c = 0; c < 3; ++c) groups[group].push_back(split.faces(f, c));
  }
  struct Look {
    const char* name;
    std::array<double, 4> color;  // linear RGB
    double roughness;
  };
  const Look looks[3] = {{"skin", {0.80, 0.56, 0.45, 1.0}, 0.55},
                         {"eye_white", {0.85, 0.84, 0.80, 1.0}, 0.15},
                         {"eye_iris", {0.09, 0.05, 0.03, 1.0}, 0.1}};
  for (int g = 0; g < 3; ++g) {
    if (groups[g].empty()) continue;
    tinygltf::Material m;
    m.name = looks[g].name;
    m.pbrMetallicRoughness.baseColorFactor = {looks[g].color.begin(), looks[g].color.end()};
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = looks[g].roughness;
    doc.materials.push_back(m);
    tinygltf::Primitive prim = shared;
    prim.material = static_cast<int>(doc.materials.size()) - 1;
    const int view =
        bb.add_view(groups[g].data(), groups[g].size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    prim.indices = bb.add_accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                   groups[g].size());
    gmesh.primitives.push_back(prim);
  }
}

tinygltf::Model build_document(const Model& model, const Eigen::VectorXf& betas_in, FileKind kind,
                               const ExportOptions& options) {
  const Eigen::Index K = model.shapedirs.cols();
  BodyMesh shaped;
  try {
    shaped = evaluate(model, betas_in);
  } catch (const std::invalid_argument& e) {
    throw ExportError(e.what());
  }
  Eigen::VectorXf betas = Eigen::VectorXf::Zero(K);
  betas.head(betas_in.size()) = betas_in;

  const int J = model.joint_count();
  if (J < 1 || static_cast<int>(model.parents.size()) != J ||
      model.weights.rows() != shaped.vertices.rows() || model.weights.cols() != J) {
    throw ExportError("model '" + model.name + "' has an inconsistent skeleton (joints " +
                      std::to_string(J) + ", parents " + std::to_string(model.parents.size()) +
                      ", weights " + std::to_string(model.weights.rows()) + "x" +
                      std::to_string(model.weights.cols()) + ")");
  }
  int root = 0;
  for (int j = 0; j < J; ++j) {
    if (model.parents[static_cast<std::size_t>(j)] < 0) root = j;
  }

  // The rest pose: the model's own, or a T-pose made with the model's own skinning (and pose
  // correctives); the design's mesh and joints in that pose are the file's bind pose.
  const bool t_pose = options.rest_pose == RestPose::t ||
                      (options.rest_pose == RestPose::automatic && kind == FileKind::vrm);
  if (kind == FileKind::vrm && !t_pose) {
    throw ExportError("VRM 1.0 requires a T-pose; use rest pose 't' (or automatic) for .vrm");
  }
  std::optional<Skinning> skin_pose;
  bool correctives = false;
  Vertices rest = shaped.vertices, joints = shaped.joints;
  if (t_pose) {
    Rotations local;
    try {
      local = t_pose_rotations(model, shaped.joints);
    } catch (const ModelError& e) {
      throw ExportError(e.what());
    }
    skin_pose.emplace(model, local);
    Vertices with_correctives = shaped.vertices;
    const Eigen::VectorXf offsets = pose_correctives(model, local);
    if (offsets.size() == 3 * shaped.vertices.rows()) {
      Eigen::Map<Eigen::VectorXf>(with_correctives.data(), offsets.size()) += offsets;
      correctives = true;
    }
    rest = skin_pose->vertices(with_correctives, shaped.joints);
    joints = skin_pose->joints(shaped.joints);
  }
  const float offset = rest.rows() ? -rest.col(1).minCoeff() : 0.0f;
  rest.col(1).array() += offset;
  joints.col(1).array() += offset;
  Vertices normals;
  compute_vertex_normals(rest, model.faces, normals);

  // A shape change (vertex field dv, joint displacement dj) in the rest pose.
  const Eigen::SparseMatrix<float, Eigen::RowMajor> regressor = model.j_regressor.sparseView();
  auto posed_delta = [&](const float* column, const float* joint_column) {
    const Eigen::Map<const Vertices> dv(column, model.vertex_count(), 3);
    if (!skin_pose) return Vertices(dv);
    Vertices dj = joint_column ? Vertices(Eigen::Map<const Vertices>(joint_column, J, 3))
                               : Vertices(regressor * dv);
    return skin_pose->vertices(dv, dj);
  };

  const SplitMesh split = split_along_seams(model);
  const std::size_t V = split.source.size();

  tinygltf::Model doc;
  doc.asset.version = "2.0";
  doc.asset.generator = "Sequential Gallery for body shapes";
  BufferBuilder bb(doc);

  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  {
    const auto pos = gather(rest, split.source);
    prim.attributes["POSITION"] = bb.add_vec3(pos.data(), V, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    const auto nrm = gather(normals, split.source);
    prim.attributes["NORMAL"] = bb.add_vec3(nrm.data(), V, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  }
  if (!split.uv.empty()) {
    const int view =
        bb.add_view(split.uv.data(), split.uv.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["TEXCOORD_0"] =
        bb.add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, V);
  }

  // Skin attributes.
  std::vector<float> wdata(4 * V);
  std::vector<std::uint8_t> j8;
  std::vector<std::uint16_t> j16;
  const bool small = J <= 256;
  (small ? j8.resize(4 * V) : j16.resize(4 * V));
  for (std::size_t v = 0; v < V; ++v) {
    std::array<int, 4> jj;
    std::array<float, 4> ww;
    top4(model.weights, static_cast<Eigen::Index>(split.source[v]), root, jj, ww);
    for (std::size_t k = 0; k < 4; ++k) {
      wdata[4 * v + k] = ww[k];
      if (small) {
        j8[4 * v + k] = static_cast<std::uint8_t>(jj[k]);
      } else {
        j16[4 * v + k] = static_cast<std::uint16_t>(jj[k]);
      }
    }
  }
  {
    const int view = small ? bb.add_view(j8.data(), j8.size(), TINYGLTF_TARGET_ARRAY_BUFFER)
                           : bb.add_view(j16.data(), j16.size() * 2, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["JOINTS_0"] = bb.add_accessor(
        view,
        small ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE : TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
        TINYGLTF_TYPE_VEC4, V);
    const int wview = bb.add_view(wdata.data(), wdata.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["WEIGHTS_0"] =
        bb.add_accessor(wview, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, V);
  }

  tinygltf::Mesh gmesh;
  gmesh.name = model.name.empty() ? "body" : model.name;
  const bool morph = options.morph_targets && K > 0;
  const Eigen::Index E = model.expression_dirs.rows() == 3 * model.v_template.rows()
                             ? model.expression_dirs.cols()
                             : 0;
  std::vector<std::pair<std::string, int>> expression_targets;  // name, morph target index
  if (morph || E > 0) {
    // Every default weight is 0: the base mesh already is the design.
    tinygltf::Value::Array names;
    auto add_target = [&](const Vertices& delta, float scale, const std::string& label) {
      std::vector<float> d = gather(delta, split.source);
      for (auto& x : d) x *= scale;
      std::map<std::string, int> target;
      target["POSITION"] = bb.add_vec3(d.data(), V, TINYGLTF_TARGET_ARRAY_BUFFER, true);
      // The normals' change too, so that shading follows the shape key in engines (a target
      // with positions only keeps the base mesh's normals).
      Vertices moved_normals;
      compute_vertex_normals(Vertices(rest + scale * delta), model.faces, moved_normals);
      const std::vector<float> dn = gather(Vertices(moved_normals - normals), split.source);
      target["NORMAL"] = bb.add_vec3(dn.data(), V, TINYGLTF_TARGET_ARRAY_BUFFER, false);
      prim.targets.push_back(target);
      names.emplace_back(label);
      gmesh.weights.push_back(0.0);
    };
    char label[48];
    const bool joint_cache = model.joint_shapedirs.rows() == 3 * J &&
                             model.joint_shapedirs.cols() == model.shapedirs.cols();
    for (Eigen::Index k = 0; morph && k < K; ++k) {
      const Vertices delta =
          posed_delta(model.shapedirs.col(k).data(),
                      joint_cache ? model.joint_shapedirs.col(k).data() : nullptr);
      if (options.morph_encoding == MorphEncoding::betas) {
        std::snprintf(label, sizeof label, "shape_%02d", static_cast<int>(k));
        add_target(delta, 1.0f, label);
      } else {
        std::snprintf(label, sizeof label, "shape_%02d_pos", static_cast<int>(k));
        add_target(delta, 3.0f, label);
        std::snprintf(label, sizeof label, "shape_%02d_neg", static_cast<int>(k));
        add_target(delta, -3.0f, label);
      }
    }
    for (Eigen::Index e = 0; e < E; ++e) {
      std::snprintf(label, sizeof label, "expr_%02d", static_cast<int>(e));
      expression_targets.emplace_back(label, static_cast<int>(prim.targets.size()));
      add_target(posed_delta(model.expression_dirs.col(e).data(), nullptr), 1.0f, label);
    }
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(names);
    gmesh.extras = tinygltf::Value(extras);
  }
  add_primitives(doc, bb, model, split, prim, gmesh);
  doc.meshes.push_back(gmesh);

  // Skeleton: node 0 is the skinned mesh, nodes 1..J the joints, each rotated so its +Y
  // points along its bone; bind pose = the design in the rest pose.
  std::vector<std::string> names(static_cast<std::size_t>(J));
  for (int j = 0; j < J; ++j) {
    const auto js = static_cast<std::size_t>(j);
    names[js] = js < model.joint_names.size() && !model.joint_names[js].empty()
                    ? model.joint_names[js]
                    : "joint_" + std::to_string(j);
  }
  std::vector<std::string> node_names = names;
  if (options.joint_naming != JointNaming::model) {
    // Every SMPL-family joint gets a name of the engine's style (a model with other joint
    // names keeps those it has no mapping for).
    for (std::size_t j = 0; j < names.size(); ++j) {
      const std::string engine = options.joint_naming == JointNaming::humanoid
                                     ? humanoid_bone_name(names[j])
                                     : unreal_bone_name(names[j]);
      if (!engine.empty()) node_names[j] = engine;
    }
  }
  const std::vector<Eigen::Matrix3f> frames = bone_frames(model.parents, names, joints);

  tinygltf::Value::Object info;
  info["model"] = tinygltf::Value(model.name);
  info["components"] = tinygltf::Value(static_cast<int>(K));
  info["betas"] = number_array(betas);
  info["expressions"] = tinygltf::Value(static_cast<int>(E));
  info["ground_offset_m"] = tinygltf::Value(static_cast<double>(offset));
  info["rest_pose"] = str(t_pose ? (correctives ? "T (model's skinning and pose correctives)"
                                                : "T (model's skinning, no pose correctives)")
                                 : "the model's own");
  info["morph_targets"] =
      str(!morph ? std::string("none (shape baked)")
          : options.morph_encoding == MorphEncoding::betas
              ? std::string("base mesh = the design; shape_NN at weight w adds w to beta NN")
              : std::string("base mesh = the design; shape_NN_pos / _neg at weight w add +3w / -3w "
                            "to beta NN (w = 1: 3 standard deviations)"));
  tinygltf::Node body_node;
  body_node.name = gmesh.name;
  body_node.mesh = 0;
  body_node.skin = 0;
  body_node.extras = tinygltf::Value(info);
  doc.nodes.push_back(body_node);
  for (int j = 0; j < J; ++j) {
    const auto js = static_cast<std::size_t>(j);
    tinygltf::Node n;
    n.name = node_names[js];
    const int p = model.parents[js];
    Eigen::Vector3f t = joints.row(j).transpose();
    Eigen::Matrix3f r = frames[js];
    if (p >= 0) {
      const Eigen::Matrix3f& rp = frames[static_cast<std::size_t>(p)];
      t = rp.transpose() * (t - joints.row(p).transpose());
      r = rp.transpose() * r;
    }
    n.translation = {t.x(), t.y(), t.z()};
    const auto q = quaternion_of(r);
    n.rotation = {q[0], q[1], q[2], q[3]};
    doc.nodes.push_back(n);
  }
  for (int j = 0; j < J; ++j) {
    const int p = model.parents[static_cast<std::size_t>(j)];
    if (p >= 0) doc.nodes[static_cast<std::size_t>(1 + p)].children.push_back(1 + j);
  }
  // Inverse bind matrix = inverse of the joint's rest world transform [R | p]: [R^T | -R^T p].
  // The rotations are written as quaternions above, so the matrices are built from the same
  // (normalised) quaternions chained down the hierarchy to match what clients compute.
  std::vector<Eigen::Matrix3f> world(static_cast<std::size_t>(J));
  std::vector<Eigen::Vector3f> world_t(static_cast<std::size_t>(J));
  {
    std::vector<char> done(static_cast<std::size_t>(J), 0);
    std::function<void(int)> resolve = [&](int j) {
      const auto js = static_cast<std::size_t>(j);
      if (done[js]) return;
      const auto& n = doc.nodes[1 + js];
      const Eigen::Matrix3f r =
          Eigen::Quaternionf(static_cast<float>(n.rotation[3]), static_cast<float>(n.rotation[0]),
                             static_cast<float>(n.rotation[1]), static_cast<float>(n.rotation[2]))
              .toRotationMatrix();
      const Eigen::Vector3f t(static_cast<float>(n.translation[0]),
                              static_cast<float>(n.translation[1]),
                              static_cast<float>(n.translation[2]));
      const int p = model.parents[js];
      if (p < 0) {
        world[js] = r;
        world_t[js] = t;
      } else {
        resolve(p);
        world[js] = world[static_cast<std::size_t>(p)] * r;
        world_t[js] = world_t[static_cast<std::size_t>(p)] + world[static_cast<std::size_t>(p)] * t;
      }
      done[js] = 1;
    };
    for (int j = 0; j < J; ++j) resolve(j);
  }
  std::vector<float> ibm(16 * static_cast<std::size_t>(J), 0.0f);
  for (int j = 0; j < J; ++j) {
    const auto js = static_cast<std::size_t>(j);
    Eigen::Matrix4f inv = Eigen::Matrix4f::Identity();
    inv.topLeftCorner<3, 3>() = world[js].transpose();
    inv.topRightCorner<3, 1>() = -(world[js].transpose() * world_t[js]);
    std::memcpy(ibm.data() + 16 * js, inv.data(), 16 * sizeof(float));  // column-major
  }
  tinygltf::Skin skin;
  skin.name = "skeleton";
  skin.skeleton = 1 + root;
  for (int j = 0; j < J; ++j) skin.joints.push_back(1 + j);
  skin.inverseBindMatrices =
      bb.add_accessor(bb.add_view(ibm.data(), ibm.size() * 4, 0), TINYGLTF_COMPONENT_TYPE_FLOAT,
                      TINYGLTF_TYPE_MAT4, static_cast<std::size_t>(J));
  doc.skins.push_back(skin);

  tinygltf::Scene scene;
  scene.name = "body";
  scene.nodes = {0, 1 + root};
  doc.scenes.push_back(scene);
  doc.defaultScene = 0;
  doc.asset.extras = tinygltf::Value(info);
  if (kind == FileKind::vrm) {
    doc.extensionsUsed.push_back("VRMC_vrm");
    doc.extensions["VRMC_vrm"] = vrm_extension(
        model, names, options, vrm_look_at(names, joints, frames), expression_targets);
  }
  return doc;
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

int morph_target_count(const Model& model, const ExportOptions& options) {
  const int K = model.component_count();
  const int shape = !options.morph_targets                           ? 0
                    : options.morph_encoding == MorphEncoding::betas ? K
                                                                     : 2 * K;
  const bool expressions = model.expression_dirs.rows() == 3 * model.v_template.rows();
  return shape + (expressions ? static_cast<int>(model.expression_dirs.cols()) : 0);
}

std::string export_gltf_bytes(const Model& model, const Eigen::VectorXf& betas, FileKind kind,
                              const ExportOptions& options) {
  tinygltf::Model doc = build_document(model, betas, kind, options);
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  const bool binary = kind != FileKind::gltf;
  bool written = false;
  try {
    written = writer.WriteGltfSceneToStream(&doc, out, !binary, binary);
  } catch (const std::exception& e) {  // the JSON library refuses e.g. text that is not UTF-8
    throw ExportError(std::string("the document could not be serialised: ") + e.what());
  }
  if (!written) {
    throw ExportError("tinygltf could not serialise the document");
  }
  return out.str();
}

void export_gltf(const Model& model, const Eigen::VectorXf& betas,
                 const std::filesystem::path& path, const ExportOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext != ".glb" && ext != ".gltf" && ext != ".vrm") {
    throw ExportError(path.string() + ": unknown extension '" + ext +
                      "' (use .glb for binary glTF, .gltf for JSON or .vrm for a VRM 1.0 avatar)");
  }
  const FileKind kind = ext == ".glb"    ? FileKind::glb
                        : ext == ".gltf" ? FileKind::gltf
                                         : FileKind::vrm;
  std::string bytes;
  try {
    bytes = export_gltf_bytes(model, betas, kind, options);
  } catch (const ExportError& e) {
    throw ExportError(path.string() + ": " + e.what());
  }
  try {
    write_file_atomically(path, bytes);
  } catch (const FileWriteError& e) {
    throw ExportError(e.what());
  }
}

}  // namespace body
