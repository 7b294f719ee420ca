// Which vertices are the eyes' whites and irises: the eyeballs are the vertices an eye joint
// alone moves (weight >= 0.99 to left_eye_smplhf or right_eye_smplhf, as in SMPL-X and the
// built-in models), and the iris is the part of an eyeball that faces forward (+z) within 30
// degrees of its joint (a 12 mm iris on a 24 mm eyeball). Models without eye joints have no
// eye vertices. The glTF export gives them their own materials and the renderer its colours,
// so that a face reads with open eyes instead of skin-coloured lumps.
#pragma once

#include <cstdint>
#include <vector>

#include "body/body_model.hpp"

namespace body {

enum class EyePart : std::uint8_t { kSkin = 0, kWhite = 1, kIris = 2 };

// One entry per vertex of the model, from its rest template (the eyes move rigidly, so the
// parts hold for every shape and pose).
std::vector<EyePart> eye_parts(const Model& model);

}  // namespace body
