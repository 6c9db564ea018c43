// segment.frag — flat colour: the force colour map at
// t = (ratio - threshold) / (max ratio - threshold), max ratio being where
// the width saturates; or the fixed colour of wall edges.
in float v_ratio;

uniform float u_threshold;
uniform float u_width_px;
uniform float u_max_width_px;
uniform float u_fixed_width_px;
uniform vec4 u_fixed_color;

void main() {
  if (u_fixed_width_px > 0.0) {
    emit(u_fixed_color.rgb, u_fixed_color.a, 0.0);
    return;
  }
  float max_ratio = max(u_max_width_px / max(u_width_px, 1e-6), u_threshold + 1e-3);
  float t = clamp((v_ratio - u_threshold) / (max_ratio - u_threshold), 0.0, 1.0);
  emit(texelFetch(u_colormap, ivec2(int(floor(t * float(u_colormap_size - 1) + 0.5)), 0), 0).rgb,
       1.0, 0.0);
}
