#include "body/model_loader.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "body/joint_names.hpp"
#include "body/model_validation.hpp"
#include "body/npz_reader.hpp"
#include "util/utf8.hpp"

#if defined(SG_HAVE_DEFAULT_MODEL)
extern "C" const unsigned char sg_model_female_begin[];
extern "C" const unsigned char sg_model_female_end[];
extern "C" const unsigned char sg_model_male_begin[];
extern "C" const unsigned char sg_model_male_end[];
extern "C" const unsigned char sg_model_neutral_begin[];
extern "C" const unsigned char sg_model_neutral_end[];
#endif

namespace body {

namespace {

// A built-in model's `source` (and the name its errors carry): "<embedded NAME>".
std::string embedded_source(const std::string& name) {
  return "<embedded " + name + ">";
}

constexpr std::int64_t kRootParentU32 = 4294967295LL;  // -1 stored as uint32

std::vector<int> read_parents(const NpzArchive& npz, long long joints) {
  const std::string name = "kintree_table";
  const NpyArray a = read_required_array(npz, name);
  require_shape(npz, name, a.header, {2, joints}, "(2, J) with J = " + std::to_string(joints));
  const auto v = integer_values(npz, name, a);
  const auto J = static_cast<std::size_t>(joints);
  // Row 0: parent ids; row 1: the joint ids (normally 0..J-1).
  std::vector<int> parents(J, -2);
  for (std::size_t i = 0; i < J; ++i) {
    const std::int64_t id = v[J + i];
    std::int64_t parent = v[i];
    if (id < 0 || id >= joints) {
      fail_array(npz, name,
                 "joint id " + std::to_string(id) + " at index (1, " + std::to_string(i) +
                     ") is out of range [0, " + std::to_string(joints) + ")");
    }
    if (parents[static_cast<std::size_t>(id)] != -2) {
      fail_array(npz, name, "joint id " + std::to_string(id) + " appears twice in row 1");
    }
    if (parent == kRootParentU32 || parent == -1) {
      parent = -1;
    } else if (parent < 0 || parent >= joints) {
      fail_array(npz, name,
                 "parent " + std::to_string(parent) + " of joint " + std::to_string(id) +
                     " is out of range (root parent is -1 or " + "4294967295)");
    }
    parents[static_cast<std::size_t>(id)] = static_cast<int>(parent);
  }
  int roots = 0;
  for (std::size_t j = 0; j < J; ++j) {
    if (parents[j] == -1) ++roots;
    // Walk to the root; more than J steps means a cycle.
    int k = static_cast<int>(j);
    std::size_t steps = 0;
    while (k >= 0 && steps <= J) {
      k = parents[static_cast<std::size_t>(k)];
      ++steps;
    }
    if (steps > J) {
      fail_array(npz, name, "the joint hierarchy has a cycle through joint " + std::to_string(j));
    }
  }
  if (roots != 1) {
    fail_array(npz, name,
               "the joint hierarchy must have exactly one root, found " + std::to_string(roots));
  }
  return parents;
}

std::vector<std::string> read_joint_names(const NpzArchive& npz, std::size_t J) {
  if (const auto* builtin = builtin_joint_names(J); builtin && !npz.contains("joint_names")) {
    return *builtin;
  }
  std::vector<std::string> names;
  if (npz.contains("joint_names")) {
    const NpyArray a = npz.read("joint_names");
    if (a.header.kind != 'S' && a.header.kind != 'U') {
      fail_array(npz, "joint_names",
                 "must be an array of strings, found dtype " + a.header.dtype_name());
    }
    if (a.header.shape.size() != 1 || a.header.shape[0] != J) {
      fail_array(
          npz, "joint_names",
          "wrong shape: expected (" + std::to_string(J) + ",), found " + a.header.shape_string());
    }
    names = a.to_strings();
  }
  // Names go into glTF (JSON) and the window: invalid bytes become U+FFFD here, once.
  for (auto& n : names) n = util::to_valid_utf8(n);
  for (std::size_t j = 0; j < J; ++j) {
    if (names.size() <= j) names.push_back("joint_" + std::to_string(j));
    if (names[j].empty()) names[j] = "joint_" + std::to_string(j);
  }
  return names;
}

// SMPL-X (55 joints) stores its expression components after the shape components in
// `shapedirs`: 300 + 100 in v1.1 (400 columns), 10 + 10 in v1.0 (20 columns). Any other
// skeleton has shape components only.
long long shape_columns(const NpzArchive& npz, long long joints, long long columns) {
  if (joints != 55) return columns;
  // A 55-joint file that says how many shape components it has (the built-in models'
  // variance_share, one entry per component) is believed; it is checked against (K,) when read.
  if (npz.contains("variance_share")) {
    const NpyHeader h = npz.header("variance_share");
    if (!h.needs_pickle() && h.shape.size() == 1 && h.shape[0] >= 1 &&
        static_cast<long long>(h.shape[0]) <= columns)
      return static_cast<long long>(h.shape[0]);
  }
  return columns > 300 ? 300 : (columns + 1) / 2;
}

using RowMat = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Reads `posedirs` (V x 3 x P -> 3V x P, row 3v + axis) into `out`, or only checks every value
// when `out` is null; returns P (0 if there are none or they need pickle).
long long read_posedirs(const NpzArchive& npz, long long V, Eigen::MatrixXf* out) {
  if (!npz.contains("posedirs")) return 0;
  const NpyHeader h = npz.header("posedirs");
  if (h.needs_pickle()) return 0;
  require_shape(npz, "posedirs", h, {V, 3, -1},
                "(V, 3, P) with V = " + std::to_string(V) + " from v_template");
  // Straight into the matrix: as large as a shape basis, with no copies on the way.
  read_finite_columns(npz, "posedirs", h, {{0, h.shape[2], out}});
  return static_cast<long long>(h.shape[2]);
}

// The joint count J_regressor's header gives, or -1 if it cannot say; only a guide for which
// shapedirs columns to read (J_regressor itself is checked in full later).
long long peek_joint_count(const NpzArchive& npz) {
  if (!npz.contains("J_regressor")) return -1;
  try {
    const NpyHeader h = npz.header("J_regressor");
    if (h.needs_pickle() || h.shape.size() != 2) return -1;
    return static_cast<long long>(h.shape[0]);
  } catch (const ModelError&) {
    return -1;
  }
}

void read_optional_arrays(const NpzArchive& npz, Model& m) {
  if (npz.contains("vt") != npz.contains("ft")) {
    fail_array(npz, npz.contains("vt") ? "vt" : "ft",
               "texture coordinates need both 'vt' (T, 2) and 'ft' (F, 3); the other is missing");
  }
  if (npz.contains("vt")) {
    const NpyArray vt = npz.read("vt");
    const NpyArray ft = npz.read("ft");
    if (vt.header.needs_pickle() || ft.header.needs_pickle()) return;
    require_shape(npz, "vt", vt.header, {-1, 2}, "(T, 2)");
    const long long T = static_cast<long long>(vt.header.shape[0]);
    if (T < 1) fail_array(npz, "vt", "has no texture coordinates");
    require_shape(npz, "ft", ft.header, {m.faces.rows(), 3},
                  "(F, 3) with F = " + std::to_string(m.faces.rows()) + " from f");
    const auto uv = finite_floats(npz, "vt", vt);
    const auto idx = integer_values(npz, "ft", ft);
    m.uvs =
        Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, 2, Eigen::RowMajor>>(uv.data(), T, 2);
    m.uv_faces.resize(m.faces.rows(), 3);
    for (std::size_t i = 0; i < idx.size(); ++i) {
      if (idx[i] < 0 || idx[i] >= T) {
        fail_array(npz, "ft",
                   "texture index " + std::to_string(idx[i]) + " at " +
                       index_string(ft.header.shape, i) + " is out of range [0, " +
                       std::to_string(T) + ")");
      }
      m.uv_faces.data()[i] = static_cast<std::uint32_t>(idx[i]);
    }
  }
}

// `check_all`: also check the shapedirs columns that are not kept (for `inspect`, which keeps
// one column but answers for them all).
Model load_from_archive(const NpzArchive& npz, int components, const std::string& model_name,
                        int expressions, bool check_all = false) {
  if (expressions < 0) {
    throw ModelError(npz.label() + ": the number of expression components must be >= 0, got " +
                     std::to_string(expressions));
  }
  if (components < 0) {
    throw ModelError(npz.label() + ": the number of shape components must be >= 0 (0 = all), got " +
                     std::to_string(components));
  }
  Model m;
  m.name = util::to_valid_utf8(model_name);  // file names need not be UTF-8
  m.source = util::to_valid_utf8(npz.label());

  // v_template (V x 3)
  NpyArray a = read_required_array(npz, "v_template");
  require_shape(npz, "v_template", a.header, {-1, 3}, "(V, 3)");
  const long long V = static_cast<long long>(a.header.shape[0]);
  if (V < 3) fail_array(npz, "v_template", "needs at least 3 vertices, found " + std::to_string(V));
  {
    const auto v = finite_floats(npz, "v_template", a);
    m.v_template = Eigen::Map<const Vertices>(v.data(), V, 3);
  }
  const std::string vdesc = " with V = " + std::to_string(V) + " from v_template";

  // shapedirs (V x 3 x K) -> 3V x K, row 3v + axis. Only the kept columns are read and
  // converted (SMPL-X has 400, a search uses 10); which ones depends on whether this is SMPL-X
  // (shape + expressions), which J_regressor's joint count says.
  const NpyHeader sd = read_required_header(npz, "shapedirs");
  require_shape(npz, "shapedirs", sd, {V, 3, -1}, "(V, 3, K)" + vdesc);
  const long long columns = static_cast<long long>(sd.shape[2]);
  if (columns < 1) fail_array(npz, "shapedirs", "has no shape components (K = 0)");
  const long long peeked_joints = peek_joint_count(npz);
  const long long K = shape_columns(npz, peeked_joints, columns);
  m.total_components = static_cast<int>(K);
  m.total_expressions = static_cast<int>(columns - K);
  const long long keep = (components == 0 || components > K) ? K : components;
  const long long keep_expr = std::min<long long>(expressions, columns - K);
  {
    const auto u = [](long long v) { return static_cast<std::size_t>(v); };
    std::vector<ColumnSlice> slices = {{0, u(keep), &m.shapedirs}};
    if (check_all) {
      slices.push_back({u(keep), u(columns - keep), nullptr});
    } else {
      slices.push_back({u(K), u(keep_expr), &m.expression_dirs});
    }
    read_finite_columns(npz, "shapedirs", sd, slices);
  }

  // f (F x 3), indices in [0, V)
  a = read_required_array(npz, "f");
  require_shape(npz, "f", a.header, {-1, 3}, "(F, 3)");
  const long long F = static_cast<long long>(a.header.shape[0]);
  if (F < 1) fail_array(npz, "f", "has no faces");
  {
    const auto f = integer_values(npz, "f", a);
    m.faces.resize(F, 3);
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (f[i] < 0 || f[i] >= V) {
        fail_array(npz, "f",
                   "face index " + std::to_string(f[i]) + " at " + index_string(a.header.shape, i) +
                       " is out of range [0, " + std::to_string(V) + ")");
      }
      m.faces.data()[i] = static_cast<std::uint32_t>(f[i]);
    }
  }

