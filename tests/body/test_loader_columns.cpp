// Loading only the shape columns that are used: with K components the loader
// reads and converts K columns of shapedirs, in every storage variant (C / Fortran order,
// float32 / float64, stored / deflated), and gets exactly the numbers a full load has.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>

#include "body/model_loader.hpp"
#include "body/model_validation.hpp"
#include "body/npz_reader.hpp"
#include "npz_fixtures.hpp"

using Catch::Contains;
using fixtures::Array;
using fixtures::Dtype;

namespace {

using ArrayMap = std::map<std::string, Array>;

struct Variant {
  bool fortran = false;
  bool float64 = false;
  bool compressed = false;
  bool big_endian = false;
  std::string name() const {
    return std::string(fortran ? "F" : "C") + (float64 ? "-f8" : "-f4") +
           (compressed ? "-deflate" : "-stored") + (big_endian ? "-big" : "");
  }
};

std::vector<Variant> all_variants() {
  std::vector<Variant> out;
  for (bool fortran : {false, true}) {
    for (bool float64 : {false, true}) {
      for (bool compressed : {false, true}) out.push_back({fortran, float64, compressed, false});
    }
  }
  out.push_back({true, true, true, true});  // byte-swapped on the way, too
  return out;
}

std::filesystem::path write_variant(const std::string& dir, const ArrayMap& arrays,
                                    const Variant& v) {
  const auto path = fixtures::scratch_dir(dir + "-" + v.name()) / "model.npz";
  fixtures::write_npz(path, fixtures::encode_model(arrays, {v.big_endian, v.fortran}, v.float64),
                      v.compressed);
  return path;
}

// Largest |a - b| over two matrices of the same size (infinity if the sizes differ), so a
// failure prints one number rather than two matrices.
double max_abs_diff(const Eigen::MatrixXf& a, const Eigen::MatrixXf& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return std::numeric_limits<double>::infinity();
  if (a.size() == 0) return 0.0;
  return static_cast<double>((a - b).cwiseAbs().maxCoeff());
}

// Columns [first, first + count) of a (V, 3, K) fixture array (values in C order) as the 3V x
// count matrix the loader should make of them, rounded to float as the loader does.
Eigen::MatrixXf fixture_columns(const Array& a, std::size_t first, std::size_t count) {
  const std::size_t rows = a.shape[0] * a.shape[1], K = a.shape[2];
  Eigen::MatrixXf m(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(count));
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t j = 0; j < count; ++j) {
      m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(j)) =
          static_cast<float>(a.values[r * K + first + j]);
    }
  }
  return m;
}

