#include "body/npy_reader.hpp"

#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>

namespace body {

namespace {

constexpr std::uint8_t kMagic[6] = {0x93, 'N', 'U', 'M', 'P', 'Y'};

bool host_is_big_endian() {
  const std::uint16_t probe = 1;
  std::uint8_t first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 0;
}

// A tiny reader for the Python dict literal in the header, e.g.
// {'descr': '<f4', 'fortran_order': False, 'shape': (6890, 3), }
class HeaderText {
 public:
  explicit HeaderText(std::string text) : s_(std::move(text)) {}

  void skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool eat(char c) {
    skip_space();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "'");
  }
  bool peek(char c) {
    skip_space();
    return i_ < s_.size() && s_[i_] == c;
  }
  std::string quoted() {
    skip_space();
    if (i_ >= s_.size() || (s_[i_] != '\'' && s_[i_] != '"')) fail("expected a quoted string");
    const char q = s_[i_++];
    const auto end = s_.find(q, i_);
    if (end == std::string::npos) fail("unterminated string");
    std::string out = s_.substr(i_, end - i_);
    i_ = end + 1;
    return out;
  }
  std::string word() {
    skip_space();
    const std::size_t start = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_'))
      ++i_;
    if (start == i_) fail("expected a value");
    return s_.substr(start, i_ - start);
  }
  // Skips a balanced value we do not interpret (e.g. a structured dtype list).
  void skip_value() {
    skip_space();
    int depth = 0;
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '\'' || c == '"') {
        quoted();
        continue;
      }
      if (c == '(' || c == '[' || c == '{') ++depth;
      if (c == ')' || c == ']' || c == '}') {
        if (depth == 0) return;
        --depth;
      }
      if (c == ',' && depth == 0) return;
      ++i_;
    }
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw NpyError("malformed .npy header (" + what + " at character " + std::to_string(i_) +
                   " of \"" + s_ + "\")");
  }

 private:
  std::string s_;
  std::size_t i_ = 0;
};

void parse_descr(const std::string& descr, NpyHeader& h) {
  if (descr.size() == 2 && descr[1] == 'O') {  // '|O': pickled Python objects
    h.kind = 'O';
    h.item_size = 8;
    return;
  }
  if (descr.size() < 3) throw NpyError("unsupported dtype '" + descr + "'");
  const char order = descr[0];
  if (order != '<' && order != '>' && order != '|' && order != '=') {
    throw NpyError("unsupported dtype '" + descr + "' (unknown byte order)");
  }
  h.kind = descr[1];
  std::size_t n = 0;
  try {
    std::size_t used = 0;
    n = std::stoul(descr.substr(2), &used);
    if (used != descr.size() - 2) throw NpyError("");
  } catch (const std::exception&) {
    throw NpyError("unsupported dtype '" + descr + "'");
  }
  h.big_endian = order == '>' || (order == '=' && host_is_big_endian());
  switch (h.kind) {
    case 'f':
      if (n != 4 && n != 8)
        throw NpyError("unsupported dtype '" + descr + "' (float" + std::to_string(8 * n) +
                       "; use float32 or float64)");
      h.item_size = n;
      break;
    case 'i':
    case 'u':
      if (n != 1 && n != 2 && n != 4 && n != 8) throw NpyError("unsupported dtype '" + descr + "'");
      h.item_size = n;
      break;
    case 'b':
      if (n != 1) throw NpyError("unsupported dtype '" + descr + "'");
      h.item_size = 1;
      break;
    case 'S':
    case 'U':
      // Zero-width strings hold no bytes, so a huge shape would pass the size check against
      // the file and then allocate one string per element.
      if (n == 0) throw NpyError("unsupported dtype '" + descr + "' (zero-width strings)");
      if (n > std::numeric_limits<std::size_t>::max() / 4) throw NpyError("dtype too large");
      h.item_size = h.kind == 'S' ? n : 4 * n;
      break;
    case 'O':
      h.item_size = 8;
      break;
    default:
      throw NpyError("unsupported dtype '" + descr + "'");
  }
}