  // J_regressor (J x V), dense
  a = read_required_array(npz, "J_regressor");
  require_shape(npz, "J_regressor", a.header, {-1, V}, "(J, V)" + vdesc);
  const long long J = static_cast<long long>(a.header.shape[0]);
  if (J < 1) fail_array(npz, "J_regressor", "has no joints");
  // The same header as peeked above (a J_regressor it could not read failed just now).
  if (J != peeked_joints) throw std::logic_error("load_model: J_regressor's joint count changed");
  {
    const auto jr = finite_floats(npz, "J_regressor", a);
    m.j_regressor = Eigen::Map<const RowMat>(jr.data(), J, V);
  }

  // weights (V x J)
  a = read_required_array(npz, "weights");
  require_shape(npz, "weights", a.header, {V, J},
                "(V, J)" + vdesc + " and J = " + std::to_string(J) + " from J_regressor");
  {
    const auto w = finite_floats(npz, "weights", a);
    m.weights = Eigen::Map<const RowMat>(w.data(), V, J);
  }
  a = NpyArray{};

  m.parents = read_parents(npz, J);
  m.joint_names = read_joint_names(npz, static_cast<std::size_t>(J));
  read_optional_arrays(npz, m);

  // Optional: variance_share (K,)
  if (npz.contains("variance_share")) {
    const NpyArray vs = npz.read("variance_share");
    if (!vs.header.needs_pickle()) {
      require_shape(npz, "variance_share", vs.header, {K}, "(K,) with K = " + std::to_string(K));
      const auto v = finite_floats(npz, "variance_share", vs);
      m.variance_share = Eigen::Map<const Eigen::VectorXf>(v.data(), K).head(keep);
    }
  }
  m.prepare();
  return m;
}

}  // namespace

