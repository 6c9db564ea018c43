#include "solver/apparatus/triaxial/triaxial_analysis.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "solver/common/line_fit.h"
#include "solver/common/number_text.h"
#include "solver/common/errors.h"

namespace simsols {
namespace {

// triaxial.csv's columns, in order (written and read back below)
constexpr const char* kColumns[] = {
    "time_s", "step", "axial_strain", "volumetric_strain", "sigma_x_kPa", "sigma_y_kPa",
    "sigma_z_kPa", "p_kPa", "q_kPa", "q_over_p", "friction_angle_deg", "void_ratio",
    "coordination", "lw_x_kPa", "lw_y_kPa", "lw_z_kPa", "lw_gap", "fabric_anisotropy",
    "kinetic_energy_J", "inertial_number", "membrane_axial_kPa", "membrane_shell_kPa"};
constexpr size_t kColumnCount = sizeof kColumns / sizeof kColumns[0];
constexpr size_t kColumnsBeforeMembrane = kColumnCount - 2;  // files written before the membrane's columns

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

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + h, v.end());
  const double hi = v[h];
  if (v.size() % 2) return hi;
  return 0.5 * (hi + *std::max_element(v.begin(), v.begin() + h));
}

// The median of `value` over the rows within kPeakWindow / 2 of row i's
// axial strain.
double window_median(const std::vector<TriaxialRow>& rows, size_t i,
                     double (*value)(const TriaxialRow&)) {
  std::vector<double> v;
  for (const TriaxialRow& r : rows)
    if (std::fabs(r.axial_strain - rows[i].axial_strain) <= 0.5 * kPeakWindow * (1 + 1e-9))
      v.push_back(value(r));
  return median(std::move(v));
}

double angle_of(const TriaxialRow& r) { return r.friction_angle; }
double ratio_of(const TriaxialRow& r) { return r.p > 0 ? r.q / r.p : 0; }
double q_of(const TriaxialRow& r) { return r.q; }
double p_of(const TriaxialRow& r) { return r.p; }
double sigma1_of(const TriaxialRow& r) { return std::max({r.sigma_x, r.sigma_y, r.sigma_z}); }
double sigma3_of(const TriaxialRow& r) { return std::min({r.sigma_x, r.sigma_y, r.sigma_z}); }

// The peak: the largest running median of the mobilised angle, and the
// medians of the other readings over the same window.
void read_peak(const std::vector<TriaxialRow>& rows, TriaxialSummary& s) {
  size_t best = 0;
  double best_angle = -1;
  for (size_t i = 0; i < rows.size(); ++i)
    if (const double a = window_median(rows, i, angle_of); a > best_angle) {
      best_angle = a;
      best = i;
    }
  s.peak_angle = best_angle;
  s.peak_axial_strain = rows[best].axial_strain;
  s.peak_q_over_p = window_median(rows, best, ratio_of);
  s.peak_q = window_median(rows, best, q_of);
  s.peak_p = window_median(rows, best, p_of);
  s.peak_sigma1 = window_median(rows, best, sigma1_of);
  s.peak_sigma3 = window_median(rows, best, sigma3_of);
}

}  // namespace