std::uint64_t load_uint(const std::uint8_t* p, std::size_t n, bool swap) {
  std::uint8_t tmp[8];
  for (std::size_t k = 0; k < n; ++k) tmp[k] = swap ? p[n - 1 - k] : p[k];
  switch (n) {
    case 1:
      return tmp[0];
    case 2: {
      std::uint16_t v;
      std::memcpy(&v, tmp, 2);
      return v;
    }
    case 4: {
      std::uint32_t v;
      std::memcpy(&v, tmp, 4);
      return v;
    }
    default: {
      std::uint64_t v;
      std::memcpy(&v, tmp, 8);
      return v;
    }
  }
}

// Calls fn(storage_index) for every element in C order, whatever the storage order.
template <typename Fn>
void for_each_c_order(const NpyHeader& h, Fn fn) {
  const std::size_t count = h.element_count();
  const std::size_t rank = h.shape.size();
  if (!h.fortran_order || rank <= 1) {
    for (std::size_t i = 0; i < count; ++i) fn(i);
    return;
  }
  std::vector<std::size_t> stride(rank, 1);  // Fortran strides in elements
  for (std::size_t d = 1; d < rank; ++d) stride[d] = stride[d - 1] * h.shape[d - 1];
  std::vector<std::size_t> idx(rank, 0);
  std::size_t offset = 0;
  for (std::size_t i = 0; i < count; ++i) {
    fn(offset);
    // Increment the C-order multi-index (last axis fastest).
    for (std::size_t d = rank; d-- > 0;) {
      ++idx[d];
      offset += stride[d];
      if (idx[d] < h.shape[d]) break;
      offset -= stride[d] * idx[d];
      idx[d] = 0;
    }
  }
}

// One stored numeric item (n = h.item_size bytes) as T, sign-extending signed integers.
template <typename T>
T decode_one(const NpyHeader& h, const std::uint8_t* p, bool swap) {
  const std::size_t n = h.item_size;
  const std::uint64_t bits = load_uint(p, n, swap);
  if (h.kind == 'f') {
    if (n == 4) {
      float f;
      const auto b32 = static_cast<std::uint32_t>(bits);
      std::memcpy(&f, &b32, 4);
      return static_cast<T>(f);
    }
    double d;
    std::memcpy(&d, &bits, 8);
    return static_cast<T>(d);
  }
  if (h.kind == 'i') {
    // Sign-extend from n bytes.
    const unsigned shift = static_cast<unsigned>(64 - 8 * n);
    const auto v = static_cast<std::int64_t>(bits << shift) >> shift;
    return static_cast<T>(v);
  }
  return static_cast<T>(bits);
}

template <typename T>
void decode_run(const NpyHeader& h, const std::uint8_t* bytes, std::size_t n, T* out) {
  if (!h.is_numeric()) throw NpyError("dtype " + h.dtype_name() + " is not numeric");
  const bool swap = h.big_endian != host_is_big_endian();
  // The common case (native float of the same width) is a plain copy; model files are mostly
  // that, and shape bases run to tens of millions of values.
  if (!swap && h.kind == 'f' && h.item_size == sizeof(T)) {
    std::memcpy(out, bytes, n * sizeof(T));
    return;
  }
  for (std::size_t i = 0; i < n; ++i) out[i] = decode_one<T>(h, bytes + i * h.item_size, swap);
}

template <typename T>
std::vector<T> convert_numeric(const NpyArray& a) {
  const NpyHeader& h = a.header;
  if (!h.is_numeric()) throw NpyError("dtype " + h.dtype_name() + " is not numeric");
  const bool swap = h.big_endian != host_is_big_endian();
  std::vector<T> out;
  out.reserve(h.element_count());
  const std::uint8_t* base = a.data.data();
  const std::size_t n = h.item_size;
  for_each_c_order(h, [&](std::size_t s) { out.push_back(decode_one<T>(h, base + s * n, swap)); });
  return out;
}

}  // namespace

