// Oedometer analysis: an oedometer test's measurements and what is read
// from them (docs/oedometer.md), apart from the apparatus that measured
// them.
//
// OedometerRow is one row of the test, the means over the steps since the
// previous row (every half millisecond while a load step is held); the row
// that ends a load step says how it ended (in equilibrium, or at
// step_time). analyse_oedometer() reads the ends of the steps as a
// laboratory reads its dial gauge after each increment:
//   void ratio      e = L W H / V_s - 1, V_s the beads' volume, H the
//                   platen's height over the floor;
//   Cc, Cs          compression and swelling indices, -de/dlog10(sigma'_v),
//                   least-squares slopes over the loading branch from its
//                   third step on (the first two seat the specimen; all
//                   its steps when it has fewer than four) and over the
//                   unloading branch with the largest step;
//   K0              sigma'_h / sigma'_v at rest: sigma'_h the mean normal
//                   stress on the four sides over their wetted area
//                   2 (L + W) H, sigma'_v the mean of the platen's and the
//                   floor's stresses (the vertical stress averaged over
//                   the height, as sigma'_h is); its normally consolidated
//                   value is the mean over the loading steps Cc uses;
//   Jaky            K0 = 1 - sin(phi') for the friction angle the scene
//                   gives, and the phi' the measured K0 implies;
//   side friction   the share of the platen's load the sides carry by
//                   friction, 1 - (sigma_base - weight/A) / sigma_top;
//   plastic share   what unloading did not recover of the loading branch's
//                   compression: whether Cc is a virgin compression index;
//   Mayne-Kulhawy   K0 on unloading against K0_nc OCR^(sin phi').
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace simsols {

struct OedometerRow {
  double time = 0;            // s
  std::int64_t step = 0;
  int load_step = 0;          // 1-based index into load_steps
  double sigma_target = 0;    // Pa
  double sigma_top = 0;       // Pa, the platen's reaction / area
  double sigma_base = 0;      // Pa, the floor's reaction / area
  double sigma_hx = 0;        // Pa, mean normal stress on the two x sides
  double sigma_hy = 0;        // Pa, on the two y sides
  double sigma_h = 0;         // Pa, on all four sides
  double height = 0;          // m, platen over floor
  double void_ratio = 0;
  double k0 = 0;              // sigma_h / ((sigma_top + sigma_base) / 2)
  double side_friction = 0;   // share of the platen's load carried by the sides
  double coordination = 0;    // contacts per bead (bead and wall contacts)
  double kinetic_energy = 0;  // J
  // 0 while the step is held, 1 for the row that ends it in equilibrium, 2
  // for one that ends it at step_time without equilibrium.
  int end_of_step = 0;
};

// One load step as it ended.
struct OedometerStep {
  double sigma_target = 0, sigma_top = 0, sigma_h = 0;  // Pa
  double void_ratio = 0, strain = 0, k0 = 0, side_friction = 0;
  double height = 0;          // m
  double duration = 0;        // s held
  bool equilibrium = false;   // ended in equilibrium (else at step_time)
  bool loading = true;        // on the loading branch (up to the largest step)
  // Unloading steps: the overconsolidation ratio sigma_max / sigma and
  // Mayne & Kulhawy's K0 for it (OedometerSummary::mayne_kulhawy_*); 1 and
  // 0 on the loading branch.
  double ocr = 1, mayne_kulhawy_k0 = 0;
};

struct OedometerSummary {
  std::vector<OedometerStep> steps;
  double bead_diameter = 0;     // m, mean
  double initial_void_ratio = 0;  // e when the platen first touched (the first row)
  double seated_void_ratio = 0;   // e at the end of the first step
  double height = 0;            // m, at the end of the first step
  double cc = 0, cs = 0;        // compression and swelling indices
  int cc_points = 0, cs_points = 0;
  double k0_nc = 0;             // normally consolidated K0 (mean over Cc's steps)
  double k0_end = 0, ocr_end = 0;  // K0 after unloading, at OCR = sigma_max / sigma_last
  double jaky_friction_angle = 0;  // deg given by the scene (0: none)
  double jaky_k0 = 0;           // 1 - sin(phi') for it (0: none)
  double implied_friction_angle = 0;  // deg, asin(1 - k0_nc)
  double side_friction = 0;     // mean over the loading steps
  // How much of the loading branch was plastic: the void ratio lost from
  // the seated state to the largest step that unloading to the last step
  // did not recover, (e_seated - e_last) / (e_seated - e_max). The loading
  // branch is a virgin compression line when more than half is
  // irrecoverable (plastic_share > 0.5); below that it is mostly the
  // contacts' elastic compression and Cc is not a virgin index.
  double plastic_share = 0;
  bool virgin = false;
  // Mayne & Kulhawy (1982): K0 = K0_nc OCR^(sin phi') on unloading, with
  // K0_nc the measured one and phi' the scene's friction_angle, else the
  // one Jaky's formula implies from K0_nc; the largest |measured / that - 1|
  // over the unloading steps.
  double mayne_kulhawy_friction_angle = 0, mayne_kulhawy_worst = 0;
  bool valid = true;            // every step ended in equilibrium
  double settle_time = 0;       // s
  double wall_seconds = 0;      // filled in by the caller
};

// The steps' ends from the rows and the indices from the steps (`peak` is
// the index of the largest load step, oedometer_peak_step).
OedometerSummary analyse_oedometer(const std::vector<OedometerRow>& rows, int peak,
                                   double jaky_friction_angle_deg);

// Least-squares slope -de/dlog10(sigma) through (sigma, e) points; 0 for
// fewer than two.
double compression_index(const std::vector<double>& sigma, const std::vector<double>& e);

// The rows as CSV (kPa, mm, J) and back; the summary as "key = value"
// lines with a table of the steps. The parser throws std::runtime_error on
// malformed text.
std::string oedometer_rows_csv(const std::vector<OedometerRow>& rows);
std::vector<OedometerRow> parse_oedometer_rows_csv(const std::string& text);
std::string oedometer_summary_text(const OedometerSummary& s);

}  // namespace simsols
