#version 330 core
// Photo colour enhancement (12 parameters): brightness, contrast and saturation, then colour
// balance for shadows, midtones and highlights. The same formula runs on the CPU for
// exports (src/spaces/photo_enhancement.cpp); keep the two in step.
in vec2 v_uv;
out vec4 frag_colour;

uniform sampler2D u_image;
uniform float u_p[12];  // each in [-1, 1]; 0 leaves the photo as it is
uniform vec4 u_rect;    // image rectangle in the viewport: x0, y0, x1, y1 in [0, 1]
uniform vec3 u_backdrop;

const vec3 kLuma = vec3(0.2126, 0.7152, 0.0722);
// What +-1 of a parameter does (the constants of photo_enhancement.cpp).
const float kBalanceShift = 0.12;
const float kBrightnessLog2Gamma = 0.6;
const float kContrastLog2Slope = 0.6;
const float kSaturationRange = 0.5;

vec3 enhance(vec3 c) {
  // Tone first, colour balance last (see photo_enhancement.cpp).
  c = pow(c, vec3(exp2(-kBrightnessLog2Gamma * u_p[0])));
  c = clamp((c - 0.5) * exp2(kContrastLog2Slope * u_p[1]) + 0.5, 0.0, 1.0);
  float l = dot(c, kLuma);
  c = clamp(mix(vec3(l), c, 1.0 + kSaturationRange * u_p[2]), 0.0, 1.0);
  float w_shadow = (1.0 - l) * (1.0 - l);  // Bernstein weights (see photo_enhancement.cpp)
  float w_high = l * l;
  float w_mid = 1.0 - w_shadow - w_high;
  vec3 shift = kBalanceShift * (w_shadow * vec3(u_p[3], u_p[4], u_p[5]) +
                                w_mid * vec3(u_p[6], u_p[7], u_p[8]) +
                                w_high * vec3(u_p[9], u_p[10], u_p[11]));
  shift -= dot(shift, kLuma);  // luminosity preserved (see photo_enhancement.cpp)
  return clamp(c + shift, 0.0, 1.0);
}

void main() {
  vec2 t = (v_uv - u_rect.xy) / (u_rect.zw - u_rect.xy);
  if (t.x < 0.0 || t.x > 1.0 || t.y < 0.0 || t.y > 1.0) {
    frag_colour = vec4(u_backdrop, 1.0);
    return;
  }
  vec3 c = texture(u_image, vec2(t.x, 1.0 - t.y)).rgb;  // image rows top-down
  frag_colour = vec4(enhance(c), 1.0);
}
