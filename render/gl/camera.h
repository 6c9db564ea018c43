// Camera: an orbit camera around a target point, in the world frame of the
// solver (z up, x the shear direction of the shear box).
//
// The state is what a user manipulates: the target, the distance to it, the
// azimuth (yaw, from the -y side, positive turning toward +x) and elevation
// (pitch, positive looking down), the vertical field of view, or an
// orthographic height. Everything else (view and projection matrices, near
// and far planes) is derived, so presets, fitting and mouse orbiting only
// touch these few numbers.
//
// Presets (named like the views of a bench photograph):
//   front          looks along +y: the shear plane edge-on, x to the right
//   side           looks along -x: the shear direction toward the viewer
//   top            looks down -z, x to the right
//   three-quarter  yaw 35 deg, pitch 25 deg: the default
// fit() keeps the direction and sets target and distance so that a bounding
// box fills the view with a margin.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string_view>

namespace simsols::render {

enum class ViewPreset { Front, Side, Top, ThreeQuarter };
const char* to_string(ViewPreset p);  // "front", "side", "top", "three-quarter"
std::optional<ViewPreset> parse_view_preset(std::string_view s);

struct Camera {
  glm::dvec3 target{0, 0, 0};
  double distance = 1;      // m, > 0
  double yaw_deg = 35;      // azimuth
  double pitch_deg = 25;    // elevation, in (-90, 90)
  double fov_y_deg = 30;    // perspective vertical field of view
  bool orthographic = false;
  double ortho_height = 1;  // m, visible height in orthographic mode
  double near_far_radius = 1;  // radius of the scene around the target (sets near/far)

  glm::dvec3 eye() const;
  glm::dvec3 forward() const;  // unit, from the eye to the target
  glm::dvec3 up() const;       // unit, screen up
  glm::dvec3 right() const;    // unit, screen right
  glm::dmat4 view() const;
  glm::dmat4 projection(double aspect) const;  // aspect = width / height
  double near_plane() const;
  double far_plane() const;

  // World point -> pixel (x right, y down from the top-left corner of a
  // width x height image, pixel centres at +0.5) and view-space depth (> 0
  // in front). Used by tests and by picking.
  struct Projected {
    glm::dvec2 pixel;
    double depth;
  };
  Projected project(const glm::dvec3& p, int width, int height) const;
  // Pixels per metre at view depth `depth` (perspective) or everywhere (ortho).
  double pixels_per_metre(double depth, int height) const;

  void set_preset(ViewPreset p);  // direction only
  // Target and distance (or ortho height) so the box [lo, hi] fits the view.
  void fit(const glm::dvec3& lo, const glm::dvec3& hi, double aspect, double margin = 1.08);
  // Interactive moves: angles in degrees; pan by fractions of the view
  // height, the scene following the drag (dx > 0: it moves right, dy > 0:
  // up); zoom multiplies the distance (factor < 1 zooms in).
  void orbit(double dyaw_deg, double dpitch_deg);
  void pan(double dx_fraction, double dy_fraction);
  void zoom(double factor);
};

// A view and projection matrix pair: what the renderer draws with (one
// camera, or one view of a stereo rig).
struct ViewProjection {
  glm::dmat4 view{1}, projection{1};
  bool orthographic = false;
  static ViewProjection of(const Camera& camera, double aspect) {
    return {camera.view(), camera.projection(aspect), camera.orthographic};
  }
};

}  // namespace simsols::render