std::size_t NpyHeader::element_count() const {
  std::size_t n = 1;
  for (auto d : shape) n *= d;
  return n;
}

std::string NpyHeader::shape_string() const {
  std::string s = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    if (i) s += ", ";
    s += std::to_string(shape[i]);
  }
  if (shape.size() == 1) s += ",";
  return s + ")";
}

std::string NpyHeader::dtype_name() const {
  switch (kind) {
    case 'f':
      return "float" + std::to_string(8 * item_size);
    case 'i':
      return "int" + std::to_string(8 * item_size);
    case 'u':
      return "uint" + std::to_string(8 * item_size);
    case 'b':
      return "bool";
    case 'S':
      return "bytes" + std::to_string(item_size);
    case 'U':
      return "str" + std::to_string(item_size / 4);
    case 'O':
      return "object";
    default:
      return descr;
  }
}

std::size_t npy_header_size(const std::uint8_t* bytes, std::size_t size) {
  if (size < 10) return 0;
  if (std::memcmp(bytes, kMagic, 6) != 0) throw NpyError("not a .npy array (bad magic bytes)");
  const std::uint8_t major = bytes[6];
  if (major == 1)
    return 10 + static_cast<std::size_t>(load_uint(bytes + 8, 2, host_is_big_endian()));
  if (major == 2 || major == 3) {
    if (size < 12) return 0;
    return 12 + static_cast<std::size_t>(load_uint(bytes + 8, 4, host_is_big_endian()));
  }
  throw NpyError("unsupported .npy format version " + std::to_string(major));
}

NpyHeader parse_npy_header(const std::uint8_t* bytes, std::size_t size) {
  if (size < 10) throw NpyError("truncated .npy (only " + std::to_string(size) + " bytes)");
  const std::size_t total = npy_header_size(bytes, size);
  if (total == 0 || total > size) throw NpyError("truncated .npy header");
  const std::size_t text_start = bytes[6] == 1 ? 10 : 12;
  HeaderText t(std::string(reinterpret_cast<const char*>(bytes) + text_start, total - text_start));

  NpyHeader h;
  h.data_offset = total;
  bool have_descr = false, have_order = false, have_shape = false;
  t.expect('{');
  while (!t.eat('}')) {
    const std::string key = t.quoted();
    t.expect(':');
    if (key == "descr") {
      if (t.peek('[')) throw NpyError("unsupported dtype (structured arrays are not supported)");
      h.descr = t.quoted();
      parse_descr(h.descr, h);
      have_descr = true;
    } else if (key == "fortran_order") {
      const std::string w = t.word();
      if (w != "True" && w != "False") t.fail("fortran_order must be True or False");
      h.fortran_order = w == "True";
      have_order = true;
    } else if (key == "shape") {
      t.expect('(');
      while (!t.eat(')')) {
        const std::string w = t.word();
        std::size_t d = 0;
        for (char c : w) {
          if (!std::isdigit(static_cast<unsigned char>(c))) t.fail("bad dimension '" + w + "'");
          if (d > (std::numeric_limits<std::size_t>::max() - 9) / 10) t.fail("dimension too large");
          d = d * 10 + static_cast<std::size_t>(c - '0');
        }
        h.shape.push_back(d);
        if (!t.eat(',') && !t.peek(')')) t.fail("expected ',' or ')' in shape");
      }
      have_shape = true;
    } else {
      t.skip_value();
    }
    if (!t.eat(',') && !t.peek('}')) t.fail("expected ',' or '}'");
  }
  if (!have_descr || !have_order || !have_shape) {
    throw NpyError("malformed .npy header (needs 'descr', 'fortran_order' and 'shape')");
  }
  // Guard against element counts that overflow size_t.
  std::size_t count = 1;
  for (auto d : h.shape) {
    if (d != 0 && count > std::numeric_limits<std::size_t>::max() / d) {
      throw NpyError("shape " + h.shape_string() + " is too large");
    }
    count *= d;
  }
  if (h.item_size != 0 && count > std::numeric_limits<std::size_t>::max() / h.item_size) {
    throw NpyError("shape " + h.shape_string() + " is too large");
  }
  return h;
}

