#include "solver/apparatus/shear_box/shear_analysis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <utility>
#include <sstream>
#include <stdexcept>

#include "solver/common/line_fit.h"
#include "solver/common/errors.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRad = 180.0 / kPi;

// A first peak is a maximum of mobilised strength: while the running
// maximum of tau/sigma is below this share of the test's largest, its
// wiggles (noise about zero at the start of shearing) are not softening.
constexpr double kPeakMobilised = 0.25;

// Slope of y(x) by least squares over rows [a, b).
double slope(const std::vector<ShearRow>& r, size_t a, size_t b) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(b - a);
  for (size_t i = a; i < b; ++i) {
    sx += r[i].displacement;
    sy += r[i].dilation;
    sxx += r[i].displacement * r[i].displacement;
    sxy += r[i].displacement * r[i].dilation;
  }
  const double den = n * sxx - sx * sx;
  return den > 0 ? (n * sxy - sx * sy) / den : 0;
}

// Rows [a, b) whose displacement lies within w/2 of row i's.
std::pair<size_t, size_t> window_around(const std::vector<ShearRow>& rows, size_t i, double w) {
  size_t a = i, b = i + 1;
  while (a > 0 && rows[a - 1].displacement >= rows[i].displacement - 0.5 * w) --a;
  while (b < rows.size() && rows[b].displacement <= rows[i].displacement + 0.5 * w) ++b;
  return {a, b};
}

// The median of `v` (reordered; the mean of the middle two when even).
double median(std::vector<double>& v) {
  const size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + m, v.end());
  if (v.size() % 2) return v[m];
  return 0.5 * (v[m] + *std::max_element(v.begin(), v.begin() + m));
}

// The row's target normal stress (rows read from older files have none).
double target_of(const ShearRow& r, double test_target) {
  return r.sigma_target > 0 ? r.sigma_target : test_target;
}

// Whether the platen carried the load in this row (a platen that lost
// contact gives no ratio).
bool loaded(const ShearRow& r, double test_target) {
  return r.sigma > 0.5 * target_of(r, test_target);
}

// Mean tau and tau/sigma over the loaded rows [a, b).
Residual mean_strength(const std::vector<ShearRow>& rows, size_t a, size_t b, double target) {
  Residual r;
  int count = 0;
  for (size_t i = a; i < b; ++i)
    if (loaded(rows[i], target)) {
      r.tau += rows[i].tau;
      r.ratio += rows[i].tau / rows[i].sigma;
      ++count;
    }
  if (count > 0) {
    r.tau /= count;
    r.ratio /= count;
  }
  return r;
}

// The first row of the last 20 % of the travel: at 0.8 x the end when rows
// are evenly spaced, included whether the displacements are exact or read
// back from shear.csv (9 digits).
size_t last_fifth(const std::vector<ShearRow>& rows) {
  const double from = 0.8 * rows.back().displacement * (1 - 1e-7);
  size_t start = rows.size();
  while (start > 0 && rows[start - 1].displacement >= from) --start;
  return start;
}

// The sliding window (rows) of the dilatancy angle and Taylor's check:
// about 1/40 of the test, at least 3 rows.
size_t dilatancy_window(const std::vector<ShearRow>& rows) {
  return std::max<size_t>(3, rows.size() / 40);
}

}  // namespace

std::string shear_rows_csv(const std::vector<ShearRow>& rows) {
  std::string out =
      "time_s,step,displacement_mm,shear_force_N,shear_force_upper_N,tau_kPa,tau_corrected_kPa,"
      "normal_force_N,sigma_kPa,dilation_mm,tau_over_sigma,friction_angle_deg,coordination,"
      "kinetic_energy_J,inertial_number,outside,sigma_target_kPa,sigma_plane_kPa,cap_tilt_deg\n";
  char buf[512];
  for (const ShearRow& r : rows) {
    std::snprintf(buf, sizeof buf,
                  "%.9g,%lld,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%.9g,%.9g,"
                  "%.6g\n",
                  r.time, static_cast<long long>(r.step), r.displacement * 1e3, r.shear_force,
                  r.shear_force_upper, r.tau * 1e-3, r.tau_corrected * 1e-3, r.normal_force,
                  r.sigma * 1e-3, r.dilation * 1e3, r.sigma > 0 ? r.tau / r.sigma : 0,
                  r.friction_angle, r.coordination, r.kinetic_energy, r.inertial_number,
                  r.outside, r.sigma_target * 1e-3, r.sigma_plane * 1e-3, r.cap_tilt * kRad);
    out += buf;
  }
  return out;
}

