// Holds on a body's measurements as the session's constraint projector
// (app/constraint_projector.hpp): the surface where the held measurements keep their values,
// points solved onto it and its normals the measurements' Jacobian; every cell of a plane is
// projected by Gauss-Newton steps that reuse the Jacobian at the plane's centre
// (body/measurement_solve.hpp). No GL: the window's BodySpace and the body benchmark share it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "app/constraint_projector.hpp"
#include "body/body_model.hpp"

namespace spaces {

// `holds`: "name" or "name=value" (body/measurements.hpp names; a bare name holds the value of
// the body at `reference`, in [0,1]^K). nullptr for no holds. Throws std::invalid_argument
// with a message for the user.
std::shared_ptr<const app::ConstraintProjector> make_body_holds(
    std::shared_ptr<const body::Model> model, const std::vector<std::string>& holds,
    const Eigen::VectorXd& reference);

}  // namespace spaces
