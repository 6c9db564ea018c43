// segment.vert — one screen-space quad per segment (instanced, 4 vertices).
// Force chains: a_p0/a_p1 = (end xyz, |F_n|); the width in pixels is
//   w = clamp(u_width_px * |F_n| / u_mean_force, 1, u_max_width_px)
// and segments with |F_n| / u_mean_force < u_threshold collapse (not drawn).
// Fixed lines (wall edges): u_fixed_width_px > 0 sets the width and
// u_fixed_color the colour.
layout(location = 0) in vec4 a_p0;
layout(location = 1) in vec4 a_p1;

uniform mat4 u_view;
uniform mat4 u_proj;
uniform vec2 u_viewport;     // pixels
uniform float u_mean_force;
uniform float u_threshold;
uniform float u_width_px;
uniform float u_max_width_px;
uniform float u_fixed_width_px;

out float v_ratio;

void main() {
  float ratio = u_fixed_width_px > 0.0 ? 1.0 : a_p0.w / max(u_mean_force, 1e-30);
  v_ratio = ratio;
  vec4 c0 = u_proj * u_view * vec4(a_p0.xyz, 1.0);
  vec4 c1 = u_proj * u_view * vec4(a_p1.xyz, 1.0);
  vec2 s0 = c0.xy / c0.w * 0.5 * u_viewport;
  vec2 s1 = c1.xy / c1.w * 0.5 * u_viewport;
  vec2 d = s1 - s0;
  float len = length(d);
  if ((u_fixed_width_px <= 0.0 && ratio < u_threshold) || len < 1e-6) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: nothing drawn
    return;
  }
  float w = u_fixed_width_px > 0.0 ? u_fixed_width_px
                                   : clamp(u_width_px * ratio, 1.0, u_max_width_px);
  vec2 nrm = vec2(-d.y, d.x) / len;
  float side = (gl_VertexID & 2) != 0 ? 0.5 : -0.5;
  vec4 c = (gl_VertexID & 1) != 0 ? c1 : c0;
  c.xy += nrm * side * w / (0.5 * u_viewport) * c.w;
  gl_Position = c;
}