Residual residual_of(const std::vector<ShearRow>& rows, double sigma_target) {
  return rows.empty() ? Residual{} : mean_strength(rows, last_fifth(rows), rows.size(), sigma_target);
}

FirstPeak first_peak(const std::vector<ShearRow>& rows, double sigma_target, double recovery,
                     double softening) {
  // what counts as a peak: a quarter of the test's largest ratio, and no
  // less than its residual strength
  double top = 0;
  for (const ShearRow& r : rows)
    if (loaded(r, sigma_target)) top = std::max(top, r.tau / r.sigma);
  const double floor = std::max(kPeakMobilised * top, residual_of(rows, sigma_target).ratio);
  FirstPeak best;
  double fell_at = 0;  // displacement where the curve fell below (1 - softening) x best
  bool fallen = false;
  for (const ShearRow& r : rows) {
    if (!loaded(r, sigma_target)) continue;
    const double ratio = r.tau / r.sigma;
    if (ratio > best.ratio) {
      best.ratio = ratio;
      best.displacement = r.displacement;
      best.row = static_cast<int>(&r - rows.data());
      best.tau = r.tau;
      fallen = false;
    } else if (!fallen && best.ratio >= floor && ratio < (1 - softening) * best.ratio) {
      fallen = true;
      fell_at = r.displacement;
    }
    if (fallen && r.displacement - fell_at >= recovery) break;  // softened, not regained
  }
  return best;
}

std::vector<ShearRow> smoothed_rows(const std::vector<ShearRow>& rows, double window) {
  std::vector<ShearRow> out = rows;
  std::vector<double> ratio, spread;
  const auto ratio_of = [](const ShearRow& r) { return r.sigma > 0 ? r.tau / r.sigma : 0; };
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto [a, b] = window_around(rows, i, window);
    ratio.clear();
    for (size_t j = a; j < b; ++j) ratio.push_back(ratio_of(rows[j]));
    const double m = median(ratio);
    spread.clear();
    for (const double x : ratio) spread.push_back(std::fabs(x - m));
    const double mad = median(spread);
    if (std::fabs(ratio_of(rows[i]) - m) > kHampelThreshold * 1.4826 * mad)
      out[i].tau = m * rows[i].sigma;  // an outlier: the window's median
  }
  return out;
}

FirstPeak peak_of(const std::vector<ShearRow>& rows, double sigma_target, double d) {
  const double spacing =
      rows.size() > 1 ? (rows.back().displacement - rows.front().displacement) / (rows.size() - 1) : 0;
  const double window = std::max(kPeakSmoothingDiameters * d, 6.5 * spacing);  // seven rows or more
  return first_peak(smoothed_rows(rows, window), sigma_target, kPeakRecoveryDiameters * d);
}

