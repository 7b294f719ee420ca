#include "sps/json_fields.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>

namespace sps::json_fields {

long long integer(const nlohmann::json& j, const std::string& what, long long lo, long long hi) {
  long long v = 0;
  if (j.is_number_unsigned()) {
    const auto u = j.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(hi)) {
      throw std::runtime_error(what + " is " + j.dump() + ", must be at most " +
                               std::to_string(hi));
    }
    v = static_cast<long long>(u);
  } else if (j.is_number_integer()) {
    v = j.get<std::int64_t>();
  } else {
    throw std::runtime_error(what + " must be an integer, found " + j.dump());
  }
  if (v < lo || v > hi) {
    throw std::runtime_error(what + " is " + std::to_string(v) + ", must lie in [" +
                             std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
}

double number(const nlohmann::json& j, const std::string& what, double lo, double hi) {
  if (!j.is_number()) throw std::runtime_error(what + " must be a number, found " + j.dump());
  const double v = j.get<double>();
  if (!std::isfinite(v) || v < lo || v > hi) {
    std::ostringstream range;
    range << what << " is " << j.dump() << ", must lie in [" << lo << ", " << hi << "]";
    throw std::runtime_error(range.str());
  }
  return v;
}

}  // namespace sps::json_fields