void analyse_triaxial_rows(const std::vector<TriaxialRow>& rows, TriaxialSummary& s) {
  if (rows.empty()) return;
  s.initial_void_ratio = rows.front().void_ratio;
  read_peak(rows, s);
  std::vector<double> gaps;
  for (const TriaxialRow& r : rows) {
    if (r.friction_angle > s.max_angle) {
      s.max_angle = r.friction_angle;
      s.max_axial_strain = r.axial_strain;
    }
    s.max_inertial_number = std::max(s.max_inertial_number, r.inertial_number);
    s.wall_internal_gap = std::max(s.wall_internal_gap, r.lw_gap);
    gaps.push_back(r.lw_gap);
  }
  s.median_wall_internal_gap = median(std::move(gaps));
  s.end_membrane_axial = rows.back().membrane_axial;
  s.end_membrane_shell = rows.back().membrane_shell;
  const double from = 0.8 * rows.back().axial_strain * (1 - 1e-7);
  int n = 0;
  for (const TriaxialRow& r : rows)
    if (r.axial_strain >= from && r.p > 0) {
      s.critical_angle += r.friction_angle;
      s.critical_q_over_p += r.q / r.p;
      s.critical_void_ratio += r.void_ratio;
      s.critical_p += r.p;
      s.critical_sigma1 += std::max({r.sigma_x, r.sigma_y, r.sigma_z});
      s.critical_sigma3 += std::min({r.sigma_x, r.sigma_y, r.sigma_z});
      ++n;
    }
  if (n > 0) {
    s.critical_angle /= n;
    s.critical_q_over_p /= n;
    s.critical_void_ratio /= n;
    s.critical_p /= n;
    s.critical_sigma1 /= n;
    s.critical_sigma3 /= n;
  }
  s.max_dilatancy_angle = max_dilatancy(rows);
}

std::string triaxial_rows_csv(const std::vector<TriaxialRow>& rows) {
  std::string out;
  for (size_t i = 0; i < kColumnCount; ++i) out += std::string(i ? "," : "") + kColumns[i];
  out += "\n";
  char buf[512];
  for (const TriaxialRow& r : rows) {
    std::snprintf(buf, sizeof buf,
                  "%.9g,%lld,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,"
                  "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                  r.time, static_cast<long long>(r.step), r.axial_strain, r.volumetric_strain,
                  r.sigma_x * 1e-3, r.sigma_y * 1e-3, r.sigma_z * 1e-3, r.p * 1e-3, r.q * 1e-3,
                  r.p > 0 ? r.q / r.p : 0, r.friction_angle, r.void_ratio, r.coordination,
                  r.lw_x * 1e-3, r.lw_y * 1e-3, r.lw_z * 1e-3, r.lw_gap, r.fabric_anisotropy,
                  r.kinetic_energy, r.inertial_number, r.membrane_axial * 1e-3, r.membrane_shell * 1e-3);
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
  key("max_friction_angle_deg", s.max_angle);
  key("max_angle_axial_strain", s.max_axial_strain);
  key("peak_q_over_p", s.peak_q_over_p);
  key("peak_axial_strain", s.peak_axial_strain);
  key("peak_q_kPa", s.peak_q * 1e-3);
  key("peak_p_kPa", s.peak_p * 1e-3);
  key("peak_sigma1_kPa", s.peak_sigma1 * 1e-3);
  key("peak_sigma3_kPa", s.peak_sigma3 * 1e-3);
  key("critical_friction_angle_deg", s.critical_angle);
  key("critical_q_over_p", s.critical_q_over_p);
  key("critical_void_ratio", s.critical_void_ratio);
  key("critical_p_kPa", s.critical_p * 1e-3);
  key("critical_sigma1_kPa", s.critical_sigma1 * 1e-3);
  key("critical_sigma3_kPa", s.critical_sigma3 * 1e-3);
  key("max_dilatancy_angle_deg", s.max_dilatancy_angle);
  key("wall_internal_gap_percent", 100 * s.wall_internal_gap);
  key("median_wall_internal_gap_percent", 100 * s.median_wall_internal_gap);
  key("max_inertial_number", s.max_inertial_number);
  o << "cell = " << (s.membrane ? "membrane" : "rigid") << "\n";
  if (s.membrane) {
    key("max_membrane_stress_kPa", s.max_membrane_stress * 1e-3);
    key("end_membrane_axial_kPa", s.end_membrane_axial * 1e-3);
    key("end_membrane_shell_kPa", s.end_membrane_shell * 1e-3);
  }
  key("settle_time_s", s.settle_time);
  key("consolidate_time_s", s.consolidate_time);
  key("wall_seconds", s.wall_seconds);
  return o.str();
}

namespace {

std::vector<double> csv_numbers(const std::string& line, size_t row, size_t columns) {
  std::vector<double> v;
  std::istringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) {
    size_t used = 0;
    double x = 0;
    try {
      x = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != field.size())
      throw ReadError("triaxial.csv row " + std::to_string(row) + ", column " +
                               kColumns[std::min(v.size(), kColumnCount - 1)] + ": '" + field +
                               "' is not a number");
    v.push_back(x);
  }
  if (v.size() != columns)
    throw ReadError("triaxial.csv row " + std::to_string(row) + " has " +
                             std::to_string(v.size()) + " fields, expected " +
                             std::to_string(columns));
  return v;
}

}  // namespace