CriticalState critical_state_of(const std::vector<ShearRow>& rows, double sigma_target, double d) {
  CriticalState c;
  if (rows.size() < 3) return c;
  const size_t n = rows.size();
  const double travel = rows.back().displacement;
  const double shortest = std::max(kCriticalMinDiameters * d, 0.1 * travel);
  // the longest tail from the second half on whose dilation rate, and that
  // of each of its halves, is near zero
  size_t start = n;
  for (size_t a = 0; a + 2 < n; ++a) {
    if (rows[a].displacement < 0.5 * travel) continue;
    if (travel - rows[a].displacement < shortest * (1 - 1e-7)) break;
    const size_t mid = a + (n - a) / 2;
    if (std::fabs(slope(rows, a, n)) <= kCriticalDilationRate &&
        std::fabs(slope(rows, a, mid)) <= 2 * kCriticalDilationRate &&
        std::fabs(slope(rows, mid, n)) <= 2 * kCriticalDilationRate) {
      start = a;
      break;
    }
  }
  c.reached = start < n;
  if (!c.reached) start = last_fifth(rows);  // as residual_of
  const Residual r = mean_strength(rows, start, n, sigma_target);
  c.from = rows[start].displacement;
  c.tau = r.tau;
  c.ratio = r.ratio;
  c.rate = n - start >= 2 ? slope(rows, start, n) : 0;
  return c;
}

TaylorCheck taylor_check(const std::vector<ShearRow>& rows, double sigma_target, double from) {
  TaylorCheck t;
  const size_t w = dilatancy_window(rows);
  bool inside = false, first = true;
  for (size_t a = 0; a + w <= rows.size(); ++a) {
    if (rows[a].displacement < from) continue;
    const Residual m = mean_strength(rows, a, a + w, sigma_target);
    const double mu = m.ratio - slope(rows, a, a + w);
    if (first || mu < t.min_mu) {
      t.min_mu = mu;
      t.at = rows[a + w / 2].displacement;
      first = false;
    }
    if (mu < 0 && !inside) ++t.events;
    inside = mu < 0;
  }
  return t;
}

namespace {

// The normal stress's band and RMS deviation from each row's target, and
// the test's validity.
void sigma_band(const std::vector<ShearRow>& rows, ShearSummary& s) {
  const double target = s.normal_stress_target;
  s.sigma_min = s.sigma_max = rows[0].sigma;
  s.sigma_band_lo = s.sigma_band_hi = rows[0].sigma / target_of(rows[0], target) - 1;
  double sum2 = 0;
  for (const ShearRow& r : rows) {
    const double dev = r.sigma / target_of(r, target) - 1;
    s.sigma_min = std::min(s.sigma_min, r.sigma);
    s.sigma_max = std::max(s.sigma_max, r.sigma);
    s.sigma_band_lo = std::min(s.sigma_band_lo, dev);
    s.sigma_band_hi = std::max(s.sigma_band_hi, dev);
    sum2 += dev * dev;
  }
  s.sigma_rms = std::sqrt(sum2 / static_cast<double>(rows.size()));
  s.valid = s.sigma_band_lo >= -kValidSigmaBand && s.sigma_band_hi <= kValidSigmaBand;
}

// The shear plane's normal stress of a row (older rows: the applied one).
double plane_sigma(const ShearRow& r) { return r.sigma_plane > 0 ? r.sigma_plane : r.sigma; }

// The wall-friction correction (ShearSummary::wall_load_percent and the
// angles on the plane), once the peak row and the residual window are known.
void plane_readings(const std::vector<ShearRow>& rows, int peak_row, ShearSummary& s) {
  const double target = s.normal_stress_target;
  if (std::none_of(rows.begin(), rows.end(), [](const ShearRow& r) { return r.sigma_plane > 0; })) {
    s.wall_load_percent = s.peak_angle_plane = s.residual_angle_plane =
        std::numeric_limits<double>::quiet_NaN();  // rows written before it was recorded
    return;
  }
  double lost = 0, ratio = 0;
  int n = 0, m = 0;
  for (const ShearRow& r : rows) {
    if (r.displacement <= 0 || !loaded(r, target)) continue;
    lost += 1 - plane_sigma(r) / r.sigma;
    ++n;
    if (r.displacement >= s.residual_from) {
      ratio += r.tau / plane_sigma(r);
      ++m;
    }
  }
  s.wall_load_percent = n > 0 ? 100 * lost / n : 0;
  s.residual_angle_plane = m > 0 ? std::atan(ratio / m) * kRad : 0;
  const double peak_scale = peak_row >= 0 && plane_sigma(rows[peak_row]) > 0
                                ? rows[peak_row].sigma / plane_sigma(rows[peak_row])
                                : 1;
  s.peak_angle_plane = std::atan(s.peak_ratio * peak_scale) * kRad;
}

}  // namespace

