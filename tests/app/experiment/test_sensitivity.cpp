// The sensitivity study (app/experiment/shear_box/sensitivity.h): its Morris design,
// its analysis on responses whose effects are known, the study's plan and
// the cluster files of cluster.h. The ci preset's run end to end is the
// ctest `sensitivity_ci`; the paper's figures are in docs/sensitivity.md.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "app/experiment/cluster.h"
#include "app/experiment/shear_box/sensitivity.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

TEST(Sensitivity, FactorLevelsMapOntoTheirRanges) {
  for (const SensitivityFactor& f : sensitivity_factors()) {
    EXPECT_NEAR(f.value(0), f.low, 1e-12 * std::abs(f.low) + 1e-15) << f.key;
    EXPECT_NEAR(f.value(1), f.high, 1e-12 * f.high) << f.key;
    EXPECT_NEAR(f.value(f.level(f.base)), f.base, 1e-12 * f.base) << f.key;
    EXPECT_LE(f.low, f.base);
    EXPECT_LE(f.base, f.high);
  }
  // a log factor's middle level is the geometric mean
  const SensitivityFactor& mu = sensitivity_factors()[0];
  ASSERT_TRUE(mu.log_scale);
  EXPECT_NEAR(mu.value(0.5), std::sqrt(mu.low * mu.high), 1e-12);
}

TEST(Sensitivity, MorrisTrajectoriesMoveOneFactorByDeltaOnTheGrid) {
  const int k = 5, r = 6, p = 4;
  const auto design = morris_design(k, r, p, 7);
  ASSERT_EQ(design.size(), size_t(r));
  const double delta = 2.0 / 3.0;
  for (const auto& traj : design) {
    ASSERT_EQ(traj.size(), size_t(k + 1));
    std::set<int> moved;
    for (size_t j = 0; j < traj.size(); ++j) {
      for (double u : traj[j]) {
        EXPECT_GE(u, -1e-12);
        EXPECT_LE(u, 1 + 1e-12);
        EXPECT_NEAR(u * (p - 1), std::round(u * (p - 1)), 1e-9);  // a grid level
      }
      if (j == 0) continue;
      int changed = 0;
      for (int i = 0; i < k; ++i)
        if (std::abs(traj[j][i] - traj[j - 1][i]) > 1e-12) {
          ++changed;
          moved.insert(i);
          EXPECT_NEAR(std::abs(traj[j][i] - traj[j - 1][i]), delta, 1e-12);
        }
      EXPECT_EQ(changed, 1);
    }
    EXPECT_EQ(moved.size(), size_t(k));  // every factor once
  }
  EXPECT_EQ(morris_design(k, r, p, 7), design);  // deterministic
  EXPECT_NE(morris_design(k, r, p, 8), design);
  EXPECT_THROW(morris_design(k, r, 5, 7), std::invalid_argument);  // an odd grid is biased
}

// y = 3 u0 - 2 u2 + u1 u3 (+ the seed's noise at the base): Morris gives
// μ* = 3 and 2 with σ = 0 for the linear factors, 0 for u4, and an
// interaction's spread for u1 and u3; OAT the ends' differences.
TEST(Sensitivity, AnalysisRecoversKnownEffects) {
  auto y_of = [](const FactorLevels& u) { return 3 * u[0] - 2 * u[2] + u[1] * u[3]; };
  std::vector<SensitivityPoint> pts;
  std::vector<std::array<double, kSensitivityResponses>> ys;
  auto add = [&](SensitivityPoint p, double noise = 0) {
    const double y = y_of(p.levels) + noise;
    pts.push_back(p);
    ys.push_back({y, 2 * y, -y});
  };
  const FactorLevels base{0.5, 0.5, 0.5, 0.5, 0.5};
  add({Design::base, base, 1, -1, -1, 0, "base"});
  add({Design::noise, base, 2, -1, -1, 0, "n2"}, 1.0);
  add({Design::noise, base, 3, -1, -1, 0, "n3"}, -1.0);
  for (int i = 0; i < kSensitivityFactors; ++i)
    for (double u : {0.0, 1.0}) {
      FactorLevels l = base;
      l[i] = u;
      add({Design::oat, l, 1, -1, -1, 0, "oat"});
    }
  const auto design = morris_design(kSensitivityFactors, 10, 4, 3);
  for (size_t t = 0; t < design.size(); ++t)
    for (size_t j = 0; j < design[t].size(); ++j)
      add({Design::morris, design[t][j], 1, int(t), int(j), 0, "m"});
  const SensitivityAnalysis a = analyse_sensitivity(pts, ys, 4);
  EXPECT_DOUBLE_EQ(a.morris_delta, 2.0 / 3.0);
  EXPECT_EQ(a.noise_runs, 3);
  EXPECT_NEAR(a.noise_sd[0], 1.0, 1e-12);
  EXPECT_NEAR(a.noise_sd[1], 2.0, 1e-12);
  EXPECT_NEAR(a.noise_mu_star[0], std::sqrt(2 / M_PI) * std::sqrt(2.0) * 1.5, 1e-12);
  EXPECT_NEAR(a.effects[0][0].oat_low, -1.5, 1e-12);
  EXPECT_NEAR(a.effects[0][0].oat_high, 1.5, 1e-12);
  EXPECT_NEAR(a.effects[2][2].oat_high, 1.0, 1e-12);  // response 2 is -y
  EXPECT_EQ(a.effects[0][0].effects, 10);
  EXPECT_NEAR(a.effects[0][0].mu_star, 3, 1e-9);
  EXPECT_NEAR(a.effects[0][0].mu, 3, 1e-9);
  EXPECT_NEAR(a.effects[0][0].sigma, 0, 1e-9);
  EXPECT_NEAR(a.effects[2][0].mu, -2, 1e-9);
  EXPECT_NEAR(a.effects[2][1].mu_star, 4, 1e-9);
  EXPECT_NEAR(a.effects[4][0].mu_star, 0, 1e-12);
  // the interaction: u1's effect is u3, so it varies with where u3 stands
  EXPECT_GT(a.effects[1][0].sigma, 0.1);
  EXPECT_GT(a.effects[1][0].mu_star, 0.1);
  EXPECT_LT(a.effects[1][0].mu_star, 1.0 + 1e-9);
}

