// The ParaView series (solver/io/paraview.h): the three documents hold the
// state they were given, array by array, in VTK's appended raw layout; the
// .pvd collections index the dumps by time, and a resumed run keeps only
// the entries up to its checkpoint. (tests/app/cli/test_paraview_vtk.py
// reads a run's series back with the VTK library itself.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <regex>

#include "solver/core/simulation.h"
#include "solver/io/output.h"
#include "solver/io/paraview.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

namespace fs = std::filesystem;

// Reads the arrays of a document written by paraview.cpp.
class Vtp {
 public:
  explicit Vtp(std::string text) : text_(std::move(text)) {
    const std::string mark = "<AppendedData encoding=\"raw\">\n_";
    const size_t at = text_.find(mark);
    if (at == std::string::npos) throw std::runtime_error("no appended data");
    data_ = at + mark.size();
  }
  // The raw values of the array `name` (the first of that name).
  template <class T>
  std::vector<T> array(const std::string& name) const {
    const std::regex e("Name=\"" + name + "\" NumberOfComponents=\"[0-9]+\" format=\"appended\" offset=\"([0-9]+)\"");
    std::smatch m;
    const std::string head = text_.substr(0, data_);
    if (!std::regex_search(head, m, e)) throw std::runtime_error("no array " + name);
    const size_t at = data_ + std::stoull(m[1]);
    std::uint64_t bytes;
    std::memcpy(&bytes, text_.data() + at, sizeof bytes);
    std::vector<T> v(bytes / sizeof(T));
    std::memcpy(v.data(), text_.data() + at + sizeof bytes, bytes);
    return v;
  }
  // The value of attribute `key` of the Piece.
  long long piece(const std::string& key) const {
    std::smatch m;
    const std::string head = text_.substr(0, data_);
    if (!std::regex_search(head, m, std::regex(key + "=\"([0-9]+)\""))) throw std::runtime_error(key);
    return std::stoll(m[1]);
  }
  double time() const {
    std::smatch m;
    const std::string head = text_.substr(0, data_);
    if (!std::regex_search(head, m, std::regex("Name=\"TimeValue\"[^>]*>([^<]+)<"))) throw std::runtime_error("time");
    return std::stod(m[1]);
  }

 private:
  std::string text_;
  size_t data_ = 0;
};

// Three beads (0 and 1 the members of clump 0), a floor plane at z = 0 and
// a lid rectangle at z = 5 mm; 0 presses 1 (4 N along the line of centres,
// 3 N across it) and 2 rests on the floor with 2 N.
struct Fixture {
  Scene scene = empty_scene(Precision::Double, glass());
  ContactSample sample;
  Fixture() {
    scene.particles = {sphere(1e-3, {0, 0, 1e-3}), sphere(1e-3, {2e-3, 0, 1e-3}), sphere(0.5e-3, {5e-3, 0, 0.5e-3})};
    scene.particles[0].clump = scene.particles[1].clump = 0;
    scene.walls = {plane("floor", {0, 0, 0}, {0, 0, 1}), plane("lid", {0, 0, 5e-3}, {0, 0, -1})};
    Wall& lid = scene.walls[1];
    lid.shape = WallShape::Rectangle;
    lid.axis_u = {1, 0, 0};
    lid.half_u = 4e-3;
    lid.half_v = 3e-3;
    ParticleSnapshot& b = sample.beads;
    for (const Particle& p : scene.particles) {
      b.position.push_back(p.position);
      b.radius.push_back(p.radius);
      b.velocity.push_back({0.1, 0, 0});
      b.angular_velocity.push_back({0, 0, 5});
      b.force.push_back({0, 0, -1});
      b.material.push_back(0);
      b.contacts.push_back(1);
    }
    sample.contacts = {{0, 1, {-4, 0, 3}}, {2, -1, {0, 0, 2}}};
    sample.wall_points = {{0, 0, 0}, {1e-3, 0, 5e-3}};
  }
};

TEST(Paraview, ParticlesCarryTheirState) {
  const Fixture f;
  const Vtp v(particles_vtp(f.sample, f.scene, 0.125));
  EXPECT_EQ(v.piece("NumberOfPoints"), 3);
  EXPECT_EQ(v.piece("NumberOfVerts"), 3);
  EXPECT_EQ(v.time(), 0.125);
  EXPECT_EQ(v.array<double>("radius"), (std::vector<double>{1e-3, 1e-3, 0.5e-3}));
  EXPECT_EQ(v.array<std::int32_t>("grain"), (std::vector<std::int32_t>{0, 0, -1}));
  const std::vector<double> points = v.array<double>("Points");
  ASSERT_EQ(points.size(), 9u);
  EXPECT_EQ(points[6], 5e-3);
  EXPECT_EQ(v.array<double>("spin")[2], 5);
  EXPECT_EQ(v.array<std::int64_t>("offsets"), (std::vector<std::int64_t>{1, 2, 3}));
}

