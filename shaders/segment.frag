// segment.frag — a capsule of radius v_radius pixels around the segment,
// shaded as a tube lit from the viewer's side (on its axis the colour itself); the
// force colour map at v_t for a bead pair, u_wall_color for a wall contact,
// or the flat u_fixed_color of wall edges.
noperspective in vec2 v_local;
flat in float v_length;
flat in float v_radius;
flat in float v_t;
flat in float v_wall;

uniform float u_fixed_width_px;
uniform vec4 u_fixed_color;
uniform vec4 u_wall_color;

void main() {
  float x = v_local.x - clamp(v_local.x, 0.0, v_length);
  float s = length(vec2(x, v_local.y)) / max(v_radius, 1e-6);
  if (s > 1.0) discard;
  if (u_fixed_width_px > 0.0) {
    emit(u_fixed_color.rgb, u_fixed_color.a, 0.0);
    return;
  }
  vec3 base = v_wall > 0.5
                  ? u_wall_color.rgb
                  : texelFetch(u_colormap, ivec2(int(floor(v_t * float(u_colormap_size - 1) + 0.5)), 0), 0).rgb;
  float facing = sqrt(1.0 - s * s);  // the tube's normal towards the viewer
  emit(base * (0.45 + 0.55 * facing), 1.0, 0.0);  // on the axis: the colour map's own
}
