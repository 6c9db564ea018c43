#include "solver/io/output.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "solver/common/errors.h"

namespace simsols {
namespace {

std::string fmt(double v) { return format_number("%.9g", v); }

}  // namespace

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string format_number(const char* printf_format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, value);
  return buf;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.emplace_back();
    else if (c != '\r') out.back() += c;
  }
  return out;
}

void write_particles_csv(const std::string& path, const ParticleSnapshot& p) {
  std::string s = "id,material,radius_m,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,wz_rad_s,"
                  "fx_N,fy_N,fz_N,contacts\n";
  s.reserve(p.radius.size() * 200);
  for (size_t i = 0; i < p.radius.size(); ++i) {
    s += std::to_string(i) + "," + std::to_string(p.material[i]) + "," + fmt(p.radius[i]);
    for (const Vec3* v : {&p.position[i], &p.velocity[i], &p.angular_velocity[i], &p.force[i]})
      for (double c : *v) s += "," + fmt(c);
    s += "," + std::to_string(p.contacts[i]) + "\n";
  }
  write_file_atomic(path, s);
}

TimeSeries::TimeSeries(const std::string& path, const std::vector<std::string>& wall_names,
                       long long resume_step)
    : path_(path), written_(std::chrono::steady_clock::now()) {
  std::string header = "time_s,step,kinetic_energy_J,rotational_energy_J,elastic_energy_J,"
                       "gravitational_energy_J,contacts,coordination";
  for (const std::string& w : wall_names)
    for (const char* c : {"_fx_N", "_fy_N", "_fz_N", "_x_m", "_y_m", "_z_m"}) header += "," + w + c;
  text_ = header + "\n";
  if (resume_step >= 0) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      const size_t a = line.find(',');
      const size_t b = line.find(',', a + 1);
      if (a == std::string::npos || b == std::string::npos) break;
      if (std::stoll(line.substr(a + 1, b - a - 1)) > resume_step) break;
      text_ += line + "\n";
    }
  }
  flush();
}

TimeSeries::~TimeSeries() {
  try {
    if (dirty_) flush();
  } catch (...) {  // a destructor must not throw; the last flush() reported it
  }
}

void TimeSeries::flush() {
  write_file_atomic(path_, text_);
  dirty_ = false;
  written_ = std::chrono::steady_clock::now();
}

void TimeSeries::append(double time, long long step, const Observables& o,
                        const std::vector<WallReaction>& walls,
                        const std::vector<Vec3>& wall_points) {
  // o.contacts counts each pair twice and each wall contact once
  int wall_contacts = 0;
  for (const WallReaction& w : walls) wall_contacts += w.contacts;
  const double pair_contacts = 0.5 * (o.contacts - wall_contacts);
  std::string s = fmt(time) + "," + std::to_string(step) + "," + fmt(o.kinetic_translational) + "," +
                  fmt(o.kinetic_rotational) + "," + fmt(o.elastic_energy) + "," +
                  fmt(o.gravitational_energy) + "," + fmt(pair_contacts + wall_contacts) + "," +
                  fmt(o.contacts / std::max(1.0, o.particles));
  for (size_t w = 0; w < walls.size(); ++w) {
    for (double c : walls[w].force) s += "," + fmt(c);
    for (double c : wall_points[w]) s += "," + fmt(c);
  }
  text_ += s + "\n";
  dirty_ = true;
  const double since =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - written_).count();
  if (since > 10) flush();
}

}  // namespace simsols
