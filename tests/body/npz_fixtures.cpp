#include "npz_fixtures.hpp"

#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fixtures {

namespace {

std::size_t item_size(Dtype d) {
  return (d == Dtype::f4 || d == Dtype::i4 || d == Dtype::u4) ? 4 : 8;
}

std::string descr_of(Dtype d, bool big) {
  const char* names[] = {"f4", "f8", "i4", "i8", "u4", "u8"};
  return std::string(big ? ">" : "<") + names[static_cast<int>(d)];
}

void append_value(std::string& out, double v, Dtype d, bool big) {
  unsigned char b[8];
  switch (d) {
    case Dtype::f4: {
      const float f = static_cast<float>(v);
      std::memcpy(b, &f, 4);
      break;
    }
    case Dtype::f8:
      std::memcpy(b, &v, 8);
      break;
    case Dtype::i4: {
      const auto x = static_cast<std::int32_t>(v);
      std::memcpy(b, &x, 4);
      break;
    }
    case Dtype::i8: {
      const auto x = static_cast<std::int64_t>(v);
      std::memcpy(b, &x, 8);
      break;
    }
    case Dtype::u4: {
      const auto x = static_cast<std::uint32_t>(static_cast<std::int64_t>(v));
      std::memcpy(b, &x, 4);
      break;
    }
    case Dtype::u8: {
      const auto x = static_cast<std::uint64_t>(static_cast<std::int64_t>(v));
      std::memcpy(b, &x, 8);
      break;
    }
  }
  const std::size_t n = item_size(d);
  if (big) {  // the test machine is little-endian (x86-64)
    for (std::size_t k = 0; k < n; ++k) out.push_back(static_cast<char>(b[n - 1 - k]));
  } else {
    out.append(reinterpret_cast<const char*>(b), n);
  }
}

std::string shape_text(const std::vector<std::size_t>& shape) {
  std::string s = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) s += std::to_string(shape[i]) + ", ";
  if (shape.size() > 1) s.erase(s.size() - 1);
  if (shape.size() > 1) s.erase(s.size() - 1);
  return s + ")";
}

}  // namespace

std::string encode_npy_raw(const std::string& descr, const std::string& shape, bool fortran,
                           const std::string& data) {
  std::string header = "{'descr': '" + descr +
                       "', 'fortran_order': " + (fortran ? "True" : "False") +
                       ", 'shape': " + shape + ", }";
  // Pad so that magic (6) + version (2) + length (2) + header is a multiple of 64.
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(header.size() & 0xff);
  out += static_cast<char>((header.size() >> 8) & 0xff);
  return out + header + data;
}

std::string encode_npy(const Array& a, const Encoding& enc) {
  std::size_t count = 1;
  for (auto d : a.shape) count *= d;
  if (count != a.values.size()) throw std::logic_error("fixture: shape and values disagree");
  std::string data;
  data.reserve(count * item_size(a.dtype));
  if (enc.fortran && a.shape.size() > 1) {
    // Walk Fortran order (first axis fastest) and pick the C-order element.
    const std::size_t rank = a.shape.size();
    std::vector<std::size_t> idx(rank, 0);
    for (std::size_t n = 0; n < count; ++n) {
      std::size_t c = 0;
      for (std::size_t d = 0; d < rank; ++d) c = c * a.shape[d] + idx[d];
      append_value(data, a.values[c], a.dtype, enc.big_endian);
      for (std::size_t d = 0; d < rank; ++d) {
        if (++idx[d] < a.shape[d]) break;
        idx[d] = 0;
      }
    }
  } else {
    for (double v : a.values) append_value(data, v, a.dtype, enc.big_endian);
  }
  return encode_npy_raw(descr_of(a.dtype, enc.big_endian), shape_text(a.shape), enc.fortran, data);
}

