#include "render/camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace render {

std::optional<ViewPreset> parse_view_preset(const std::string& text) {
  if (text == "front") return ViewPreset::kFront;
  if (text == "side") return ViewPreset::kSide;
  if (text == "three-quarter" || text == "3/4" || text == "34" || text == "3-4") {
    return ViewPreset::kThreeQuarter;
  }
  return std::nullopt;
}

const char* view_preset_name(ViewPreset preset) {
  switch (preset) {
    case ViewPreset::kFront:
      return "front";
    case ViewPreset::kSide:
      return "side";
    case ViewPreset::kThreeQuarter:
      return "three-quarter";
  }
  return "front";
}

void Camera::set_preset(ViewPreset preset) {
  switch (preset) {
    case ViewPreset::kFront:
      yaw_degrees = 0.0f;
      break;
    case ViewPreset::kSide:
      yaw_degrees = 90.0f;
      break;
    case ViewPreset::kThreeQuarter:
      yaw_degrees = 35.0f;
      break;
  }
  pitch_degrees = 6.0f;
}

void Camera::orbit(float dx_pixels, float dy_pixels) {
  yaw_degrees = std::fmod(yaw_degrees + 0.4f * dx_pixels, 360.0f);
  pitch_degrees = std::clamp(pitch_degrees + 0.3f * dy_pixels, -60.0f, 60.0f);
}

Camera Camera::scaled_about_floor(float s) const {
  return scaled_about_height(s, 0.0f);
}

Camera Camera::scaled_about_height(float s, float pivot_y) const {
  s = std::clamp(std::isfinite(s) ? s : 1.0f, 0.1f, 10.0f);
  const glm::vec3 pivot(0.0f, std::isfinite(pivot_y) ? pivot_y : 0.0f, 0.0f);
  Camera scaled = *this;
  scaled.distance = distance * s;
  scaled.target = pivot + (target - pivot) * s;
  return scaled;
}

glm::vec3 Camera::eye() const {
  const float yaw = glm::radians(yaw_degrees);
  const float pitch = glm::radians(pitch_degrees);
  const glm::vec3 dir(std::sin(yaw) * std::cos(pitch), std::sin(pitch),
                      std::cos(yaw) * std::cos(pitch));
  return target + distance * dir;
}

glm::mat4 Camera::view() const {
  return glm::lookAt(eye(), target, glm::vec3(0.0f, 1.0f, 0.0f));
}

glm::mat4 Camera::projection(float aspect) const {
  return glm::perspective(glm::radians(fov_y_degrees), aspect, 0.1f, 50.0f);
}

}  // namespace render
