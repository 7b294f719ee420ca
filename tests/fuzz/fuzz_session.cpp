// libFuzzer target: session restore as the window does it (Session::from_json, which runs
// PlaneSearch::from_json), then undo to every history entry and a JSON round trip at each.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/session.hpp"

namespace {

void round_trip(const app::Session& s) {
  const std::string text = s.to_json();
  try {
    const app::Session again = app::Session::from_json(text);
    if (again.to_json() != text) {
      std::fprintf(stderr, "round trip changed the session\n");
      std::abort();
    }
  } catch (const std::runtime_error& e) {
    // The tool must never write a session it cannot read back.
    std::fprintf(stderr, "a loaded session does not read back: %s\n", e.what());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::optional<app::Session> session;
  try {
    session = app::Session::from_json(text);
  } catch (const std::runtime_error&) {
    return 0;  // refused with a message: fine
  }
  round_trip(*session);
  for (int steps = 0; steps < 64 && session->undo_click(); ++steps) round_trip(*session);
  (void)session->cells();
  (void)session->current_best();
  return 0;
}
