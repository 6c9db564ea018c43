// What a new user meets first. Commands run from any directory: the
// campaign's default base scene and the display profiles are built in. A
// file's problems are reported together, the file named once, with "did you
// mean" for a mistyped key or name. The lab's script errors list what is
// accepted (the commands, the Table 1 sizes) and name no file the user did
// not give.
#include <unistd.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/cli_support.h"
#include "render/gl/alioscopy.h"
#include "solver/common/errors.h"
#include "solver/io/scene_toml.h"
#include "solver/apparatus/shear_box/shear_analysis.h"

namespace {

namespace fs = std::filesystem;

using Result = simsols::testing::CliResult;

// Runs the shell command `cmd` in directory `cwd`.
Result shell_in(const fs::path& cwd, const std::string& cmd) {
  return simsols::testing::shell("cd '" + cwd.string() + "' && " + cmd);
}

// Runs `simsols ARGS` in directory `cwd`.
Result run_in(const fs::path& cwd, const std::string& args) {
  return shell_in(cwd, std::string(SIMSOLS_EXE) + " " + args);
}

// An empty directory outside the repository.
fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("simsols_cli_errors_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

size_t count(const std::string& text, const std::string& word) {
  size_t n = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

std::string example_scene() { return read(fs::path(SIMSOLS_ASSETS_DIR) / "scenes/example_minimal.toml"); }

// `text` with the first occurrence of `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

}  // namespace

// ---------------------------------------------------------------- calibrate

TEST(CliErrors, CalibrationFileProblemsNameTheFieldBeforeAnythingRuns) {
  const fs::path d = fresh_dir("calibrate");
  std::ofstream(d / "m.csv") << "eps,eta\n0,0\n0.1,1\n";
  std::ofstream(d / "cal.toml")
      << "[calibration]\nbugdet = 10\n[[parameters]]\nname = \"mu\"\n"
         "key = \"materials.beads.sliding_friction\"\nmin = 0.1\nmax = 0.5\nscale = \"lin\"\n"
         "[[targets]]\nname = \"t\"\nscene = \"" SIMSOLS_ASSETS_DIR "/tests/periodic_triaxial_small.toml\"\n"
         "data = \"nowhere.csv\"\n";
  const Result r = run_in(d, "calibrate cal.toml --out out");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("calibration.bugdet"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("did you mean 'budget'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("parameters[0].scale"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"linear\", \"log\""), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "out" / "runs")) << "nothing ran";
  // The bad choice stopped the reading; mended, the next problem is named.
  std::string text = read(d / "cal.toml");
  text.replace(text.find("bugdet"), 6, "budget");
  text.replace(text.find("\"lin\""), 5, "\"log\"");
  std::ofstream(d / "cal.toml") << text;
  const Result m = run_in(d, "calibrate cal.toml --out out");
  EXPECT_EQ(m.status, 2) << m.out;
  EXPECT_NE(m.out.find("targets[0].data"), std::string::npos) << m.out;
  EXPECT_NE(m.out.find("nowhere.csv' does not exist"), std::string::npos) << m.out;
  const Result p = run_in(d, "predict cal.toml --out out");
  EXPECT_EQ(p.status, 2) << p.out;
  EXPECT_NE(p.out.find("prediction.calibrated"), std::string::npos) << p.out;
}

// ---------------------------------------------------------------- campaign

TEST(CliErrors, CampaignRunsOutsideTheRepositoryFromTheBuiltInScene) {
  const fs::path d = fresh_dir("campaign");
  // 4.76 is how the docs print Table 1's 4.7625 mm
  const Result r = run_in(d, "campaign --out c --sizes 4.76 --stresses 160 --displacement 0.02 -q");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(fs::exists(d / "c/d4.7625mm_160kPa/summary.txt")) << r.out;
  EXPECT_NE(read(d / "c/summary.md").find("built-in shear_box.toml"), std::string::npos);
}

// `plot` draws tests from their folders or CSVs; a mismatched --label and a
// file that is not a shear.csv are refused with the flag / file named, and
// nothing is drawn.
TEST(CliErrors, PlotDrawsCurvesAndNamesBadInputs) {
  const fs::path d = fresh_dir("plot");
  std::vector<simsols::ShearRow> rows(15);
  for (int i = 0; i < 15; ++i) {
    rows[i].displacement = i * 1e-4;
    rows[i].sigma = rows[i].sigma_target = 1e5;
    rows[i].tau = (0.6 - 0.05 * std::abs(i - 7)) * 1e5;  // a peak of 0.6 at the eighth row
  }
  fs::create_directories(d / "a");
  std::ofstream(d / "a/shear.csv") << simsols::shear_rows_csv(rows);
  std::ofstream(d / "b.csv") << simsols::shear_rows_csv(rows);
  std::ofstream(d / "bad.csv") << "x,y\n1,2\n";
  const Result ok = run_in(d, "plot a b.csv --out fig --title T");
  ASSERT_EQ(ok.status, 0) << ok.out;
  EXPECT_TRUE(fs::exists(d / "fig_stress.png") && fs::exists(d / "fig_dilation.png"));
  EXPECT_NE(ok.out.find("a: 15 rows, peak tau/sigma 0.600"), std::string::npos) << ok.out;
  const Result labels = run_in(d, "plot a b.csv --label one --out g");
  EXPECT_EQ(labels.status, 2);
  EXPECT_NE(labels.out.find("--label"), std::string::npos) << labels.out;
  const Result bad = run_in(d, "plot a bad.csv --out h");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("bad.csv"), std::string::npos) << bad.out;
  EXPECT_FALSE(fs::exists(d / "g_stress.png") || fs::exists(d / "h_stress.png"));
}

