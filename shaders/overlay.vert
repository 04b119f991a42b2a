#version 330 core
// 2D overlay (legend) in pixel coordinates, origin top-left.
layout(location = 0) in vec2 a_position;
layout(location = 1) in vec4 a_color;
layout(location = 2) in float a_ramp;  // >= 0: colour-map coordinate instead of a_color

uniform vec2 u_viewport;

out vec4 v_color;
out float v_ramp;

void main() {
  v_color = a_color;
  v_ramp = a_ramp;
  gl_Position = vec4(2.0 * a_position.x / u_viewport.x - 1.0,
                     1.0 - 2.0 * a_position.y / u_viewport.y, 0.0, 1.0);
}
