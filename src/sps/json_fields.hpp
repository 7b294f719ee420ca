// Reading numbers from stored state (session files, the search's JSON) safely: every value is
// checked before it is used or sizes anything. A float where an integer belongs (1e300
// converted to int is undefined behaviour), a string, NaN or an out-of-range value throws
// std::runtime_error naming the field, so a broken file is reported, never trusted.
#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace sps::json_fields {

// What a JSON text the tool reads may hold. Stored state is a few levels deep with short
// strings; a file nesting arrays 100,000 deep, or holding a 100 MB string, is broken or an
// attack, and is refused before a tree is built from it (a deep tree overflows the stack of
// anything that walks it recursively, such as dump()).
struct JsonLimits {
  std::size_t max_bytes = 256u << 20;
  int max_depth = 64;
  std::size_t max_string_bytes = 64u << 10;
};

// Parses `text` after checking it against `limits` with a flat scan. Throws
// std::runtime_error "<problem> (at byte N)" for text over the limits and "not valid JSON
// (...)" for a parse error.
nlohmann::json parse_bounded(const std::string& text, const JsonLimits& limits = {});

// j[key], which must exist: throws std::runtime_error "<what> is missing" otherwise (also when
// j is not an object).
const nlohmann::json& field(const nlohmann::json& j, const char* key, const std::string& what);

// j[key] as text of at most `max_bytes`: "<what> is missing", "<what> must be text, found
// null", "<what> is a text of N bytes, at most M".
std::string text(const nlohmann::json& j, const char* key, const std::string& what,
                 std::size_t max_bytes = 4096);

// The JSON library's message for a value of the wrong form, without its "[json.exception...]"
// prefix, for "malformed ...: <message>" texts.
std::string library_message(const nlohmann::json::exception& e);

// A short description of a value for a message: numbers and short strings as they are,
// longer strings cut, arrays and objects by their size ("an array of 3 values"). Never more
// than about 80 characters, whatever the value holds.
std::string brief(const nlohmann::json& j);

// An integer in [lo, hi].
long long integer(const nlohmann::json& j, const std::string& what, long long lo, long long hi);

// A finite number in [lo, hi].
double number(const nlohmann::json& j, const std::string& what, double lo, double hi);

}  // namespace sps::json_fields
