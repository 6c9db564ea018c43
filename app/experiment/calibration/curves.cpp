#include "app/experiment/calibration/curves.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>

#include "solver/common/csv_table.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"

namespace simsols {

namespace {

// The column called `name` of `t`; `fail` with the allowed names when absent.
template <class Fail>
int column_or_fail(const CsvTable& t, const std::string& name, Fail fail) {
  const int c = t.column(name);
  if (c < 0) fail("no column '" + name + "'; the columns are: " + t.names());
  return c;
}

// Rows of `t` kept by "column=value" (all when `where` is empty).
std::vector<size_t> kept_rows(const CsvTable& t, const std::string& where,
                              const std::function<void(const std::string&)>& fail) {
  std::vector<size_t> out;
  const size_t eq = where.find('=');
  const int c = where.empty() ? -1 : column_or_fail(t, where.substr(0, eq), fail);
  const std::string value = where.empty() ? "" : where.substr(eq + 1);
  for (size_t r = 0; r < t.rows.size(); ++r)
    if (c < 0 || t.rows[r][static_cast<size_t>(c)] == value) out.push_back(r);
  if (out.empty()) fail("no row has " + where);
  return out;
}

// Each y counted from its value at x0 (on the first branch that reaches
// it), which the curve must reach: a
// ReadError when x0 lies outside the rows' x's (a run whose first row
// comes after it, say).
void make_relative(Curve& c, double x0) {
  for (std::vector<double>& y : c.y) {
    const double y0 = value_at(c.x, y, x0);
    if (!std::isfinite(y0))
      throw ReadError("zero_at (" + format_number("%g", x0) + " in SI units) lies outside the x's " +
                      "of its rows" + (c.x.empty() ? std::string() :
                      " (the first at " + format_number("%g", c.x.front()) + ")") +
                      ": give a zero_at every curve reaches");
    for (double& v : y) v -= y0;
  }
}

Curve read_curve(const CsvTable& t, const std::vector<size_t>& rows, const std::vector<int>& cols,
                 const std::vector<double>& factors) {
  Curve c;
  c.y.resize(cols.size() - 1);
  for (size_t r : rows) {
    c.x.push_back(t.number(r, cols[0]) * factors[0]);
    for (size_t j = 1; j < cols.size(); ++j) c.y[j - 1].push_back(t.number(r, cols[j]) * factors[j]);
  }
  return c;
}

}  // namespace

Curve measured_curve(const CalibrationTarget& target) {
  const auto fail = [&](const std::string& field, const std::string& what) {
    throw SceneError("bad_data", target.data, 0, "targets." + target.name + "." + field, what);
  };
  try {
    const CsvTable t = read_csv(target.data);
    std::vector<int> cols{column_or_fail(t, target.x.column, [&](auto m) { fail("x", m); })};
    std::vector<double> factors{unit_factor(target.x.unit)->first};
    for (const CurveColumn& y : target.y) {
      cols.push_back(column_or_fail(t, y.column, [&](auto m) { fail("y", m); }));
      factors.push_back(unit_factor(y.unit)->first);
    }
    const std::vector<size_t> rows = kept_rows(t, target.where, [&](auto m) { fail("where", m); });
    for (size_t r : rows)
      for (int c : cols)
        if (!std::isfinite(t.number(r, c)))
          fail("data", t.source + ":" + std::to_string(t.lines[r]) + ": column '" +
                           t.header[static_cast<size_t>(c)] + "' is not a finite number");
    Curve c = read_curve(t, rows, cols, factors);
    if (target.zero_at) make_relative(c, *target.zero_at * factors[0]);
    return c;
  } catch (const ReadError& e) {
    fail("data", e.what());
  }
  return {};
}

Curve simulated_curve(const CalibrationTarget& target, const ApparatusKind& kind,
                      const std::string& dir) {
  // The kind's rows file is the one .csv of the run folder that has the
  // quantities' columns: its name is the programme's, found by its columns.
  const auto quantity = [&](const std::string& name) -> const CurveQuantity& {
    for (const CurveQuantity& q : kind.curves)
      if (name == q.name) return q;
    throw ReadError(std::string(kind.name) + " measures no '" + name + "'");
  };
  const CurveQuantity& qx = quantity(target.x.quantity);
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".csv") continue;
    const CsvTable t = read_csv(entry.path().string());
    if (t.column(qx.column) < 0 || t.column("step") < 0) continue;
    const auto fail = [&](const std::string& m) { throw ReadError(t.source + ": " + m); };
    std::vector<int> cols{column_or_fail(t, qx.column, fail)};
    std::vector<double> factors{unit_factor(qx.unit)->first};
    for (const CurveColumn& y : target.y) {
      const CurveQuantity& q = quantity(y.quantity);
      cols.push_back(column_or_fail(t, q.column, fail));
      factors.push_back(unit_factor(q.unit)->first);
    }
    Curve c = read_curve(t, kept_rows(t, kind.curve_rows ? kind.curve_rows : "", fail), cols, factors);
    try {
      if (target.zero_at) make_relative(c, *target.zero_at * unit_factor(target.x.unit)->first);
    } catch (const ReadError& e) {
      fail(e.what());
    }
    return c;
  }
  throw ReadError(dir + ": no rows file with a column '" + qx.column + "'");
}

double value_at(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  for (size_t i = 0; i + 1 < xs.size(); ++i) {
    const double a = xs[i], b = xs[i + 1];
    if ((a - x) * (b - x) > 0) continue;
    return a == b ? ys[i] : ys[i] + (ys[i + 1] - ys[i]) * (x - a) / (b - a);
  }
  return xs.size() == 1 && xs[0] == x ? ys[0] : NAN;
}

std::vector<double> comparison_points(const Curve& measured, int points) {
  const double lo = measured.x.front();
  const double hi = *std::max_element(measured.x.begin(), measured.x.end());
  std::vector<double> out;
  // The last point a little short of the end: a simulation stopped at the
  // measured end's strain, give or take a step, still reaches it.
  for (int k = 1; k <= points; ++k)
    out.push_back(lo + (hi - lo) * std::min(double(k) / points, 0.995));
  return out;
}

}  // namespace simsols