// Each kind of failure has its own status (solver/common/errors.h): a flag
// out of range is a usage error (2); a figure that cannot be written is an
// I/O error (5), and the write leaves no temporary file behind. The figure's
// name is taken by a folder, so the rename fails even as root.
TEST(CliErrors, UsageAndWriteFailuresHaveTheirOwnStatus) {
  const fs::path d = fresh_dir("io_status");
  std::vector<simsols::ShearRow> rows(3);
  for (int i = 0; i < 3; ++i) rows[i].displacement = i * 1e-4, rows[i].sigma = 1e5, rows[i].tau = 3e4;
  std::ofstream(d / "t.csv") << simsols::shear_rows_csv(rows);
  fs::create_directories(d / "fig_stress.png/inside");
  const Result io = run_in(d, "plot t.csv --out fig");
  EXPECT_EQ(io.status, 5) << io.out;
  EXPECT_NE(io.out.find("cannot write PNG"), std::string::npos) << io.out;
  EXPECT_TRUE(fs::is_directory(d / "fig_stress.png/inside"));
  for (const auto& e : fs::directory_iterator(d))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  const Result usage = run_in(d, "campaign --out c --stresses -5");
  EXPECT_EQ(usage.status, 2) << usage.out;
  EXPECT_NE(usage.out.find("command line: field '--stresses'"), std::string::npos) << usage.out;
}