void check_npy_data_size(const NpyHeader& h, std::size_t available) {
  if (h.needs_pickle()) return;
  const std::size_t need = h.element_count() * h.item_size;
  if (need > available) {
    throw NpyError("array larger than the file: shape " + h.shape_string() + " of " +
                   h.dtype_name() + " needs " + std::to_string(need) + " bytes but only " +
                   std::to_string(available) + " are stored");
  }
}

void decode_numbers(const NpyHeader& h, const std::uint8_t* bytes, std::size_t n, float* out) {
  decode_run(h, bytes, n, out);
}
void decode_numbers(const NpyHeader& h, const std::uint8_t* bytes, std::size_t n, double* out) {
  decode_run(h, bytes, n, out);
}

NpyArray parse_npy(const std::uint8_t* bytes, std::size_t size) {
  NpyArray a;
  a.header = parse_npy_header(bytes, size);
  if (a.header.needs_pickle()) return a;  // no data: object arrays are pickled Python objects
  check_npy_data_size(a.header, size - a.header.data_offset);
  const std::size_t need = a.header.element_count() * a.header.item_size;
  a.data.assign(bytes + a.header.data_offset, bytes + a.header.data_offset + need);
  return a;
}

std::vector<float> NpyArray::to_float() const {
  return convert_numeric<float>(*this);
}
std::vector<double> NpyArray::to_double() const {
  return convert_numeric<double>(*this);
}

std::vector<std::int64_t> NpyArray::to_int64() const {
  if (header.kind == 'f') {
    const auto d = to_double();
    std::vector<std::int64_t> out(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (!std::isfinite(d[i]) || d[i] != std::floor(d[i]) || std::fabs(d[i]) > 9.0e15) {
        throw NpyError("value " + std::to_string(d[i]) + " at index " + std::to_string(i) +
                       " is not an integer");
      }
      out[i] = static_cast<std::int64_t>(d[i]);
    }
    return out;
  }
  if (header.kind == 'u' && header.item_size == 8) {
    // uint64 above int64's range cannot be an index; keep the bits (callers range-check).
    return convert_numeric<std::int64_t>(*this);
  }
  return convert_numeric<std::int64_t>(*this);
}

std::vector<std::string> NpyArray::to_strings() const {
  if (header.kind != 'S' && header.kind != 'U') {
    throw NpyError("dtype " + header.dtype_name() + " is not a string type");
  }
  const bool swap = header.big_endian != host_is_big_endian();
  std::vector<std::string> out;
  out.reserve(header.element_count());
  const std::size_t n = header.item_size;
  for_each_c_order(header, [&](std::size_t s) {
    const std::uint8_t* p = data.data() + s * n;
    std::string str;
    if (header.kind == 'S') {
      str.assign(reinterpret_cast<const char*>(p), n);
    } else {
      for (std::size_t k = 0; k + 4 <= n; k += 4) {
        const auto cp = static_cast<std::uint32_t>(load_uint(p + k, 4, swap));
        if (cp == 0) break;
        if (cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
          str += "\xEF\xBF\xBD";  // U+FFFD: not a Unicode scalar value
        } else if (cp < 0x80) {
          str += static_cast<char>(cp);
        } else if (cp < 0x800) {
          str += static_cast<char>(0xC0 | (cp >> 6));
          str += static_cast<char>(0x80 | (cp & 0x3F));
        } else if (cp < 0x10000) {
          str += static_cast<char>(0xE0 | (cp >> 12));
          str += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
          str += static_cast<char>(0x80 | (cp & 0x3F));
        } else {
          str += static_cast<char>(0xF0 | ((cp >> 18) & 0x07));
          str += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
          str += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
          str += static_cast<char>(0x80 | (cp & 0x3F));
        }
      }
    }
    while (!str.empty() && str.back() == '\0') str.pop_back();
    out.push_back(std::move(str));
  });
  return out;
}

}  // namespace body
