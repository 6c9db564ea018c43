// The desktop lab end to end, under Xvfb: a scripted session loads a
// preset, prepares it, applies the normal stress, shears, changes the normal
// stress, takes a screenshot and a checkpoint; a second session loads the
// checkpoint. Asserted: the experiment's state (displacement advanced, the
// servo target changed, the checkpoint reloads to the same state and goes
// on exactly as the first session did) and the screenshot (the panel drawn,
// the beads visible in the viewport).
#include <unistd.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "render/plot/png.h"

namespace fs = std::filesystem;

namespace {

int run(const std::string& cmd) {
  const int s = std::system((cmd + " > /dev/null 2>&1").c_str());
  return WIFEXITED(s) ? WEXITSTATUS(s) : -1;
}

std::map<std::string, std::string> read_state(const fs::path& p) {
  std::map<std::string, std::string> m;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find(" = ");
    if (eq != std::string::npos) m[line.substr(0, eq)] = line.substr(eq + 3);
  }
  return m;
}

std::string lab(const fs::path& script) {
  return "xvfb-run -a -s '-screen 0 1600x1000x24' " + std::string(SIMSOLS_EXE) +
         " lab --size 1400x860 --script " + script.string();
}

}  // namespace

TEST(Lab, ScriptedSessionShearsChangesStressAndCheckpoints) {
  if (run("command -v xvfb-run") != 0) GTEST_SKIP() << "xvfb-run not installed (Debian: xvfb)";
  const fs::path d = fs::temp_directory_path() / ("simsols_lab_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "one.txt") << "preset 6.35 160\nprepare\nload\nstart\nrows 3\nstate "
                               << (d / "pre.state").string() << "\n"
                               << "set_stress 280\nrows 6\nscreenshot " << (d / "shot.png").string()
                               << "\nstate " << (d / "a.state").string() << "\ncheckpoint "
                               << (d / "c.bin").string() << "\nrows 9\nstate "
                               << (d / "b.state").string() << "\n";
  std::ofstream(d / "two.txt") << "load_checkpoint " << (d / "c.bin").string() << "\nframes 2\n"
                               << "state " << (d / "a2.state").string() << "\nrows 9\nstate "
                               << (d / "b2.state").string() << "\n"
                               << "view opaque\nframes 1\nview alioscopy\nframes 3\nframe "
                               << (d / "alio.png").string() << "\n"
                               // a checkpoint loaded over a running simulation: the view
                               // follows the new one at once
                               << "view transparent\nload_checkpoint " << (d / "c.bin").string()
                               << "\nframes 2\nstate " << (d / "a3.state").string() << "\n"
                               // a slab through the middle, coloured by non-affine motion
                               << "section y:1.5\ncolor nonaffine\nframes 2\nstate "
                               << (d / "a4.state").string() << "\n";
  std::ofstream(d / "bad_section.txt") << "section w\n";
  ASSERT_EQ(run(lab(d / "one.txt")), 0);
  ASSERT_EQ(run(lab(d / "two.txt")), 0);

  auto a = read_state(d / "a.state"), b = read_state(d / "b.state");
  auto a2 = read_state(d / "a2.state"), b2 = read_state(d / "b2.state");
  EXPECT_EQ(a["stage"], "shearing");
  EXPECT_EQ(a["rows"], "6");
  EXPECT_GT(std::stod(a["displacement_mm"]), 0.05);
  EXPECT_DOUBLE_EQ(std::stod(a["sigma_target_kpa"]), 280);
  // the servo followed the new target: the measured stress is near 280, not 160
  EXPECT_NEAR(std::stod(a["sigma_kpa"]), 280, 0.1 * 280);
  // and the shear speed followed, holding the inertial number (v ~ sqrt(sigma))
  auto pre = read_state(d / "pre.state");
  const double speed_ratio = std::stod(a["shear_speed_mm_s"]) / std::stod(pre["shear_speed_mm_s"]);
  std::printf("[measure] shear speed x %.4f for sigma 160 -> 280 kPa (sqrt: %.4f); I %s -> %s\n",
              speed_ratio, std::sqrt(280.0 / 160), pre["inertial_number"].c_str(),
              a["inertial_number"].c_str());
  EXPECT_NEAR(speed_ratio, std::sqrt(280.0 / 160), 0.01);
  EXPECT_NEAR(std::stod(a["inertial_number"]), std::stod(pre["inertial_number"]),
              0.05 * std::stod(pre["inertial_number"]));
  EXPECT_GT(std::stod(b["displacement_mm"]), std::stod(a["displacement_mm"]));
  // the checkpoint reloads to the same state and continues identically
  EXPECT_EQ(a2["hash"], a["hash"]);
  EXPECT_EQ(a2["steps"], a["steps"]);
  EXPECT_EQ(b2["hash"], b["hash"]);
  EXPECT_EQ(b2["steps"], b["steps"]);
  auto a3 = read_state(d / "a3.state");
  EXPECT_EQ(a3["hash"], a["hash"]);
  EXPECT_EQ(a3["steps"], a["steps"]);
  EXPECT_EQ(a3["section"], "off");
  auto a4 = read_state(d / "a4.state");
  EXPECT_EQ(a4["section"], "y:1.5");
  EXPECT_EQ(a4["color"], "nonaffine");
  EXPECT_EQ(run(lab(d / "bad_section.txt")), 2) << "a section that is not x|y|z[:WIDTH]|off";
  // the Alioscopy view: the interleaved image over the whole window, the
  // beads in the look of the last flat view (opaque: coloured by layer)
  const simsols::plot::Image alio = simsols::plot::read_png((d / "alio.png").string());
  EXPECT_EQ(alio.width, 1400);
  EXPECT_EQ(alio.height, 860);
  long coloured = 0;
  for (int y = 0; y < alio.height; ++y)
    for (int x = 0; x < alio.width; ++x) {
      const auto p = simsols::plot::pixel(alio, x, y);
      coloured += std::max({p.r, p.g, p.b}) - std::min({p.r, p.g, p.b}) > 40;
    }
  EXPECT_GT(coloured, 5000) << "beads in the interleaved image";

  const simsols::plot::Image img = simsols::plot::read_png((d / "shot.png").string());
  ASSERT_EQ(img.width, 1400);
  ASSERT_EQ(img.height, 860);
  // the panel (left 430 px): text and widgets, many distinct colours
  std::map<std::uint32_t, int> panel_colours;
  long colourful = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const auto p = simsols::plot::pixel(img, x, y);
      if (x < 430) panel_colours[(p.r << 16) | (p.g << 8) | p.b]++;
      else if (std::max({p.r, p.g, p.b}) - std::min({p.r, p.g, p.b}) > 40) ++colourful;
    }
  EXPECT_GT(panel_colours.size(), 30u) << "panel drawn";
  EXPECT_GT(colourful, 5000) << "beads (coloured by layer) visible in the viewport";
  // the four live plots (tau/sigma, tau, sigma and its target, dilation) in
  // the window's height, each tall enough to read, each with its curve
  EXPECT_EQ(a["live_plots"], "4");
  EXPECT_GE(std::stod(a["live_plot_height_px"]), 150);
  const int curve_x0 = 1400 - 300;  // the column is at least 300 px wide
  for (int q = 0; q < 4; ++q) {
    int curve = 0;
    for (int y = q * img.height / 4; y < (q + 1) * img.height / 4; ++y)
      for (int x = curve_x0; x < img.width; ++x) {
        const auto p = simsols::plot::pixel(img, x, y);
        curve += std::abs(p.r - 90) < 30 && std::abs(p.g - 170) < 30 && p.b > 220;
      }
    EXPECT_GT(curve, 30) << "no curve in the plot column's quarter " << q;
  }
}