std::vector<TriaxialRow> parse_triaxial_rows_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line, header, older;
  for (size_t i = 0; i < kColumnCount; ++i) {
    header += std::string(i ? "," : "") + kColumns[i];
    if (i + 1 == kColumnsBeforeMembrane) older = header;
  }
  std::getline(in, line);
  if (line != header && line != older) throw ReadError("not a triaxial.csv (its header differs)");
  const size_t columns = line == header ? kColumnCount : kColumnsBeforeMembrane;
  std::vector<TriaxialRow> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<double> v = csv_numbers(line, rows.size() + 1, columns);
    TriaxialRow r;
    r.time = v[0];
    r.step = static_cast<std::int64_t>(v[1]);
    r.axial_strain = v[2];
    r.volumetric_strain = v[3];
    r.sigma_x = v[4] * 1e3;
    r.sigma_y = v[5] * 1e3;
    r.sigma_z = v[6] * 1e3;
    r.p = v[7] * 1e3;
    r.q = v[8] * 1e3;
    r.friction_angle = v[10];
    r.void_ratio = v[11];
    r.coordination = v[12];
    r.lw_x = v[13] * 1e3;
    r.lw_y = v[14] * 1e3;
    r.lw_z = v[15] * 1e3;
    r.lw_gap = v[16];
    r.fabric_anisotropy = v[17];
    r.kinetic_energy = v[18];
    r.inertial_number = v[19];
    if (columns == kColumnCount) {
      r.membrane_axial = v[20] * 1e3;
      r.membrane_shell = v[21] * 1e3;
    }
    rows.push_back(r);
  }
  return rows;
}

MohrCoulomb fit_mohr_circles(const std::vector<double>& sigma1, const std::vector<double>& sigma3) {
  MohrCoulomb m;
  const size_t n = std::min(sigma1.size(), sigma3.size());
  std::vector<double> s(n), t(n);
  for (size_t i = 0; i < n; ++i) {
    s[i] = 0.5 * (sigma1[i] + sigma3[i]);
    t[i] = 0.5 * (sigma1[i] - sigma3[i]);
  }
  const LineFit f = fit_line(s, t);
  m.points = f.points;
  if (!f.fitted) return m;
  const double sin_phi = std::clamp(f.slope, -0.999999, 0.999999);
  const double cos_phi = std::sqrt(1 - sin_phi * sin_phi);
  m.phi_deg = std::asin(sin_phi) * kDeg;
  m.tan_phi = sin_phi / cos_phi;
  m.cohesion = f.intercept / cos_phi;
  m.r2 = f.r2;
  m.exact = f.points == 2;
  m.phi_se_deg = f.slope_se / cos_phi * kDeg;  // d(phi) = d(sin phi) / cos phi
  m.tan_phi_se = f.slope_se / (cos_phi * cos_phi * cos_phi);
  m.cohesion_se = f.intercept_se / cos_phi;  // NaN with two circles
  return m;
}

CriticalStateLine fit_critical_state_line(const std::vector<double>& p, const std::vector<double>& e) {
  CriticalStateLine c;
  const size_t n = std::min(p.size(), e.size());
  std::vector<double> lnp(n);
  for (size_t i = 0; i < n; ++i) lnp[i] = std::log(p[i] / 1e3);
  const LineFit f = fit_line(lnp, e);
  c.points = f.points;
  if (!f.fitted) return c;
  c.gamma = f.intercept;
  c.lambda = -f.slope;
  c.lambda_se = f.slope_se;
  c.r2 = f.r2;
  return c;
}


}  // namespace simsols