TEST(Sensitivity, ThePlanBuildsEveryDesignsScenes) {
  const SensitivityPreset p = sensitivity_preset("ci");
  const auto tests = plan_sensitivity(p, "/tmp/unused_sensitivity_plan");
  // base, seeds, OAT (E's high end is the base), Morris, scale
  const size_t expected = 1 + (p.seeds - 1) + (2 * kSensitivityFactors - 1) +
                          p.trajectories * (kSensitivityFactors + 1) + p.box_ratios.size();
  ASSERT_EQ(tests.size(), expected);
  std::set<std::string> names;
  for (const SensitivityTest& t : tests) {
    names.insert(t.scene.name);
    EXPECT_GT(t.cost, 0);
    EXPECT_EQ(t.scene.apparatus_as<ShearBox>()->specimen.method, Specimen::Method::Pour);
    // the factor values are in the scene
    const Material& glass = t.scene.materials[t.scene.apparatus_as<ShearBox>()->specimen.material];
    const auto& f = sensitivity_factors();
    EXPECT_DOUBLE_EQ(glass.sliding_friction, f[0].value(t.point.levels[0]));
    EXPECT_DOUBLE_EQ(glass.young_modulus, f[3].value(t.point.levels[3]));
    EXPECT_DOUBLE_EQ(*t.scene.apparatus_as<ShearBox>()->specimen.preparation.friction,
                     f[4].value(t.point.levels[4]));
  }
  EXPECT_EQ(names.size(), tests.size());  // one folder each
  const SensitivityTest& scale = tests.back();
  EXPECT_NEAR(scale.scene.apparatus_as<ShearBox>()->length / (2 * scale.scene.particles[0].radius),
              p.box_ratios.back(), 1e-9);
  EXPECT_GT(scale.scene.particles.size(), tests.front().scene.particles.size());
  EXPECT_THROW(sensitivity_preset("fast"), UsageError);
}

TEST(Cluster, TheJobListsEveryTestAndItsArgumentsComeBack) {
  const fs::path dir = fs::temp_directory_path() / "simsols_cluster_job";
  fs::remove_all(dir);
  ClusterJob job;
  job.command = "campaign";
  job.args = {"campaign", "/a b/base.toml", "--out", dir.string(), "--sizes", "6.35,4.7625"};
  job.out_dir = dir;
  job.executable = "/usr/bin/simsols";
  job.tests = {{"d6.35mm_160kPa", dir / "d6.35mm_160kPa", 324, 4e9},
               {"d4.7625mm_160kPa", dir / "d4.7625mm_160kPa", 1000, 6e10}};
  write_slurm_job(job);
  const Manifest m = read_manifest(dir);
  EXPECT_EQ(m.args, job.args);
  EXPECT_EQ(m.command, "campaign");
  EXPECT_EQ(m.tests, (std::vector<std::string>{"d6.35mm_160kPa", "d4.7625mm_160kPa"}));
  const std::string array = read_text((dir / "slurm" / "array.sbatch").string());
  EXPECT_NE(array.find("#SBATCH --array=0-1\n"), std::string::npos) << array;
  EXPECT_NE(array.find("'/a b/base.toml'"), std::string::npos);
  EXPECT_NE(array.find("--task \"$SLURM_ARRAY_TASK_ID\""), std::string::npos);
  // the largest test's needs
  const ClusterNeeds big = cluster_needs(job.tests[1]);
  EXPECT_NE(array.find("#SBATCH --time=" + std::to_string(big.minutes) + "\n"), std::string::npos);
  EXPECT_NE(array.find("#SBATCH --mem=" + std::to_string(big.memory_mb) + "M\n"), std::string::npos);
  EXPECT_GT(big.minutes, cluster_needs(job.tests[0]).minutes);
  EXPECT_NE(read_text((dir / "slurm" / "collect.sbatch").string()).find("campaign --collect " + dir.string()),
            std::string::npos);
  // submit.sh passes its arguments (a partition, an account) to both jobs
  const std::string submit = read_text((dir / "slurm" / "submit.sh").string());
  EXPECT_NE(submit.find("sbatch --parsable \"$@\" array.sbatch"), std::string::npos) << submit;
  EXPECT_NE(submit.find("sbatch --parsable \"$@\" --dependency=afterany"), std::string::npos) << submit;
  EXPECT_TRUE((fs::status(dir / "slurm" / "submit.sh").permissions() & fs::perms::owner_exec) !=
              fs::perms::none);
  EXPECT_THROW(read_manifest(dir / "nothing"), SceneError);
  // sbatch's #SBATCH lines cannot carry a space or a '%'
  ClusterJob spaced = job;
  spaced.out_dir = dir / "a b";
  EXPECT_THROW(write_slurm_job(spaced), UsageError);
  EXPECT_FALSE(fs::exists(dir / "a b"));
  ClusterJob none = job;
  none.tests.clear();
  EXPECT_THROW(write_slurm_job(none), UsageError);
  EXPECT_EQ(shell_word("it's"), "'it'\\''s'");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace simsols
