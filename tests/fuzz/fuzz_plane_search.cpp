// libFuzzer target: PlaneSearch::from_json on its own, then undo to every snapshot with a
// JSON round trip at each, and the posterior at the current plane's centre.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

#include "sps/plane_search.hpp"

namespace {

void round_trip(const sps::PlaneSearch& s) {
  const std::string text = s.to_json();
  try {
    if (sps::PlaneSearch::from_json(text).to_json() != text) {
      std::fprintf(stderr, "round trip changed the plane search\n");
      std::abort();
    }
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "a loaded plane search does not read back: %s\n", e.what());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::optional<sps::PlaneSearch> search;
  try {
    search = sps::PlaneSearch::from_json(text);
  } catch (const std::runtime_error&) {
    return 0;
  }
  round_trip(*search);
  const Eigen::VectorXd c = search->current_plane().c;
  const double mean = search->posterior_mean(c);
  const double variance = search->posterior_variance(c);
  if (!std::isfinite(mean) || !std::isfinite(variance)) {
    std::fprintf(stderr, "a loaded plane search predicts NaN/inf (mean %g, variance %g)\n", mean,
                 variance);
    std::abort();
  }
  while (search->undo()) round_trip(*search);
  return 0;
}