void analyse_shear_rows(const std::vector<ShearRow>& rows, ShearSummary& out) {
  // the apparatus' fields are kept; the rest is derived afresh
  ShearSummary s;
  s.normal_stress_target = out.normal_stress_target;
  s.shear_speed = out.shear_speed;
  s.specimen_height = out.specimen_height;
  s.bead_diameter = out.bead_diameter;
  s.settle_time = out.settle_time;
  s.consolidate_time = out.consolidate_time;
  s.platen_mass = out.platen_mass;
  s.upper_half_floating = out.upper_half_floating;
  s.upper_half_rise = out.upper_half_rise;
  s.cap_tilting = out.cap_tilting;
  s.wall_seconds = out.wall_seconds;
  out = s;
  if (rows.empty()) return;
  const double target = s.normal_stress_target;
  for (const ShearRow& r : rows) {
    const double ratio = loaded(r, target) ? r.tau / r.sigma : 0;
    if (ratio > s.max_ratio) {
      s.max_ratio = ratio;
      s.max_displacement = r.displacement;
    }
    s.max_tau = std::max(s.max_tau, r.tau);
    s.max_inertial_number = std::max(s.max_inertial_number, r.inertial_number);
    s.max_outside = std::max(s.max_outside, r.outside);
    if (std::fabs(r.cap_tilt) > std::fabs(s.cap_tilt_max)) s.cap_tilt_max = r.cap_tilt;
  }
  sigma_band(rows, s);
  s.quasi_static = s.max_inertial_number < kQuasiStaticInertialNumber;
  s.start_tau = rows[0].tau;
  s.start_ratio = rows[0].sigma > 0 ? rows[0].tau / rows[0].sigma : 0;
  s.max_angle = std::atan(s.max_ratio) * kRad;
  const FirstPeak first = peak_of(rows, target, s.bead_diameter);
  s.peak_ratio = first.ratio;
  s.peak_displacement = first.displacement;
  s.peak_angle = std::atan(first.ratio) * kRad;
  s.peak_tau = first.tau;
  const CriticalState cs = critical_state_of(rows, target, s.bead_diameter);
  s.residual_tau = cs.tau;
  s.residual_ratio = cs.ratio;
  s.residual_angle = std::atan(cs.ratio) * kRad;
  s.critical_state = cs.reached;
  s.residual_from = cs.from;
  s.residual_dilation_rate = cs.rate;
  // Dilatancy: least-squares slope of dz(dx) over a sliding window, the
  // steepest rise.
  const size_t w = dilatancy_window(rows);
  double steepest = 0;
  size_t at = 0;
  for (size_t a = 0; a + w <= rows.size(); ++a)
    if (const double k = slope(rows, a, a + w); k > steepest) {
      steepest = k;
      at = a;
    }
  s.max_dilatancy_angle = std::atan(steepest) * kRad;
  plane_readings(rows, first.row, s);
  double mobilised = rows.back().displacement;  // tau/sigma reaches half the peak
  for (const ShearRow& r : rows)
    if (loaded(r, target) && r.tau / r.sigma >= 0.5 * s.peak_ratio) {
      mobilised = r.displacement;
      break;
    }
  const TaylorCheck taylor = taylor_check(rows, target, mobilised);
  s.taylor_min = taylor.min_mu;
  s.taylor_min_displacement = taylor.at;
  s.dynamic_events = taylor.events;
  s.max_dilatancy_dynamic =
      rows.size() >= w && mean_strength(rows, at, at + w, target).ratio < steepest;
  out = s;
}