// Issue 9 in the lab: the panel's slot choices (scripted with `effect`, the
// same action as the combo boxes) rebuild the kernels at Prepare, and the
// status line (here the state file, which prints the same line) shows what
// is compiled in: no rolling and no tangential code; with the damping on,
// the normal dashpot's record is the only history (16 bytes per contact),
// without it there is none. Then back to the paper's slots: both compiled,
// 16 bytes per contact.
TEST(Lab, EffectSlotsSwitchTheCompiledKernels) {
  if (run("command -v xvfb-run") != 0) GTEST_SKIP() << "xvfb-run not installed (Debian: xvfb)";
  const fs::path d = fs::temp_directory_path() / ("simsols_lab_slots_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "s.txt") << "preset 6.35 160\neffect rolling none\neffect tangential none\n"
                             << "prepare\nstate " << (d / "off.state").string() << "\n"
                             << "effect damping none\nprepare\nstate "
                             << (d / "undamped.state").string() << "\neffect damping viscous\n"
                             << "effect rolling constant_torque\neffect tangential mindlin\n"
                             << "prepare\nstate " << (d / "on.state").string() << "\n";
  ASSERT_EQ(run(lab(d / "s.txt")), 0);
  auto off = read_state(d / "off.state"), on = read_state(d / "on.state");
  auto undamped = read_state(d / "undamped.state");
  ASSERT_FALSE(off["compiled"].empty()) << "no compiled-slots line";
  EXPECT_NE(off["compiled"].find("tangential=none"), std::string::npos) << off["compiled"];
  EXPECT_NE(off["compiled"].find("rolling=none"), std::string::npos) << off["compiled"];
  EXPECT_EQ(off["history_bytes"], "16");  // float: the dashpot's record, in a record of 4 reals
  EXPECT_NE(undamped["compiled"].find("damping=none"), std::string::npos) << undamped["compiled"];
  EXPECT_EQ(undamped["history_bytes"], "0");
  EXPECT_NE(on["compiled"].find("tangential=mindlin"), std::string::npos) << on["compiled"];
  EXPECT_NE(on["compiled"].find("rolling=constant_torque"), std::string::npos) << on["compiled"];
  EXPECT_EQ(on["history_bytes"], "16");  // float: one spring of 4 reals
  // an unknown choice is refused with the script's error status
  std::ofstream(d / "bad.txt") << "effect rolling sticky\n";
  EXPECT_NE(run(lab(d / "bad.txt")), 0);
}

// The fast profile (run_profile.h) applies at prepare: dt 0.5 instead of
// 0.25 x Rayleigh, a step twice as long.
TEST(Lab, TheFastProfileLengthensTheStep) {
  if (run("command -v xvfb-run") != 0) GTEST_SKIP() << "xvfb-run not installed (Debian: xvfb)";
  const fs::path d = fs::temp_directory_path() / ("simsols_lab_profile_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "s.txt") << "preset 6.35 160\nprepare\nstate " << (d / "paper.state").string()
                             << "\nprofile fast\nprepare\nstate " << (d / "fast.state").string() << "\n";
  ASSERT_EQ(run(lab(d / "s.txt")), 0);
  auto paper = read_state(d / "paper.state"), fast = read_state(d / "fast.state");
  EXPECT_EQ(paper["profile"], "paper");
  EXPECT_EQ(fast["profile"], "fast");
  const double ratio = std::stod(fast["dt_s"]) / std::stod(paper["dt_s"]);
  EXPECT_NEAR(ratio, 2.0, 1e-6 * ratio);
  std::ofstream(d / "bad.txt") << "profile quick\n";
  EXPECT_NE(run(lab(d / "bad.txt")), 0);
  fs::remove_all(d);
}

// A calibration's result in the lab (lab_calibration.h): `material` sets
// the calibrated friction on the scene's material and prepares a specimen
// with it; the measured curve it was fitted to is drawn over the live plot
// that measures its quantities (the periodic cell's stress ratio against
// the axial strain), every one of its points; a target the file does not
// have is refused naming the ones it has.
TEST(Lab, ACalibratedMaterialAndItsMeasuredCurve) {
  if (run("command -v xvfb-run") != 0) GTEST_SKIP() << "xvfb-run not installed (Debian: xvfb)";
  const fs::path d = fs::temp_directory_path() / ("simsols_lab_calibrated_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  const std::string scene = std::string(SIMSOLS_ASSETS_DIR) + "/tests/periodic_triaxial_small.toml";
  std::ofstream(d / "m.csv") << "# measured\neps_pct,eta\n0,0\n1,0.6\n2,0.9\n5,1.1\n10,1.0\n";
  std::ofstream(d / "cal.toml")
      << "[calibrated]\n\"materials.beads.sliding_friction\" = 0.42\n"
         "[[measured]]\nname = \"lab\"\nscene = \"" << scene << "\"\ndata = \"m.csv\"\n"
         "x = { column = \"eps_pct\", unit = \"%\", quantity = \"axial_strain\" }\n"
         "[[measured.y]]\ncolumn = \"eta\"\nunit = \"-\"\nquantity = \"stress_ratio\"\n";
  std::ofstream(d / "s.txt") << "open " << scene << "\nmaterial " << (d / "cal.toml").string()
                             << "\nprepare\nstart\nrows 40\nstate " << (d / "lab.state").string() << "\n";
  ASSERT_EQ(run(lab(d / "s.txt")), 0);
  auto state = read_state(d / "lab.state");
  EXPECT_EQ(state["sliding_friction.beads"], "0.42");
  EXPECT_EQ(state["measured_points"], "5");
  std::ofstream(d / "bad.txt") << "open " << scene << "\nmaterial " << (d / "cal.toml").string()
                               << " TMD2\n";
  EXPECT_NE(run(lab(d / "bad.txt")), 0);
  fs::remove_all(d);
}