void load_pose_correctives(Model& model) {
  if (model.posedirs.size() > 0) return;
  // A built-in model reads them from the embedded bytes, a file's from the file; models from
  // memory have none to read.
  for (const std::string& name : builtin_model_names())
    if (model.source == embedded_source(name)) {
      read_posedirs(open_builtin_model_archive(name), model.vertex_count(), &model.posedirs);
      return;
    }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(model.source, ec)) return;
  const NpzArchive npz = NpzArchive::open_file(model.source);
  read_posedirs(npz, model.vertex_count(), &model.posedirs);
}

ModelCheck check_model(const std::string& name_or_path) {
  ModelCheck out;
  if (name_or_path.empty() || is_builtin_model_name(name_or_path)) {
    const std::string name = name_or_path.empty() ? "neutral" : name_or_path;
    const NpzArchive npz = open_builtin_model_archive(name);
    out.model = load_from_archive(npz, 1, name, 0, true);
    out.model.name = name;
    out.pose_columns = static_cast<int>(read_posedirs(npz, out.model.vertex_count(), nullptr));
    return out;
  }
  const std::filesystem::path path(name_or_path);
  const NpzArchive npz = NpzArchive::open_file(path);
  out.model = load_from_archive(npz, 1, path.stem().string(), 0, true);
  out.pose_columns = static_cast<int>(read_posedirs(npz, out.model.vertex_count(), nullptr));
  return out;
}

