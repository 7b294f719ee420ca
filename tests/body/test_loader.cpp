// Loading SMPL-layout .npz models: every storage variant, and a clear error for every kind of
// broken file (naming the file, the array and the problem).
#include <catch2/catch.hpp>

#include "common/first_difference.hpp"

#include <cmath>
#include <fstream>
#include <limits>

#include "body/gltf_export.hpp"
#include "body/model_loader.hpp"
#include "body/npz_reader.hpp"
#include "npz_fixtures.hpp"
#include "util/utf8.hpp"

using Catch::Contains;
using fixtures::Array;
using fixtures::Dtype;

namespace {

using ArrayMap = std::map<std::string, Array>;

std::filesystem::path write_model(const std::string& name, const ArrayMap& arrays,
                                  const fixtures::Encoding& enc = {}, bool float64 = false,
                                  bool compressed = false) {
  const auto path = fixtures::scratch_dir("loader") / (name + ".npz");
  fixtures::write_npz(path, fixtures::encode_model(arrays, enc, float64), compressed);
  return path;
}

void check_same(const body::Model& a, const body::Model& b) {
  CHECK(a.v_template.isApprox(b.v_template, 1e-6f));
  CHECK(a.shapedirs.isApprox(b.shapedirs, 1e-6f));
  REQUIRE(a.faces.rows() == b.faces.rows());
  CHECK((a.faces.array() == b.faces.array()).all());
  CHECK(a.j_regressor.isApprox(b.j_regressor, 1e-6f));
  CHECK(a.weights.isApprox(b.weights, 1e-6f));
  CHECK(test_support::first_difference_in(a.parents, b.parents) == "");
  CHECK(test_support::first_difference_in(a.joint_names, b.joint_names) == "");
}

// Loading must fail with a ModelError whose message contains all the given parts.
void expect_error(const std::filesystem::path& path, const std::vector<std::string>& parts) {
  try {
    body::load_model(path);
    FAIL("loading " << path << " did not fail");
  } catch (const body::ModelError& e) {
    const std::string msg = e.what();
    INFO("message: " << msg);
    CHECK(msg.find(path.string()) != std::string::npos);
    for (const auto& p : parts) CHECK(msg.find(p) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("loader: the cylinder fixture loads with the SMPL layout", "[loader]") {
  const auto arrays = fixtures::cylinder_model();
  const auto m = body::load_model(write_model("plain", arrays));
  const int V = 32 * 41 + 2;
  CHECK(m.vertex_count() == V);
  CHECK(m.component_count() == 10);
  CHECK(m.total_components == 10);
  CHECK(m.joint_count() == 24);
  CHECK(m.faces.rows() == 2 * 32 * 40 + 2 * 32);
  CHECK(m.parents == std::vector<int>{-1, 0, 0, 0,  1,  2,  3,  4,  5,  6,  7,  8,
                                      9,  9, 9, 12, 13, 14, 16, 17, 18, 19, 20, 21});
  CHECK(m.joint_names.front() == "pelvis");
  CHECK(m.joint_names.back() == "right_hand");
  CHECK(m.name == "plain");
  // Spot values: vertex 5 and shapedirs (v = 5, axis 0, component 0) = x of vertex 5.
  const auto& vt = arrays.at("v_template").values;
  CHECK(m.v_template(5, 0) == Approx(vt[15]));
  CHECK(m.v_template(5, 2) == Approx(vt[17]));
  CHECK(m.shapedirs(3 * 5 + 0, 0) == Approx(vt[15]));
  CHECK(m.shapedirs(3 * 5 + 1, 1) == Approx(vt[16] + 1.0));  // y - base_y, base_y = -1
  CHECK(m.j_regressor.row(3).sum() == Approx(1.0f));
}

TEST_CASE("loader: compressed, float64, Fortran, big-endian and memory variants agree",
          "[loader]") {
  const auto arrays = fixtures::cylinder_model();
  const auto ref = body::load_model(write_model("ref", arrays));
  check_same(body::load_model(write_model("deflate", arrays, {}, false, true)), ref);
  check_same(body::load_model(write_model("f8", arrays, {}, true)), ref);
  check_same(body::load_model(write_model("fortran", arrays, {false, true})), ref);
  check_same(body::load_model(write_model("big", arrays, {true, false})), ref);
  check_same(body::load_model(write_model("all", arrays, {true, true}, true, true)), ref);
  const auto bytes = fixtures::read_file(write_model("mem", arrays, {}, false, true));
  const auto mem = body::load_model_from_memory(bytes.data(), bytes.size(), "in-memory.npz");
  check_same(mem, ref);
  CHECK(mem.source == "in-memory.npz");
}

TEST_CASE("loader: int32/int64/uint64 faces and uint32 root parent", "[loader]") {
  auto arrays = fixtures::cylinder_model();
  const auto ref = body::load_model(write_model("ref2", arrays));
  for (Dtype d : {Dtype::i4, Dtype::i8, Dtype::u8}) {
    arrays["f"].dtype = d;
    check_same(body::load_model(write_model("faces", arrays)), ref);
  }
  arrays["kintree_table"].dtype = Dtype::u4;
  arrays["kintree_table"].values[0] = 4294967295.0;
  CHECK(body::load_model(write_model("u32root", arrays)).parents[0] == -1);
}

TEST_CASE("loader: component count is the user's choice", "[loader]") {
  fixtures::Cylinder c;
  c.components = 16;
  const auto path = write_model("k16", fixtures::cylinder_model(c));
  CHECK(body::load_model(path).component_count() == 10);  // default: the paper's 10
  CHECK(body::load_model(path, 4).component_count() == 4);
  CHECK(body::load_model(path, 0).component_count() == 16);
  CHECK(body::load_model(path, 300).component_count() == 16);
  CHECK(body::load_model(path, 4).total_components == 16);
  const auto full = body::load_model(path, 0);
  CHECK(body::load_model(path, 4).shapedirs.isApprox(full.shapedirs.leftCols(4)));
  CHECK_THROWS_WITH(body::load_model(path, -1), Contains(">= 0"));
}

TEST_CASE("loader: object arrays and extra arrays are skipped, optional arrays used", "[loader]") {
  auto arrays = fixtures::cylinder_model();
  auto entries = fixtures::encode_model(arrays);
  entries.push_back({"joint2num", fixtures::encode_npy_raw("|O", "()", false, "\x80\x02}q\x00.")});
  entries.push_back({"lmk_faces_idx", fixtures::encode_npy({{2, 2}, {1, 2, 3, 4}, Dtype::f8})});
  entries.push_back(
      {"variance_share",
       fixtures::encode_npy({{10}, {.3, .2, .1, .1, .1, .05, .05, .04, .03, .03}, Dtype::f8})});
  const auto path = fixtures::scratch_dir("loader-extra") / "extra.npz";
  fixtures::write_npz(path, entries);
  const auto m = body::load_model(path, 4);
  REQUIRE(m.variance_share.size() == 4);
  CHECK(m.variance_share[0] == Approx(0.3));
  CHECK(m.posedirs.size() == 0);
  CHECK(m.uvs.rows() == 0);

  // Optional arrays the exporter uses (posedirs for a T-pose, vt/ft for UVs) are checked.
  auto bad = entries;
  bad.push_back({"posedirs", fixtures::encode_npy({{2, 2}, {1, 2, 3, 4}, Dtype::f8})});
  fixtures::write_npz(path, bad);
  auto loaded = body::load_model(path);  // posedirs are read on demand only
  CHECK_THROWS_WITH(body::load_pose_correctives(loaded),
                    Contains("extra.npz") && Contains("'posedirs'") && Contains("(V, 3, P)"));
  bad = entries;
  bad.push_back({"vt", fixtures::encode_npy({{2, 2}, {0, 0, 1, 1}, Dtype::f4})});
  fixtures::write_npz(path, bad);
  CHECK_THROWS_WITH(body::load_model(path), Contains("'vt'") && Contains("'ft'"));
  bad.push_back({"ft", fixtures::encode_npy({{1, 3}, {0, 1, 1}, Dtype::i4})});
  fixtures::write_npz(path, bad);
  CHECK_THROWS_WITH(body::load_model(path), Contains("'ft'") && Contains("(F, 3)"));
  fixtures::Cylinder c;
  c.uvs = true;
  auto arrays_uv = fixtures::cylinder_model(c);
  arrays_uv["ft"].values[5] = 1e6;
  fixtures::write_npz(path, fixtures::encode_model(arrays_uv));
  CHECK_THROWS_WITH(body::load_model(path), Contains("'ft'") && Contains("out of range"));
}

TEST_CASE("loader: joint names for non-SMPL skeletons", "[loader]") {
  fixtures::Cylinder c;
  c.joints = 5;
  auto arrays = fixtures::cylinder_model(c);
  CHECK(body::load_model(write_model("j5", arrays)).joint_names ==
        std::vector<std::string>{"joint_0", "joint_1", "joint_2", "joint_3", "joint_4"});
  auto entries = fixtures::encode_model(arrays);
  std::string names;
  for (const char* n : {"root", "a", "b", "c", "dd"}) {
    std::string s(n);
    s.resize(4, '\0');
    for (char ch : s) {
      const std::uint32_t cp = static_cast<unsigned char>(ch);
      names.append(reinterpret_cast<const char*>(&cp), 4);
    }
  }
  entries.push_back({"joint_names", fixtures::encode_npy_raw("<U4", "(5,)", false, names)});
  const auto path = fixtures::scratch_dir("loader-names") / "named.npz";
  fixtures::write_npz(path, entries);
  const auto m = body::load_model(path);
  CHECK(m.joint_names == std::vector<std::string>{"root", "a", "b", "c", "dd"});
  CHECK(m.parents == std::vector<int>{-1, 0, 0, 1, 1});
}

TEST_CASE("loader: missing, wrongly shaped and inconsistent arrays", "[loader][errors]") {
  const auto good = fixtures::cylinder_model();
  const std::size_t V = 32 * 41 + 2;
  for (const char* key :
       {"v_template", "shapedirs", "f", "J_regressor", "weights", "kintree_table"}) {
    auto a = good;
    a.erase(key);
    expect_error(write_model(std::string("missing_") + key, a),
                 {std::string("array '") + key + "'", "missing"});
  }
  {
    auto a = good;
    a["v_template"].shape = {V * 3};
    expect_error(write_model("rank", a), {"'v_template'", "wrong rank", "(V, 3)"});
  }
  {
    auto a = good;
    a["shapedirs"].shape = {V, 10, 3};
    expect_error(write_model("sdshape", a), {"'shapedirs'", "wrong shape", "(1314, 10, 3)"});
  }
  {
    auto a = good;  // one vertex fewer in weights than in v_template
    a["weights"].shape[0] = V - 1;
    a["weights"].values.resize((V - 1) * 24);
    expect_error(write_model("mismatchV", a), {"'weights'", "V = 1314", "(1313, 24)"});
  }
  {
    auto a = good;
    a["J_regressor"].shape = {24, V - 2};
    a["J_regressor"].values.resize(24 * (V - 2));
    expect_error(write_model("mismatchJR", a), {"'J_regressor'", "V = 1314"});
  }
  {
    auto a = good;
    a["kintree_table"].shape = {2, 23};
    a["kintree_table"].values.resize(46);
    expect_error(write_model("kintree", a), {"'kintree_table'", "J = 24"});
  }
  {
    auto a = good;
    a["kintree_table"].values[5] = 40;
    expect_error(write_model("parent", a), {"'kintree_table'", "parent 40", "out of range"});
  }
  {
    auto a = good;
    a["kintree_table"].values[0] = 3;  // pelvis -> spine1 -> pelvis
    expect_error(write_model("cycle", a), {"'kintree_table'", "cycle"});
  }
  {
    auto a = good;
    a["f"].values[7] = static_cast<double>(V);
    expect_error(write_model("faces", a),
                 {"'f'", "face index 1314", "(2, 1)", "out of range [0, 1314)"});
    a["f"].dtype = Dtype::i4;
    a["f"].values[7] = -1;
    expect_error(write_model("faces_neg", a), {"'f'", "face index -1"});
  }
  {
    auto a = good;
    a["f"].dtype = Dtype::f4;
    a["f"].values[4] = 2.5;
    expect_error(write_model("faces_float", a), {"'f'", "not an integer"});
  }
}

TEST_CASE("loader: NaN and Inf are rejected with their position", "[loader][errors]") {
  auto a = fixtures::cylinder_model();
  a["v_template"].values[7] = std::numeric_limits<double>::quiet_NaN();
  expect_error(write_model("nan", a), {"'v_template'", "NaN", "(2, 1)"});
  a = fixtures::cylinder_model();
  a["shapedirs"].values[3 * 10 + 2] = std::numeric_limits<double>::infinity();
  expect_error(write_model("inf", a), {"'shapedirs'", "Inf", "(1, 0, 2)"});
  a = fixtures::cylinder_model();
  a["weights"].values[1] = 1e300;  // finite in float64, Inf as float32
  expect_error(write_model("huge", a, {}, true), {"'weights'", "Inf"});
}

TEST_CASE("loader: required arrays that need pickle are errors", "[loader][errors]") {
  auto entries = fixtures::encode_model(fixtures::cylinder_model());
  for (auto& e : entries) {
    if (e.name == "J_regressor") e.bytes = fixtures::encode_npy_raw("|O", "()", false, "\x80\x02.");
  }
  const auto path = fixtures::scratch_dir("loader-obj") / "sparse.npz";
  fixtures::write_npz(path, entries);
  expect_error(path, {"'J_regressor'", "pickle", "smpl_pkl_to_npz.py"});
}

TEST_CASE("loader: broken files", "[loader][errors]") {
  const auto dir = fixtures::scratch_dir("loader-broken");
  const auto good = write_model("good", fixtures::cylinder_model(), {}, false, true);
  const std::string bytes = fixtures::read_file(good);

  expect_error(dir / "does_not_exist.npz", {"not found"});

  const auto text = dir / "notzip.npz";
  std::ofstream(text) << "this is not a zip file, just some text that is long enough";
  expect_error(text, {"not a zip archive"});

  const auto empty = dir / "empty.npz";
  std::ofstream(empty).flush();
  CHECK_THROWS_AS(body::load_model(empty), body::ModelError);

  for (std::size_t keep : {bytes.size() / 2, bytes.size() - 30, std::size_t{100}}) {
    const auto cut = dir / ("cut" + std::to_string(keep) + ".npz");
    std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(keep));
    // Names the file and says why: the zip directory at the end is gone.
    expect_error(cut, {"truncated"});
  }

  // Flip bytes in the middle of the compressed data: CRC or inflate error, named per array.
  std::string corrupt = bytes;
  for (std::size_t i = corrupt.size() / 3; i < corrupt.size() / 3 + 64; ++i) corrupt[i] ^= 0x5a;
  const auto bad = dir / "corrupt.npz";
  std::ofstream(bad, std::ios::binary)
      .write(corrupt.data(), static_cast<std::streamsize>(corrupt.size()));
  expect_error(bad, {"array '"});

  // A header that promises more data than the entry holds.
  auto entries = fixtures::encode_model(fixtures::cylinder_model());
  for (auto& e : entries) {
    if (e.name == "weights") e.bytes.resize(e.bytes.size() - 100);
  }
  const auto short_path = dir / "short.npz";
  fixtures::write_npz(short_path, entries);
  expect_error(short_path, {"'weights'", "array larger than the file"});

  // Not an npy inside the zip.
  for (auto& e : entries) {
    if (e.name == "f") e.bytes = "hello";
  }
  const auto junk = dir / "junk.npz";
  fixtures::write_npz(junk, entries);
  expect_error(junk, {"'f'"});

  // In-memory: label instead of a path.
  CHECK_THROWS_WITH(body::load_model_from_memory("PK", 2, "mem.npz"), Contains("mem.npz"));
}

TEST_CASE("npz: list() shows every array with its header", "[loader]") {
  auto entries = fixtures::encode_model(fixtures::cylinder_model());
  entries.push_back({"part2num", fixtures::encode_npy_raw("|O", "()", false, "\x80\x02.")});
  const auto path = fixtures::scratch_dir("npz-list") / "list.npz";
  fixtures::write_npz(path, entries, true);
  const auto npz = body::NpzArchive::open_file(path);
  const auto list = npz.list();
  REQUIRE(list.size() == 7);
  bool saw_object = false, saw_shapedirs = false;
  for (const auto& e : list) {
    REQUIRE(e.header);
    CHECK(e.compressed);
    if (e.name == "part2num") saw_object = e.header->needs_pickle();
    if (e.name == "shapedirs") saw_shapedirs = e.header->shape_string() == "(1314, 3, 10)";
  }
  CHECK(saw_object);
  CHECK(saw_shapedirs);
}

TEST_CASE("loader: the embedded default model", "[loader]") {
  // Either it is built in (assets/body_*.npz existed at configure time) and is a usable
  // body, or the error says it was not built in.
  body::Model m;
  try {
    m = body::load_default_model();
  } catch (const body::ModelError& e) {
    CHECK_THAT(e.what(), Contains("not built in"));
    return;
  }
  CHECK(m.source == "<embedded neutral>");
  CHECK(m.name == "neutral");
  CHECK(m.joint_count() == 55);  // SMPL-X's skeleton
  CHECK(m.joint_names.front() == "pelvis");
  CHECK(m.joint_names.at(22) == "jaw");
  CHECK(m.uvs.rows() > m.vertex_count());  // seams split texture vertices
  CHECK(m.uv_faces.rows() == m.faces.rows());
  CHECK(m.component_count() == std::min(10, m.total_components));
  const auto mesh = body::evaluate(m, Eigen::VectorXf());
  const double height = mesh.vertices.col(1).maxCoeff() - mesh.vertices.col(1).minCoeff();
  CHECK(height > 1.4);
  CHECK(height < 2.1);
  const auto all = body::load_default_model(0);
  CHECK(all.component_count() == all.total_components);
}

TEST_CASE("loader: joint and file names that are not UTF-8 become valid UTF-8",
          "[loader][errors]") {
  // Such names once made 'inspect' say usable while 'export' failed with nlohmann's
  // "[json.exception.type_error.316] invalid UTF-8 byte".
  fixtures::Cylinder c;
  c.joints = 5;
  auto entries = fixtures::encode_model(fixtures::cylinder_model(c));
  std::string names;
  for (const std::string n : {"ro\xff", "a\xc3", "b", "\xed\xa0\x80", "ok"}) {
    std::string s = n;
    s.resize(4, '\0');
    names += s;
  }
  entries.push_back({"joint_names", fixtures::encode_npy_raw("|S4", "(5,)", false, names)});
  const auto path = fixtures::scratch_dir("loader-utf8") / "caf\xe9-\xff.npz";
  fixtures::write_npz(path, entries);
  const auto m = body::load_model(path);
  CHECK(m.joint_names == std::vector<std::string>{"ro\xEF\xBF\xBD", "a\xEF\xBF\xBD", "b",
                                                  "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD", "ok"});
  CHECK(m.name == "caf\xEF\xBF\xBD-\xEF\xBF\xBD");
  for (const auto& n : m.joint_names) CHECK(util::is_valid_utf8(n));
  // The exporter takes the names as they are now: no library exception.
  CHECK_NOTHROW(body::export_gltf_bytes(m, Eigen::VectorXf::Zero(2), true));
  CHECK_NOTHROW(body::export_gltf_bytes(m, Eigen::VectorXf::Zero(2), false));
}