void write_npz(const std::filesystem::path& path, const std::vector<Entry>& entries,
               bool compressed) {
  int err = 0;
  zip_t* z = zip_open(path.string().c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  if (!z) throw std::runtime_error("fixture: cannot create " + path.string());
  for (const auto& e : entries) {
    // The entries vector outlives zip_close, so libzip may read the bytes in place.
    zip_source_t* src = zip_source_buffer(z, e.bytes.data(), e.bytes.size(), 0);
    const zip_int64_t idx = zip_file_add(z, (e.name + ".npy").c_str(), src, ZIP_FL_OVERWRITE);
    if (idx < 0) {
      zip_source_free(src);
      zip_discard(z);
      throw std::runtime_error("fixture: zip_file_add failed");
    }
    zip_set_file_compression(z, static_cast<zip_uint64_t>(idx),
                             compressed ? ZIP_CM_DEFLATE : ZIP_CM_STORE, 0);
  }
  if (zip_close(z) != 0) {
    const std::string msg = zip_strerror(z);
    zip_discard(z);
    throw std::runtime_error("fixture: zip_close failed: " + msg);
  }
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::map<std::string, Array> cylinder_model(const Cylinder& c) {
  const int S = c.segments, R = c.rings, K = c.components, J = c.joints;
  // Rings, then bottom and top cap centres, then any padding points.
  const int V = std::max(S * R + 2, c.vertices);
  const double pi = 3.14159265358979323846;
  auto pos = [&](int v, double& x, double& y, double& z) {
    if (v >= S * R) {
      x = 0.0, z = 0.0;
      y = c.base_y + (v == S * R ? 0.0 : v == S * R + 1 ? c.height : 0.5 * c.height);
      return;
    }
    const int ring = v / S, seg = v % S;
    const double th = 2.0 * pi * seg / S;
    x = c.radius * std::cos(th);
    z = c.radius * std::sin(th);
    y = c.base_y + c.height * ring / (R - 1);
  };
  std::map<std::string, Array> m;
  Array vt{{static_cast<std::size_t>(V), 3}, {}, Dtype::f4};
  Array sd{{static_cast<std::size_t>(V), 3, static_cast<std::size_t>(K)}, {}, Dtype::f4};
  for (int v = 0; v < V; ++v) {
    double x, y, z;
    pos(v, x, y, z);
    vt.values.insert(vt.values.end(), {x, y, z});
    const double p[3] = {x, y, z};
    for (int a = 0; a < 3; ++a) {
      for (int k = 0; k < K; ++k) {
        double d = 0.0;
        if (k == 0)
          d = (a == 1) ? 0.0 : p[a];
        else if (k == 1)
          d = (a == 1) ? (y - c.base_y) : 0.0;
        else
          d = 0.002 * std::sin(0.7 * k * (v + 1) + a);
        sd.values.push_back(d);
      }
    }
  }
  m["v_template"] = vt;
  m["shapedirs"] = sd;

  // Faces, wound counter-clockwise seen from outside (checked against the outward direction).
  Array f{{0, 3}, {}, Dtype::u4};
  auto add_face = [&](int a, int b, int cc, double ox, double oy, double oz) {
    double pa[3], pb[3], pc[3];
    pos(a, pa[0], pa[1], pa[2]);
    pos(b, pb[0], pb[1], pb[2]);
    pos(cc, pc[0], pc[1], pc[2]);
    const double e1[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
    const double e2[3] = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    if (n[0] * ox + n[1] * oy + n[2] * oz < 0) std::swap(b, cc);
    f.values.insert(f.values.end(), {double(a), double(b), double(cc)});
  };
  for (int r = 0; r + 1 < R; ++r) {
    for (int s = 0; s < S; ++s) {
      const int a = r * S + s, b = r * S + (s + 1) % S, up_a = a + S, up_b = b + S;
      const double th = 2.0 * pi * (s + 0.5) / S;
      add_face(a, b, up_b, std::cos(th), 0, std::sin(th));
      add_face(a, up_b, up_a, std::cos(th), 0, std::sin(th));
    }
  }
  for (int s = 0; s < S; ++s) {
    add_face(S * R, s, (s + 1) % S, 0, -1, 0);
    add_face(S * R + 1, (R - 1) * S + s, (R - 1) * S + (s + 1) % S, 0, 1, 0);
  }
  f.shape[0] = f.values.size() / 3;
  m["f"] = f;

  // Joint j: average of ring (j * (R - 1)) / (J - 1).
  Array jr{{static_cast<std::size_t>(J), static_cast<std::size_t>(V)}, {}, Dtype::f4};
  jr.values.assign(static_cast<std::size_t>(J * V), 0.0);
  for (int j = 0; j < J; ++j) {
    const int ring = J > 1 ? j * (R - 1) / (J - 1) : 0;
    for (int s = 0; s < S; ++s) jr.values[static_cast<std::size_t>(j * V + ring * S + s)] = 1.0 / S;
  }
  m["J_regressor"] = jr;

  // Weights: up to five joints per vertex with falling weights (sums to 1).
  Array w{{static_cast<std::size_t>(V), static_cast<std::size_t>(J)}, {}, Dtype::f4};
  w.values.assign(static_cast<std::size_t>(V * J), 0.0);
  for (int v = 0; v < V; ++v) {
    const double share[5] = {0.4, 0.25, 0.15, 0.12, 0.08};
    const int n = 1 + v % 5;
    double sum = 0.0;
    for (int k = 0; k < n; ++k) sum += share[k];
    for (int k = 0; k < n; ++k) {
      w.values[static_cast<std::size_t>(v * J + (v + 3 * k) % J)] += share[k] / sum;
    }
  }
  m["weights"] = w;

  const int smpl_parents[24] = {-1, 0, 0, 0,  1,  2,  3,  4,  5,  6,  7,  8,
                                9,  9, 9, 12, 13, 14, 16, 17, 18, 19, 20, 21};
  // SMPL+H (52) and SMPL-X (55): SMPL's first 22 joints, (SMPL-X) jaw and eyes on the head,
  // then three-joint finger chains on each wrist, as the models' public descriptions have it.
  std::vector<int> family(static_cast<std::size_t>(J), 0);
  if (J == 52 || J == 55) {
    for (int j = 0; j < 22; ++j) family[static_cast<std::size_t>(j)] = smpl_parents[j];
    int next = 22;
    if (J == 55) {
      for (; next < 25; ++next) family[static_cast<std::size_t>(next)] = 15;
    }
    for (int wrist : {20, 21}) {
      for (int finger = 0; finger < 5; ++finger, next += 3) {
        family[static_cast<std::size_t>(next)] = wrist;
        family[static_cast<std::size_t>(next + 1)] = next;
        family[static_cast<std::size_t>(next + 2)] = next + 1;
      }
    }
  }
  Array kt{{2, static_cast<std::size_t>(J)}, {}, Dtype::i8};
  for (int j = 0; j < J; ++j) {
    kt.values.push_back(J == 24              ? smpl_parents[j]
                        : j == 0             ? 4294967295.0
                        : J == 52 || J == 55 ? family[static_cast<std::size_t>(j)]
                                             : (j - 1) / 2);
  }
  for (int j = 0; j < J; ++j) kt.values.push_back(j);
  if (J != 24) kt.dtype = Dtype::u4;
  m["kintree_table"] = kt;

  if (c.uvs) {
    // (S + 1) columns per ring so the seam has u = 0 on one side and u = 1 on the other.
    Array vt{{static_cast<std::size_t>((S + 1) * R + 2), 2}, {}, Dtype::f4};
    for (int r = 0; r < R; ++r) {
      for (int s = 0; s <= S; ++s) {
        vt.values.insert(vt.values.end(), {double(s) / S, double(r) / (R - 1)});
      }
    }
    vt.values.insert(vt.values.end(), {0.5, 0.0, 0.5, 1.0});
    Array ft{{f.shape[0], 3}, {}, Dtype::i4};
    for (std::size_t i = 0; i < f.shape[0]; ++i) {
      bool has_first = false, has_last = false;
      for (int k = 0; k < 3; ++k) {
        const int v = static_cast<int>(f.values[3 * i + static_cast<std::size_t>(k)]);
        if (v < S * R && v % S == 0) has_first = true;
        if (v < S * R && v % S == S - 1) has_last = true;
      }
      for (int k = 0; k < 3; ++k) {
        const int v = static_cast<int>(f.values[3 * i + static_cast<std::size_t>(k)]);
        int t = 0;
        if (v >= S * R) {
          t = (S + 1) * R + (v - S * R);
        } else {
          const int seg = (v % S == 0 && has_first && has_last) ? S : v % S;
          t = (v / S) * (S + 1) + seg;
        }
        ft.values.push_back(t);
      }
    }
    m["vt"] = vt;
    m["ft"] = ft;
  }
  if (c.pose_columns > 0) {
    Array pd{
        {static_cast<std::size_t>(V), 3, static_cast<std::size_t>(c.pose_columns)}, {}, Dtype::f4};
    pd.values.assign(static_cast<std::size_t>(V * 3 * c.pose_columns), 0.0);
    for (int v = 0; v < V; ++v) {
      const int column = std::min(135, c.pose_columns - 1);
      pd.values[static_cast<std::size_t>((v * 3 + 1) * c.pose_columns + column)] = c.pose_lift;
    }
    m["posedirs"] = pd;
  }
  return m;
}

std::vector<Entry> encode_model(const std::map<std::string, Array>& arrays, const Encoding& enc,
                                bool float64) {
  std::vector<Entry> out;
  for (const auto& [name, a] : arrays) {
    Array copy = a;
    if (float64 && copy.dtype == Dtype::f4) copy.dtype = Dtype::f8;
    out.push_back({name, encode_npy(copy, enc)});
  }
  return out;
}

namespace {

// The per-process scratch root, removed at exit unless SG_KEEP_TEST_FILES is set.
struct ScratchRoot {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("sg_body_tests_" + std::to_string(::getpid()));
  ~ScratchRoot() {
    std::error_code ec;
    if (std::getenv("SG_KEEP_TEST_FILES") == nullptr) std::filesystem::remove_all(path, ec);
  }
};

}  // namespace

std::filesystem::path scratch_dir(const std::string& name) {
  static ScratchRoot root;
  const auto dir = root.path / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace fixtures
