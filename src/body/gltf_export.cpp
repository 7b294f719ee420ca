// glTF 2.0 writer for one body: a skinned mesh with the model's skeleton, optional morph
// targets for the shape components, metres, +Y up, facing +Z, feet on y = 0.
#include "body/gltf_export.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <numeric>
#include <sstream>

#include "body/atomic_file.hpp"

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

tinygltf::Model build_document(const Model& model, const Eigen::VectorXf& betas_in,
                               const ExportOptions& options) {
  const Eigen::Index K = model.shapedirs.cols();
  BodyMesh mesh;
  try {
    mesh = evaluate(model, betas_in);
  } catch (const std::invalid_argument& e) {
    throw ExportError(e.what());
  }
  const float offset = place_on_ground(mesh);
  Eigen::VectorXf betas = Eigen::VectorXf::Zero(K);
  betas.head(betas_in.size()) = betas_in;

  const auto V = static_cast<std::size_t>(mesh.vertices.rows());
  const int J = model.joint_count();
  if (J < 1 || static_cast<int>(model.parents.size()) != J ||
      model.weights.rows() != mesh.vertices.rows() || model.weights.cols() != J) {
    throw ExportError("model '" + model.name + "' has an inconsistent skeleton (joints " +
                      std::to_string(J) + ", parents " + std::to_string(model.parents.size()) +
                      ", weights " + std::to_string(model.weights.rows()) + "x" +
                      std::to_string(model.weights.cols()) + ")");
  }
  int root = 0;
  for (int j = 0; j < J; ++j) {
    if (model.parents[static_cast<std::size_t>(j)] < 0) root = j;
  }

  tinygltf::Model doc;
  doc.asset.version = "2.0";
  doc.asset.generator = "Sequential Gallery for body shapes";
  BufferBuilder bb(doc);

  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  const bool morph = options.morph_targets && K > 0;
  if (morph) {
    // Base = template (grounded with this body's offset); the weights (= betas) add the shape.
    Vertices base = model.v_template;
    base.col(1).array() += offset;
    prim.attributes["POSITION"] = bb.add_vec3(base.data(), V, TINYGLTF_TARGET_ARRAY_BUFFER, true);
  } else {
    prim.attributes["POSITION"] =
        bb.add_vec3(mesh.vertices.data(), V, TINYGLTF_TARGET_ARRAY_BUFFER, true);
  }
  prim.attributes["NORMAL"] =
      bb.add_vec3(mesh.normals.data(), V, TINYGLTF_TARGET_ARRAY_BUFFER, false);

  // Skin attributes.
  std::vector<float> wdata(4 * V);
  std::vector<std::uint8_t> j8;
  std::vector<std::uint16_t> j16;
  const bool small = J <= 256;
  (small ? j8.resize(4 * V) : j16.resize(4 * V));
  for (std::size_t v = 0; v < V; ++v) {
    std::array<int, 4> jj;
    std::array<float, 4> ww;
    top4(model.weights, static_cast<Eigen::Index>(v), root, jj, ww);
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
  {
    const int view =
        bb.add_view(model.faces.data(), static_cast<std::size_t>(model.faces.size()) * 4,
                    TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    prim.indices = bb.add_accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                   static_cast<std::size_t>(model.faces.size()));
  }

  tinygltf::Mesh gmesh;
  gmesh.name = model.name.empty() ? "body" : model.name;
  if (morph) {
    tinygltf::Value::Array names;
    auto add_target = [&](const float* data, const char* suffix, Eigen::Index k, double w) {
      std::map<std::string, int> target;
      target["POSITION"] = bb.add_vec3(data, V, TINYGLTF_TARGET_ARRAY_BUFFER, true);
      prim.targets.push_back(target);
      char label[48];
      std::snprintf(label, sizeof label, "shape_%02d%s", static_cast<int>(k), suffix);
      names.emplace_back(std::string(label));
      gmesh.weights.push_back(w);
    };
    Eigen::VectorXf scaled(3 * static_cast<Eigen::Index>(V));
    for (Eigen::Index k = 0; k < K; ++k) {
      const double b = betas[k];
      if (options.morph_encoding == MorphEncoding::betas) {
        add_target(model.shapedirs.col(k).data(), "", k, b);
      } else {
        scaled = 3.0f * model.shapedirs.col(k);
        add_target(scaled.data(), "_pos", k, b > 0.0 ? b / 3.0 : 0.0);
        scaled = -scaled;
        add_target(scaled.data(), "_neg", k, b < 0.0 ? -b / 3.0 : 0.0);
      }
    }
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(names);
    gmesh.extras = tinygltf::Value(extras);
  }
  gmesh.primitives.push_back(prim);
  doc.meshes.push_back(gmesh);

  // Skeleton: node 0 is the skinned mesh, nodes 1..J the joints (bind pose = this body).
  tinygltf::Value::Object info;
  info["model"] = tinygltf::Value(model.name);
  info["components"] = tinygltf::Value(static_cast<int>(K));
  info["betas"] = number_array(betas);
  info["ground_offset_m"] = tinygltf::Value(static_cast<double>(offset));
  info["morph_targets"] = tinygltf::Value(
      !morph ? std::string("none (shape baked)")
      : options.morph_encoding == MorphEncoding::betas
          ? std::string("one per component, weight = beta")
          : std::string("shape_NN_pos/_neg = +-3 sigma, weight = max(+-beta, 0) / 3"));
  tinygltf::Node body_node;
  body_node.name = gmesh.name;
  body_node.mesh = 0;
  body_node.skin = 0;
  body_node.extras = tinygltf::Value(info);
  doc.nodes.push_back(body_node);
  for (int j = 0; j < J; ++j) {
    tinygltf::Node n;
    n.name = static_cast<std::size_t>(j) < model.joint_names.size()
                 ? model.joint_names[static_cast<std::size_t>(j)]
                 : "joint_" + std::to_string(j);
    const int p = model.parents[static_cast<std::size_t>(j)];
    Eigen::Vector3f t = mesh.joints.row(j).transpose();
    if (p >= 0) t -= mesh.joints.row(p).transpose();
    n.translation = {t.x(), t.y(), t.z()};
    doc.nodes.push_back(n);
  }
  for (int j = 0; j < J; ++j) {
    const int p = model.parents[static_cast<std::size_t>(j)];
    if (p >= 0) doc.nodes[static_cast<std::size_t>(1 + p)].children.push_back(1 + j);
  }
  std::vector<float> ibm(16 * static_cast<std::size_t>(J), 0.0f);
  for (int j = 0; j < J; ++j) {
    float* m = ibm.data() + 16 * j;
    m[0] = m[5] = m[10] = m[15] = 1.0f;  // column-major: translation in m[12..14]
    m[12] = -mesh.joints(j, 0);
    m[13] = -mesh.joints(j, 1);
    m[14] = -mesh.joints(j, 2);
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
  return doc;
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

std::string export_gltf_bytes(const Model& model, const Eigen::VectorXf& betas, bool binary,
                              const ExportOptions& options) {
  tinygltf::Model doc = build_document(model, betas, options);
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&doc, out, !binary, binary)) {
    throw ExportError("tinygltf could not serialise the document");
  }
  return out.str();
}

void export_gltf(const Model& model, const Eigen::VectorXf& betas,
                 const std::filesystem::path& path, const ExportOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext != ".glb" && ext != ".gltf") {
    throw ExportError(path.string() + ": unknown extension '" + ext +
                      "' (use .glb for binary glTF or .gltf for JSON)");
  }
  std::string bytes;
  try {
    bytes = export_gltf_bytes(model, betas, ext == ".glb", options);
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