TEST(Paraview, ContactsSplitTheirForce) {
  const Fixture f;
  const Vtp v(contacts_vtp(f.sample, f.scene, 0));
  EXPECT_EQ(v.piece("NumberOfLines"), 2);
  const std::vector<double> fn = v.array<double>("normal_force"), ft = v.array<double>("tangential_force");
  ASSERT_EQ(fn.size(), 2u);
  EXPECT_NEAR(fn[0], 4, 1e-15);  // 1 pushes 0 back along -x: compression
  EXPECT_NEAR(ft[0], 3, 1e-15);
  EXPECT_NEAR(fn[1], 2, 1e-15);  // the floor pushes bead 2 up
  EXPECT_NEAR(ft[1], 0, 1e-15);
  EXPECT_EQ(v.array<std::int32_t>("wall"), (std::vector<std::int32_t>{-1, 0}));
  const std::vector<double> p = v.array<double>("Points");
  ASSERT_EQ(p.size(), 12u);
  EXPECT_EQ(p[3], 2e-3);   // the pair's line ends at bead 1's centre
  EXPECT_EQ(p[11], 0.0);   // the wall contact's at the floor under bead 2
  EXPECT_EQ(p[9], 5e-3);
}

TEST(Paraview, WallsWhereTheyAreWithTheirLoad) {
  const Fixture f;
  const Vtp v(walls_vtp(f.sample, f.scene, 0));
  EXPECT_EQ(v.piece("NumberOfPolys"), 2);
  const std::vector<double> p = v.array<double>("Points"), force = v.array<double>("force");
  ASSERT_EQ(p.size(), 24u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(p[3 * k + 2], 0.0);  // the floor's quad at z = 0
  double lo_x = 1, hi_x = -1;
  for (int k = 4; k < 8; ++k) {
    EXPECT_EQ(p[3 * k + 2], 5e-3);  // the lid where it is now, its own size about its centre
    lo_x = std::min(lo_x, p[3 * k]);
    hi_x = std::max(hi_x, p[3 * k]);
  }
  EXPECT_NEAR(lo_x, -3e-3, 1e-15);
  EXPECT_NEAR(hi_x, 5e-3, 1e-15);
  EXPECT_EQ(force[2], -2.0);  // bead 2 presses the floor down
  EXPECT_EQ(force[5], 0.0);
}

std::vector<std::string> pvd_files(const fs::path& pvd, std::vector<double>* times) {
  const std::string text = read_text(pvd.string());
  const std::regex e(R"re(timestep="([^"]+)" group="" part="0" file="([^"]+)")re");
  std::vector<std::string> files;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), e); it != std::sregex_iterator(); ++it) {
    files.push_back((*it)[2]);
    if (times) times->push_back(std::stod((*it)[1]));
  }
  return files;
}

// A bead falling onto a floor: dumps at steps 0, 10, 20; the run resumed
// from step 10 drops the entry of step 20 and adds its own.
TEST(Paraview, SeriesIndexesDumpsAndResumesFromTheCheckpoint) {
  Scene scene = empty_scene(Precision::Double, glass());
  scene.particles = {sphere(1e-3, {0, 0, 1.5e-3})};
  scene.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  Simulation sim(default_device(), scene);
  const fs::path dir = fs::path(::testing::TempDir()) / ("simsols_paraview_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  {
    ParaviewSeries series(dir);
    for (int k = 0; k < 3; ++k) {
      if (k > 0) sim.advance(10);
      series.write(sim);
    }
  }
  std::vector<double> times;
  EXPECT_EQ(pvd_files(dir / "walls.pvd", nullptr),
            (std::vector<std::string>{"walls_000000000.vtp", "walls_000000010.vtp", "walls_000000020.vtp"}));
  ASSERT_EQ(pvd_files(dir / "particles.pvd", &times).size(), 3u);
  EXPECT_EQ(times[1], 10 * sim.dt());
  EXPECT_EQ(Vtp(read_text((dir / "particles_000000020.vtp").string())).time(), sim.time());
  sim.advance(5);
  ParaviewSeries resumed(dir, 10);
  resumed.write(sim);
  EXPECT_EQ(pvd_files(dir / "contacts.pvd", nullptr),
            (std::vector<std::string>{"contacts_000000000.vtp", "contacts_000000010.vtp", "contacts_000000025.vtp"}));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace simsols::testing
