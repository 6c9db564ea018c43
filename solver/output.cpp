#include "output.h"

#include <bit>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "errors.h"

namespace simsols {
namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// Legacy VTK binary data is big endian.
void put_be(std::string& out, float v) {
  std::uint32_t u = std::bit_cast<std::uint32_t>(v);
  if constexpr (std::endian::native == std::endian::little) u = __builtin_bswap32(u);
  out.append(reinterpret_cast<const char*>(&u), 4);
}
void put_be(std::string& out, std::int32_t v) {
  std::uint32_t u = static_cast<std::uint32_t>(v);
  if constexpr (std::endian::native == std::endian::little) u = __builtin_bswap32(u);
  out.append(reinterpret_cast<const char*>(&u), 4);
}

}  // namespace

void write_file_atomic(const std::string& path, const std::string& content) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw DeviceError("cannot write " + tmp);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    if (!out) throw DeviceError("failed writing " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

void write_particles_csv(const std::string& path, const ParticleSnapshot& p) {
  std::string s = "id,material,radius,x,y,z,vx,vy,vz,wx,wy,wz,fx,fy,fz,contacts\n";
  s.reserve(p.radius.size() * 200);
  for (size_t i = 0; i < p.radius.size(); ++i) {
    s += std::to_string(i) + "," + std::to_string(p.material[i]) + "," + fmt(p.radius[i]);
    for (const Vec3* v : {&p.position[i], &p.velocity[i], &p.angular_velocity[i], &p.force[i]})
      for (double c : *v) s += "," + fmt(c);
    s += "," + std::to_string(p.contacts[i]) + "\n";
  }
  write_file_atomic(path, s);
}

void write_particles_vtk(const std::string& path, const ParticleSnapshot& p, double time) {
  const size_t n = p.radius.size();
  std::string s = "# vtk DataFile Version 3.0\nSimSols particles t=" + fmt(time) +
                  "\nBINARY\nDATASET POLYDATA\nPOINTS " + std::to_string(n) + " float\n";
  for (size_t i = 0; i < n; ++i)
    for (double c : p.position[i]) put_be(s, static_cast<float>(c));
  s += "\nVERTICES " + std::to_string(n) + " " + std::to_string(2 * n) + "\n";
  for (size_t i = 0; i < n; ++i) {
    put_be(s, std::int32_t{1});
    put_be(s, static_cast<std::int32_t>(i));
  }
  s += "\nPOINT_DATA " + std::to_string(n) + "\n";
  s += "SCALARS radius float 1\nLOOKUP_TABLE default\n";
  for (size_t i = 0; i < n; ++i) put_be(s, static_cast<float>(p.radius[i]));
  auto vectors = [&](const char* name, const std::vector<Vec3>& v) {
    s += std::string("\nVECTORS ") + name + " float\n";
    for (size_t i = 0; i < n; ++i)
      for (double c : v[i]) put_be(s, static_cast<float>(c));
  };
  vectors("velocity", p.velocity);
  vectors("angular_velocity", p.angular_velocity);
  vectors("force", p.force);
  auto ints = [&](const char* name, const std::vector<int>& v) {
    s += std::string("\nSCALARS ") + name + " int 1\nLOOKUP_TABLE default\n";
    for (size_t i = 0; i < n; ++i) put_be(s, static_cast<std::int32_t>(v[i]));
  };
  ints("contacts", p.contacts);
  ints("material", p.material);
  s += "\n";
  write_file_atomic(path, s);
}

TimeSeries::TimeSeries(const std::string& path, const std::vector<std::string>& wall_names,
                       long long resume_step) {
  std::string header = "time,step,kinetic_energy,rotational_energy,elastic_energy,"
                       "gravitational_energy,contacts,coordination";
  for (const std::string& w : wall_names)
    for (const char* c : {"_fx", "_fy", "_fz", "_x", "_y", "_z"}) header += "," + w + c;
  std::string keep = header + "\n";
  if (resume_step >= 0) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      const size_t a = line.find(',');
      const size_t b = line.find(',', a + 1);
      if (a == std::string::npos || b == std::string::npos) break;
      if (std::stoll(line.substr(a + 1, b - a - 1)) > resume_step) break;
      keep += line + "\n";
    }
  }
  write_file_atomic(path, keep);
  out_.open(path, std::ios::app);
  if (!out_) throw DeviceError("cannot append to " + path);
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
  out_ << s << "\n";
  out_.flush();
}

}  // namespace simsols