// A mistyped command is named with the closest one and the list; help
// after a known command is that command's, with status 0.
TEST(CliErrors, AMistypedCommandIsNamedWithTheClosestOne) {
  const fs::path d = fresh_dir("mistyped");
  const Result typo = run_in(d, "campain --out c");
  EXPECT_EQ(typo.status, 2) << typo.out;
  EXPECT_NE(typo.out.find("unknown command 'campain' (did you mean 'campaign'?)"), std::string::npos)
      << typo.out;
  EXPECT_NE(typo.out.find("run, bench, campaign"), std::string::npos) << typo.out;
  const Result far = run_in(d, "xyzzy");
  EXPECT_EQ(far.status, 2) << far.out;
  EXPECT_EQ(far.out.find("did you mean"), std::string::npos) << far.out;
  const Result help = run_in(d, "run --help");
  EXPECT_EQ(help.status, 0) << help.out;
  EXPECT_NE(help.out.find("--stop-at"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("settle,consolidate,compress"), std::string::npos) << help.out;
}

TEST(CliErrors, CampaignChecksItsFlagsAfterLoadingTheBuiltInScene) {
  const fs::path d = fresh_dir("campaign_flag");
  const Result r = run_in(d, "campaign --out c --layers -3");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--layers"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("cannot read"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "c"));
}

// The cluster flags (app/cli/cluster_flags.h): each bad value or
// combination names its flag, and nothing runs or is written.
TEST(CliErrors, ClusterFlagsNameTheProblem) {
  const fs::path d = fresh_dir("cluster_flags");
  const std::string campaign = "campaign --sizes 6.35 --stresses 80,160 --out c ";
  struct Case {
    std::string args, flag, words;
  } cases[] = {
      {campaign + "--task 2", "--task", "allowed [0, 1]"},
      {campaign + "--emit pbs", "--emit", "not one of: slurm"},
      {campaign + "--emit slurm --task 0", "--task", "give one"},
      {"campaign --collect nowhere", "--collect", "no manifest here"},
      {"study shape --out s --task 0", "--task", "sensitivity and size studies"},
      {"study size --out s", "--scene", "give the apparatus' scene"},
      {"study shape --out s --bulk b.csv", "--bulk", "flag of the size study"},
      {"study sensitivity --out s --preset quick", "--preset", "paper, ci"},
      {campaign + "--profile quick", "--profile", "the profiles: paper, fast"},
      {"campaign " SIMSOLS_SOURCE_DIR "/assets/scenes/triaxial.toml --profile fast --out c",
       "--profile", "measured on the direct shear box only"},
  };
  for (const Case& c : cases) {
    const Result r = run_in(d, c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.flag), std::string::npos) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.words), std::string::npos) << c.args << "\n" << r.out;
  }
  EXPECT_FALSE(fs::exists(d / "c" / "d6.35mm_80kPa" / "summary.txt"));
  // collecting tests that never ran names them
  ASSERT_EQ(run_in(d, campaign + "-q --emit slurm").status, 0);
  // the array reruns the command as given (given_args): the options in
  // their parsed form, the folder absolute, no cluster flag
  const std::string args = "args = ['campaign', '--out', '" +
                           fs::absolute(d / "c").lexically_normal().string() +
                           "', '--sizes', '6.35', '--stresses', '80', '--stresses', '160', "
                           "'--quiet']";
  EXPECT_NE(read(d / "c" / "slurm" / "manifest.toml").find(args), std::string::npos)
      << read(d / "c" / "slurm" / "manifest.toml");
  const Result r = run_in(d, "campaign --collect c");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("2 of 2 tests have not finished: 0 (d6.35mm_80kPa), 1 (d6.35mm_160kPa)"),
            std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "c" / "summary.csv"));
  const Result both = run_in(d, "campaign --collect c --task 0");
  EXPECT_EQ(both.status, 2) << both.out;
  EXPECT_NE(both.out.find("give one"), std::string::npos) << both.out;
  // a task whose arguments plan other tests than the manifest's
  const Result other = run_in(d, "campaign --sizes 6.35 --stresses 80 --out c --task 0");
  EXPECT_EQ(other.status, 2) << other.out;
  EXPECT_NE(other.out.find("plan other tests than"), std::string::npos) << other.out;
  // ... and the same plan given in other words passes that check (and
  // stops at the index's range)
  const Result same = run_in(d, "campaign -o c --stresses 80 --stresses 160 --sizes 6.35 -q --task 7");
  EXPECT_NE(same.out.find("allowed [0, 1]"), std::string::npos) << same.out;
  // a study's folder collected as a campaign names the right command
  ASSERT_EQ(run_in(d, "study sensitivity --preset ci --out s --emit slurm").status, 0);
  const Result wrong = run_in(d, "campaign --collect s");
  EXPECT_EQ(wrong.status, 2) << wrong.out;
  EXPECT_NE(wrong.out.find("simsols study --collect"), std::string::npos) << wrong.out;
}

// ------------------------------------------------------------ scene files

