// sphere.frag — ray-sphere intersection per fragment: exact outline, exact
// depth (gl_FragDepth from the hit point), per-pixel normal for lighting.
#ifdef GL_ARB_conservative_depth  // enabled in the prelude (render/gl/shader.cpp)
layout(depth_greater) out float gl_FragDepth;
#endif
in vec3 v_quad;
flat in vec3 v_centre;
flat in float v_radius;
flat in float v_value;

uniform mat4 u_proj;
uniform int u_ortho;
uniform int u_lighting;
uniform float u_alpha;
uniform vec4 u_flat_color;  // a > 0: every bead in this colour (ghost beads)

void main() {
  // Ray from the eye (or, orthographic, along -z through the quad point).
  vec3 ro = u_ortho != 0 ? vec3(v_quad.xy, v_quad.z + 1.0) : vec3(0.0);
  vec3 rd = u_ortho != 0 ? vec3(0.0, 0.0, -1.0) : normalize(v_quad);
  // Closest approach of the ray to the centre, computed from the centre's
  // offset (accurate when the bead is small compared with its distance).
  vec3 oc = v_centre - ro;
  float b = dot(oc, rd);
  vec3 perp = oc - b * rd;
  float h2 = v_radius * v_radius - dot(perp, perp);
  if (h2 < 0.0) discard;
  float t = b - sqrt(h2);
  vec3 hit = ro + t * rd;
  // clip z and w: the projections used (perspective, off-axis, orthographic)
  // take them from the view depth alone
  float clip_z = u_proj[2][2] * hit.z + u_proj[3][2];
  float clip_w = u_proj[2][3] * hit.z + u_proj[3][3];
  gl_FragDepth = 0.5 * (clip_z / clip_w) + 0.5;

  vec3 base = u_flat_color.a > 0.0 ? u_flat_color.rgb : map_value(v_value);
  vec3 color = base;
  if (u_lighting != 0) {
    vec3 n = (hit - v_centre) / v_radius;
    vec3 l = normalize(vec3(0.35, 0.55, 1.0));
    float diffuse = max(dot(n, l), 0.0);
    vec3 hv = normalize(l - rd);
    float c = max(dot(n, hv), 0.0);  // c^40 by squaring (pow costs an exp and a log)
    float c2 = c * c, c4 = c2 * c2, c8 = c4 * c4, c32 = c8 * c8 * c8 * c8;
    float spec = c32 * c8;
    color = base * (0.30 + 0.70 * diffuse) + vec3(0.22 * spec);
  }
  emit(color, u_alpha, -hit.z);
}
