// Holds: keeping some quantities of every shown cell fixed (a body's height, its mass...)
// while the search explores everything else. The design space supplies them as one object
// (BodySpace: spaces/body_holds.hpp, on body/measurement_solve.hpp): the held surface the
// optimizer builds its planes on (sps::SearchHold) and that every cell shown is projected
// onto, with what the window and the session file say about it. No GL, no body model here.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "sps/held_search.hpp"

namespace app {

// One held quantity as saved with the session: its name and value (the space's units, SI for
// a body: metres, kg).
struct HeldValue {
  std::string name;
  double value = 0.0;
};

// Held values as the texts SpaceMeasurements::hold_projector() takes ("height=1.8": the value in
// the space's units, every digit kept).
inline std::vector<std::string> hold_texts(const std::vector<HeldValue>& held) {
  std::vector<std::string> texts;
  for (const auto& h : held) {
    char value[64];
    std::snprintf(value, sizeof value, "%.17g", h.value);
    texts.push_back(h.name + "=" + value);
  }
  return texts;
}

// The holds in force: the surface (for the optimizer, sps::PlaneSearch::set_hold, and for the
// cells, sps::hold_plane and project_near) and its description.
class ConstraintProjector : public sps::SearchHold {
 public:
  // What is held, for the window and messages: "height 180.0 cm, mass 90.0 kg".
  virtual std::string description() const = 0;
  // What is held, for the session file (a resumed session holds them again). Empty: the
  // holds cannot be rebuilt from names and values (they are not saved).
  virtual std::vector<HeldValue> held_values() const { return {}; }
};

}  // namespace app
