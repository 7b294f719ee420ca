#version 330 core
// Body surface: world-space position and normal to the fragment stage; lights live in view
// space so every orbit angle is lit the same way.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_tint;  // 0 skin, 1 eye white, 2 iris (0 when not given)

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_view_position;
out vec3 v_view_normal;
out float v_height;
out float v_tint;

void main() {
  vec4 view_position = u_view * vec4(a_position, 1.0);
  v_view_position = view_position.xyz;
  v_view_normal = mat3(u_view) * a_normal;
  v_height = a_position.y;
  v_tint = a_tint;
  gl_Position = u_projection * view_position;
}
