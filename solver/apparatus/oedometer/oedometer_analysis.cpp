#include "solver/apparatus/oedometer/oedometer_analysis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "solver/common/line_fit.h"
#include "solver/common/number_text.h"
#include "solver/common/errors.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180.0 / kPi;

constexpr const char* kHeader =
    "time_s,step,load_step,sigma_target_kPa,sigma_top_kPa,sigma_base_kPa,sigma_hx_kPa,"
    "sigma_hy_kPa,sigma_h_kPa,height_mm,void_ratio,k0,side_friction,coordination,"
    "kinetic_energy_J,end_of_step";
constexpr size_t kColumns = 16;

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / double(v.size());
}

// The steps' ends, in order.
std::vector<OedometerStep> steps_of(const std::vector<OedometerRow>& rows, int peak) {
  std::vector<OedometerStep> steps;
  double start = rows.empty() ? 0 : rows.front().time;
  for (const OedometerRow& r : rows) {
    if (r.end_of_step == 0) continue;
    OedometerStep s;
    s.sigma_target = r.sigma_target;
    s.sigma_top = r.sigma_top;
    s.sigma_h = r.sigma_h;
    s.void_ratio = r.void_ratio;
    s.height = r.height;
    s.k0 = r.k0;
    s.side_friction = r.side_friction;
    s.duration = r.time - start;
    s.equilibrium = r.end_of_step == 1;
    s.loading = r.load_step - 1 <= peak;
    steps.push_back(s);
    start = r.time;
  }
  return steps;
}

// The plastic share and the K0-OCR comparison of a test that unloaded
// after its largest step `peak`.
void unloading_readings(OedometerSummary& s, int peak) {
  const double e_max = s.steps[peak].void_ratio, e_last = s.steps.back().void_ratio;
  if (s.seated_void_ratio > e_max)
    s.plastic_share = (s.seated_void_ratio - e_last) / (s.seated_void_ratio - e_max);
  s.virgin = s.plastic_share > 0.5;
  const double phi = s.jaky_friction_angle > 0 ? s.jaky_friction_angle : s.implied_friction_angle;
  s.mayne_kulhawy_friction_angle = phi;
  if (phi <= 0) return;
  for (size_t i = peak + 1; i < s.steps.size(); ++i) {
    OedometerStep& st = s.steps[i];
    st.ocr = s.steps[peak].sigma_top / st.sigma_top;
    st.mayne_kulhawy_k0 = s.k0_nc * std::pow(st.ocr, std::sin(phi / kDeg));
    s.mayne_kulhawy_worst = std::max(s.mayne_kulhawy_worst, std::fabs(st.k0 / st.mayne_kulhawy_k0 - 1));
  }
}

}  // namespace

double compression_index(const std::vector<double>& sigma, const std::vector<double>& e) {
  const size_t n = sigma.size();
  if (n < 2 || e.size() != n) return 0;
  std::vector<double> x;
  for (double s : sigma) x.push_back(std::log10(s));
  const LineFit f = fit_line(x, e);
  return f.fitted ? -f.slope : 0;
}

OedometerSummary analyse_oedometer(const std::vector<OedometerRow>& rows, int peak,
                                   double jaky_friction_angle_deg) {
  OedometerSummary s;
  s.steps = steps_of(rows, peak);
  if (!rows.empty()) s.initial_void_ratio = rows.front().void_ratio;
  s.jaky_friction_angle = jaky_friction_angle_deg;
  if (jaky_friction_angle_deg > 0) s.jaky_k0 = 1 - std::sin(jaky_friction_angle_deg / kDeg);
  if (s.steps.empty()) return s;
  s.seated_void_ratio = s.steps.front().void_ratio;
  s.height = s.steps.front().height;
  const double e_ref = s.seated_void_ratio;
  std::vector<double> load_sigma, load_e, load_k0, unload_sigma, unload_e, friction;
  const int loading = std::min<int>(peak + 1, static_cast<int>(s.steps.size()));
  const int first = loading >= 4 ? 2 : 0;
  for (int i = 0; i < static_cast<int>(s.steps.size()); ++i) {
    OedometerStep& st = s.steps[i];
    st.strain = (e_ref - st.void_ratio) / (1 + e_ref);  // vertical = volumetric strain
    s.valid = s.valid && st.equilibrium;
    if (i < loading) friction.push_back(st.side_friction);
    if (i >= first && i < loading) {
      load_sigma.push_back(st.sigma_top);
      load_e.push_back(st.void_ratio);
      load_k0.push_back(st.k0);
    }
    if (i >= peak) {
      unload_sigma.push_back(st.sigma_top);
      unload_e.push_back(st.void_ratio);
    }
  }
  s.cc = compression_index(load_sigma, load_e);
  s.cc_points = static_cast<int>(load_sigma.size());
  s.cs = compression_index(unload_sigma, unload_e);
  s.cs_points = unload_sigma.size() >= 2 ? static_cast<int>(unload_sigma.size()) : 0;
  s.k0_nc = mean(load_k0);
  s.side_friction = mean(friction);
  s.implied_friction_angle =
      s.k0_nc > 0 && s.k0_nc < 1 ? std::asin(1 - s.k0_nc) * kDeg : 0;
  if (static_cast<int>(s.steps.size()) > peak + 1) {
    s.k0_end = s.steps.back().k0;
    s.ocr_end = s.steps[peak].sigma_target / s.steps.back().sigma_target;
    unloading_readings(s, peak);
  }
  return s;
}

