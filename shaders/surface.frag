#version 330 core
// Flat shading with a headlight (a light fixed to the camera, slightly above and
// left of the eye so that faces of different orientation read apart): the face
// normal comes from the screen-space derivatives of the view position, so no
// normals are stored.
in vec3 v_view_position;
flat in float v_stretch;
flat in uint v_material;
noperspective in vec3 v_barycentric;

// 0: stretch through the colour map, 1: material, 2: u_solid_color, 3: u_solid_color in
// diagonal stripes with white, u_stripe pixels wide (a surface group: a pattern that no
// colour map or material colour has)
uniform int u_color_mode;
uniform sampler2D u_colormap;  // 256 x 1
uniform vec2 u_range;          // stretch at the two ends of the colour map
uniform vec3 u_palette[256];  // render::kColorCycle
uniform vec3 u_solid_color;
uniform float u_stripe;
uniform float u_alpha;
uniform int u_wireframe;
uniform vec3 u_wire_color;

out vec4 o_color;

void main() {
  vec3 normal = normalize(cross(dFdx(v_view_position), dFdy(v_view_position)));
  vec3 to_light = normalize(normalize(-v_view_position) + vec3(-0.35, 0.45, 0.0));
  float lambert = abs(dot(normal, to_light));
  vec3 base;
  if (u_color_mode == 0) {
    float t = clamp((v_stretch - u_range.x) / (u_range.y - u_range.x), 0.0, 1.0);
    base = texture(u_colormap, vec2(t * (255.0 / 256.0) + 0.5 / 256.0, 0.5)).rgb;
  } else if (u_color_mode == 1) {
    base = u_palette[v_material % 256u];
  } else if (u_color_mode == 2 || mod(gl_FragCoord.x + gl_FragCoord.y, 2.0 * u_stripe) < u_stripe) {
    base = u_solid_color;
  } else {
    base = vec3(1.0);
  }
  vec3 color = base * (0.3 + 0.7 * lambert);
  if (u_wireframe != 0) {
    vec3 width = fwidth(v_barycentric);
    vec3 inside = smoothstep(vec3(0.0), 1.5 * width, v_barycentric);
    float edge = 1.0 - min(min(inside.x, inside.y), inside.z);
    color = mix(color, u_wire_color, 0.85 * edge);
  }
  o_color = vec4(color, u_alpha);
}