std::string shear_summary_text(const ShearSummary& s) {
  char buf[2560];
  std::snprintf(
      buf, sizeof buf,
      "normal_stress_kPa = %.6g\nbead_diameter_mm = %.6g\nspecimen_height_mm = %.6g\n"
      "shear_speed_mm_s = %.6g\nplaten_mass_kg = %.6g\nvalid = %s\n"
      "start_tau_kPa = %.6g\nstart_tau_over_sigma = %.6g\npeak_tau_kPa = %.6g\n"
      "peak_tau_over_sigma = %.6g\npeak_friction_angle_deg = %.4f\npeak_displacement_mm = %.6g\n"
      "max_tau_kPa = %.6g\nmax_tau_over_sigma = %.6g\nmax_friction_angle_deg = %.4f\n"
      "max_displacement_mm = %.6g\nresidual_tau_kPa = %.6g\n"
      "residual_tau_over_sigma = %.6g\nresidual_friction_angle_deg = %.4f\n"
      "max_dilatancy_angle_deg = %.4f\nmax_inertial_number = %.4g\nquasi_static = %s\n"
      "sigma_min_kPa = %.6g\n"
      "sigma_max_kPa = %.6g\nsigma_band_percent = %+.3f %+.3f\nsigma_rms_percent = %.3f\n"
      "max_beads_outside = %d\nsettle_time_s = %.6g\nconsolidate_time_s = %.6g\n"
      "wall_seconds = %.1f\n",
      s.normal_stress_target * 1e-3, s.bead_diameter * 1e3, s.specimen_height * 1e3,
      s.shear_speed * 1e3, s.platen_mass, s.valid ? "yes" : "no", s.start_tau * 1e-3,
      s.start_ratio, s.peak_tau * 1e-3, s.peak_ratio, s.peak_angle, s.peak_displacement * 1e3,
      s.max_tau * 1e-3, s.max_ratio, s.max_angle, s.max_displacement * 1e3,
      s.residual_tau * 1e-3, s.residual_ratio, s.residual_angle, s.max_dilatancy_angle,
      s.max_inertial_number, s.quasi_static ? "yes" : "no", s.sigma_min * 1e-3, s.sigma_max * 1e-3, 100 * s.sigma_band_lo,
      100 * s.sigma_band_hi, 100 * s.sigma_rms, s.max_outside, s.settle_time,
      s.consolidate_time, s.wall_seconds);
  char more[512];
  std::snprintf(more, sizeof more,
                "critical_state = %s\nresidual_from_mm = %.6g\nresidual_dilation_rate = %.4g\n"
                "taylor_min_mu = %.4g\ntaylor_min_displacement_mm = %.6g\ndynamic_events = %d\n"
                "max_dilatancy_dynamic = %s\nwall_load_percent = %.3f\n"
                "peak_friction_angle_plane_deg = %.4f\nresidual_friction_angle_plane_deg = %.4f\n"
                "upper_half = %s\nupper_half_rise_mm = %.6g\ncap = %s\ncap_tilt_max_deg = %.4g\n",
                s.critical_state ? "yes" : "no", s.residual_from * 1e3, s.residual_dilation_rate,
                s.taylor_min, s.taylor_min_displacement * 1e3, s.dynamic_events,
                s.max_dilatancy_dynamic ? "yes" : "no", s.wall_load_percent, s.peak_angle_plane,
                s.residual_angle_plane, s.upper_half_floating ? "floating" : "fixed",
                s.upper_half_rise * 1e3, s.cap_tilting ? "tilting" : "held", s.cap_tilt_max * kRad);
  return std::string(buf) + more;
}

namespace {

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == sep) {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

double to_double(const std::string& s, const std::string& what) {
  try {
    size_t used = 0;
    const double v = std::stod(s, &used);
    if (used == 0) throw std::invalid_argument(s);
    return v;
  } catch (const std::exception&) {
    throw ReadError("malformed number '" + s + "' in " + what);
  }
}

}  // namespace

