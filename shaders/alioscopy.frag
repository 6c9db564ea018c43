// alioscopy.frag — composes the eight views (a 2D texture array) into the
// output, 1:1 (see render/gl/alioscopy.h):
//   u_mode 0  interleaved for the lenticular screen (nearest texel):
//             v = (Y - (3X + c) + phase) mod 8, or with flip_slant
//             (-Y - (3X + c) + phase) mod 8; view = v or 7 - v (reversed);
//             X, Y physical screen pixels, Y from the top
//   u_mode 1  a u_grid.x by u_grid.y grid of the views (grid_layout in
//             alioscopy.h), view 0 top left, each fitted in its cell with
//             the views' aspect (that of the output) kept
//   u_mode 2  view u_single, full size
uniform sampler2DArray u_views;
uniform ivec2 u_output;         // output size, pixels
uniform ivec2 u_view_size;      // the views' size, pixels
uniform ivec2 u_origin;         // the output's bottom-left corner in the target
uniform ivec2 u_window;         // the output's top-left pixel on the screen
uniform int u_phase;
uniform int u_reversed;
uniform int u_flip_slant;
uniform int u_mode;
uniform int u_single;
uniform ivec2 u_grid;           // columns, rows

int view_of(int X, int Y, int c) {
  int s = (u_flip_slant != 0 ? -Y : Y) - (3 * X + c) + u_phase;
  int v = ((s % 8) + 8) % 8;
  return u_reversed != 0 ? 7 - v : v;
}

void main() {
  ivec2 f = ivec2(gl_FragCoord.xy) - u_origin;  // GL: row 0 at the bottom
  int row_from_top = u_output.y - 1 - f.y;
  vec2 uv = (vec2(f) + 0.5) / vec2(u_output);  // the same point in every view
  if (u_mode == 0) {
    int X = u_window.x + f.x, Y = u_window.y + row_from_top;
    vec3 rgb;
    // nearest texel: a row samples each view at 3 subpixels in 8, which the
    // default views (3/8 of the output) match one texel per sample
    ivec2 t = min(ivec2(uv * vec2(u_view_size)), u_view_size - 1);
    for (int c = 0; c < 3; ++c) rgb[c] = texelFetch(u_views, ivec3(t, view_of(X, Y, c)), 0)[c];
    emit(rgb, 1.0, 0.0);
  } else if (u_mode == 1) {
    vec2 cell = vec2(u_output) / vec2(u_grid);
    int col = min(int(float(f.x) / cell.x), u_grid.x - 1);
    int row = min(int(float(row_from_top) / cell.y), u_grid.y - 1);
    int view = row * u_grid.x + col;
    float aspect = float(u_output.x) / float(u_output.y);
    vec2 shown = aspect > cell.x / cell.y ? vec2(cell.x, cell.x / aspect)
                                          : vec2(cell.y * aspect, cell.y);
    vec2 origin = vec2(float(col), float(u_grid.y - 1 - row)) * cell + 0.5 * (cell - shown);
    vec2 local = (vec2(f) + 0.5 - origin) / shown;
    if (view >= textureSize(u_views, 0).z || any(lessThan(local, vec2(0.0))) || any(greaterThan(local, vec2(1.0))))
      emit(vec3(0.0), 1.0, 0.0);
    else
      emit(texture(u_views, vec3(local, float(view))).rgb, 1.0, 0.0);
  } else {
    emit(texture(u_views, vec3(uv, float(u_single))).rgb, 1.0, 0.0);
  }
}
