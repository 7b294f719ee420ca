// Reading numbers from stored state (session files, the search's JSON) safely: every value is
// checked before it is used or sizes anything. A float where an integer belongs (1e300
// converted to int is undefined behaviour), a string, NaN or an out-of-range value throws
// std::runtime_error naming the field, so a broken file is reported, never trusted.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace sps::json_fields {

// An integer in [lo, hi].
long long integer(const nlohmann::json& j, const std::string& what, long long lo, long long hi);

// A finite number in [lo, hi].
double number(const nlohmann::json& j, const std::string& what, double lo, double hi);

}  // namespace sps::json_fields