std::vector<ShearRow> parse_shear_rows_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (line.rfind("time_s,step,displacement_mm", 0) != 0)
    throw ReadError("not a shear.csv (header differs)");
  std::vector<ShearRow> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto f = split(line, ',');
    // 16: written before sigma_target_kPa, 17: before sigma_plane_kPa, 18: before cap_tilt_deg
    if (f.size() < 16 || f.size() > 19)
      throw ReadError("shear.csv row " + std::to_string(rows.size() + 1) + " has " +
                               std::to_string(f.size()) + " fields, expected 19");
    const std::string where = "shear.csv row " + std::to_string(rows.size() + 1);
    std::vector<double> v;
    for (const std::string& x : f) v.push_back(to_double(x, where));
    ShearRow r;
    r.time = v[0];
    r.step = static_cast<std::int64_t>(v[1]);
    r.displacement = v[2] * 1e-3;
    r.shear_force = v[3];
    r.shear_force_upper = v[4];
    r.tau = v[5] * 1e3;
    r.tau_corrected = v[6] * 1e3;
    r.normal_force = v[7];
    r.sigma = v[8] * 1e3;
    r.dilation = v[9] * 1e-3;
    r.friction_angle = v[11];
    r.coordination = v[12];
    r.kinetic_energy = v[13];
    r.inertial_number = v[14];
    r.outside = static_cast<int>(v[15]);
    if (v.size() > 16) r.sigma_target = v[16] * 1e3;
    if (v.size() > 17) r.sigma_plane = v[17] * 1e3;  // else 0: not recorded
    if (v.size() > 18) r.cap_tilt = v[18] / kRad;
    rows.push_back(r);
  }
  return rows;
}

namespace {

// Summaries written before the peak meant the first peak called the overall
// maximum peak_* and the first peak first_peak_*: their keys, renamed.
void rename_older_keys(std::map<std::string, std::string>& kv) {
  if (!kv.count("first_peak_tau_over_sigma")) return;
  for (const char* k : {"tau_kPa", "tau_over_sigma", "friction_angle_deg", "displacement_mm"}) {
    const std::string peak = std::string("peak_") + k, first = "first_" + peak;
    if (kv.count(peak)) kv["max_" + std::string(k)] = kv[peak];
    kv.erase(peak);
    if (kv.count(first)) kv[peak] = kv[first];
  }
}

// The band as written ("lo hi" in percent), or from sigma_min/max and the
// target in older summaries; valid as written, or from the band.
void read_band(const std::map<std::string, std::string>& kv, ShearSummary& s) {
  const auto band = kv.find("sigma_band_percent");
  std::istringstream in(band != kv.end() ? band->second : std::string());
  double lo = 0, hi = 0;
  if (in >> lo >> hi) {
    s.sigma_band_lo = lo * 1e-2;
    s.sigma_band_hi = hi * 1e-2;
  } else if (s.normal_stress_target > 0) {
    s.sigma_band_lo = s.sigma_min / s.normal_stress_target - 1;
    s.sigma_band_hi = s.sigma_max / s.normal_stress_target - 1;
  }
  s.quasi_static = s.max_inertial_number < kQuasiStaticInertialNumber;
  const auto valid = kv.find("valid");
  s.valid = valid != kv.end() ? valid->second == "yes"
                              : s.sigma_band_lo >= -kValidSigmaBand &&
                                    s.sigma_band_hi <= kValidSigmaBand;
}

}  // namespace

std::map<std::string, std::string> summary_keys(const std::string& text) {
  std::map<std::string, std::string> kv;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const size_t eq = line.find(" = ");
    if (eq != std::string::npos) kv[line.substr(0, eq)] = line.substr(eq + 3);
  }
  return kv;
}

