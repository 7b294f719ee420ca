// Holds (issue 13): keeping some quantities of every shown cell fixed (a body's height, its
// mass...) while the search explores everything else. The design space supplies the
// projector (BodySpace: body/measurement_solve.hpp); the session only calls it where planes
// and cells are made. No GL, no body model here.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sps/held_search.hpp"
#include "sps/plane.hpp"

namespace app {

// The optimizer's plane adapted to the holds: its centre moved onto them and its directions
// projected onto those that leave the held quantities unchanged to first order.
class HeldPlane {
 public:
  virtual ~HeldPlane() = default;
  // A point of `plane` (or near it) moved back onto the holds: the nearest such point inside
  // the box [0,1]^n. Thread-safe.
  virtual Eigen::VectorXd project(const Eigen::VectorXd& x) const = 0;
  sps::Plane plane;
};

// One held quantity as saved with the session: its name and value (the space's units, SI for
// a body: metres, kg).
struct HeldValue {
  std::string name;
  double value = 0.0;
};

// Held values as the texts DesignSpace::hold_projector() takes ("height=1.8": the value in
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

class ConstraintProjector {
 public:
  virtual ~ConstraintProjector() = default;
  virtual std::shared_ptr<const HeldPlane> hold(const sps::Plane& plane) const = 0;
  // What is held, for the window and messages: "height 180.0 cm, mass 90.0 kg".
  virtual std::string description() const = 0;
  // What is held, for the session file (a resumed session holds them again). Empty: the
  // projector cannot be rebuilt from names and values (it is not saved).
  virtual std::vector<HeldValue> held_values() const { return {}; }
  // The held surface for the optimizer (sps::PlaneSearch::set_hold), so that it builds its
  // planes on it instead of having them projected afterwards. nullptr: it does not.
  virtual std::shared_ptr<const sps::SearchHold> search_hold() const { return nullptr; }
};

}  // namespace app