// The message of the ModelError that fn throws ("(no error)" if it throws none).
template <typename Fn>
std::string error_of(Fn fn) {
  try {
    fn();
  } catch (const body::ModelError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("loader columns: K components are the first K columns of a full load",
          "[loader][columns]") {
  fixtures::Cylinder c;
  c.components = 16;
  const ArrayMap arrays = fixtures::cylinder_model(c);
  const Array& sd = arrays.at("shapedirs");
  for (const Variant& v : all_variants()) {
    INFO("variant " << v.name());
    const auto path = write_variant("columns", arrays, v);
    const body::Model full = body::load_model(path, 0);
    REQUIRE(full.component_count() == 16);
    // The full load against the fixture's own values: the loader's column mapping is checked,
    // not only its agreement with itself.
    CHECK(max_abs_diff(full.shapedirs, fixture_columns(sd, 0, 16)) <= 1e-7);
    for (int k : {1, 4, 10, 15}) {
      INFO("components " << k);
      const body::Model part = body::load_model(path, k);
      REQUIRE(part.component_count() == k);
      CHECK(part.total_components == 16);
      CHECK(max_abs_diff(part.shapedirs, full.shapedirs.leftCols(k)) <= 1e-7);
      // Everything else is the same as with all components.
      CHECK(max_abs_diff(part.v_template, full.v_template) <= 1e-7);
      CHECK(max_abs_diff(part.joint_shapedirs, full.joint_shapedirs.leftCols(k)) <= 1e-6);
    }
  }
}

TEST_CASE("loader columns: SMPL-X's expression columns come from after the shape columns",
          "[loader][columns]") {
  // 55 joints and 20 columns: 10 shape + 10 expression components (SMPL-X v1.0's layout).
  fixtures::Cylinder c;
  c.joints = 55;
  c.components = 20;
  const ArrayMap arrays = fixtures::cylinder_model(c);
  const Array& sd = arrays.at("shapedirs");
  for (const Variant& v : all_variants()) {
    INFO("variant " << v.name());
    const auto path = write_variant("columns-x", arrays, v);
    const body::Model m = body::load_model(path, 3, 4);
    CHECK(m.total_components == 10);
    CHECK(m.total_expressions == 10);
    CHECK(max_abs_diff(m.shapedirs, fixture_columns(sd, 0, 3)) <= 1e-7);
    CHECK(max_abs_diff(m.expression_dirs, fixture_columns(sd, 10, 4)) <= 1e-7);
    const body::Model all = body::load_model(path, 0, 10);
    CHECK(max_abs_diff(all.shapedirs, fixture_columns(sd, 0, 10)) <= 1e-7);
    CHECK(max_abs_diff(all.expression_dirs, fixture_columns(sd, 10, 10)) <= 1e-7);
    CHECK(max_abs_diff(m.shapedirs, all.shapedirs.leftCols(3)) <= 1e-7);
    CHECK(max_abs_diff(m.expression_dirs, all.expression_dirs.leftCols(4)) <= 1e-7);
  }
}

TEST_CASE("loader columns: a 55-joint file's variance_share says all its columns are shapes",
          "[loader][columns]") {
  // The built-in models: SMPL-X's skeleton, 18 shape components and no expressions; their
  // variance_share (one entry per shape component) keeps them from being read as shapes and
  // expressions half and half. This look-alike has 16 (8 + 8 without it).
  fixtures::Cylinder c;
  c.joints = 55;
  c.components = 16;
  ArrayMap arrays = fixtures::cylinder_model(c);
  Array share;
  share.shape = {16};
  share.values.assign(16, 1.0 / 16);
  arrays["variance_share"] = share;
  const auto path = write_variant("columns-share", arrays, all_variants().front());
  const body::Model m = body::load_model(path, 0, 4);
  CHECK(m.total_components == 16);
  CHECK(m.total_expressions == 0);
  CHECK(m.expression_dirs.size() == 0);
  CHECK(max_abs_diff(m.shapedirs, fixture_columns(arrays.at("shapedirs"), 0, 16)) <= 1e-7);
  // Longer than shapedirs has columns, it is not believed, and the mismatch is an error.
  share.shape = {20};
  share.values.assign(20, 0.05);
  arrays["variance_share"] = share;
  const auto bad = write_variant("columns-share-bad", arrays, all_variants().front());
  CHECK_THAT(error_of([&] { body::load_model(bad, 0); }), Catch::Contains("variance_share"));
  // Other skeletons keep every column as a shape component whatever variance_share says.
  fixtures::Cylinder smpl;
  smpl.components = 16;
  ArrayMap arrays24 = fixtures::cylinder_model(smpl);
  share.shape = {10};
  share.values.assign(10, 0.1);
  arrays24["variance_share"] = share;
  const auto p24 = write_variant("columns-share-24", arrays24, all_variants().front());
  CHECK_THAT(error_of([&] { body::load_model(p24, 0); }), Catch::Contains("variance_share"));
}

TEST_CASE("loader columns: columns far apart are reached by seeking or inflating past the gap",
          "[loader][columns]") {
  // SMPL-X's layout with 100 + 100 columns: in Fortran order the expression columns lie 1.5 MB
  // after the first shape columns, beyond what one read block holds, so a stored file seeks
  // over the gap and a deflated one inflates through it.
  fixtures::Cylinder c;
  c.joints = 55;
  c.components = 200;
  const ArrayMap arrays = fixtures::cylinder_model(c);
  const Array& sd = arrays.at("shapedirs");
  for (const Variant& v : all_variants()) {
    INFO("variant " << v.name());
    const auto path = write_variant("columns-far", arrays, v);
    const body::Model m = body::load_model(path, 2, 3);
    CHECK(m.total_components == 100);
    CHECK(max_abs_diff(m.shapedirs, fixture_columns(sd, 0, 2)) <= 1e-7);
    CHECK(max_abs_diff(m.expression_dirs, fixture_columns(sd, 100, 3)) <= 1e-7);
  }
}

TEST_CASE("loader columns: pose correctives read straight into their matrix", "[loader][columns]") {
  fixtures::Cylinder c;
  c.pose_columns = 9 * 23;
  ArrayMap arrays = fixtures::cylinder_model(c);
  // Distinct values everywhere, so a transposed or shifted read cannot pass.
  Array& pd = arrays["posedirs"];
  for (std::size_t i = 0; i < pd.values.size(); ++i) pd.values[i] = 1e-4 * std::sin(0.37 * i);
  for (const Variant& v : all_variants()) {
    INFO("variant " << v.name());
    body::Model m = body::load_model(write_variant("columns-pose", arrays, v));
    CHECK(m.posedirs.size() == 0);
    body::load_pose_correctives(m);
    CHECK(max_abs_diff(m.posedirs, fixture_columns(pd, 0, 9 * 23)) <= 1e-7);
  }
}

TEST_CASE("loader columns: a file's unused columns are not read, inspect checks them all",
          "[loader][columns][errors]") {
  fixtures::Cylinder c;
  c.components = 16;
  ArrayMap arrays = fixtures::cylinder_model(c);
  // NaN in column 12 of vertex 7 (axis 2) and Inf in column 14 of vertex 3 (axis 0): the Inf
  // comes first in C order, the NaN first in Fortran order (vertices fastest). Both must name
  // the Inf, as a full conversion in C order did.
  const auto at = [](std::size_t v, std::size_t axis, std::size_t k) {
    return (v * 3 + axis) * 16 + k;
  };
  arrays["shapedirs"].values[at(7, 2, 12)] = std::numeric_limits<double>::quiet_NaN();
  arrays["shapedirs"].values[at(3, 0, 14)] = std::numeric_limits<double>::infinity();
  for (const Variant& v : all_variants()) {
    INFO("variant " << v.name());
    const auto path = write_variant("columns-nan", arrays, v);
    // Ten components never touch columns 12 and 14.
    const body::Model m = body::load_model(path, 10);
    CHECK(m.component_count() == 10);
    const std::string all = error_of([&] { body::load_model(path, 0); });
    CHECK_THAT(all, Contains(path.string()) && Contains("'shapedirs'") && Contains("Inf") &&
                        Contains("(3, 0, 14)"));
    const std::string check = error_of([&] { body::check_model(path.string()); });
    CHECK(check == all);
  }
}

TEST_CASE("loader columns: check_model reports what the file holds, keeping one column",
          "[loader][columns]") {
  fixtures::Cylinder c;
  c.joints = 55;
  c.components = 20;
  c.pose_columns = 9 * 54;
  const ArrayMap arrays = fixtures::cylinder_model(c);
  for (const Variant& v : {Variant{false, true, false}, Variant{true, false, true}}) {
    INFO("variant " << v.name());
    const auto path = write_variant("columns-check", arrays, v);
    const body::ModelCheck check = body::check_model(path.string());
    CHECK(check.model.component_count() == 1);
    CHECK(check.model.total_components == 10);
    CHECK(check.model.total_expressions == 10);
    CHECK(check.model.expression_dirs.cols() == 0);
    CHECK(check.model.posedirs.size() == 0);
    CHECK(check.pose_columns == 9 * 54);
    CHECK(check.model.name == "model");
    CHECK(max_abs_diff(check.model.shapedirs, body::load_model(path, 1).shapedirs) <= 1e-7);
  }
  // A NaN in the pose correctives makes the file unusable for inspect, as it did when inspect
  // read them whole.
  ArrayMap bad = arrays;
  bad["posedirs"].values[(5 * 3 + 1) * 486 + 300] = std::numeric_limits<double>::quiet_NaN();
  const auto path = write_variant("columns-check-nan", bad, {true, true, true});
  CHECK_THAT(error_of([&] { body::check_model(path.string()); }),
             Contains("'posedirs'") && Contains("NaN") && Contains("(5, 1, 300)"));
  CHECK_NOTHROW(body::load_model(path, 0, 10));  // posedirs are read on demand only
}

TEST_CASE("loader columns: broken shape bases fail before anything is allocated",
          "[loader][columns][errors]") {
  const ArrayMap arrays = fixtures::cylinder_model();
  const std::size_t V = 32 * 41 + 2;
  for (bool compressed : {false, true}) {
    INFO("compressed " << compressed);
    // A header that promises a billion columns over the data of ten: named, never allocated.
    auto entries = fixtures::encode_model(arrays);
    for (auto& e : entries) {
      if (e.name != "shapedirs") continue;
      const auto* head = reinterpret_cast<const std::uint8_t*>(e.bytes.data());
      const std::string data = e.bytes.substr(body::npy_header_size(head, e.bytes.size()));
      e.bytes = fixtures::encode_npy_raw("<f4", "(" + std::to_string(V) + ", 3, 1000000000)", false,
                                         data);
    }
    const auto dir = fixtures::scratch_dir("columns-broken");
    fixtures::write_npz(dir / "huge.npz", entries, compressed);
    for (int k : {1, 0}) {
      CHECK_THAT(error_of([&] { body::load_model(dir / "huge.npz", k); }),
                 Contains("huge.npz") && Contains("'shapedirs'") &&
                     Contains("array larger than the file"));
    }
    // Cut short by one value: the same message whichever columns are wanted.
    entries = fixtures::encode_model(arrays);
    for (auto& e : entries) {
      if (e.name == "shapedirs") e.bytes.resize(e.bytes.size() - 4);
    }
    fixtures::write_npz(dir / "short.npz", entries, compressed);
    CHECK_THAT(error_of([&] { body::load_model(dir / "short.npz", 1); }),
               Contains("'shapedirs'") && Contains("array larger than the file"));
    // Not numbers.
    entries = fixtures::encode_model(arrays);
    for (auto& e : entries) {
      if (e.name == "shapedirs") {
        e.bytes = fixtures::encode_npy_raw("|S4", "(" + std::to_string(V) + ", 3, 2)", false,
                                           std::string(V * 3 * 2 * 4, 'a'));
      }
    }
    fixtures::write_npz(dir / "strings.npz", entries, compressed);
    CHECK_THAT(error_of([&] { body::load_model(dir / "strings.npz", 1); }),
               Contains("'shapedirs'") && Contains("dtype bytes4 is not numeric"));
    // An object array (pickle) where the basis should be.
    for (auto& e : entries) {
      if (e.name == "shapedirs") e.bytes = fixtures::encode_npy_raw("|O", "()", false, "\x80.");
    }
    fixtures::write_npz(dir / "object.npz", entries, compressed);
    CHECK_THAT(error_of([&] { body::load_model(dir / "object.npz", 1); }),
               Contains("'shapedirs'") && Contains("pickle"));
  }
}

TEST_CASE("npz: read_spans hands on exactly the wanted bytes", "[loader][columns]") {
  // A (4, 5) int32 array holding 0..19: spans of items 1-2, 6, 15-19 (gaps skipped).
  Array a{{4, 5}, {}, Dtype::i4};
  for (int i = 0; i < 20; ++i) a.values.push_back(i);
  for (bool compressed : {false, true}) {
    INFO("compressed " << compressed);
    const auto path = fixtures::scratch_dir("npz-spans") / "a.npz";
    fixtures::write_npz(path, {{"a", fixtures::encode_npy(a)}}, compressed);
    const auto npz = body::NpzArchive::open_file(path);
    const std::vector<std::pair<std::uint64_t, std::uint64_t>> spans = {{4, 8}, {24, 4}, {60, 20}};
    std::size_t next = 0;
    std::vector<std::int32_t> got;
    const body::NpyHeader h = npz.read_spans(
        "a",
        [&](std::uint64_t& offset, std::uint64_t& size) {
          if (next == spans.size()) return false;
          offset = spans[next].first;
          size = spans[next].second;
          ++next;
          return true;
        },
        [&](const std::uint8_t* bytes, std::size_t size) {
          REQUIRE(size % 4 == 0);
          for (std::size_t i = 0; i < size; i += 4) {
            std::int32_t x;
            std::memcpy(&x, bytes + i, 4);
            got.push_back(x);
          }
        });
    CHECK(h.shape == std::vector<std::size_t>{4, 5});
    CHECK(got == std::vector<std::int32_t>{1, 2, 6, 15, 16, 17, 18, 19});
    CHECK(npz.header("a").dtype_name() == "int32");
    CHECK_THAT(error_of([&] { npz.header("b"); }), Contains("array 'b'") && Contains("missing"));
  }
}
