// common_vertex.glsl — prepended to every vertex shader after the #version
// line and the variant #defines (see render/gl/shader.cpp).

// Section (ViewSettings::section_axis): only what lies within u_section.w
// of the plane dot(u_section.xyz, x) = u_section_offset is drawn (x in the
// render frame, m); u_section.w <= 0: everything.
uniform vec4 u_section;
uniform float u_section_offset;

bool outside_section(vec3 x) {
  return u_section.w > 0.0 && abs(dot(u_section.xyz, x) - u_section_offset) > u_section.w;
}