ShearSummary parse_shear_summary(const std::string& text) {
  std::map<std::string, std::string> kv = summary_keys(text);
  rename_older_keys(kv);
  ShearSummary s;
  const struct {
    const char* key;
    double* target;
    double scale;
  } fields[] = {{"normal_stress_kPa", &s.normal_stress_target, 1e3},
                {"bead_diameter_mm", &s.bead_diameter, 1e-3},
                {"specimen_height_mm", &s.specimen_height, 1e-3},
                {"shear_speed_mm_s", &s.shear_speed, 1e-3},
                {"peak_tau_kPa", &s.peak_tau, 1e3},
                {"peak_tau_over_sigma", &s.peak_ratio, 1},
                {"peak_friction_angle_deg", &s.peak_angle, 1},
                {"peak_displacement_mm", &s.peak_displacement, 1e-3},
                {"max_tau_kPa", &s.max_tau, 1e3},
                {"max_tau_over_sigma", &s.max_ratio, 1},
                {"max_friction_angle_deg", &s.max_angle, 1},
                {"max_displacement_mm", &s.max_displacement, 1e-3},
                {"residual_tau_kPa", &s.residual_tau, 1e3},
                {"residual_tau_over_sigma", &s.residual_ratio, 1},
                {"residual_friction_angle_deg", &s.residual_angle, 1},
                {"max_dilatancy_angle_deg", &s.max_dilatancy_angle, 1},
                {"max_inertial_number", &s.max_inertial_number, 1},
                {"sigma_min_kPa", &s.sigma_min, 1e3},
                {"sigma_max_kPa", &s.sigma_max, 1e3},
                {"sigma_rms_percent", &s.sigma_rms, 1e-2},
                {"start_tau_kPa", &s.start_tau, 1e3},
                {"start_tau_over_sigma", &s.start_ratio, 1},
                {"platen_mass_kg", &s.platen_mass, 1},
                {"settle_time_s", &s.settle_time, 1},
                {"consolidate_time_s", &s.consolidate_time, 1},
                {"wall_seconds", &s.wall_seconds, 1},
                {"residual_from_mm", &s.residual_from, 1e-3},
                {"residual_dilation_rate", &s.residual_dilation_rate, 1},
                {"taylor_min_mu", &s.taylor_min, 1},
                {"taylor_min_displacement_mm", &s.taylor_min_displacement, 1e-3},
                {"wall_load_percent", &s.wall_load_percent, 1},
                {"peak_friction_angle_plane_deg", &s.peak_angle_plane, 1},
                {"residual_friction_angle_plane_deg", &s.residual_angle_plane, 1},
                {"upper_half_rise_mm", &s.upper_half_rise, 1e-3},
                {"cap_tilt_max_deg", &s.cap_tilt_max, 1 / kRad}};
  int seen = 0;
  for (const auto& f : fields)
    if (const auto it = kv.find(f.key); it != kv.end()) {
      *f.target = to_double(it->second, "summary key " + it->first) * f.scale;
      ++seen;
    }
  if (const auto it = kv.find("max_beads_outside"); it != kv.end())
    s.max_outside = static_cast<int>(to_double(it->second, it->first));
  if (const auto it = kv.find("dynamic_events"); it != kv.end())
    s.dynamic_events = static_cast<int>(to_double(it->second, it->first));
  s.critical_state = kv.count("critical_state") && kv.at("critical_state") == "yes";
  s.upper_half_floating = kv.count("upper_half") && kv.at("upper_half") == "floating";
  s.cap_tilting = kv.count("cap") && kv.at("cap") == "tilting";
  s.max_dilatancy_dynamic =
      kv.count("max_dilatancy_dynamic") && kv.at("max_dilatancy_dynamic") == "yes";
  if (seen < 10) throw ReadError("not a shear-test summary (too few keys)");
  read_band(kv, s);
  return s;
}

MohrCoulomb fit_mohr_coulomb(const std::vector<double>& sigma, const std::vector<double>& tau) {
  MohrCoulomb m;
  const LineFit f = fit_line(sigma, tau);
  m.points = f.points;
  if (!f.fitted) return m;
  m.tan_phi = f.slope;
  m.cohesion = f.intercept;
  m.phi_deg = std::atan(m.tan_phi) * kRad;
  m.r2 = f.r2;
  m.exact = f.points == 2;
  m.tan_phi_se = f.slope_se;
  m.cohesion_se = f.intercept_se;
  m.phi_se_deg = m.exact ? f.slope_se : m.tan_phi_se / (1 + m.tan_phi * m.tan_phi) * kRad;
  return m;
}

}  // namespace simsols
