#version 330 core
in vec4 v_color;
in float v_ramp;

uniform sampler2D u_colormap;

out vec4 o_color;

void main() {
  if (v_ramp >= 0.0) {
    o_color = vec4(texture(u_colormap, vec2(v_ramp * (255.0 / 256.0) + 0.5 / 256.0, 0.5)).rgb, 1.0);
  } else {
    o_color = v_color;
  }
}
