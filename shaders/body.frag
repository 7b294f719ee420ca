#version 330 core
// Soft studio lighting: a warm key light from the upper left, a cool fill from the right,
// a rim light from behind, hemispheric ambient and a little ground occlusion near the feet.
in vec3 v_view_position;
in vec3 v_view_normal;
in float v_height;
in float v_tint;

uniform vec3 u_albedo;
uniform float u_floor_y;

out vec4 frag_colour;

float soft_diffuse(vec3 n, vec3 l, float wrap) {
  return max((dot(n, l) + wrap) / (1.0 + wrap), 0.0);
}

void main() {
  vec3 n = normalize(v_view_normal);
  vec3 to_eye = normalize(-v_view_position);
  // Open meshes: light the inside like the outside. Whether a fragment shows the inside is
  // decided by the triangle's own plane (screen-space derivatives), not by the interpolated
  // normal: near a silhouette that normal turns slightly away from the eye on the outside
  // too, and flipping it there left dark specks along the outlines of heads and backs.
  vec3 face = normalize(cross(dFdx(v_view_position), dFdy(v_view_position)));
  if (dot(face, to_eye) < 0.0) face = -face;
  if (dot(n, face) < 0.0) n = -n;

  const vec3 key_dir = normalize(vec3(-0.55, 0.65, 0.55));
  const vec3 fill_dir = normalize(vec3(0.8, 0.1, 0.45));
  const vec3 rim_dir = normalize(vec3(0.2, 0.35, -1.0));
  const vec3 key_colour = vec3(1.00, 0.96, 0.90) * 0.85;
  const vec3 fill_colour = vec3(0.70, 0.78, 0.95) * 0.35;
  const vec3 rim_colour = vec3(0.9, 0.95, 1.0) * 0.35;

  float sky = 0.5 + 0.5 * n.y;
  vec3 ambient = mix(vec3(0.16, 0.15, 0.15), vec3(0.30, 0.32, 0.36), sky);
  float occlusion = mix(0.55, 1.0, smoothstep(0.0, 0.25, v_height - u_floor_y));

  vec3 light = ambient * occlusion;
  light += key_colour * soft_diffuse(n, key_dir, 0.25);
  light += fill_colour * soft_diffuse(n, fill_dir, 0.5);
  float facing = 1.0 - max(dot(n, to_eye), 0.0);
  float rim = facing * facing * facing;
  light += rim_colour * rim * max(dot(n, rim_dir) + 0.6, 0.0);

  vec3 h = normalize(key_dir + to_eye);
  // x^32 by repeated squaring: pow() is costly in a software rasterizer.
  float s = max(dot(n, h), 0.0);
  s *= s;
  s *= s;
  s *= s;
  s *= s;
  s *= s;
  float specular = s * 0.12;

  // The eyes: white, and a dark iris where the tint passes 1.5 (a crisp edge between
  // vertices of the two parts); glossier than skin. The white starts near 1, at the eyeball's
  // own vertices: its neighbours are the lids', and half of the triangles between them
  // showed white lids.
  vec3 albedo = u_albedo;
  if (v_tint > 0.9) {
    albedo = v_tint > 1.5 ? vec3(0.16, 0.10, 0.07) : vec3(0.88, 0.86, 0.82);
    specular *= 2.5;
  }
  vec3 colour = albedo * light + vec3(specular);
  colour = colour * (1.12 - 0.12 * colour);  // mild tone curve (brightens mid-tones)
  frag_colour = vec4(clamp(colour, 0.0, 1.0), 1.0);
}
