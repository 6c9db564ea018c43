// wall.frag — a flat translucent plate (drawn in the transparent pass).
in float v_depth;
uniform vec4 u_color;
void main() { emit(u_color.rgb, u_color.a, v_depth); }
