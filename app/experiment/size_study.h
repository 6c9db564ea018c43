// The size study: one apparatus' test at growing size against the grains,
// several specimens per size, against the bulk value of the same material
// measured in the periodic cell (docs/size-study.md).
//
// Every test runs the base scene (a shear box, oedometer or triaxial cell,
// not yet placed) resized by the registry's `resize` (solver/apparatus/
// registry.h): lengths across times the scale; the specimen's height
// (layers) times the scale too when the study is `similar` (geometrically
// similar specimens), unchanged when not (the specimen keeps its
// thickness). Each scale runs `seeds` specimens (the base's seed and the
// next ones) in OUT/x<scale>_s<seed>/ (apparatus_run.h), resumable and on a
// cluster like the campaigns (campaign_loop.h). The results are the kind's
// headline keys, read back from each test's summary.txt.
//
// Afterwards: OUT/tests.csv (one row per test), OUT/summary.csv and .md
// (per size: the mean of each headline over the specimens with its 95 %
// Student interval; beside the bulk value, the difference and the size from
// which the mean stays within 1° of it), OUT/size_<key>.png (the headline
// against L/d with its intervals, the bulk value and its interval).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/experiment/campaign_loop.h"
#include "app/experiment/shear_box/study_stats.h"
#include "solver/apparatus/registry.h"

namespace simsols {

struct SizeStudySpec {
  std::vector<double> scales{1, 1.5, 2};
  bool similar = true;  // the specimen's height grows with the box
  int seeds = 3;
  std::optional<Precision> precision;
};

// The bulk value of the material from a periodic-cell campaign's
// summary.csv (cell_campaign.h): the first row's stress ratio as an angle
// atan(tau/sigma) and its mobilised angle, each with its 95 % interval.
struct BulkValue {
  std::string source;
  double p_kpa = 0, inertial = 0;
  int specimens = 0;
  Interval plane, mobilised;  // deg
  const Interval* for_match(BulkMatch m) const {
    return m == BulkMatch::PlaneAngle ? &plane : m == BulkMatch::MobilisedAngle ? &mobilised : nullptr;
  }
};
// SceneError naming `path` and the column when it cannot be read.
BulkValue read_bulk_value(const std::string& path);

struct SizeTest {
  double scale = 1, ratio = 0;  // L/d
  std::int64_t seed = 0;
  Scene scene;  // placed
  std::filesystem::path dir;
  double cost = 0;  // particle-steps, roughly
  std::map<std::string, double> results;  // the headline keys, and wall_seconds
};

// The tests of `spec` from `base` (named `base_name` in messages). Throws
// UsageError naming the flag or SceneError naming the base.
std::vector<SizeTest> plan_size_study(const Scene& base, const std::string& base_name,
                                      const SizeStudySpec& spec, const std::string& out_dir);

// One size over its specimens: each headline's mean and interval.
struct SizePoint {
  double scale = 1, ratio = 0;
  int specimens = 0, beads = 0;
  std::vector<Interval> values;  // in the kind's headline order
  double wall_seconds = 0;       // mean per test
};
std::vector<SizePoint> size_points(const ApparatusKind& kind, const std::vector<SizeTest>& tests);

// The smallest L/d from which every larger size's mean is within `tolerance`
// degrees of the bulk value; NaN when none is.
double ratio_within(const std::vector<SizePoint>& points, size_t headline, const Interval& bulk,
                    double tolerance);

std::string size_summary_markdown(const ApparatusKind& kind, const std::vector<SizePoint>& points,
                                  const std::optional<BulkValue>& bulk);

// Runs the tests not finished yet, then writes the report (unless
// interrupted or one array task); `what` names the study in the plots'
// titles ("shear_poured, height grows with the box").
CampaignOutcome run_size_study(std::vector<SizeTest>& tests, const std::optional<BulkValue>& bulk,
                               const std::string& what, const std::string& out_dir, const CampaignRun& run);

// "<base scene's name>, height grows with the box" or "..., fixed height".
std::string size_study_title(const Scene& base, const SizeStudySpec& spec);

}  // namespace simsols
