// oit_composite.frag — resolves the weighted blended transparency over the
// opaque image. Blended with SRC_ALPHA, ONE_MINUS_SRC_ALPHA:
//   out = (sum C a w / sum a w) (1 - R) + opaque R,   R = prod (1 - a_i).
uniform sampler2D u_accum;
uniform sampler2D u_weight;
// o_color: declared in common.glsl
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 accum = texelFetch(u_accum, p, 0);
  float revealage = accum.a;
  if (revealage >= 1.0) discard;  // nothing transparent here
  float weight = texelFetch(u_weight, p, 0).r;
  o_color = vec4(accum.rgb / max(weight, 1e-12), 1.0 - revealage);
}