TEST(CliErrors, ThreeUnknownKeysAreReportedTogether) {
  std::string text = replaced(example_scene(), "restitution = 0.9", "restitution = 0.9\nfrction = 0.3");
  text = replaced(text, "duration = 0.01", "duration = 0.01\ndt_fractoin = 0.1");
  text += "\n[view]\ncolr_by = \"speed\"\n";
  try {
    simsols::parse_scene(text, "three.toml");
    FAIL() << "accepted three unknown keys";
  } catch (const simsols::SceneError& e) {
    ASSERT_EQ(e.problems.size(), 3u) << e.what();
    EXPECT_EQ(e.problems[0].field, "materials[0].frction");
    EXPECT_EQ(e.problems[1].field, "numerics.dt_fractoin");
    EXPECT_EQ(e.problems[2].field, "view.colr_by");
    for (const auto& p : e.problems) {
      EXPECT_EQ(p.code, "unknown_key");
      EXPECT_GT(p.line, 0);
    }
    const std::string m = e.what();
    EXPECT_NE(m.find("(did you mean 'dt_fraction'?)"), std::string::npos) << m;
    EXPECT_NE(m.find("(did you mean 'color_by'?)"), std::string::npos) << m;
    EXPECT_EQ(count(m, "three.toml"), 1u) << m;
  }
}

TEST(CliErrors, ValuesOutOfRangeAreReportedTogetherWithUnknownKeys) {
  std::string text = replaced(example_scene(), "poisson_ratio = 0.23", "poisson_ratio = 0.7");
  text = replaced(text, "restitution = 0.9", "restitution = 1.5");
  text = replaced(text, "radius = 0.001 ", "radius = -0.001 ");
  text = replaced(text, "duration = 0.01", "duraton = 0.01\nduration = 0.01");
  const fs::path d = fresh_dir("ranges");
  std::ofstream(d / "ranges.toml") << text;
  const Result r = run_in(d, "run ranges.toml --out o");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("4 problems"), std::string::npos) << r.out;
  for (const char* f : {"numerics.duraton", "materials[0].poisson_ratio", "materials[0].restitution",
                        "particles[0].radius"})
    EXPECT_NE(r.out.find(f), std::string::npos) << f << "\n" << r.out;
  EXPECT_NE(r.out.find("(did you mean 'duration'?)"), std::string::npos) << r.out;
  EXPECT_EQ(count(r.out, "ranges.toml"), 1u) << r.out;
  EXPECT_FALSE(fs::exists(d / "o"));
}

// --------------------------------------------------------- display profiles

