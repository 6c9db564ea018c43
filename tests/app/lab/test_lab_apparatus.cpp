// The desktop lab operating the triaxial cell and the oedometer, under
// Xvfb: one scripted session consolidates a small triaxial specimen to
// sigma3 = 100 kPa (settle, isotropic consolidation, hold), starts the
// compression, changes the strain rate, checkpoints, exports; then opens an
// oedometer scene and runs its two load steps to the end, exports. A second
// session continues the triaxial test from the checkpoint; a third asks the
// oedometer for a setting it has not.
//
// Asserted: consolidated with p' within 1 % of sigma3 (the test's
// equilibrium criterion is each plate within 1 %); the platen moves at the
// strain rate before and after the change (d eps_a / dt of the rows, within
// 1 %: the platen is strain controlled, so the theory is exact); the rows
// and the exported CSV agree and parse; the plots and the summary exist;
// the screenshot shows the panel and the beads; the oedometer ends both
// steps at their targets and its void ratio falls under the larger load;
// the checkpoint reloads to the same state and continues identically.
#include <unistd.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "render/plot/png.h"

namespace fs = std::filesystem;

namespace {

int run(const std::string& cmd, const fs::path& log = "/dev/null") {
  const int s = std::system((cmd + " > " + log.string() + " 2>&1").c_str());
  return WIFEXITED(s) ? WEXITSTATUS(s) : -1;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
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

double num(std::map<std::string, std::string>& m, const std::string& key) {
  if (m.count(key) == 0) {
    ADD_FAILURE() << "no '" << key << "' in the state";
    return NAN;
  }
  return std::stod(m[key]);
}

// A CSV file's columns by header name; every field must parse as a number.
std::map<std::string, std::vector<double>> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::vector<std::string> names;
  std::map<std::string, std::vector<double>> cols;
  if (!std::getline(in, line)) return cols;
  for (std::stringstream h(line); std::getline(h, line, ',');) names.push_back(line);
  while (std::getline(in, line)) {
    std::stringstream r(line);
    std::string field;
    for (std::size_t k = 0; std::getline(r, field, ','); ++k) {
      std::size_t used = 0;
      const double v = std::stod(field, &used);
      EXPECT_EQ(used, field.size()) << p << ": '" << field << "' is not a number";
      if (k < names.size()) cols[names[k]].push_back(v);
    }
  }
  return cols;
}

// Glass ten times softer than the paper's (the step 3.2 times longer): the
// lab's path is under test, not the packing.
constexpr const char* kGlass = R"(
[[materials]]
name = "glass"
young_modulus = 6.2784e9
poisson_ratio = 0.2
density = 2230
restitution = 0.87
sliding_friction = 0.3
rolling_friction = 5e-5
)";

// test_triaxial.cpp's 150 beads of 6.35 mm in a 5.5 d cell, in float; the
// pour is settled for 0.05 s only (the consolidation packs it).
std::string triaxial_scene() {
  return std::string(kGlass) + R"(
[triaxial]
length = 34.925e-3
width = 34.925e-3
confining_stress = 100e3
axial_strain = 0.03
inertial_number = 3e-4
settle_time = 0.05
rows = 15

[triaxial.specimen]
method = "pour"
material = "glass"
diameter = 6.35e-3
layers = 6
seed = 2

[numerics]
precision = "float"
dt_fraction = 0.25
duration = 1
)";
}

// test_oedometer.cpp's ring (108 beads), two load steps held 30 ms at most;
// the pour settles for up to 0.3 s (at 0.15 s some seeds still rain, and the
// platen would spend the first step reaching them).
std::string oedometer_scene() {
  return std::string(kGlass) + R"(
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
density = 7850
restitution = 0.87
sliding_friction = 0
rolling_friction = 0

[oedometer]
length = 41.275e-3
width = 41.275e-3
load_steps = [25e3, 50e3]
settle_time = 0.3
step_time = 0.03

[oedometer.specimen]
method = "pour"
material = "glass"
diameter = 6.35e-3
layers = 3
seed = 4

[numerics]
precision = "float"
dt_fraction = 0.25
duration = 1
)";
}

// A smaller window than test_lab.cpp's: the solver gets what drawing leaves
// of each frame.
std::string lab(const fs::path& script) {
  return "xvfb-run -a -s '-screen 0 1600x1000x24' " + std::string(SIMSOLS_EXE) +
         " lab --size 1000x640 --script " + script.string();
}

// Coloured pixels in the viewport (right of the 430 px panel).
long coloured_viewport_pixels(const simsols::plot::Image& img) {
  long n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 430; x < img.width; ++x) {
      const auto p = simsols::plot::pixel(img, x, y);
      n += std::max({p.r, p.g, p.b}) - std::min({p.r, p.g, p.b}) > 40;
    }
  return n;
}

