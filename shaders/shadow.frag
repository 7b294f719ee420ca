#version 330 core
// Soft contact shadow: dark in the middle of the footprint, fading to nothing at its rim.
in vec2 v_local;

uniform float u_strength;

out vec4 frag_colour;

void main() {
  float r = length(v_local);
  float a = u_strength * (1.0 - smoothstep(0.15, 1.0, r));
  frag_colour = vec4(0.0, 0.0, 0.0, a);
}
