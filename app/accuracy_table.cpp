#include "accuracy_table.h"

#include <cmath>
#include <sstream>

namespace simsols {

const char* embedded_accuracy_csv();  // accuracy_csv.cpp (generated)

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.emplace_back();
    else out.back() += c;
  }
  return out;
}

std::vector<AccuracyEntry> parse() {
  std::vector<AccuracyEntry> t;
  std::istringstream in(embedded_accuracy_csv());
  std::string line;
  std::getline(in, line);  // header
  double ref_wall = 0;
  while (std::getline(in, line)) {
    const auto f = split_csv(line);
    if (f.size() < 24) continue;
    AccuracyEntry e;
    e.label = f[1];
    e.dt_fraction = std::atof(f[2].c_str());
    e.precision = f[3] == "double" ? Precision::Double : Precision::Float;
    e.stiffness_scale = std::atof(f[4].c_str());
    e.inertial_number = std::atof(f[5].c_str());
    e.status = f[15];
    if (e.status == "ok" && !f[19].empty()) e.peak_error_pct = std::atof(f[19].c_str());
    e.wall_s = std::atof(f[22].c_str());
    if (f[0] == "reference") ref_wall = e.wall_s;
    t.push_back(e);
  }
  for (AccuracyEntry& e : t) e.reference_wall_s = ref_wall;
  return t;
}

}  // namespace

const std::vector<AccuracyEntry>& accuracy_table() {
  static const std::vector<AccuracyEntry> table = parse();
  return table;
}

const AccuracyEntry* expected_accuracy(double dt, Precision p) {
  const AccuracyEntry* best = nullptr;
  double best_d = 1e300;
  for (const AccuracyEntry& e : accuracy_table()) {
    if (e.precision != p || e.stiffness_scale != 1) continue;
    const double d = std::fabs(std::log(e.dt_fraction / dt));
    if (d < best_d) {
      best_d = d;
      best = &e;
    }
  }
  return best;
}

}  // namespace simsols
