#version 330 core
// A quad on the floor plane around the body's footprint, built from gl_VertexID.
uniform mat4 u_view;
uniform mat4 u_projection;
uniform vec3 u_centre;   // on the floor
uniform vec2 u_radius;   // x and z half-extent of the ellipse

out vec2 v_local;

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
  v_local = corner;
  vec3 world = u_centre + vec3(corner.x * u_radius.x, 0.0, corner.y * u_radius.y);
  gl_Position = u_projection * u_view * vec4(world, 1.0);
}
