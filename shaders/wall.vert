// wall.vert — one rectangle (a wall of the box) as a 4-vertex strip:
// centre +- axis_u +- axis_v (half extents included in the axes).
uniform mat4 u_view;
uniform mat4 u_proj;
uniform vec3 u_centre;
uniform vec3 u_axis_u;
uniform vec3 u_axis_v;

out float v_depth;

void main() {
  float su = (gl_VertexID & 1) != 0 ? 1.0 : -1.0;
  float sv = (gl_VertexID & 2) != 0 ? 1.0 : -1.0;
  vec4 p = u_view * vec4(u_centre + su * u_axis_u + sv * u_axis_v, 1.0);
  v_depth = -p.z;
  gl_Position = u_proj * p;
}
