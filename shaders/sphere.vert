// sphere.vert — one camera-facing quad per bead (instanced, 4 vertices as a
// triangle strip, corners from gl_VertexID). The quad is normal to the view
// ray through the centre, at the sphere's nearest point (distance d - r),
// with half size (d - r) r / sqrt(d^2 - r^2): the cross-section there of the
// cone of rays tangent to the sphere, so it covers the outline under
// perspective (an ellipse off the axis) without waste. Orthographic: half
// size r, at the front of the sphere. Because the quad is in front of every
// point of the sphere, the depth the fragment shader writes is never nearer
// than the quad's (depth_greater): the depth test can reject hidden beads
// before shading them.
layout(location = 0) in vec4 a_bead;   // centre xyz (m, relative to the render origin), radius
layout(location = 1) in float a_value; // the colour field's value

uniform mat4 u_view;
uniform mat4 u_proj;
uniform int u_ortho;

out vec3 v_quad;            // view-space point on the quad
flat out vec3 v_centre;     // view-space centre
flat out float v_radius;
flat out float v_value;

void main() {
  if (outside_section(a_bead.xyz)) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: nothing drawn
    return;
  }
  vec2 corner = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  vec3 c = (u_view * vec4(a_bead.xyz, 1.0)).xyz;
  float r = a_bead.w;
  vec3 q;
  if (u_ortho != 0) {
    q = c + vec3(corner * r, r);
  } else {
    float d = length(c);
    vec3 w = c / d;
    vec3 u = normalize(cross(w, abs(w.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 v = cross(u, w);
    float front = max(d - r, 1e-3 * d);
    float h = r * front / sqrt(max(d * d - r * r, 1e-6 * d * d));
    q = w * front + (corner.x * u + corner.y * v) * h;
  }
  v_quad = q;
  v_centre = c;
  v_radius = r;
  v_value = a_value;
  gl_Position = u_proj * vec4(q, 1.0);
}
