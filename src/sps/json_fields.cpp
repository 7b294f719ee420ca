#include "sps/json_fields.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>

namespace sps::json_fields {

namespace {

std::string at_byte(std::size_t i) {
  return " (at byte " + std::to_string(i) + ")";
}

}  // namespace

nlohmann::json parse_bounded(const std::string& text, const JsonLimits& limits) {
  if (text.size() > limits.max_bytes) {
    throw std::runtime_error("too large (" + std::to_string(text.size()) + " bytes, at most " +
                             std::to_string(limits.max_bytes) + ")");
  }
  // Brackets outside strings give the depth; a string's length is counted between its quotes
  // (escapes included, so the limit is on what the file holds).
  int depth = 0;
  bool in_string = false;
  std::size_t string_start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
      if (i - string_start > limits.max_string_bytes) {
        throw std::runtime_error("holds a text longer than " +
                                 std::to_string(limits.max_string_bytes) + " bytes" +
                                 at_byte(string_start));
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
      string_start = i;
    } else if (c == '[' || c == '{') {
      if (++depth > limits.max_depth) {
        throw std::runtime_error("nested more than " + std::to_string(limits.max_depth) +
                                 " levels deep" + at_byte(i));
      }
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("not valid JSON (") + e.what() + ")");
  }
}

std::string brief(const nlohmann::json& j) {
  constexpr std::size_t kMaxText = 40;
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::boolean:
      return j.get<bool>() ? "true" : "false";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
    case nlohmann::json::value_t::number_float:
      return j.dump();
    case nlohmann::json::value_t::string: {
      const auto& s = j.get_ref<const std::string&>();
      if (s.size() <= kMaxText)
        return nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
      return "a text of " + std::to_string(s.size()) + " bytes";
    }
    case nlohmann::json::value_t::array:
      return "an array of " + std::to_string(j.size()) + (j.size() == 1 ? " value" : " values");
    case nlohmann::json::value_t::object:
      return "an object of " + std::to_string(j.size()) + (j.size() == 1 ? " field" : " fields");
    default:
      return "a binary value";
  }
}

const nlohmann::json& field(const nlohmann::json& j, const char* key, const std::string& what) {
  if (!j.is_object()) throw std::runtime_error(what + " is missing (its parent is not an object)");
  const auto it = j.find(key);
  if (it == j.end()) throw std::runtime_error(what + " is missing");
  return *it;
}

std::string text(const nlohmann::json& j, const char* key, const std::string& what,
                 std::size_t max_bytes) {
  const nlohmann::json& v = field(j, key, what);
  if (!v.is_string()) throw std::runtime_error(what + " must be text, found " + brief(v));
  const auto& s = v.get_ref<const std::string&>();
  if (s.size() > max_bytes) {
    throw std::runtime_error(what + " is a text of " + std::to_string(s.size()) +
                             " bytes, at most " + std::to_string(max_bytes) + " expected");
  }
  return s;
}

std::string library_message(const nlohmann::json::exception& e) {
  std::string m = e.what();
  if (!m.empty() && m.front() == '[') {
    const auto close = m.find("] ");
    if (close != std::string::npos) m.erase(0, close + 2);
  }
  return m;
}

long long integer(const nlohmann::json& j, const std::string& what, long long lo, long long hi) {
  long long v = 0;
  if (j.is_number_unsigned()) {
    const auto u = j.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(hi)) {
      throw std::runtime_error(what + " is " + brief(j) + ", must be at most " +
                               std::to_string(hi));
    }
    v = static_cast<long long>(u);
  } else if (j.is_number_integer()) {
    v = j.get<std::int64_t>();
  } else {
    throw std::runtime_error(what + " must be an integer, found " + brief(j));
  }
  if (v < lo || v > hi) {
    throw std::runtime_error(what + " is " + std::to_string(v) + ", must lie in [" +
                             std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
}

double number(const nlohmann::json& j, const std::string& what, double lo, double hi) {
  if (!j.is_number()) throw std::runtime_error(what + " must be a number, found " + brief(j));
  const double v = j.get<double>();
  if (!std::isfinite(v) || v < lo || v > hi) {
    std::ostringstream range;
    range << what << " is " << brief(j) << ", must lie in [" << lo << ", " << hi << "]";
    throw std::runtime_error(range.str());
  }
  return v;
}

}  // namespace sps::json_fields
