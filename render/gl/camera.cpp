#include "render/gl/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace simsols::render {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180;
}

const char* to_string(ViewPreset p) {
  switch (p) {
    case ViewPreset::Front: return "front";
    case ViewPreset::Side: return "side";
    case ViewPreset::Top: return "top";
    case ViewPreset::ThreeQuarter: return "three-quarter";
  }
  return "?";
}

std::optional<ViewPreset> parse_view_preset(std::string_view s) {
  for (ViewPreset p : {ViewPreset::Front, ViewPreset::Side, ViewPreset::Top, ViewPreset::ThreeQuarter})
    if (s == to_string(p)) return p;
  return std::nullopt;
}

glm::dvec3 Camera::forward() const {
  // yaw 0, pitch 0: looking along +y (from the -y side)
  const double y = yaw_deg * kDeg, p = pitch_deg * kDeg;
  return {std::sin(y) * std::cos(p), std::cos(y) * std::cos(p), -std::sin(p)};
}

glm::dvec3 Camera::right() const {
  const double y = yaw_deg * kDeg;
  return {std::cos(y), -std::sin(y), 0};
}

glm::dvec3 Camera::up() const { return glm::cross(right(), forward()); }

glm::dvec3 Camera::eye() const { return target - distance * forward(); }

glm::dmat4 Camera::view() const { return glm::lookAt(eye(), target, up()); }

double Camera::near_plane() const {
  if (orthographic) return std::max(1e-6, distance - 2 * near_far_radius);
  return std::max(distance * 1e-3, distance - 1.5 * near_far_radius);
}

double Camera::far_plane() const { return distance + 1.5 * near_far_radius; }

glm::dmat4 Camera::projection(double aspect) const {
  if (orthographic) {
    const double h = ortho_height / 2, w = h * aspect;
    return glm::ortho(-w, w, -h, h, near_plane(), far_plane());
  }
  return glm::perspective(fov_y_deg * kDeg, aspect, near_plane(), far_plane());
}

Camera::Projected Camera::project(const glm::dvec3& p, int width, int height) const {
  const glm::dvec4 v = view() * glm::dvec4(p, 1);
  const glm::dvec4 c = projection(double(width) / height) * v;
  const glm::dvec2 ndc(c.x / c.w, c.y / c.w);
  return {{(ndc.x * 0.5 + 0.5) * width, (0.5 - ndc.y * 0.5) * height}, -v.z};
}

double Camera::pixels_per_metre(double depth, int height) const {
  if (orthographic) return height / ortho_height;
  return height / (2 * depth * std::tan(fov_y_deg * kDeg / 2));
}

void Camera::set_preset(ViewPreset p) {
  switch (p) {
    case ViewPreset::Front: yaw_deg = 0; pitch_deg = 0; break;
    case ViewPreset::Side: yaw_deg = -90; pitch_deg = 0; break;
    case ViewPreset::Top: yaw_deg = 0; pitch_deg = 89.999; break;
    case ViewPreset::ThreeQuarter: yaw_deg = 35; pitch_deg = 25; break;
  }
}

void Camera::fit(const glm::dvec3& lo, const glm::dvec3& hi, double aspect, double margin) {
  target = 0.5 * (lo + hi);
  // The box's extent across the screen axes, then the distance at which
  // that extent fits the narrower field of view.
  const glm::dvec3 r = right(), u = up(), f = forward();
  double ex = 0, ey = 0, ez = 0;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
    const glm::dvec3 d = c - target;
    ex = std::max(ex, std::abs(glm::dot(d, r)));
    ey = std::max(ey, std::abs(glm::dot(d, u)));
    ez = std::max(ez, std::abs(glm::dot(d, f)));
  }
  near_far_radius = std::max(1e-9, glm::length(hi - lo) / 2);
  const double half_h = std::max(ey, ex / aspect) * margin;
  ortho_height = 2 * half_h;
  // perspective: the nearest face of the box (ez in front of the target)
  // must fit too
  distance = half_h / std::tan(fov_y_deg * kDeg / 2) + ez;
}

void Camera::orbit(double dyaw_deg, double dpitch_deg) {
  yaw_deg = std::fmod(yaw_deg + dyaw_deg, 360.0);
  pitch_deg = std::clamp(pitch_deg + dpitch_deg, -89.999, 89.999);
}

void Camera::pan(double dx_fraction, double dy_fraction) {
  const double h = orthographic ? ortho_height : 2 * distance * std::tan(fov_y_deg * kDeg / 2);
  target -= (dx_fraction * h) * right() + (dy_fraction * h) * up();
}

void Camera::zoom(double factor) {
  factor = std::clamp(factor, 1e-3, 1e3);
  distance *= factor;
  ortho_height *= factor;
}

}  // namespace simsols::render