std::string oedometer_rows_csv(const std::vector<OedometerRow>& rows) {
  std::string out = std::string(kHeader) + "\n";
  char buf[768];
  const int g = 9;
  for (const OedometerRow& r : rows) {
    std::snprintf(buf, sizeof buf,
                  "%.*g,%lld,%d,%.*g,%.*g,%.*g,%.*g,%.*g,%.*g,%.*g,%.*g,%.*g,%.*g,%.*g,%.*g,%d\n", g,
                  r.time, static_cast<long long>(r.step), r.load_step, g, r.sigma_target * 1e-3,
                  g, r.sigma_top * 1e-3, g, r.sigma_base * 1e-3, g, r.sigma_hx * 1e-3, g,
                  r.sigma_hy * 1e-3, g, r.sigma_h * 1e-3, g, r.height * 1e3, g, r.void_ratio, g,
                  r.k0, g, r.side_friction, g, r.coordination, g, r.kinetic_energy, r.end_of_step);
    out += buf;
  }
  return out;
}

std::vector<OedometerRow> parse_oedometer_rows_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (line != kHeader) throw ReadError("not an oedometer.csv (header differs)");
  std::vector<OedometerRow> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::string where = "oedometer.csv row " + std::to_string(rows.size() + 1);
    std::vector<double> v;
    std::istringstream fields(line);
    std::string f;
    while (std::getline(fields, f, ',')) {
      char* end = nullptr;
      v.push_back(std::strtod(f.c_str(), &end));
      if (f.empty() || *end != '\0') throw ReadError(where + ": '" + f + "' is not a number");
    }
    if (v.size() != kColumns)
      throw ReadError(where + " has " + std::to_string(v.size()) + " fields, expected " +
                               std::to_string(kColumns));
    OedometerRow r;
    r.time = v[0];
    r.step = static_cast<std::int64_t>(v[1]);
    r.load_step = static_cast<int>(v[2]);
    r.sigma_target = v[3] * 1e3;
    r.sigma_top = v[4] * 1e3;
    r.sigma_base = v[5] * 1e3;
    r.sigma_hx = v[6] * 1e3;
    r.sigma_hy = v[7] * 1e3;
    r.sigma_h = v[8] * 1e3;
    r.height = v[9] * 1e-3;
    r.void_ratio = v[10];
    r.k0 = v[11];
    r.side_friction = v[12];
    r.coordination = v[13];
    r.kinetic_energy = v[14];
    r.end_of_step = static_cast<int>(v[15]);
    rows.push_back(r);
  }
  return rows;
}

std::string oedometer_summary_text(const OedometerSummary& s) {
  std::ostringstream o;
  auto key = [&](const char* k, double v) { o << k << " = " << shortest_number(v) << "\n"; };
  o << "# oedometer test: load steps at rest, indices and K0 (docs/oedometer.md)\n";
  key("bead_diameter_mm", s.bead_diameter * 1e3);
  key("initial_void_ratio", s.initial_void_ratio);
  key("seated_void_ratio", s.seated_void_ratio);
  key("seated_height_mm", s.height * 1e3);
  key("compression_index_cc", s.cc);
  key("cc_points", s.cc_points);
  key("swelling_index_cs", s.cs);
  key("cs_points", s.cs_points);
  key("k0_normally_consolidated", s.k0_nc);
  key("k0_after_unloading", s.k0_end);
  key("ocr_after_unloading", s.ocr_end);
  key("jaky_friction_angle_deg", s.jaky_friction_angle);
  key("jaky_k0", s.jaky_k0);
  key("implied_friction_angle_deg", s.implied_friction_angle);
  key("side_friction_share", s.side_friction);
  key("plastic_share", s.plastic_share);
  o << "virgin_compression = " << (s.virgin ? "yes" : "no (mostly elastic: Cc is no virgin index)")
    << "\n";
  key("mayne_kulhawy_friction_angle_deg", s.mayne_kulhawy_friction_angle);
  key("mayne_kulhawy_worst_error", s.mayne_kulhawy_worst);
  o << "valid = " << (s.valid ? "yes" : "no (a step ended at step_time, not in equilibrium)")
    << "\n";
  key("settle_time_s", s.settle_time);
  key("wall_seconds", s.wall_seconds);
  o << "# step sigma_target_kPa sigma_top_kPa sigma_h_kPa void_ratio strain k0 side_friction "
       "held_s equilibrium branch ocr mayne_kulhawy_k0\n";
  char buf[256];
  for (size_t i = 0; i < s.steps.size(); ++i) {
    const OedometerStep& st = s.steps[i];
    std::snprintf(buf, sizeof buf,
                  "step_%zu = %.6g %.6g %.6g %.6f %.6g %.4f %.4f %.4g %s %s %.4g %.4f\n", i + 1,
                  st.sigma_target * 1e-3, st.sigma_top * 1e-3, st.sigma_h * 1e-3, st.void_ratio,
                  st.strain, st.k0, st.side_friction, st.duration, st.equilibrium ? "yes" : "no",
                  st.loading ? "loading" : "unloading", st.ocr, st.mayne_kulhawy_k0);
    o << buf;
  }
  return o.str();
}

}  // namespace simsols
