#version 330 core
// Surface triangles: one tet face per triangle, drawn unindexed so that
// gl_VertexID % 3 is the corner within its triangle (for the wireframe).
layout(location = 0) in vec3 a_position;
layout(location = 1) in float a_stretch;
layout(location = 2) in uint a_material;

uniform mat4 u_view;
uniform mat4 u_view_projection;

out vec3 v_view_position;
flat out float v_stretch;
flat out uint v_material;
noperspective out vec3 v_barycentric;

void main() {
  v_view_position = (u_view * vec4(a_position, 1.0)).xyz;
  v_stretch = a_stretch;
  v_material = a_material;
  int corner = gl_VertexID % 3;
  v_barycentric = vec3(corner == 0, corner == 1, corner == 2);
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}
