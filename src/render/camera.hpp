// The one orbit camera every grid cell shares, so body heights compare at a glance: it looks at
// a fixed point at mid-body height from a fixed distance and never reframes per body (a grid
// as a whole is framed to its tallest body with scaled_about_floor).
#pragma once

#include <optional>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace render {

enum class ViewPreset { kFront, kSide, kThreeQuarter };

// "front", "side", "three-quarter" (also "3/4", "34"); nullopt for anything else.
std::optional<ViewPreset> parse_view_preset(const std::string& text);
const char* view_preset_name(ViewPreset preset);

struct Camera {
  float yaw_degrees = 0.0f;    // 0 = looking at the body's front (from +z), 90 = its left side
  float pitch_degrees = 6.0f;  // positive = looking slightly down
  float distance = 4.0f;       // metres from the target
  float fov_y_degrees = 30.0f;
  glm::vec3 target{0.0f, 0.98f, 0.0f};

  void set_preset(ViewPreset preset);
  // Drag by (dx, dy) pixels: yaw follows dx, pitch follows dy (clamped to +-60 degrees).
  void orbit(float dx_pixels, float dy_pixels);

  // The same view with the target and the eye moved s times as far from the floor point under
  // the body (the origin): everything appears 1/s larger, the floor stays where it was on
  // screen and the orbit angles are kept. s is clamped to [0.1, 10].
  Camera scaled_about_floor(float s) const;
  // The same about the point `pivot_y` metres above the floor point: heights near the pivot
  // stay where they were on screen (a grid framed on a band of the body). s as above; a pivot
  // that is not finite is taken as 0.
  Camera scaled_about_height(float s, float pivot_y) const;

  glm::vec3 eye() const;
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
};

}  // namespace render
