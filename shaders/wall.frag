// wall.frag — a flat translucent plate (the transparent pass, or blended
// straight over the opaque frame: Renderer::draw_walls_blended).
in float v_depth;
uniform vec4 u_color;
void main() { emit(u_color.rgb, u_color.a, v_depth); }
