#include "solver/apparatus/triaxial_analysis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "solver/common/number_text.h"

namespace simsols {
namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;
constexpr double kDilatancyWindow = 0.01;  // axial strain

// The steepest dilation: -d eps_v / d eps_a over a window, as an angle.
double max_dilatancy(const std::vector<TriaxialRow>& rows) {
  double best = 0;
  size_t j = 0;
  for (size_t i = 0; i < rows.size(); ++i) {
    while (j < i && rows[i].axial_strain - rows[j].axial_strain > kDilatancyWindow) ++j;
    const double de_a = rows[i].axial_strain - rows[j].axial_strain;
    if (de_a < 0.5 * kDilatancyWindow) continue;
    const double r = (rows[i].volumetric_strain - rows[j].volumetric_strain) / de_a;
    best = std::max(best, std::asin(std::clamp(-r / (2 - r), -1.0, 1.0)) * kDeg);
  }
  return best;
}

}  // namespace

double mobilised_friction_angle(double sx, double sy, double sz) {
  const double s1 = std::max({sx, sy, sz}), s3 = std::min({sx, sy, sz});
  return s1 + s3 > 0 ? std::asin((s1 - s3) / (s1 + s3)) * kDeg : 0;
}

void analyse_triaxial_rows(const std::vector<TriaxialRow>& rows, TriaxialSummary& s) {
  if (rows.empty()) return;
  s.initial_void_ratio = rows.front().void_ratio;
  for (const TriaxialRow& r : rows) {
    if (r.friction_angle > s.peak_angle) {
      s.peak_angle = r.friction_angle;
      s.peak_q_over_p = r.p > 0 ? r.q / r.p : 0;
      s.peak_axial_strain = r.axial_strain;
      s.peak_q = r.q;
      s.peak_p = r.p;
    }
    s.max_inertial_number = std::max(s.max_inertial_number, r.inertial_number);
    s.wall_internal_gap = std::max(s.wall_internal_gap, r.lw_gap);
  }
  const double from = 0.8 * rows.back().axial_strain;
  int n = 0;
  for (const TriaxialRow& r : rows)
    if (r.axial_strain >= from && r.p > 0) {
      s.critical_angle += r.friction_angle;
      s.critical_q_over_p += r.q / r.p;
      s.critical_void_ratio += r.void_ratio;
      s.critical_p += r.p;
      ++n;
    }
  if (n > 0) {
    s.critical_angle /= n;
    s.critical_q_over_p /= n;
    s.critical_void_ratio /= n;
    s.critical_p /= n;
  }
  s.max_dilatancy_angle = max_dilatancy(rows);
}

std::string triaxial_rows_csv(const std::vector<TriaxialRow>& rows) {
  std::string out =
      "time_s,step,axial_strain,volumetric_strain,sigma_x_kPa,sigma_y_kPa,sigma_z_kPa,p_kPa,q_kPa,"
      "q_over_p,friction_angle_deg,void_ratio,coordination,lw_x_kPa,lw_y_kPa,lw_z_kPa,"
      "lw_gap,fabric_anisotropy,kinetic_energy_J,inertial_number\n";
  char buf[512];
  for (const TriaxialRow& r : rows) {
    std::snprintf(buf, sizeof buf,
                  "%.9g,%lld,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,"
                  "%.9g,%.9g,%.9g,%.9g\n",
                  r.time, static_cast<long long>(r.step), r.axial_strain, r.volumetric_strain,
                  r.sigma_x * 1e-3, r.sigma_y * 1e-3, r.sigma_z * 1e-3, r.p * 1e-3, r.q * 1e-3,
                  r.p > 0 ? r.q / r.p : 0, r.friction_angle, r.void_ratio, r.coordination,
                  r.lw_x * 1e-3, r.lw_y * 1e-3, r.lw_z * 1e-3, r.lw_gap, r.fabric_anisotropy,
                  r.kinetic_energy, r.inertial_number);
    out += buf;
  }
  return out;
}

std::string triaxial_summary_text(const TriaxialSummary& s) {
  std::ostringstream o;
  auto key = [&](const char* k, double v) { o << k << " = " << shortest_number(v) << "\n"; };
  o << "# triaxial test: peak and critical state (docs/triaxial.md)\n";
  key("confining_stress_kPa", s.confining_stress * 1e-3);
  key("strain_rate_per_s", s.strain_rate);
  key("bead_diameter_mm", s.bead_diameter * 1e3);
  key("initial_void_ratio", s.initial_void_ratio);
  key("peak_friction_angle_deg", s.peak_angle);
  key("peak_q_over_p", s.peak_q_over_p);
  key("peak_axial_strain", s.peak_axial_strain);
  key("peak_q_kPa", s.peak_q * 1e-3);
  key("peak_p_kPa", s.peak_p * 1e-3);
  key("critical_friction_angle_deg", s.critical_angle);
  key("critical_q_over_p", s.critical_q_over_p);
  key("critical_void_ratio", s.critical_void_ratio);
  key("critical_p_kPa", s.critical_p * 1e-3);
  key("max_dilatancy_angle_deg", s.max_dilatancy_angle);
  key("wall_internal_gap_percent", 100 * s.wall_internal_gap);
  key("max_inertial_number", s.max_inertial_number);
  key("settle_time_s", s.settle_time);
  key("consolidate_time_s", s.consolidate_time);
  key("wall_seconds", s.wall_seconds);
  return o.str();
}

}  // namespace simsols
