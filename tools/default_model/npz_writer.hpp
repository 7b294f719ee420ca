// A minimal, deterministic .npz writer: .npy v1.0 arrays in a deflated zip archive, as
// numpy.savez_compressed writes them, with fixed timestamps (the bytes depend only on the
// arrays and the zlib version).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace default_model {

struct NpyArray {
  std::string name;   // without ".npy"
  std::string descr;  // numpy dtype string, e.g. "<f4", "<u4", "<i8"
  std::vector<std::size_t> shape;
  std::vector<std::uint8_t> data;  // C order, little endian
};

// `value` rounded to a multiple of 2^-fraction_bits. Arrays of metres rounded so (far below
// the 1e-5 within which a regenerated model must match the committed one) have zeros in their
// floats' low mantissa bits, which the .npz's deflate packs much tighter than noise.
inline double rounded_to_binary_step(double value, int fraction_bits) {
  return std::ldexp(std::round(std::ldexp(value, fraction_bits)), -fraction_bits);
}

std::vector<std::uint8_t> npy_bytes(const NpyArray& array);
std::vector<std::uint8_t> npz_bytes(const std::vector<NpyArray>& arrays);

template <typename T>
NpyArray make_array(const std::string& name, const std::string& descr,
                    std::vector<std::size_t> shape, const std::vector<T>& values) {
  NpyArray a{name, descr, std::move(shape), {}};
  a.data.resize(values.size() * sizeof(T));
  for (std::size_t i = 0; i < values.size(); ++i) {
    // Little-endian serialisation independent of the host.
    std::uint64_t bits = 0;
    static_assert(sizeof(T) <= 8, "scalar types only");
    std::memcpy(&bits, &values[i], sizeof(T));
    for (std::size_t b = 0; b < sizeof(T); ++b)
      a.data[i * sizeof(T) + b] = static_cast<std::uint8_t>(bits >> (8 * b));
  }
  return a;
}

}  // namespace default_model
