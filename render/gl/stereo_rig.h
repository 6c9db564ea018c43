// StereoRig: the eight cameras of an autostereoscopic (Alioscopy) view.
//
// Parallel cameras, not toed-in: view k (0 = leftmost) is the user's camera
// moved by s_k = (k - (n-1)/2) b along its screen-right axis, looking the
// same way. Each has an off-axis (asymmetric) frustum through one common
// window on the focus plane, at distance F in front of the rig: the window
// of the user's camera there, half-height H = F tan(fov/2), half-width
// W = H aspect. A point on the focus plane therefore lands on the same pixel
// in every view (screen depth); a point at depth z (along the view axis)
// lands at window abscissa
//   X_k = s_k + (x - s_k) F / z,     so  X_k - X_0 = (s_k - s_0)(1 - F/z):
// in front of the focus plane (z < F) it moves left from view 0 to view 7,
// behind it right, in proportion to b.
//
// Defaults: F = the camera's distance to its target (the specimen sits at
// screen depth) and b = F * 6.5/400, Alioscopy's rule of thumb for the
// spacing/focus ratio of its rigs.
#pragma once

#include <glm/glm.hpp>

#include "render/gl/camera.h"

namespace simsols::render {

struct StereoRig {
  int views = 8;
  double interaxial = 0;    // b, m between neighbouring cameras; 0 = focus * ratio
  double focus = 0;         // F, m; 0 = the camera's distance to its target
  double ratio = 6.5 / 400;  // b/F when interaxial = 0

  double focus_for(const Camera& camera) const;
  double interaxial_for(const Camera& camera) const;
  // Lateral offset s_k of view k along the camera's right axis, m.
  double offset(const Camera& camera, int k) const;
  // View k of `camera` (perspective only; an orthographic camera is drawn
  // with its perspective field of view).
  ViewProjection view(const Camera& camera, int k, double aspect) const;
  // The rig's prediction: horizontal pixel shift X_k - X_0 of a point at
  // view depth z, in a view `width` pixels wide.
  double disparity_px(const Camera& camera, int k, double z, double aspect, int width) const;
};

}  // namespace simsols::render
