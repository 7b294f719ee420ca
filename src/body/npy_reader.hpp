// Parser for NumPy's .npy format (versions 1-3): little/big endian, float32/float64,
// (u)int8..64, bool, fixed-size byte and unicode strings, C and Fortran order, any rank.
// Object arrays (which need Python pickle) are recognised and reported, never decoded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace body {

// A malformed .npy; what() says what is wrong (the caller adds file and array names).
class NpyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct NpyHeader {
  std::string descr;          // as written, e.g. "<f4", "|O", "<U12"
  char kind = '?';            // 'f' float, 'i' signed, 'u' unsigned, 'b' bool, 'S', 'U', 'O'
  std::size_t item_size = 0;  // bytes per element (for 'U': 4 * characters)
  bool big_endian = false;
  bool fortran_order = false;
  std::vector<std::size_t> shape;
  std::size_t data_offset = 0;  // bytes from the start of the .npy to the data

  std::size_t element_count() const;
  bool needs_pickle() const { return kind == 'O'; }
  bool is_numeric() const { return kind == 'f' || kind == 'i' || kind == 'u' || kind == 'b'; }
  std::string shape_string() const;  // "(6890, 3)"
  std::string dtype_name() const;    // "float32", "uint32", "object", "str12", ...
};

// Parses the header at the start of `bytes` (which may hold only the beginning of the file).
NpyHeader parse_npy_header(const std::uint8_t* bytes, std::size_t size);

// Bytes needed to parse the header, from the first 10 (or 12) bytes; 0 if more are needed.
std::size_t npy_header_size(const std::uint8_t* bytes, std::size_t size);

struct NpyArray {
  NpyHeader header;
  std::vector<std::uint8_t> data;  // exactly element_count * item_size bytes, as stored

  // Values in C (row-major) order, converted to the requested type. Numeric kinds only.
  std::vector<float> to_float() const;
  std::vector<double> to_double() const;
  // Integer values; floats must be integral. Throws NpyError otherwise.
  std::vector<std::int64_t> to_int64() const;
  // Strings of a 'S' or 'U' array (ASCII/UTF-32 -> UTF-8), C order, trailing NULs removed.
  std::vector<std::string> to_strings() const;
};

// Throws NpyError "array larger than the file: ..." unless `available` bytes of data (after the
// header) hold the whole array; object arrays carry no data and always pass.
void check_npy_data_size(const NpyHeader& h, std::size_t available);

// Converts `n` stored items of a numeric array (h's dtype and byte order, contiguous) to float or
// double, exactly as NpyArray::to_float() / to_double() do, for arrays read piece by piece.
void decode_numbers(const NpyHeader& h, const std::uint8_t* bytes, std::size_t n, float* out);
void decode_numbers(const NpyHeader& h, const std::uint8_t* bytes, std::size_t n, double* out);

// Parses a complete .npy held in memory. Throws NpyError for bad magic, bad header,
// unsupported dtypes (object arrays parse their header but carry no data), and data shorter
// than the shape says ("array larger than the file").
NpyArray parse_npy(const std::uint8_t* bytes, std::size_t size);

}  // namespace body