TEST(CliErrors, DisplayProfileProblemsNameTheFileOnceWithDidYouMean) {
  const fs::path d = fresh_dir("display");
  std::ofstream(d / "example.toml") << example_scene();
  std::ofstream(d / "bad_display.toml") << "[display]\nphse = 2\nwidth = 0\n[rig]\nview_scale = 2\n";
  const Result r =
      run_in(d, "snapshot example.toml --out a.png --stereo alioscopy --display bad_display.toml");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_EQ(count(r.out, "bad_display.toml"), 1u) << r.out;
  EXPECT_NE(r.out.find("3 problems"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("'display.phse'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(did you mean 'phase'?)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("'display.width'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("'rig.view_scale'"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "a.png"));
}

TEST(CliErrors, DisplayProfileProblemsCarryTheirLines) {
  try {
    simsols::render::parse_display_profile("[display]\nwidth = 640\nphase = 8\n\n[rgi]\n", "p.toml");
    FAIL() << "accepted a bad profile";
  } catch (const simsols::render::DisplayProfileError& e) {
    ASSERT_EQ(e.problems.size(), 2u) << e.what();
    EXPECT_EQ(e.problems[0].field, "rgi");
    EXPECT_NE(e.problems[0].message.find("(did you mean 'rig'?)"), std::string::npos);
    EXPECT_EQ(e.problems[1].field, "display.phase");
    EXPECT_EQ(e.problems[1].line, 3);
    EXPECT_EQ(e.problems[1].code, "out_of_range");
  }
}

TEST(CliErrors, BuiltInDisplayProfilesWorkFromAnyDirectory) {
  const fs::path d = fresh_dir("display_builtin");
  std::ofstream(d / "example.toml") << example_scene();
  // the shipped profile equals the built-in one
  const auto text = simsols::render::builtin_display_profile("alioscopy_hd");
  ASSERT_TRUE(text.has_value());
  const auto builtin = simsols::render::parse_display_profile(*text, "built-in");
  const auto shipped = simsols::render::load_display_profile(
      std::string(SIMSOLS_ASSETS_DIR) + "/displays/alioscopy_hd.toml");
  EXPECT_EQ(builtin.name, shipped.name);
  EXPECT_EQ(builtin.width, shipped.width);
  EXPECT_EQ(builtin.phase, shipped.phase);
  // by name, and by the path the docs give, from a directory without assets/
  for (const char* name : {"alioscopy_hd", "assets/displays/alioscopy_hd.toml"}) {
    const Result r = run_in(d, "snapshot example.toml --out a.png --stereo alioscopy --display " +
                                   std::string(name));
    EXPECT_EQ(r.status, 0) << name << "\n" << r.out;
    EXPECT_TRUE(fs::exists(d / "a_grid.png")) << name;
    fs::remove(d / "a_grid.png");
  }
  const Result r =
      run_in(d, "snapshot example.toml --out b.png --stereo alioscopy --display alioscopy_dh");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("(did you mean 'alioscopy_hd'?)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--display"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "b.png"));
}

// -------------------------------------------------------------- lab scripts

namespace {

bool have_xvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

// The lab under Xvfb, running `script` from directory `d`. The status is
// the lab's own, printed by the shell inside xvfb-run: xvfb-run's is its
// own when its clean-up fails (status 5, "problem while cleaning up
// temporary directory", seen once in a fresh root when the lab stopped
// within a fraction of a second).
Result lab_script(const fs::path& d, const std::string& script) {
  std::ofstream(d / "s.txt") << script;
  Result r = shell_in(d, "xvfb-run -a -s '-screen 0 1000x700x24' sh -c '\"$0\" lab --size 900x600 "
                         "--script s.txt; echo \"[lab exit status $?]\"' " +
                         std::string(SIMSOLS_EXE));
  const size_t at = r.out.rfind("[lab exit status ");
  r.status = at == std::string::npos ? -1 : std::atoi(r.out.c_str() + at + 17);
  return r;
}

}  // namespace

TEST(CliErrors, LabScriptAcceptsPresetSizesAsTheDocsPrintThem) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not installed (Debian: xvfb)";
  const fs::path d = fresh_dir("lab_preset");
  const Result ok = lab_script(d, "preset 4.76 280\nstate a.state\nquit\n");
  ASSERT_EQ(ok.status, 0) << ok.out;
  EXPECT_NE(read(d / "a.state").find("stage = "), std::string::npos) << ok.out;
  const Result bad = lab_script(d, "preset 5 280\nquit\n");
  EXPECT_EQ(bad.status, 1) << bad.out;
  EXPECT_NE(bad.out.find("s.txt:1: "), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("2.38, 3.18, 3.97, 4.76 and 6.35 mm"), std::string::npos) << bad.out;
  EXPECT_EQ(bad.out.find("shear_box.toml"), std::string::npos) << bad.out;
}

TEST(CliErrors, LabScriptUnknownCommandListsTheCommands) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not installed (Debian: xvfb)";
  const fs::path d = fresh_dir("lab_command");
  const Result bad = lab_script(d, "prset 4.76 280\n");
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("unknown command 'prset' (did you mean 'preset'?)"), std::string::npos)
      << bad.out;
  for (const char* usage : {"preset D_MM S_KPA", "set_stress KPA", "view opaque|transparent",
                            "effect SLOT CHOICE", "load_checkpoint FILE", "quit"})
    EXPECT_NE(bad.out.find(usage), std::string::npos) << usage << "\n" << bad.out;
  EXPECT_EQ(bad.out.find(".cpp"), std::string::npos) << bad.out;
}
