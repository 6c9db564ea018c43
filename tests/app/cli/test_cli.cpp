// The simsols executable end to end: a bad scene writes nothing and exits
// with status 2; a run stopped at a checkpoint and resumed with --resume ends
// with the same state hash as the uninterrupted run; outputs exist.
#include <unistd.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/cli_support.h"
#include "render/plot/png.h"

namespace {

namespace fs = std::filesystem;

using Result = simsols::testing::CliResult;

Result run(const std::string& args) {
  return simsols::testing::shell(std::string(SIMSOLS_EXE) + " " + args);
}

std::string hash_of(const std::string& out) {
  const auto at = out.find("state hash ");
  return at == std::string::npos ? "" : out.substr(at + 11, 16);
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("simsols_cli_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

const std::string kScene = std::string(SIMSOLS_ASSETS_DIR) + "/scenes/example_minimal.toml";

TEST(Cli, BadSceneWritesNothing) {
  const fs::path out = fresh_dir("bad");
  const Result r = run("run " + std::string(SIMSOLS_ASSETS_DIR) +
                       "/tests/bad_scenes/negative_radius.toml --out " + out.string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("negative_radius.toml"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("radius"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out)) << "nothing may be written on a failed load";
}

// Stability case 10 end to end: a forced time step runs away; the run
// stops at the first bad step with status 4, names the step and the
// particle, saves the state before it, and writes no NaN into its outputs.
TEST(Cli, RunawayStopsWithTheStateBeforeIt) {
  const fs::path out = fresh_dir("runaway");
  const Result r = run("run " + std::string(SIMSOLS_ASSETS_DIR) + "/tests/runaway.toml --out " +
                       out.string() + " -q");
  EXPECT_EQ(r.status, 4) << r.out;
  EXPECT_NE(r.out.find("runaway at step "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("particle "), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(out / "fault_checkpoint.bin"));
  ASSERT_TRUE(fs::exists(out / "fault.txt"));
  std::ifstream f(out / "series.csv");
  const std::string series((std::istreambuf_iterator<char>(f)), {});
  EXPECT_GT(std::count(series.begin(), series.end(), '\n'), 10) << "one row per step until the fault";
  for (const char* bad : {"nan", "inf", "NaN", "Inf"})
    EXPECT_EQ(series.find(bad), std::string::npos) << bad << " in series.csv";
  // The saved state is the step before (tests/solver/kernels/test_stability.cpp checks
  // that one step from it is the fault).
  const auto at = r.out.find("runaway at step ");
  const long fault_step = std::atol(r.out.c_str() + at + 16);
  std::ifstream t(out / "fault.txt");
  const std::string text((std::istreambuf_iterator<char>(t)), {});
  EXPECT_NE(text.find("The state at step " + std::to_string(fault_step - 1)), std::string::npos)
      << text;
}

// `run SCENE --explain`: the compiled slots, the -D options and the history
// size, exit 0, nothing run; a slot set to none in the scene disappears.
TEST(Cli, ExplainPrintsTheCompiledSlots) {
  const Result r = run("run " + std::string(SIMSOLS_ASSETS_DIR) + "/scenes/shear_box.toml --explain");
  EXPECT_EQ(r.status, 0) << r.out;
  for (const char* s : {"tangential  mindlin", "compiled in", "-DHAS_FRICTION", "-DHIST_PLANES=1",
                        "16 bytes per contact", "cohesion    none"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s << "\n" << r.out;
  EXPECT_EQ(r.out.find("state hash"), std::string::npos) << "--explain must not run";
  const fs::path dir = fresh_dir("explain");
  fs::create_directories(dir);
  std::string text;
  {
    std::ifstream in(std::string(SIMSOLS_ASSETS_DIR) + "/scenes/shear_box.toml");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto at = text.find("[numerics]");
  ASSERT_NE(at, std::string::npos);
  // no friction, no rolling: the normal dashpot's record is the only history;
  // without the damping too, there is none
  auto explain = [&](const std::string& name, const std::string& effects) {
    std::string scene = text;
    scene.insert(at, "[effects]\n" + effects + "\n");
    std::ofstream((dir / name).string()) << scene;
    return run("run " + (dir / name).string() + " --explain");
  };
  const Result none =
      explain("dry_frictionless.toml", "tangential = \"none\"\nrolling = \"none\"\n");
  EXPECT_EQ(none.status, 0) << none.out;
  EXPECT_EQ(none.out.find("-DHAS_FRICTION"), std::string::npos) << none.out;
  EXPECT_EQ(none.out.find("-DHAS_ROLLING"), std::string::npos) << none.out;
  EXPECT_NE(none.out.find("16 bytes per contact"), std::string::npos) << none.out;
  const Result bare = explain("undamped.toml",
                              "damping = \"none\"\ntangential = \"none\"\nrolling = \"none\"\n");
  EXPECT_EQ(bare.status, 0) << bare.out;
  EXPECT_EQ(bare.out.find("-DHAS_DAMPING"), std::string::npos) << bare.out;
  EXPECT_NE(bare.out.find("0 bytes per contact"), std::string::npos) << bare.out;
}

TEST(Cli, BadFlagIsRefused) {
  const fs::path out = fresh_dir("flag");
  const Result r = run("run " + kScene + " --out " + out.string() + " --precision quad");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--precision"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, StopAndResumeIsBitForBit) {
  const fs::path a = fresh_dir("straight"), b = fresh_dir("resumed");
  const Result straight = run("run " + kScene + " --out " + a.string() + " -q --duration 0.002");
  ASSERT_EQ(straight.status, 0) << straight.out;
  const Result first = run("run " + kScene + " --out " + b.string() +
                           " -q --duration 0.002 --stop-after 777");
  ASSERT_EQ(first.status, 0) << first.out;
  EXPECT_NE(first.out.find("stopped at step 777"), std::string::npos) << first.out;
  const Result second = run("run --resume --out " + b.string() + " -q --duration 0.002");
  ASSERT_EQ(second.status, 0) << second.out;
  EXPECT_FALSE(hash_of(straight.out).empty()) << straight.out;
  EXPECT_EQ(hash_of(second.out), hash_of(straight.out)) << second.out;
  for (const char* f : {"series.csv", "scene.toml", "scene.resolved.toml", "checkpoint.bin"})
    EXPECT_TRUE(fs::exists(b / f)) << f;
  // the time series of the resumed run has no duplicate rows
  std::ifstream sa(a / "series.csv"), sb(b / "series.csv");
  const std::string ta((std::istreambuf_iterator<char>(sa)), {});
  const std::string tb((std::istreambuf_iterator<char>(sb)), {});
  EXPECT_EQ(ta, tb);
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

const std::string kShear = std::string(SIMSOLS_ASSETS_DIR) + "/tests/shear_small.toml";

// A shear test stopped in the middle of its loading program and resumed
// writes the same rows as the uninterrupted one.
TEST(Cli, ShearTestStopAndResumeGivesTheSameRows) {
  const fs::path a = fresh_dir("shear_straight"), b = fresh_dir("shear_resumed");
  const Result straight = run("run " + kShear + " --out " + a.string() + " -q");
  ASSERT_EQ(straight.status, 0) << straight.out;
  EXPECT_NE(straight.out.find("phi_peak"), std::string::npos) << straight.out;
  const Result first = run("run " + kShear + " --out " + b.string() + " -q --stop-after 30000");
  ASSERT_EQ(first.status, 0) << first.out;
  EXPECT_NE(first.out.find("stopped"), std::string::npos) << first.out;
  EXPECT_FALSE(fs::exists(b / "summary.txt"));
  const Result second = run("run --resume --out " + b.string() + " -q");
  ASSERT_EQ(second.status, 0) << second.out;
  EXPECT_EQ(read(a / "shear.csv"), read(b / "shear.csv"));
  // the summaries agree up to the wall time (the last line)
  const std::string sa = read(a / "summary.txt"), sb = read(b / "summary.txt");
  EXPECT_EQ(sa.substr(0, sa.find("wall_seconds")), sb.substr(0, sb.find("wall_seconds")));
  EXPECT_NE(sa.find("wall_seconds"), std::string::npos);
  for (const char* f : {"summary.txt", "shear.csv", "shear_stress.png", "shear_ratio.png",
                        "dilation.png", "paraview/particles.pvd", "paraview/contacts.pvd",
                        "paraview/walls.pvd", "checkpoint.bin"})
    EXPECT_TRUE(fs::exists(b / f)) << f;
  // the resumed run's series is the whole run's, with the state at the stop
  // (written when it stopped, so the stopped run opened in ParaView) as one
  // more frame
  std::string pvd = read(b / "paraview" / "particles.pvd");
  const size_t stop = pvd.find("particles_000030000.vtp");
  ASSERT_NE(stop, std::string::npos) << pvd;
  EXPECT_TRUE(fs::exists(b / "paraview" / "particles_000030000.vtp"));
  pvd.erase(pvd.rfind('\n', stop) + 1, pvd.find('\n', stop) - pvd.rfind('\n', stop));
  EXPECT_EQ(pvd, read(a / "paraview" / "particles.pvd"));
  EXPECT_EQ(read(a / "shear.csv").substr(0, 20), "time_s,step,displace");
}

TEST(Cli, ShearRunRefusesDuration) {
  const fs::path out = fresh_dir("shear_duration");
  const Result r = run("run " + kShear + " --out " + out.string() + " --duration 1");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--duration"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, CampaignBadInputWritesNothing) {
  const fs::path out = fresh_dir("campaign_bad");
  Result r = run("campaign " + kShear + " --out " + out.string() + " --sizes 7");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--sizes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Table 1"), std::string::npos) << r.out;
  r = run("campaign " + kShear + " --out " + out.string() + " --stresses -50");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--stresses"), std::string::npos) << r.out;
  // a kind without a campaign: named, with the kinds that have one
  r = run("campaign " + std::string(SIMSOLS_ASSETS_DIR) + "/scenes/oedometer.toml --out " +
          out.string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("an oedometer test has no campaign"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("shear_box, triaxial"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

// Two tests of a campaign, then the campaign again: nothing is rerun.
TEST(Cli, CampaignWritesItsTablesAndResumes) {
  const fs::path out = fresh_dir("campaign");
  const std::string args = "campaign " + kShear + " --out " + out.string() +
                           " --sizes 6.35 --stresses 100,300 --displacement 0.2 -q";
  const Result first = run(args);
  ASSERT_EQ(first.status, 0) << first.out;
  EXPECT_NE(first.out.find("Mohr-Coulomb d = 6.35 mm"), std::string::npos) << first.out;
  for (const char* f : {"summary.md", "summary.csv", "mohr_coulomb.png", "d6.35mm_stress.png",
                        "d6.35mm_dilation.png", "d6.35mm_100kPa/shear.csv",
                        "d6.35mm_300kPa/summary.txt"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const std::string table = read(out / "summary.csv");
  const Result again = run("campaign " + kShear + " --out " + out.string() +
                           " --sizes 6.35 --stresses 100,300 --displacement 0.2");
  ASSERT_EQ(again.status, 0) << again.out;
  EXPECT_NE(again.out.find("finished earlier, kept"), std::string::npos) << again.out;
  // the same numbers (wall times aside: they are kept from the first run too)
  EXPECT_EQ(read(out / "summary.csv"), table);
}

// A triaxial campaign over two confining stresses: the Mohr circles, the
// envelope tangent to them and the critical state line; run again, nothing
// is rerun and the table is the same. The shear box's flags are refused.
TEST(Cli, TriaxialCampaignFitsTheEnvelopeAndResumes) {
  const fs::path out = fresh_dir("triaxial_campaign");
  const std::string base = std::string(SIMSOLS_ASSETS_DIR) + "/tests/triaxial_small.toml";
  const Result refused = run("campaign " + base + " --out " + out.string() + " --sizes 6.35");
  EXPECT_EQ(refused.status, 2) << refused.out;
  EXPECT_NE(refused.out.find("--sizes"), std::string::npos) << refused.out;
  EXPECT_FALSE(fs::exists(out));
  const std::string args = "campaign " + base + " --out " + out.string() + " --stresses 50,150";
  const Result first = run(args + " -q");
  ASSERT_EQ(first.status, 0) << first.out;
  EXPECT_NE(first.out.find("Mohr-Coulomb envelope (peak): phi = "), std::string::npos) << first.out;
  EXPECT_NE(first.out.find("critical state line: "), std::string::npos) << first.out;
  for (const char* f : {"summary.md", "summary.csv", "envelopes.csv", "mohr_peak.png",
                        "mohr_critical.png", "csl.png", "stress_ratio.png", "volumetric.png",
                        "s3_50kPa/triaxial.csv", "s3_150kPa/summary.txt"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const std::string table = read(out / "summary.csv");
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 3) << table;
  EXPECT_EQ(table.rfind("sigma3_kPa,seed,", 0), 0u) << table;
  // one specimen: its fit's standard errors, said so
  EXPECT_NE(read(out / "envelopes.csv").find(",se\n"), std::string::npos);
  EXPECT_NE(read(out / "s3_150kPa/summary.txt").find("confining_stress_kPa = 150"),
            std::string::npos);
  const Result again = run(args);
  ASSERT_EQ(again.status, 0) << again.out;
  EXPECT_NE(again.out.find("finished earlier, kept"), std::string::npos) << again.out;
  EXPECT_EQ(read(out / "summary.csv"), table);
}

}  // namespace

// ------------------------------------------------------------------ frames
// `simsols snapshot` and `run --frames`: valid PNGs of the requested size
// that show the beads; bad sizes, paths and names are refused with the flag
// named and nothing written.
namespace {

const std::string kShearSmall = std::string(SIMSOLS_ASSETS_DIR) + "/tests/shear_small.toml";

// Pixels in the middle half of the image that differ from the corner pixel
// (the background).
long foreground(const simsols::plot::Image& img) {
  const auto bg = simsols::plot::pixel(img, 0, img.height - 1);
  long n = 0;
  for (int y = img.height / 4; y < 3 * img.height / 4; ++y)
    for (int x = img.width / 4; x < 3 * img.width / 4; ++x) n += !(simsols::plot::pixel(img, x, y) == bg);
  return n;
}

}  // namespace

TEST(Cli, SnapshotWritesAPngOfTheRequestedSize) {
  const fs::path dir = fresh_dir("snapshot");
  fs::create_directories(dir);
  for (const char* mode : {"opaque", "transparent", "chains"}) {
    const fs::path png = dir / (std::string(mode) + ".png");
    const Result r = run("snapshot " + kShearSmall + " --out " + png.string() +
                         " --size 321x207 --view front --mode " + mode + " --steps 200");
    ASSERT_EQ(r.status, 0) << r.out;
    const simsols::plot::Image img = simsols::plot::read_png(png.string());
    EXPECT_EQ(img.width, 321);
    EXPECT_EQ(img.height, 207);
    EXPECT_GT(foreground(img), 321 * 207 / 4 / 5) << mode << ": the specimen should fill the middle";
    EXPECT_FALSE(fs::exists(png.string() + ".tmp"));
  }
  // a slab one bead wide through the middle, seen face on: some beads, not
  // all (without the walls, whose tint would count as foreground)
  long pixels[2] = {};
  for (const std::string section : {"off", "y:1"}) {
    const fs::path png = dir / ("section_" + section.substr(0, 1) + ".png");
    const Result r = run("snapshot " + kShearSmall + " --out " + png.string() +
                         " --size 321x207 --view front --mode opaque --no-walls --steps 200 "
                         "--section " + section);
    ASSERT_EQ(r.status, 0) << r.out;
    pixels[section == "y:1"] = foreground(simsols::plot::read_png(png.string()));
  }
  EXPECT_GT(pixels[1], pixels[0] / 10) << "the slab's beads";
  EXPECT_LT(pixels[1], pixels[0] * 9 / 10) << "the whole specimen covers more";
}

TEST(Cli, SnapshotRefusesBadSizePathAndNames) {
  const fs::path dir = fresh_dir("snapshot_bad");
  fs::create_directories(dir);
  const std::string out = (dir / "f.png").string();
  struct Case {
    std::string args, flag, hint;
  };
  const Case cases[] = {
      {"--out " + out + " --size 0x10", "--size", "[1, 16384]"},
      {"--out " + out + " --size 20000x10", "--size", "[1, 16384]"},
      {"--out " + out + " --size wide", "--size", "WIDTHxHEIGHT"},
      {"--out " + (dir / "missing" / "f.png").string(), "--out", "does not exist"},
      {"--out " + (dir / "f.jpg").string(), "--out", ".png"},
      {"--out " + out + " --mode xray", "--mode", "opaque, transparent, chains"},
      {"--out " + out + " --color-by mood", "--color-by", "speed"},
      {"--out " + out + " --view below", "--view", "three-quarter"},
      {"--out " + out + " --threshold -1", "--threshold", ">= 0"},
      {"--out " + out + " --range 5:1", "--range", "MIN < MAX"},
      {"--out " + out + " --gl vulkan", "--gl", "egl, osmesa"},
      {"--out " + out + " --section w", "--section", "x, y, z"},
      {"--out " + out + " --section y:0", "--section", "(0, 1000]"},
  };
  for (const Case& c : cases) {
    const Result r = run("snapshot " + kShearSmall + " " + c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.flag), std::string::npos) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.hint), std::string::npos) << c.args << "\n" << r.out;
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "a refused snapshot writes nothing";
}

TEST(Cli, RunWritesAFrameEveryNSteps) {
  const fs::path out = fresh_dir("frames");
  const fs::path frames = out / "frames";
  const Result r = run("run " + kScene + " --out " + out.string() + " --frames " + frames.string() +
                       " --every 250 --size 160x120 --color-by speed -q");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto at = r.out.find("finished at step ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const long steps = std::stol(r.out.substr(at + 17));
  long count = 0;
  for (const auto& e : fs::directory_iterator(frames)) {
    ++count;
    const simsols::plot::Image img = simsols::plot::read_png(e.path().string());
    EXPECT_EQ(img.width, 160);
    EXPECT_EQ(img.height, 120);
    const long step = std::stol(e.path().stem().string().substr(6));
    EXPECT_EQ(step % 250, 0) << e.path();
  }
  EXPECT_EQ(count, steps / 250 + 1) << "frames at step 0, 250, ...";
  // a checkpoint renders too
  const fs::path png = out / "checkpoint.png";
  const Result s = run("snapshot " + (out / "checkpoint.bin").string() + " --out " + png.string() +
                       " --size 100x80");
  EXPECT_EQ(s.status, 0) << s.out;
  EXPECT_TRUE(fs::exists(png));
  // --frames and --every go together
  const Result bad = run("run " + kScene + " --out " + fresh_dir("frames_bad").string() +
                         " --frames " + frames.string());
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("--every"), std::string::npos) << bad.out;
}

// --video hands the frames to ffmpeg in PATH: here a stand-in that logs its
// arguments and writes the file it is given, so the test sees the command
// and the rename of the finished file; without ffmpeg the frames stay and
// the run says how to encode them. Bad --video flags are refused.
TEST(Cli, RunEncodesItsFramesWithFfmpeg) {
  const fs::path out = fresh_dir("video"), bin = out / "bin", frames = out / "frames";
  fs::create_directories(bin);
  std::ofstream(bin / "ffmpeg") << "#!/bin/sh\necho \"$@\" > " << (out / "ffmpeg_args.txt").string()
                                << "\nfor a; do last=$a; done\necho video > \"$last\"\n";
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
  const std::string args = "run " + kScene + " --duration 0.0005 --frames " + frames.string() +
                           " --every 1000 --size 64x48 -q --video " + (out / "film.mp4").string();
  const Result r = simsols::testing::shell("PATH=" + bin.string() + ":/usr/bin:/bin " + std::string(SIMSOLS_EXE) +
                                           " " + args + " --out " + (out / "a").string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(read(out / "film.mp4"), "video\n");
  EXPECT_FALSE(fs::exists(out / "film.mp4.part"));
  const std::string logged = read(out / "ffmpeg_args.txt");
  EXPECT_NE(logged.find("-framerate 30 -pattern_type glob -i " + frames.string() + "/frame_*.png"),
            std::string::npos) << logged;
  EXPECT_NE(r.out.find("video " + (out / "film.mp4").string()), std::string::npos) << r.out;
  const Result none = simsols::testing::shell("PATH=/nonexistent " + std::string(SIMSOLS_EXE) + " " + args +
                                              " --out " + (out / "b").string() + " --fps 12");
  ASSERT_EQ(none.status, 0) << none.out;
  EXPECT_NE(none.out.find("ffmpeg not found"), std::string::npos) << none.out;
  EXPECT_NE(none.out.find("-framerate 12"), std::string::npos) << none.out;
  EXPECT_FALSE(fs::is_empty(frames));
  const Result no_frames = run("run " + kScene + " --out " + (out / "c").string() + " --video x.mp4");
  EXPECT_EQ(no_frames.status, 2) << no_frames.out;
  EXPECT_NE(no_frames.out.find("--frames"), std::string::npos) << no_frames.out;
  const Result avi = run("run " + kScene + " --out " + (out / "d").string() + " --frames " + frames.string() +
                         " --every 10 --video x.avi");
  EXPECT_EQ(avi.status, 2) << avi.out;
  EXPECT_NE(avi.out.find("x.avi"), std::string::npos) << avi.out;
  EXPECT_FALSE(fs::exists(out / "c") || fs::exists(out / "d"));
}

// A scene's [view] section sets the defaults; flags override; a bad value
// names the file and the field.
TEST(Cli, SceneViewHintsAndOverrides) {
  const fs::path dir = fresh_dir("view_hints");
  fs::create_directories(dir);
  std::string text = read(kScene);
  auto scene_with = [&](const std::string& name, const std::string& view) {
    const fs::path p = dir / name;
    std::ofstream(p) << text << "\n[view]\n" << view;
    return p.string();
  };
  const std::string good = scene_with("good.toml", "size = \"90x70\"\nmode = \"transparent\"\n"
                                                   "view = \"top\"\ncolor_by = \"speed\"\n");
  Result r = run("snapshot " + good + " --out " + (dir / "a.png").string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(simsols::plot::read_png((dir / "a.png").string()).width, 90);
  r = run("snapshot " + good + " --out " + (dir / "b.png").string() + " --size 100x50");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(simsols::plot::read_png((dir / "b.png").string()).height, 50);
  const std::string bad = scene_with("bad.toml", "mode = \"xray\"\n");
  r = run("snapshot " + bad + " --out " + (dir / "c.png").string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("bad.toml"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("view.mode"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "c.png"));
  // refused by `run` as well, before anything is written
  r = run("run " + bad + " --out " + (dir / "run").string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_FALSE(fs::exists(dir / "run"));
}

// `snapshot --stereo alioscopy`: the interleaved image at the display's
// resolution, the eight views and the grid; a bad profile is named.
TEST(Cli, SnapshotAlioscopyWritesTheInterleavedImageAndTheViews) {
  const fs::path dir = fresh_dir("alioscopy");
  fs::create_directories(dir);
  const std::string profile = (dir / "small.toml").string();
  std::ofstream(profile) << "[display]\nwidth = 320\nheight = 180\nphase = 1\n";
  const fs::path png = dir / "a.png";
  Result r = run("snapshot " + kShearSmall + " --out " + png.string() +
                 " --stereo alioscopy --display " + profile + " --mode transparent");
  ASSERT_EQ(r.status, 0) << r.out;
  const simsols::plot::Image inter = simsols::plot::read_png(png.string());
  EXPECT_EQ(inter.width, 320);
  EXPECT_EQ(inter.height, 180);
  for (int k = 0; k < 8; ++k) {  // views at 3/8 of the output (view_scale), rounded up
    const auto v = simsols::plot::read_png((dir / ("a_view" + std::to_string(k) + ".png")).string());
    EXPECT_EQ(v.width, 120);
    EXPECT_EQ(v.height, 68);
  }
  EXPECT_TRUE(fs::exists(dir / "a_grid.png"));
  std::ofstream(profile) << "[display]\nphase = 12\n";
  r = run("snapshot " + kShearSmall + " --out " + (dir / "b.png").string() +
          " --stereo alioscopy --display " + profile);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("display.phase"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("[0, 7]"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "b.png"));
  r = run("snapshot " + kShearSmall + " --out " + (dir / "c.png").string() + " --stereo anaglyph");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--stereo"), std::string::npos) << r.out;
}

// `simsols study accuracy --preset ci`: the reduced study. Errors fall as the
// time step shrinks; float and double agree; a time step beyond the
// stability limit is reported as failed, not as a number.
namespace {

std::vector<std::vector<std::string>> read_csv(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> f(1);
    bool q = false;
    for (char c : line) {
      if (c == '"') q = !q;
      else if (c == ',' && !q) f.emplace_back();
      else f.back() += c;
    }
    rows.push_back(f);
  }
  return rows;
}

}  // namespace

TEST(Cli, AccuracyStudyReducedForm) {
  const fs::path out = fresh_dir("study");
  const Result r = run("study accuracy --preset ci --out " + out.string() + " -q");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto rows = read_csv(out / "cases.csv");
  ASSERT_EQ(rows.size(), 18u) << "header + layered 5 settings x 2 members + the reference's "
                                 "round-off twin + poured 2 x 2 + its two twins";
  const auto col = [&](const std::string& name) {
    const auto it = std::find(rows[0].begin(), rows[0].end(), name);
    EXPECT_NE(it, rows[0].end()) << name;
    return static_cast<size_t>(it - rows[0].begin());
  };
  std::map<std::string, std::vector<std::string>> by;  // seed 1's, by specimen and label
  for (size_t i = 1; i < rows.size(); ++i) by.emplace(rows[i][0] + " " + rows[i][2], rows[i]);
  auto val = [&](const std::string& label, const std::string& column) {
    return std::stod(by.at(label)[col(column)]);
  };
  for (const char* c : {"overlap_err_pct", "contact_time_err_pct", "restitution_err_pct"}) {
    // the reference (dt 0.15, double) is the smallest step
    EXPECT_LT(val("layered reference: dt 0.15 double", c), val("layered dt 0.2", c)) << c;
    EXPECT_LT(val("layered dt 0.2", c), val("layered dt 0.4", c)) << c;
  }
  // float and double agree: peak angle within 0.5 %, contact errors both small
  EXPECT_NEAR(val("layered dt 0.2", "peak_deg") / val("layered double dt 0.2", "peak_deg"), 1.0, 0.005);
  EXPECT_LT(val("layered dt 0.2", "overlap_err_pct"), 0.1);
  EXPECT_LT(val("layered double dt 0.2", "overlap_err_pct"), 0.1);
  // beyond the stability limit: failed, no numbers
  const auto& bad = by.at("layered dt 3.0 (forced)");
  EXPECT_EQ(bad[col("shear_status")].rfind("failed", 0), 0u) << bad[col("shear_status")];
  EXPECT_TRUE(bad[col("peak_deg")].empty());
  EXPECT_TRUE(bad[col("peak_err_pct")].empty());
  // the poured specimen runs through, compared with its own reference (in
  // this reduced form its rain has not settled: its angles mean nothing)
  for (const char* label : {"poured dt 0.4", "poured reference: dt 0.2 double",
                            "poured reference: dt 0.2 double (round-off twin at shear)"}) {
    EXPECT_EQ(by.at(label)[col("shear_status")], "ok") << label;
    EXPECT_FALSE(by.at(label)[col("peak_err_pct")].empty()) << label;
  }
  for (const char* f : {"pareto.png", "summary.md", "error_vs_time_time_step.png",
                        "poured_pareto.png", "poured_error_vs_time_time_step.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  // the ensembles: one row per setting, each member's seed in cases.csv
  const auto ens = read_csv(out / "ensemble.csv");
  ASSERT_EQ(ens.size(), 8u) << "header + 5 layered settings + 2 poured";
  const size_t runs = static_cast<size_t>(
      std::find(ens[0].begin(), ens[0].end(), "runs") - ens[0].begin());
  ASSERT_LT(runs, ens[0].size());
  EXPECT_EQ(ens[1][runs], "2");  // runs of the reference
  EXPECT_EQ(ens[6][0], "poured");
  EXPECT_EQ(rows[2][col("seed")], "2");  // the reference's second member: seed 2
  std::ifstream md(out / "summary.md");
  const std::string summary((std::istreambuf_iterator<char>(md)), {});
  for (const char* h : {"## The layered specimen", "## The poured specimen", "### Chaos",
                        "round-off twin", "### Recommendation"})
    EXPECT_NE(summary.find(h), std::string::npos) << h << "\n" << summary;
  const Result bad_ensemble = run("study accuracy --preset ci --ensemble 99 --out " + out.string());
  EXPECT_EQ(bad_ensemble.status, 2) << bad_ensemble.out;
  EXPECT_NE(bad_ensemble.out.find("--ensemble"), std::string::npos) << bad_ensemble.out;
  const Result bad_preset = run("study accuracy --preset huge --out " + out.string());
  EXPECT_EQ(bad_preset.status, 2) << bad_preset.out;
  EXPECT_NE(bad_preset.out.find("--preset"), std::string::npos);
  const Result bad_scale = run("study accuracy --preset ci --box-scale 9 --out " + out.string());
  EXPECT_EQ(bad_scale.status, 2) << bad_scale.out;
  EXPECT_NE(bad_scale.out.find("[1, 4]"), std::string::npos) << bad_scale.out;
  const Result bad_jobs = run("study accuracy --preset ci --jobs 0 --out " + out.string());
  EXPECT_EQ(bad_jobs.status, 2) << bad_jobs.out;
  EXPECT_NE(bad_jobs.out.find("[1, 16]"), std::string::npos) << bad_jobs.out;
  const Result bad_specimen = run("study accuracy --preset ci --specimen sand --out " + out.string());
  EXPECT_EQ(bad_specimen.status, 2) << bad_specimen.out;
  EXPECT_NE(bad_specimen.out.find("layered, poured"), std::string::npos) << bad_specimen.out;
  // the tables of a finished study, one per specimen; with --out its charts
  // drawn again from ensemble.csv alone, the same files the study drew
  const fs::path again = out / "charts_again";
  const Result table =
      run("study table --from " + (out / "ensemble.csv").string() + " --out " + again.string());
  EXPECT_EQ(table.status, 0) << table.out;
  EXPECT_NE(table.out.find("poured specimen:"), std::string::npos) << table.out;
  int charts = 0;
  for (const auto& e : fs::directory_iterator(out))
    if (e.path().extension() == ".png") {
      ++charts;
      EXPECT_TRUE(fs::exists(again / e.path().filename())) << e.path().filename();
    }
  EXPECT_GT(charts, 0);
}

namespace {

std::string file_text(const fs::path& p) {
  std::ifstream f(p);
  return std::string((std::istreambuf_iterator<char>(f)), {});
}

// The manifest's batch and its number of tests.
std::pair<std::string, int> manifest_batch(const fs::path& out) {
  const std::string m = file_text(out / "slurm" / "manifest.toml");
  const auto at = m.find("\nbatch = '");
  const std::string batch = at == std::string::npos ? "" : m.substr(at + 10, m.find('\'', at + 10) - at - 10);
  int tests = 0;
  for (size_t p = m.find("[[test]]"); p != std::string::npos; p = m.find("[[test]]", p + 1)) ++tests;
  return {batch, tests};
}

}  // namespace

// A calibration on a Slurm cluster is a chain of job arrays, one per batch
// (round 0, round 1, the replicates): --emit writes the first; each array
// task (--task K) runs one test; --collect writes the next batch's job, and
// after the last batch the report, which equals a run on one machine. A
// prediction is one batch. (tests/cluster/test_slurm.sh runs a campaign
// through a real Slurm; here each array task is run by hand.)
TEST(Cli, CalibrationRunsAsAChainOfJobArraysAndEqualsALocalRun) {
  const fs::path d = fresh_dir("calibration_cluster");
  fs::create_directories(d);
  {  // a measured curve: any rising stress ratio will do
    std::ofstream m(d / "measured.csv");
    m << "strain,stress_ratio\n";
    for (int i = 0; i <= 10; ++i) m << 0.003 * i << "," << 1.2 * (1 - std::exp(-i * 0.6)) << "\n";
  }
  const std::string target =
      "[[targets]]\nname = \"t\"\nscene = \"" + std::string(SIMSOLS_ASSETS_DIR) +
      "/tests/periodic_triaxial_small.toml\"\ndata = \"measured.csv\"\n"
      "set = { \"periodic_cell.axial_strain\" = 0.03 }\n"
      "x = { column = \"strain\", unit = \"-\", quantity = \"axial_strain\" }\n"
      "[[targets.y]]\ncolumn = \"stress_ratio\"\nunit = \"-\"\nquantity = \"stress_ratio\"\n";
  std::ofstream(d / "cal.toml")
      << "[calibration]\nname = \"chain\"\nbudget = 6\nrounds = 2\nreplicates = 2\npoints = 5\n"
         "[[parameters]]\nname = \"mu_s\"\nkey = \"materials.beads.sliding_friction\"\n"
         "min = 0.1\nmax = 0.6\n" << target;
  const std::string cal = "calibrate " + (d / "cal.toml").string() + " -q --out ";
  const fs::path out = d / "cluster";
  Result r = run("calibrate " + (d / "cal.toml").string() + " --emit slurm");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("'--out'"), std::string::npos) << "a cluster run needs its folder: " << r.out;
  r = run(cal + out.string() + " --emit slurm");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(file_text(out / "slurm" / "collect.sbatch").find("submit.sh \"$@\""), std::string::npos)
      << "the collecting job submits the next batch with its own sbatch arguments";
  EXPECT_NE(file_text(out / "slurm" / "submit.sh").find("collect.sbatch \"$@\""), std::string::npos);
  r = run("calibrate -q --collect " + out.string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("have not finished"), std::string::npos) << r.out;
  std::vector<std::pair<std::string, int>> batches;
  while (!fs::exists(out / "parameters.csv") && batches.size() < 4) {
    batches.push_back(manifest_batch(out));
    for (int k = 0; k < batches.back().second; ++k) {
      r = run(cal + out.string() + " --task " + std::to_string(k));
      ASSERT_EQ(r.status, 0) << r.out;
    }
    r = run("calibrate -q --collect " + out.string());
    ASSERT_EQ(r.status, 0) << r.out;
  }
  const std::vector<std::pair<std::string, int>> expected = {
      {"round0", 3}, {"round1", 3}, {"replicates", 2}};
  EXPECT_EQ(batches, expected);
  r = run(cal + (d / "local").string());
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* f : {"parameters.csv", "design.csv", "curves.csv"})
    EXPECT_EQ(file_text(out / f), file_text(d / "local" / f)) << f;

  // the calibrated material's prediction: one batch, collected into its report
  std::ofstream(d / "predict.toml")
      << "[prediction]\nname = \"p\"\ncalibrated = \"" << (out / "calibrated.toml").string()
      << "\"\nspecimens = 2\npoints = 5\n"
      << std::regex_replace(target, std::regex("targets"), "tests");
  const fs::path pred = d / "prediction";
  r = run("predict " + (d / "predict.toml").string() + " -q --out " + pred.string() + " --emit slurm");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(manifest_batch(pred), (std::pair<std::string, int>{"tests", 2}));
  for (int k = 0; k < 2; ++k)
    ASSERT_EQ(run("predict " + (d / "predict.toml").string() + " -q --out " + pred.string() +
                  " --task " + std::to_string(k)).status, 0);
  r = run("predict -q --collect " + pred.string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(fs::exists(pred / "prediction.csv")) << r.out;
}
