// simsols plot: the curves of several shear tests on common axes.
//
//   simsols plot A B ... --out PREFIX [--label LA --label LB ...] [--title T]
//
// Each input is a test's folder (holding shear.csv, and summary.txt when
// the test finished) or a shear.csv itself: SimSols' own, a campaign's, or
// another code's written in the same columns (the LIGGGHTS cross-check's
// post.py does). Writes PREFIX_stress.png (tau against displacement, each
// test's first peak marked) and PREFIX_dilation.png, as the campaign's
// per-size figures. The first peak needs the test's target normal stress
// and bead diameter: from the folder's summary.txt (SimSols' keys
// normal_stress_kPa and bead_diameter_mm, which the LIGGGHTS cross-check's
// summary shares); else the rows' sigma_target column or their mean sigma,
// and no recovery displacement (the first softening counts). Inputs and the output folder are checked before anything is
// drawn; a bad file is named with its problem (exit status 2).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "app/cli/commands.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "app/experiment/shear_box/shear_plots.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

struct PlotOptions {
  std::vector<std::string> inputs, labels;
  std::string out, title = "Direct shear";
};

// A positive number under `key` in a summary's keys; 0 when absent or not
// one (another code's summary has its own keys).
double summary_value(const std::map<std::string, std::string>& keys, const std::string& key) {
  const auto it = keys.find(key);
  if (it == keys.end()) return 0;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  return end != it->second.c_str() && std::isfinite(v) && v > 0 ? v : 0;
}

// The test's target normal stress (Pa) and bead diameter (m), for its
// first peak.
ShearSummary apparatus_of(const fs::path& dir, const std::vector<ShearRow>& rows) {
  ShearSummary s;
  if (fs::exists(dir / "summary.txt")) {
    const auto keys = summary_keys(read_text((dir / "summary.txt").string()));
    s.normal_stress_target = 1e3 * summary_value(keys, "normal_stress_kPa");
    s.bead_diameter = 1e-3 * summary_value(keys, "bead_diameter_mm");
  }
  if (s.normal_stress_target > 0) return s;
  if (rows.front().sigma_target > 0) {
    s.normal_stress_target = rows.front().sigma_target;
    return s;
  }
  double sum = 0;
  for (const ShearRow& r : rows) sum += r.sigma;
  s.normal_stress_target = sum / static_cast<double>(rows.size());
  return s;
}

ShearCurve read_curve(const std::string& input, const std::string& label) {
  const fs::path p(input);
  const fs::path csv = fs::is_directory(p) ? p / "shear.csv" : p;
  if (!fs::exists(csv)) throw SceneError("io", csv.string(), 0, "INPUT", "no such file");
  ShearCurve c;
  try {
    c.rows = parse_shear_rows_csv(read_text(csv.string()));
  } catch (const std::runtime_error& e) {
    throw SceneError("bad_file", csv.string(), 0, "INPUT", e.what());
  }
  if (c.rows.empty()) throw SceneError("bad_file", csv.string(), 0, "INPUT", "has no rows");
  c.summary = apparatus_of(csv.parent_path(), c.rows);
  analyse_shear_rows(c.rows, c.summary);
  c.label = label.empty() ? (fs::is_directory(p) ? p.filename().string() : p.stem().string())
                          : label;
  return c;
}

int plot(const PlotOptions& o) {
  if (!o.labels.empty() && o.labels.size() != o.inputs.size())
    throw UsageError("bad_flag", "--label",
                     "give one --label per input (" + std::to_string(o.inputs.size()) +
                         " inputs, " + std::to_string(o.labels.size()) + " labels)");
  const fs::path prefix(o.out);
  const fs::path dir = prefix.parent_path().empty() ? fs::path(".") : prefix.parent_path();
  if (!fs::is_directory(dir))
    throw UsageError("io", o.out, 0, "--out", "the folder '" + dir.string() + "' does not exist");
  std::vector<ShearCurve> curves;
  for (size_t i = 0; i < o.inputs.size(); ++i) {
    curves.push_back(read_curve(o.inputs[i], o.labels.empty() ? "" : o.labels[i]));
    const ShearSummary& s = curves.back().summary;
    std::printf("%s: %zu rows, peak tau/sigma %.3f (%.2f deg) at %.2f mm, residual %.3f\n",
                curves.back().label.c_str(), curves.back().rows.size(), s.peak_ratio,
                s.peak_angle, s.peak_displacement * 1e3, s.residual_ratio);
  }
  write_size_plots(o.out + "_stress.png", o.out + "_dilation.png", o.title, curves);
  std::printf("wrote %s_stress.png and %s_dilation.png\n", o.out.c_str(), o.out.c_str());
  return 0;
}

}  // namespace

CommandRunner add_plot_command(CLI::App& app) {
  auto opt = std::make_shared<PlotOptions>();
  CLI::App* c = app.add_subcommand("plot", "Draw the curves of several shear tests on common axes (PNG)");
  c->add_option("inputs", opt->inputs, "Test folders or shear.csv files")->required();
  c->add_option("-o,--out", opt->out, "Output prefix: writes PREFIX_stress.png and PREFIX_dilation.png")
      ->required();
  c->add_option("--label", opt->labels, "A legend label per input, in order (default: folder names)");
  c->add_option("--title", opt->title, "Figure title");
  return [opt] { return plot(*opt); };
}

}  // namespace simsols
