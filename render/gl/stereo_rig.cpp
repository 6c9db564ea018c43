#include "render/gl/stereo_rig.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace simsols::render {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180;
}

double StereoRig::focus_for(const Camera& camera) const {
  return focus > 0 ? focus : camera.distance;
}

double StereoRig::interaxial_for(const Camera& camera) const {
  return interaxial > 0 ? interaxial : ratio * focus_for(camera);
}

double StereoRig::offset(const Camera& camera, int k) const {
  return (k - (views - 1) / 2.0) * interaxial_for(camera);
}

ViewProjection StereoRig::view(const Camera& camera, int k, double aspect) const {
  const double F = focus_for(camera), s = offset(camera, k);
  const glm::dvec3 shift = s * camera.right();
  ViewProjection vp;
  vp.view = glm::lookAt(camera.eye() + shift, camera.target + shift, camera.up());
  const double n = camera.near_plane(), f = camera.far_plane();
  const double H = F * std::tan(camera.fov_y_deg * kDeg / 2), W = H * aspect;
  // the common window [-W, W] x [-H, H] on the focus plane, seen from s
  vp.projection = glm::frustum((-W - s) * n / F, (W - s) * n / F, -H * n / F, H * n / F, n, f);
  return vp;
}

double StereoRig::disparity_px(const Camera& camera, int k, double z, double aspect,
                               int width) const {
  const double F = focus_for(camera);
  const double W = F * std::tan(camera.fov_y_deg * kDeg / 2) * aspect;
  const double dX = (offset(camera, k) - offset(camera, 0)) * (1 - F / z);
  return dX / (2 * W) * width;
}

}  // namespace simsols::render
