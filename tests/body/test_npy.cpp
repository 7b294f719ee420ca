// .npy parsing: dtypes, byte orders, memory orders, ranks, object arrays and broken files.
#include <catch2/catch.hpp>

#include "body/npy_reader.hpp"
#include "npz_fixtures.hpp"

using body::NpyError;
using body::parse_npy;
using fixtures::Array;
using fixtures::Dtype;
using fixtures::Encoding;

namespace {

body::NpyArray parse(const std::string& bytes) {
  return parse_npy(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

}  // namespace

TEST_CASE("npy: every supported dtype in both byte orders and both memory orders", "[npy]") {
  const Array base{{2, 3, 4}, {}, Dtype::f4};
  std::vector<double> values;
  for (int i = 0; i < 24; ++i) values.push_back(i * 3 - 20);  // negative and positive integers
  for (Dtype d : {Dtype::f4, Dtype::f8, Dtype::i4, Dtype::i8, Dtype::u4, Dtype::u8}) {
    for (bool big : {false, true}) {
      for (bool fortran : {false, true}) {
        Array a = base;
        a.dtype = d;
        a.values = values;
        if (d == Dtype::u4 || d == Dtype::u8) {
          for (auto& v : a.values) v = std::abs(v);
        }
        const auto arr = parse(fixtures::encode_npy(a, Encoding{big, fortran}));
        INFO("dtype " << static_cast<int>(d) << " big " << big << " fortran " << fortran);
        CHECK(arr.header.shape == std::vector<std::size_t>{2, 3, 4});
        CHECK(arr.header.big_endian == big);
        CHECK(arr.header.fortran_order == fortran);
        const auto f = arr.to_double();
        REQUIRE(f.size() == 24);
        for (std::size_t i = 0; i < 24; ++i) CHECK(f[i] == a.values[i]);
        const auto n = arr.to_int64();
        for (std::size_t i = 0; i < 24; ++i) CHECK(n[i] == static_cast<std::int64_t>(a.values[i]));
      }
    }
  }
}

TEST_CASE("npy: Fortran order of a rank-2 array is transposed into C order", "[npy]") {
  // 2 x 3 array [[1,2,3],[4,5,6]] stored column by column: 1 4 2 5 3 6.
  std::string data;
  for (float v : {1.f, 4.f, 2.f, 5.f, 3.f, 6.f}) data.append(reinterpret_cast<char*>(&v), 4);
  const auto arr = parse(fixtures::encode_npy_raw("<f4", "(2, 3)", true, data));
  CHECK(arr.to_float() == std::vector<float>{1, 2, 3, 4, 5, 6});
}

TEST_CASE("npy: big-endian float64 bytes are swapped", "[npy]") {
  const std::string data("\x3f\xf8\x00\x00\x00\x00\x00\x00", 8);  // 1.5 big-endian
  const auto arr = parse(fixtures::encode_npy_raw(">f8", "(1,)", false, data));
  CHECK(arr.header.dtype_name() == "float64");
  CHECK(arr.to_double() == std::vector<double>{1.5});
}

TEST_CASE("npy: scalars, empty arrays, strings, and object arrays", "[npy]") {
  const std::string one("\x00\x00\x80\x3f", 4);
  CHECK(parse(fixtures::encode_npy_raw("<f4", "()", false, one)).to_float() ==
        std::vector<float>{1.0f});
  CHECK(parse(fixtures::encode_npy_raw("<f4", "(0, 3)", false, "")).to_float().empty());

  std::string u;  // two UTF-32 strings of up to 3 characters: "ab", "xyz"
  for (char32_t ch : {U'a', U'b', U'\0', U'x', U'y', U'z'}) {
    const auto c = static_cast<std::uint32_t>(ch);
    u.append(reinterpret_cast<const char*>(&c), 4);
  }
  CHECK(parse(fixtures::encode_npy_raw("<U3", "(2,)", false, u)).to_strings() ==
        std::vector<std::string>{"ab", "xyz"});
  CHECK(parse(fixtures::encode_npy_raw("|S4", "(2,)", false, std::string("hip\0neck", 8)))
            .to_strings() == std::vector<std::string>{"hip", "neck"});

  const auto obj = parse(fixtures::encode_npy_raw("|O", "(3,)", false, "\x80\x02garbage"));
  CHECK(obj.header.needs_pickle());
  CHECK(obj.data.empty());
}

TEST_CASE("npy: header fields in another order, version 2 header", "[npy]") {
  std::string header = "{'shape': (2,), 'fortran_order': False, 'descr': '<i4'}";
  while ((12 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string bytes = "\x93NUMPY";
  bytes += '\x02';
  bytes += '\x00';
  const auto len = static_cast<std::uint32_t>(header.size());
  bytes.append(reinterpret_cast<const char*>(&len), 4);
  bytes += header;
  const std::int32_t vals[2] = {7, -9};
  bytes.append(reinterpret_cast<const char*>(vals), 8);
  CHECK(parse(bytes).to_int64() == std::vector<std::int64_t>{7, -9});
}

TEST_CASE("npy: broken files give clear errors", "[npy]") {
  const std::string four(16, '\0');
  CHECK_THROWS_WITH(parse("PK\x03\x04 not npy at all"), Catch::Contains("bad magic"));
  CHECK_THROWS_WITH(parse("\x93NUM"), Catch::Contains("truncated"));
  CHECK_THROWS_WITH(parse(fixtures::encode_npy_raw("<f4", "(10, 3)", false, four)),
                    Catch::Contains("array larger than the file") &&
                        Catch::Contains("needs 120 bytes but only 16"));
  CHECK_THROWS_WITH(parse(fixtures::encode_npy_raw("<f2", "(2,)", false, four)),
                    Catch::Contains("unsupported dtype '<f2'"));
  CHECK_THROWS_WITH(parse(fixtures::encode_npy_raw("<c8", "(2,)", false, four)),
                    Catch::Contains("unsupported dtype"));
  CHECK_THROWS_WITH(parse(fixtures::encode_npy_raw("<f4", "(2, x)", false, four)),
                    Catch::Contains("malformed .npy header"));
  CHECK_THROWS_WITH(parse(fixtures::encode_npy_raw("<f4", "(99999999999, 99999999999, 99999999999)",
                                                   false, four)),
                    Catch::Contains("too large"));
  std::string cut = fixtures::encode_npy_raw("<f4", "(2,)", false, four);
  cut.resize(30);  // inside the header
  CHECK_THROWS_AS(parse(cut), NpyError);
  // Float values that are not integers cannot be indices.
  const std::string half("\x00\x00\x00\x3f", 4);
  CHECK_THROWS_WITH(parse(fixtures::encode_npy_raw("<f4", "(1,)", false, half)).to_int64(),
                    Catch::Contains("not an integer"));
}

TEST_CASE("npy: zero-width string dtypes are refused before any string is made", "[npy][errors]") {
  // Once, '<U0' / '|S0' with a huge shape held no bytes, passed the size check
  // and then allocated one string per element in to_strings() (length_error, terabytes).
  for (const char* descr : {"<U0", "|S0", ">U0"}) {
    INFO(descr);
    CHECK_THROWS_WITH(parse(fixtures::encode_npy_raw(descr, "(1000000000000,)", false, "")),
                      Catch::Contains("zero-width"));
    CHECK_THROWS_WITH(parse(fixtures::encode_npy_raw(descr, "(3,)", false, "")),
                      Catch::Contains("zero-width"));
  }
}

TEST_CASE("npy: code points that are not Unicode become U+FFFD", "[npy]") {
  std::string u;
  for (std::uint32_t cp : {0x41u, 0xD800u, 0x110000u})
    u.append(reinterpret_cast<const char*>(&cp), 4);
  CHECK(parse(fixtures::encode_npy_raw("<U3", "(1,)", false, u)).to_strings() ==
        std::vector<std::string>{"A\xEF\xBF\xBD\xEF\xBF\xBD"});
}
