#version 330 core
// Studio backdrop: a vertical gradient with a soft vignette.
in vec2 v_uv;

uniform vec3 u_top;
uniform vec3 u_bottom;

out vec4 frag_colour;

void main() {
  vec3 colour = mix(u_bottom, u_top, smoothstep(0.0, 1.0, v_uv.y));
  vec2 d = v_uv - vec2(0.5, 0.45);
  colour *= 1.0 - 0.35 * dot(d, d);
  frag_colour = vec4(colour, 1.0);
}
