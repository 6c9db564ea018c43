// Files a run leaves (solver/io/output.h): the particle CSV
// as documented, series.csv's rows and resume, and writes that are atomic.
// No device: snapshots and observables are built by hand.
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <sstream>

#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test.
class Output : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("simsols_output_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Names in the folder (a temporary file left behind shows here).
  std::vector<std::string> listing() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }
  fs::path dir_;
};

// Three beads: values a 9-digit print holds exactly, values it must round
// (pi, 1/3), float values (as a float run downloads them), signs and
// magnitudes from 1e-300 to 1e300.
ParticleSnapshot sample_snapshot() {
  ParticleSnapshot p;
  const double third = 1.0 / 3.0, pi = std::numbers::pi;
  const double f = static_cast<float>(0.1), g = static_cast<float>(2.38e-3 / 3);
  p.position = {{0.00125, -3.5, 2e-5}, {pi * 1e-3, -third, 1e300}, {f, g, -f}};
  p.velocity = {{0, -0, 1.5}, {-1e-300, 7.25e-7, pi}, {g, f, 123456789}};
  p.angular_velocity = {{10, -20, 30.5}, {third * 1e5, -pi, 0.1}, {-g, -f, 1e-9}};
  p.force = {{-0.5, 0.25, 9.81}, {pi * 1e6, -third * 1e-6, 1e-200}, {f * 1e3, g, -g}};
  p.radius = {1e-3, 0.8e-3, g};
  p.material = {0, 1, 7};
  p.contacts = {0, 3, 12};
  return p;
}

// A printed field's value: within half a unit of the 9th significant digit.
void expect_printed(const std::string& field, double value, const std::string& what) {
  const double back = std::stod(field);
  EXPECT_LE(std::fabs(back - value), 5.0000001e-9 * std::fabs(value)) << what << ": " << field;
  if (value == static_cast<float>(value)) {  // a float survives 9 digits exactly
    EXPECT_EQ(static_cast<float>(back), static_cast<float>(value)) << what << ": " << field;
  }
}

TEST_F(Output, ParticlesCsvAsDocumented) {
  const ParticleSnapshot p = sample_snapshot();
  write_particles_csv(path("particles_0.csv"), p);
  std::istringstream in(read_text(path("particles_0.csv")));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "id,material,radius_m,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,wz_rad_s,"
            "fx_N,fy_N,fz_N,contacts");
  for (size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(std::getline(in, line));
    const std::vector<std::string> f = split_csv_line(line);
    ASSERT_EQ(f.size(), 16u) << line;
    EXPECT_EQ(f[0], std::to_string(i));
    EXPECT_EQ(f[1], std::to_string(p.material[i]));
    EXPECT_EQ(f[15], std::to_string(p.contacts[i]));
    expect_printed(f[2], p.radius[i], "radius");
    const std::vector<Vec3>* vectors[] = {&p.position, &p.velocity, &p.angular_velocity, &p.force};
    for (int v = 0; v < 4; ++v)
      for (int c = 0; c < 3; ++c) expect_printed(f[3 + 3 * v + c], (*vectors[v])[i][c], line);
  }
  EXPECT_FALSE(std::getline(in, line)) << "one row per particle";
  // the exactly printable ones read back exactly
  EXPECT_NE(read_text(path("particles_0.csv")).find("\n0,0,0.001,0.00125,-3.5,2e-05,"),
            std::string::npos);
}

// Bytes as given (NUL, CR LF, no trailing newline), replacing the old file,
// and no temporary file left.
TEST_F(Output, AtomicWriteReplacesWhole) {
  const std::string target = path("series.csv");
  const std::string first("old\r\ncontent\0with a NUL", 24), second = "new";
  write_file_atomic(target, first);
  EXPECT_EQ(read_text(target), first);
  write_file_atomic(target, second);
  EXPECT_EQ(read_text(target), second);
  EXPECT_EQ(listing(), std::vector<std::string>{"series.csv"});
}