Model load_model(const std::filesystem::path& path, int components, int expressions) {
  // A built-in model's name stands for that model unless a file of that name exists (sessions
  // and the window store the --model text as a path).
  if (is_builtin_model_name(path.string()) && !std::filesystem::exists(path))
    return load_builtin_model(path.string(), components);
  const NpzArchive npz = NpzArchive::open_file(path);
  return load_from_archive(npz, components, path.stem().string(), expressions);
}
Model load_model_from_memory(const void* data, std::size_t size, const std::string& label,
                             int components, int expressions) {
  const NpzArchive npz = NpzArchive::open_memory(data, size, label);
  std::string name = std::filesystem::path(label).stem().string();
  if (name.empty()) name = label;
  return load_from_archive(npz, components, name, expressions);
}

const std::vector<std::string>& builtin_model_names() {
  static const std::vector<std::string> names = {"female", "male", "neutral"};
  return names;
}

bool is_builtin_model_name(const std::string& name) {
  const auto& names = builtin_model_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

NpzArchive open_builtin_model_archive(const std::string& name) {
  if (!is_builtin_model_name(name)) {
    throw ModelError("'" + name + "' is not a built-in body model (built in: female, male, " +
                     "neutral)");
  }
#if defined(SG_HAVE_DEFAULT_MODEL)
  const unsigned char* begin = sg_model_neutral_begin;
  const unsigned char* end = sg_model_neutral_end;
  if (name == "female") {
    begin = sg_model_female_begin;
    end = sg_model_female_end;
  } else if (name == "male") {
    begin = sg_model_male_begin;
    end = sg_model_male_end;
  }
  return NpzArchive::open_memory(begin, static_cast<std::size_t>(end - begin),
                                 embedded_source(name));
#else
  throw ModelError(embedded_source(name) + ": the default models were not built in (assets/body_" +
                   name +
                   ".npz did not exist when the project was configured; generate them with "
                   "`sequential-gallery generate-default-model` and re-run cmake, or pass "
                   "--model FILE)");
#endif
}

Model load_builtin_model(const std::string& name, int components) {
  const NpzArchive npz = open_builtin_model_archive(name);
  Model m = load_from_archive(npz, components, name, 0);
  m.name = name;
  return m;
}

Model resolve_model(const std::string& name_or_path, int components) {
  if (name_or_path.empty()) return load_default_model(components);
  if (is_builtin_model_name(name_or_path)) return load_builtin_model(name_or_path, components);
  return load_model(name_or_path, components);
}

Model load_default_model(int components) {
  return load_builtin_model("neutral", components);
}

}  // namespace body
