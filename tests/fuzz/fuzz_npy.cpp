// libFuzzer target: the .npy parser and every conversion of what it accepts.
#include <cstddef>
#include <cstdint>
#include <exception>

#include "body/npy_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const body::NpyArray a = body::parse_npy(data, size);
    const auto convert = [&](auto&& f) {
      try {
        f();
      } catch (const body::NpyError&) {
      }
    };
    convert([&] { (void)a.to_float(); });
    convert([&] { (void)a.to_double(); });
    convert([&] { (void)a.to_int64(); });
    convert([&] { (void)a.to_strings(); });
    (void)a.header.dtype_name();
    (void)a.header.shape_string();
  } catch (const body::NpyError&) {
    // A clear refusal is the expected outcome for most inputs; anything else (another
    // exception type, a crash, a sanitizer report) is a finding.
  }
  return 0;
}