// Writing fails before anything is renamed: the existing file keeps its
// content, and the error names the file.
TEST_F(Output, FailedWriteKeepsTheOldFile) {
  const std::string target = path("particles_0.csv");
  write_file_atomic(target, "old");
  fs::create_directory(target + ".tmp");  // the temporary name cannot be opened
  try {
    write_file_atomic(target, "new");
    ADD_FAILURE() << "the write did not fail";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(target + ".tmp"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_text(target), "old");
  // a folder that does not exist
  EXPECT_THROW(write_file_atomic(path("missing/particles_0.csv"), "new"), IoError);
  EXPECT_EQ(listing(), (std::vector<std::string>{"particles_0.csv", "particles_0.csv.tmp"}));
}

// The disk fills up while writing (a file size limit stands in for it): the
// old file stays, the partial temporary file is removed.
TEST_F(Output, DiskFullKeepsTheOldFileAndLeavesNoTemporary) {
  const std::string target = path("series.csv");
  write_file_atomic(target, "old");
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit small = saved;
  small.rlim_cur = 4096;
  void (*previous)(int) = signal(SIGXFSZ, SIG_IGN);  // a write past the limit fails instead
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  bool threw = false;
  try {
    write_file_atomic(target, std::string(1 << 20, 'x'));
  } catch (const IoError& e) {
    threw = true;
    EXPECT_NE(std::string(e.what()).find("disk full"), std::string::npos) << e.what();
  }
  setrlimit(RLIMIT_FSIZE, &saved);
  signal(SIGXFSZ, previous);
  EXPECT_TRUE(threw);
  EXPECT_EQ(read_text(target), "old");
  EXPECT_EQ(listing(), std::vector<std::string>{"series.csv"});
}

TEST_F(Output, TextHelpers) {
  EXPECT_EQ(format_number("%.3f", 2.0), "2.000");
  EXPECT_EQ(format_number("%g", 1.5e-7), "1.5e-07");
  EXPECT_EQ(split_csv_line("a,\"b,c\",,d\r"), (std::vector<std::string>{"a", "b,c", "", "d"}));
  EXPECT_EQ(split_csv_line(""), std::vector<std::string>{""});
  EXPECT_EQ(read_text(path("none.csv")), "") << "a file that cannot be read";
}

Observables sample_observables(double contacts, double particles) {
  Observables o;
  o.kinetic_translational = 1.25e-6;
  o.kinetic_rotational = 1.0 / 3.0;
  o.elastic_energy = 2e-9;
  o.gravitational_energy = -0.5;
  o.contacts = contacts;
  o.particles = particles;
  return o;
}

// One row per call, in memory until flushed: pair contacts are counted
// once (o.contacts counts them twice, wall contacts once).
TEST_F(Output, SeriesRowsHeaderAndFlush) {
  const std::string file = path("series.csv");
  const std::string header =
      "time_s,step,kinetic_energy_J,rotational_energy_J,elastic_energy_J,"
      "gravitational_energy_J,contacts,coordination,lid_fx_N,lid_fy_N,lid_fz_N,lid_x_m,lid_y_m,"
      "lid_z_m\n";
  {
    TimeSeries series(file, {"lid"});
    EXPECT_EQ(read_text(file), header) << "a new file starts with its header";
    WallReaction lid;
    lid.force = {0.5, -0.25, 1e-3};
    lid.contacts = 3;
    // 3 wall contacts + 4 pairs (8 in o.contacts): 7 contacts, 11 / 4 per bead
    series.append(1.5e-4, 250, sample_observables(11, 4), {lid}, {{0.01, 0.02, 0.0125}});
    EXPECT_EQ(read_text(file), header) << "rows are kept in memory";
    series.flush();
    EXPECT_EQ(read_text(file),
              header + "0.00015,250,1.25e-06,0.333333333,2e-09,-0.5,7,2.75,0.5,-0.25,0.001,0.01,"
                       "0.02,0.0125\n");
    series.append(3e-4, 500, sample_observables(0, 0), {WallReaction{}}, {{0, 0, 0}});
  }  // the destructor writes the row not yet written
  const std::string text = read_text(file);
  EXPECT_NE(text.find("\n0.0003,500,1.25e-06,0.333333333,2e-09,-0.5,0,0,0,0,0,0,0,0\n"),
            std::string::npos)
      << text;
  EXPECT_EQ(listing(), std::vector<std::string>{"series.csv"});
}

// The steps of series.csv's rows.
std::vector<long long> series_steps(const std::string& file) {
  std::istringstream in(read_text(file));
  std::string line;
  std::getline(in, line);  // header
  std::vector<long long> steps;
  while (std::getline(in, line)) steps.push_back(std::stoll(split_csv_line(line).at(1)));
  return steps;
}

// A resumed run keeps the rows up to its checkpoint's step, at once, and
// drops the later ones (the run repeats them); a new run starts afresh.
TEST_F(Output, SeriesResumeKeepsRowsUpToTheStep) {
  const std::string file = path("series.csv");
  {
    TimeSeries series(file, {});
    for (long long step : {0, 100, 200, 300})
      series.append(1e-6 * double(step), step, sample_observables(2, 2), {}, {});
  }
  ASSERT_EQ(series_steps(file), (std::vector<long long>{0, 100, 200, 300}));
  {
    TimeSeries resumed(file, {}, 200);
    EXPECT_EQ(series_steps(file), (std::vector<long long>{0, 100, 200}));
    resumed.append(3e-4, 300, sample_observables(2, 2), {}, {});
    resumed.append(4e-4, 400, sample_observables(2, 2), {}, {});
  }
  EXPECT_EQ(series_steps(file), (std::vector<long long>{0, 100, 200, 300, 400}));
  { TimeSeries fresh(file, {}); }
  EXPECT_EQ(series_steps(file), std::vector<long long>{});
}

// The destructor's last write may fail (the folder is gone): it reports
// nothing and does not throw (a throw would terminate the test).
TEST_F(Output, SeriesDestructorIgnoresAFailedWrite) {
  auto series = std::make_unique<TimeSeries>(path("series.csv"), std::vector<std::string>{});
  series->append(0, 0, sample_observables(0, 1), {}, {});
  fs::remove_all(dir_);
  series.reset();
  EXPECT_FALSE(fs::exists(dir_));
}

// The rename itself fails (the target is a folder): nothing is left under
// the temporary name, and the failure is an IoError like the others.
TEST_F(Output, FailedRenameLeavesNoTemporary) {
  const std::string target = path("particles_0.csv");
  fs::create_directories(target + "/inside");
  EXPECT_THROW(write_file_atomic(target, "new"), IoError);
  EXPECT_EQ(listing(), std::vector<std::string>{"particles_0.csv"});
}
}  // namespace
}  // namespace simsols::testing
