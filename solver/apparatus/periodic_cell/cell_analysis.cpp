#include "solver/apparatus/periodic_cell/cell_analysis.h"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <sstream>

#include "solver/common/errors.h"

namespace simsols {
namespace {

constexpr std::array<CellColumn, kCellColumns> kColumns = {{
    {"stage", "-"}, {"time", "s"}, {"step", "-"}, {"strain", "-"},
    {"volumetric_strain", "-"}, {"sigma_xx", "kPa"}, {"sigma_yy", "kPa"}, {"sigma_zz", "kPa"},
    {"sigma_xy", "kPa"}, {"sigma_xz", "kPa"}, {"sigma_yz", "kPa"}, {"p", "kPa"}, {"q", "kPa"},
    {"stress_ratio", "-"}, {"solid_fraction", "-"}, {"void_ratio", "-"}, {"coordination", "-"},
    {"coordination_backbone", "-"}, {"fabric_zz_minus_xx", "-"}, {"fabric_xz", "-"},
    {"inertial_number", "-"}, {"kinetic_energy", "J"},
}};

std::string header() {
  std::string h;
  for (const CellColumn& c : kColumns) {
    if (!h.empty()) h += ',';
    h += c.name;
    if (std::string(c.unit) != "-") h += std::string("_") + c.unit;
  }
  return h;
}

// The mean of v and its 95 % interval from five batch means.
SteadyValue steady_of(const std::vector<double>& v) {
  SteadyValue out;
  out.rows = static_cast<int>(v.size());
  if (v.empty()) return out;
  for (double x : v) out.mean += x / v.size();
  constexpr int kBatches = 5;
  if (v.size() < 2 * kBatches) return out;
  std::array<double, kBatches> batch{};
  const size_t per = v.size() / kBatches;
  for (int b = 0; b < kBatches; ++b)
    for (size_t k = 0; k < per; ++k) batch[b] += v[b * per + k] / per;
  double mean = 0, var = 0;
  for (double b : batch) mean += b / kBatches;
  for (double b : batch) var += (b - mean) * (b - mean) / (kBatches - 1);
  out.half_width = 2.776 * std::sqrt(var / kBatches);  // t(0.975, 4)
  return out;
}

}  // namespace

const std::array<CellColumn, kCellColumns>& cell_columns() { return kColumns; }

std::string cell_rows_csv(const std::vector<CellRow>& rows) {
  std::ostringstream o;
  o.precision(9);
  o << header() << '\n';
  for (const CellRow& r : rows) {
    for (int k = 0; k < kCellColumns; ++k) o << (k ? "," : "") << r[k];
    o << '\n';
  }
  return o.str();
}

std::vector<CellRow> parse_cell_rows_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (line != header()) throw ReadError("not a cell.csv (its header differs)");
  std::vector<CellRow> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::istringstream fields(line);
    std::string field;
    CellRow r{};
    int k = 0;
    for (; k < kCellColumns && std::getline(fields, field, ','); ++k) {
      size_t used = 0;
      try {
        r[k] = std::stod(field, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != field.size())
        throw ReadError("row " + std::to_string(rows.size() + 1) + ", column " + kColumns[k].name +
                        ": '" + field + "' is not a number");
    }
    if (k != kCellColumns)
      throw ReadError("row " + std::to_string(rows.size() + 1) + " has " + std::to_string(k) +
                      " columns, " + std::to_string(kCellColumns) + " expected");
    rows.push_back(r);
  }
  return rows;
}

double mobilised_angle(const CellRow& r) {
  Eigen::Matrix3d s;
  s << r[kColSxx], r[kColSxy], r[kColSxz], r[kColSxy], r[kColSyy], r[kColSyz], r[kColSxz], r[kColSyz], r[kColSzz];
  const Eigen::Vector3d e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(s, Eigen::EigenvaluesOnly).eigenvalues();
  const double sum = e[2] + e[0];  // ascending: e[0] minor, e[2] major
  return sum > 0 ? std::asin((e[2] - e[0]) / sum) * 180 / std::numbers::pi : 0;
}

SteadyValue steady_value(const std::vector<CellRow>& rows, int column, double from) {
  std::vector<double> v;
  for (const CellRow& r : rows)
    if (r[kColStage] == 1 && r[kColStrain] >= from) v.push_back(r[column]);
  return steady_of(v);
}

SteadyValue steady_value(const std::vector<CellRow>& rows, double (*value)(const CellRow&), double from) {
  std::vector<double> v;
  for (const CellRow& r : rows)
    if (r[kColStage] == 1 && r[kColStrain] >= from) v.push_back(value(r));
  return steady_of(v);
}

CellSummary cell_summary(const std::vector<CellRow>& rows, double from) {
  CellSummary s;
  s.from = from;
  if (!rows.empty()) s.strain = rows.back()[kColStrain];
  s.ratio = steady_value(rows, kColRatio, from);
  s.phi = steady_value(rows, kColPhi, from);
  s.z = steady_value(rows, kColZ, from);
  s.p = steady_value(rows, kColP, from);
  s.volumetric = steady_value(rows, kColVolumetric, from);
  s.angle = steady_value(rows, mobilised_angle, from);
  for (const CellRow& r : rows)
    if (r[kColStage] == 0) s.phi_compressed = r[kColPhi], s.z_compressed = r[kColZ];
  return s;
}

std::string cell_summary_text(const CellSummary& s) {
  std::ostringstream o;
  o.precision(6);
  o << "test = " << s.test << "\nparticles = " << s.particles << "\npressure_kPa = " << s.pressure * 1e-3
    << "\ninertial_number = " << s.inertial_number << "\nstrain = " << s.strain
    << "\nsteady_from_strain = " << s.from << "\nsolid_fraction_compressed = " << s.phi_compressed
    << "\ncoordination_compressed = " << s.z_compressed << '\n';
  const std::pair<const char*, const SteadyValue*> values[] = {
      {"stress_ratio", &s.ratio}, {"solid_fraction", &s.phi}, {"coordination", &s.z},
      {"p_kPa", &s.p}, {"volumetric_strain", &s.volumetric}, {"friction_angle_deg", &s.angle}};
  for (const auto& [name, v] : values)
    o << name << " = " << v->mean << '\n' << name << "_ci95 = " << v->half_width << '\n';
  o << "compression_steps = " << s.compression_steps << "\nsteps = " << s.steps
    << "\nwall_seconds = " << s.wall_seconds << '\n';
  return o.str();
}

}  // namespace simsols
