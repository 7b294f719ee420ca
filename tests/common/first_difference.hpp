// Comparing large values in tests without printing them: Catch2 prints both operands of a
// failed CHECK(a == b), which for a session's JSON or a mesh's index list is megabytes. These
// helpers return "" when the values are equal and otherwise a short description of the first
// difference, so a test writes CHECK(first_difference(a, b) == "").
#pragma once

#include <algorithm>
#include <cstddef>
#include <sstream>
#include <string>

namespace test_support {

inline std::string first_difference(const std::string& a, const std::string& b) {
  if (a == b) return "";
  const std::size_t n = std::min(a.size(), b.size());
  std::size_t i = 0;
  while (i < n && a[i] == b[i]) ++i;
  const std::size_t from = i < 40 ? 0 : i - 40;
  std::ostringstream out;
  out << "sizes " << a.size() << " and " << b.size() << ", first difference at " << i << ": '"
      << a.substr(from, 80) << "' vs '" << b.substr(from, 80) << "'";
  return out.str();
}

// Any indexable container with size() and elements that stream and compare with ==.
template <typename Container>
std::string first_difference_in(const Container& a, const Container& b) {
  const std::size_t n = std::min<std::size_t>(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i)
    if (!(a[i] == b[i])) {
      std::ostringstream out;
      out << "element " << i << " of " << a.size() << " (vs " << b.size() << ") differs";
      return out.str();
    }
  if (a.size() != b.size()) {
    std::ostringstream out;
    out << "sizes differ: " << a.size() << " vs " << b.size();
    return out.str();
  }
  return "";
}

}  // namespace test_support