class LabApparatus : public ::testing::Test {
 protected:
  void SetUp() override {
    if (run("command -v xvfb-run") != 0) GTEST_SKIP() << "xvfb-run not installed (Debian: xvfb)";
    d = fs::temp_directory_path() / ("simsols_lab_app_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    std::ofstream(d / "tri.toml") << triaxial_scene();
    std::ofstream(d / "oed.toml") << oedometer_scene();
  }
  fs::path p(const std::string& name) const { return d / name; }
  // consolidated and held, compressed at two rates, exported
  void check_triaxial() {
    auto def = read_state(p("default.state"));
    EXPECT_EQ(def["scene"], "built-in triaxial.toml");

    // consolidated, σ₃ held: p' within 1 % of 100 kPa
    auto c = read_state(p("consolidated.state"));
    EXPECT_EQ(c["apparatus"], "triaxial");
    EXPECT_EQ(c["stage"], "consolidated, σ₃ held");
    EXPECT_EQ(c["consolidated"], "1");
    EXPECT_EQ(c["rows"], "0");
    std::printf("[measure] consolidated after %s steps: p' %s kPa, sigma %s %s %s kPa\n",
                c["steps"].c_str(), c["p_kpa"].c_str(), c["sigma_x_kpa"].c_str(),
                c["sigma_y_kpa"].c_str(), c["sigma_z_kpa"].c_str());
    EXPECT_NEAR(num(c, "p_kpa"), 100, 1.0);
    for (const char* k : {"sigma_x_kpa", "sigma_y_kpa", "sigma_z_kpa"}) EXPECT_NEAR(num(c, k), 100, 1.0) << k;

    // compression at the scene's rate, then at 1/s: d eps_a / dt = the rate
    auto a = read_state(p("a.state")), b = read_state(p("b.state"));
    EXPECT_EQ(a["stage"], "compressing");
    EXPECT_EQ(a["rows"], "3");
    EXPECT_EQ(b["rows"], "6");
    const double rate0 = num(a, "strain_rate");
    EXPECT_DOUBLE_EQ(num(b, "strain_rate"), 1.0);
    const double before = num(a, "axial_strain") / (num(a, "time_s") - num(c, "time_s"));
    const double after = (num(b, "axial_strain") - num(a, "axial_strain")) / (num(b, "time_s") - num(a, "time_s"));
    std::printf("[measure] d eps_a/dt %.5f 1/s (rate %.5f), then %.5f 1/s (rate 1); q %s kPa at "
                "eps_a %s\n", before, rate0, after, b["q_kpa"].c_str(), b["axial_strain"].c_str());
    EXPECT_NEAR(before, rate0, 0.01 * rate0);
    EXPECT_NEAR(after, 1.0, 0.01);
    EXPECT_GT(num(b, "q_kpa"), 5) << "a frictional packing carries a deviator";
    EXPECT_NEAR(num(b, "sigma3_target_kpa"), 100, 1e-9);

    // the export: the rows as the state says, every field a number
    auto tri = read_csv(p("tri_out/triaxial.csv"));
    ASSERT_EQ(tri["axial_strain"].size(), 6u);
    EXPECT_NEAR(tri["axial_strain"].back(), num(b, "axial_strain"), 1e-6);
    for (std::size_t i = 1; i < 6; ++i) EXPECT_GT(tri["axial_strain"][i], tri["axial_strain"][i - 1]);
    EXPECT_NEAR(tri["p_kPa"].front(), num(c, "p_kpa"), 0.01) << "the first row is the one at rest";
    EXPECT_NE(slurp(p("tri_out/summary.txt")).find("peak"), std::string::npos);
    for (const char* png : {"stress_ratio.png", "deviator.png", "volumetric.png", "e_log_p.png"})
      EXPECT_GT(simsols::plot::read_png(p("tri_out") / png).width, 0) << png;
  }

  void check_checkpoint() {
    auto a = read_state(p("a.state")), b = read_state(p("b.state"));
    // the checkpoint reloads to the same state and continues identically
    auto a2 = read_state(p("a2.state")), b2 = read_state(p("b2.state"));
    EXPECT_EQ(a2["stage"], "compressing");
    EXPECT_EQ(a2["hash"], a["hash"]);
    EXPECT_EQ(a2["steps"], a["steps"]);
    EXPECT_EQ(b2["hash"], b["hash"]);
    EXPECT_EQ(b2["steps"], b["steps"]);
  }

  void check_oedometer() {
    // the oedometer: its programme ran to the end by itself, both steps on target
    auto os = read_state(p("oed_start.state")), od = read_state(p("oed_done.state"));
    EXPECT_EQ(os["apparatus"], "oedometer");
    EXPECT_EQ(os["stage"], "load programme");
    EXPECT_EQ(os["load_step"], "1");
    EXPECT_EQ(od["stage"], "load programme finished");
    EXPECT_EQ(od["steps_ended"], "2");
    EXPECT_EQ(od["load_step"], "2");
    EXPECT_NEAR(num(od, "sigma_top_kpa"), 50, 2.5);
    auto oed = read_csv(p("oed_out/oedometer.csv"));
    ASSERT_EQ(oed["void_ratio"].size(), std::size_t(num(od, "rows")));
    std::vector<double> e_end, top_end;
    int in_equilibrium = 0;
    for (std::size_t i = 0; i < oed["end_of_step"].size(); ++i)
      if (oed["end_of_step"][i] != 0) {
        e_end.push_back(oed["void_ratio"][i]);
        top_end.push_back(oed["sigma_top_kPa"][i]);
        in_equilibrium += oed["end_of_step"][i] == 1;
      }
    ASSERT_EQ(e_end.size(), 2u);
    std::printf("[measure] oedometer: e %.5f at %.2f kPa, %.5f at %.2f kPa; %d steps in equilibrium\n",
                e_end[0], top_end[0], e_end[1], top_end[1], in_equilibrium);
    EXPECT_NEAR(top_end[0], 25, 1.25);
    EXPECT_NEAR(top_end[1], 50, 2.5);
    EXPECT_LT(e_end[1], e_end[0]) << "the larger load compresses the specimen";
    EXPECT_EQ(od["steps_in_equilibrium"], std::to_string(in_equilibrium));
    EXPECT_NE(slurp(p("oed_out/summary.txt")).find("compression_index_cc"), std::string::npos);
    for (const char* png : {"e_log_sigma.png", "k0.png", "settlement.png"})
      EXPECT_GT(simsols::plot::read_png(p("oed_out") / png).width, 0) << png;
  }

  void check_screenshots() {
    // the screenshots: the panel and the beads in the viewport
    for (const char* shot : {"tri.png", "oed.png"}) {
      const simsols::plot::Image img = simsols::plot::read_png(p(shot).string());
      ASSERT_EQ(img.width, 1000) << shot;
      ASSERT_EQ(img.height, 640) << shot;
      const long n = coloured_viewport_pixels(img);
      std::printf("[measure] %s: %ld coloured pixels in the viewport\n", shot, n);
      // the specimen covers about 60 x 200 pixels of the 570 x 640 viewport
      EXPECT_GT(n, 2000) << shot << ": beads visible";
    }
  }

  fs::path d;
};

TEST_F(LabApparatus, TriaxialAndOedometerOperatedExportedAndCheckpointed) {
  const auto t0 = std::chrono::steady_clock::now();
  std::ofstream(p("one.txt"))
      << "apparatus triaxial\nstate " << p("default.state").string() << "\n"
      << "open " << p("tri.toml").string() << "\nprepare\nload 100\nstate "
      << p("consolidated.state").string() << "\nstart\nrows 3\ncheckpoint "
      << p("tri.bin").string() << "\nstate " << p("a.state").string()
      << "\nset_rate 1\nrows 6\nstate " << p("b.state").string() << "\nview opaque\nscreenshot "
      << p("tri.png").string() << "\nexport " << p("tri_out").string() << "\nview chains\n"
      << "open " << p("oed.toml").string() << "\nprepare\nstart\nstate "
      << p("oed_start.state").string() << "\nfinish\nstate " << p("oed_done.state").string()
      << "\nscreenshot " << p("oed.png").string() << "\nexport " << p("oed_out").string() << "\n";
  std::ofstream(p("two.txt")) << "load_checkpoint " << p("tri.bin").string() << "\nframes 2\nstate "
                              << p("a2.state").string() << "\nset_rate 1\nrows 6\nstate "
                              << p("b2.state").string() << "\n";
  ASSERT_EQ(run(lab(p("one.txt")), p("one.log")), 0) << slurp(p("one.log"));
  const double one_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(run(lab(p("two.txt")), p("two.log")), 0) << slurp(p("two.log"));
  const double all_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[measure] session one %.1f s, both %.1f s\n", one_s, all_s);

  check_triaxial();
  check_checkpoint();
  check_oedometer();
  check_screenshots();
}

// A scene that asks a preparation opens in the lab and is prepared there as
// `simsols run` prepares it (test_preparation.cpp's soft cell grown by
// radius expansion to e = 0.85 between the given e_min and e_max): the
// friction the search chose becomes the scene's, its density.csv is in the
// lab's preparation folder, and Reset builds the grown specimen again.
TEST_F(LabApparatus, AScenePreparedToADensityOpensAndPrepares) {
  std::string text = triaxial_scene();
  text.replace(text.find("young_modulus = 6.2784e9"), 24, "young_modulus = 1e9");
  text.replace(text.find("layers = 6"), 10, "layers = 3");  // 75 beads: the lab's path, not the packing
  text.replace(text.find("seed = 2\n"), 9,
               "seed = 2\n\n[triaxial.specimen.preparation]\nexpansion = true\nvoid_ratio = 0.85\n"
               "e_min = 0.773\ne_max = 1.005\n");
  std::ofstream(p("dense.toml")) << text;
  std::ofstream(p("dense.txt")) << "open " << p("dense.toml").string() << "\nprepare\nstate "
                                << p("dense.state").string() << "\nprepare\nstate "
                                << p("again.state").string() << "\n";
  ASSERT_EQ(run(lab(p("dense.txt")), p("dense.log")), 0) << slurp(p("dense.log"));
  auto s = read_state(p("dense.state"));
  EXPECT_EQ(s["apparatus"], "triaxial");
  EXPECT_EQ(s["specimen_method"], "given") << "the grown specimen is the scene's";
  EXPECT_GE(num(s, "preparation_friction"), 0.0);
  EXPECT_LE(num(s, "preparation_friction"), 1.0);
  EXPECT_TRUE(fs::exists(fs::path(s["preparation_dir"]) / "density.csv")) << s["preparation_dir"];
  auto again = read_state(p("again.state"));
  EXPECT_EQ(again["hash"], s["hash"]) << "Reset builds the same specimen";
  fs::remove_all(s["preparation_dir"]);
}

// The cell is chosen in the lab (choose cell membrane) and applies at the
// next prepare: the prepared scene has the membrane's beads beside the
// specimen's (the membrane programme held at sigma3 as the lab holds it is
// test_membrane_cell.cpp's); a choice the apparatus has not, or an option
// it does not offer, is refused by name.
TEST_F(LabApparatus, TheTriaxialCellIsChosenAndBuiltAtTheNextPrepare) {
  std::ofstream(p("cell.txt")) << "open " << p("tri.toml").string() << "\nprepare\nstate "
                               << p("rigid.state").string() << "\nchoose cell membrane\nprepare\nstate "
                               << p("membrane.state").string() << "\n";
  ASSERT_EQ(run(lab(p("cell.txt")), p("cell.log")), 0) << slurp(p("cell.log"));
  auto r = read_state(p("rigid.state"));
  auto m = read_state(p("membrane.state"));
  EXPECT_EQ(r["cell"], "rigid");
  EXPECT_EQ(m["cell"], "membrane");
  EXPECT_GT(num(m, "beads"), num(r, "beads")) << "the membrane's beads wait above the cell";
  std::ofstream(p("badcell.txt")) << "open " << p("tri.toml").string()
                                  << "\nprepare\nchoose cell glass\n";
  EXPECT_EQ(run(lab(p("badcell.txt")), p("badcell.log")), 1);
  EXPECT_NE(slurp(p("badcell.log")).find("the cell is rigid|membrane"), std::string::npos)
      << slurp(p("badcell.log"));
  std::ofstream(p("badkey.txt")) << "open " << p("tri.toml").string() << "\nprepare\nchoose gap 1\n";
  EXPECT_EQ(run(lab(p("badkey.txt")), p("badkey.log")), 1);
  EXPECT_NE(slurp(p("badkey.log")).find("no choice 'gap'; its choices: cell (rigid|membrane)"),
            std::string::npos)
      << slurp(p("badkey.log"));
}

// A setting the apparatus has not is refused, naming it and listing none.
TEST_F(LabApparatus, AnUnknownSettingIsRefusedByName) {
  std::ofstream(p("bad.txt")) << "open " << p("oed.toml").string() << "\nprepare\nset_rate 1\n";
  EXPECT_EQ(run(lab(p("bad.txt")), p("bad.log")), 1);
  EXPECT_NE(slurp(p("bad.log")).find("the oedometer has no setting 'rate'"), std::string::npos)
      << slurp(p("bad.log"));
  std::ofstream(p("kind.txt")) << "apparatus triax\n";
  EXPECT_EQ(run(lab(p("kind.txt")), p("kind.log")), 2);
  EXPECT_NE(slurp(p("kind.log")).find("apparatus shear_box|oedometer|triaxial"), std::string::npos)
      << slurp(p("kind.log"));
}

}  // namespace
