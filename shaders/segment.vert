// segment.vert — one screen-space capsule per segment (instanced, 4 vertices
// of a quad that covers it).
// Force chains: a_p0 = (a.xyz, |F_n|), a_p1 = (b.xyz, kind: 0 bead pair,
// 1 wall contact). A tube of world radius
//   r = max(r_min, r_max |F_n| / F_max),   u_tube_radius = (r_max, r_min)
// projected at the segment's ends (their mean, at least 0.75 px), drawn
// where |F_n| >= F_thr; u_force_range = (F_thr, F_max). The colour
// coordinate is t = (|F_n| - F_thr) / (F_max - F_thr).
// Fixed lines (wall edges): u_fixed_width_px > 0 sets the width and
// segment.frag's u_fixed_color the colour.
layout(location = 0) in vec4 a_p0;
layout(location = 1) in vec4 a_p1;

uniform mat4 u_view;
uniform mat4 u_proj;
uniform vec2 u_viewport;     // pixels
uniform vec2 u_force_range;  // F_thr, F_max (N)
uniform vec2 u_tube_radius;  // r_max, r_min (m)
uniform float u_fixed_width_px;

noperspective out vec2 v_local;  // pixels: along the segment from a, across from its axis (screen-linear)
flat out float v_length;  // pixels from a to b
flat out float v_radius;  // pixels
flat out float v_t;       // colour coordinate
flat out float v_wall;    // 1 for a wall contact

void main() {
  bool fixed_width = u_fixed_width_px > 0.0;
  float force = a_p0.w;
  vec4 c0 = u_proj * u_view * vec4(a_p0.xyz, 1.0);
  vec4 c1 = u_proj * u_view * vec4(a_p1.xyz, 1.0);
  vec2 s0 = c0.xy / c0.w * 0.5 * u_viewport;
  vec2 s1 = c1.xy / c1.w * 0.5 * u_viewport;
  vec2 d = s1 - s0;
  float len = length(d);
  bool cut = !fixed_width && outside_section(0.5 * (a_p0.xyz + a_p1.xyz));  // wall edges stay
  if ((!fixed_width && force < u_force_range.x) || cut || len < 1e-6 || c0.w <= 0.0 || c1.w <= 0.0) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: nothing drawn
    return;
  }
  float r = max(u_tube_radius.y, u_tube_radius.x * force / max(u_force_range.y, 1e-30));
  float px = r * u_proj[1][1] * 0.5 * u_viewport.y;  // pixels per unit of 1/w
  float radius = fixed_width ? 0.5 * u_fixed_width_px : max(0.75, 0.5 * px * (1.0 / c0.w + 1.0 / c1.w));
  vec2 along = d / len;
  vec2 across = vec2(-along.y, along.x);
  float end = (gl_VertexID & 1) != 0 ? 1.0 : 0.0;
  float side = (gl_VertexID & 2) != 0 ? 1.0 : -1.0;
  vec4 c = end > 0.0 ? c1 : c0;
  vec2 offset = along * (end > 0.0 ? radius : -radius) + across * side * radius;
  c.xy += offset / (0.5 * u_viewport) * c.w;
  gl_Position = c;
  v_local = vec2(end * len + dot(offset, along), side * radius);
  v_length = len;
  v_radius = radius;
  float span = u_force_range.y - u_force_range.x;
  v_t = span > 0.0 ? clamp((force - u_force_range.x) / span, 0.0, 1.0) : 1.0;
  v_wall = a_p1.w;
}
