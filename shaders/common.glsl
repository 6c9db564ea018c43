// common.glsl — prepended to every fragment shader after the #version line
// and the variant #defines (see render/gl/shader.cpp). Colour mapping shared by beads
// and chains, so the legend (render/plot/colormap.h) and the image agree.

// Colour map: a 1 x N RGBA8 texture (the table from colormap_table()).
// Continuous maps: t = (value - min) / (max - min), clamped, nearest entry.
// Categorical maps (u_categorical = 1): entry round(value) mod N.
// Qualitative maps (u_categorical = 2, identities such as grains): entry
// 2 (h(k) mod N/2) + (k mod 2) for k = round(value), h the integer hash of
// plot::qualitative_index (render/plot/colormap.cpp), which this mirrors.
uniform sampler2D u_colormap;
uniform int u_colormap_size;
uniform int u_categorical;
uniform vec2 u_range;

int qualitative_index(int k) {
  uint x = uint(k);
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return 2 * int(x % uint(u_colormap_size / 2)) + (k & 1);
}

vec3 map_value(float value) {
  int idx;
  if (u_categorical == 2) {
    idx = qualitative_index(int(round(value)));  // value + 0.5 is inexact from 2^23 on
  } else if (u_categorical != 0) {
    int k = int(floor(value + 0.5));
    idx = ((k % u_colormap_size) + u_colormap_size) % u_colormap_size;
  } else {
    float span = u_range.y - u_range.x;
    float t = span > 0.0 ? clamp((value - u_range.x) / span, 0.0, 1.0) : 0.5;
    idx = int(floor(t * float(u_colormap_size - 1) + 0.5));
  }
  return texelFetch(u_colormap, ivec2(idx, 0), 0).rgb;
}

// Weighted blended order-independent transparency (McGuire & Bavoil, JCGT
// 2013), with the depth weight on the scene's own depth range so it does not
// depend on units: d = (view depth - near) / (far - near) in [0, 1],
//   w = alpha * max(0.01, 100 * (1 - d)^3).
uniform vec2 u_depth_range;  // near, far of the scene (view depth, m)

float oit_weight(float view_depth, float alpha) {
  float d = clamp((view_depth - u_depth_range.x) / max(u_depth_range.y - u_depth_range.x, 1e-12),
                  0.0, 1.0);
  float k = 1.0 - d;
  return alpha * max(0.01, 100.0 * k * k * k);
}

#ifdef OIT
// Both targets use the same blend function (GL 3.3 has no per-target
// blending): colour ONE, ONE and alpha ZERO, ONE_MINUS_SRC_ALPHA.
//   target 0: rgb += C a w,  a *= (1 - a_i)   (revealage, cleared to 1)
//   target 1: r += a w                          (total weight)
layout(location = 0) out vec4 o_accum;
layout(location = 1) out vec4 o_weight;
void emit(vec3 color, float alpha, float view_depth) {
  float w = oit_weight(view_depth, alpha);
  o_accum = vec4(color * w, alpha);
  o_weight = vec4(w, 0.0, 0.0, alpha);
}
#else
layout(location = 0) out vec4 o_color;
void emit(vec3 color, float alpha, float view_depth) { o_color = vec4(color, alpha); }
#endif
