#include "solver/io/paraview.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <regex>
#include <sstream>

#include "solver/common/atomic_file.h"
#include "solver/common/vec3.h"
#include "solver/core/simulation.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

constexpr const char* kByteOrder = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
constexpr const char* kKinds[] = {"particles", "walls", "contacts"};

// One data array: its VTK type, components and raw bytes.
struct Array {
  std::string name, type;
  int components = 1;
  std::string bytes;
};

template <class T>
void put(std::string& b, T v) {
  b.append(reinterpret_cast<const char*>(&v), sizeof v);
}

Array vec3s(const char* name, const std::vector<Vec3>& v) {
  Array a{name, "Float64", 3, {}};
  for (const Vec3& x : v)
    for (double c : x) put(a.bytes, c);
  return a;
}

Array doubles(const char* name, const std::vector<double>& v) {
  Array a{name, "Float64", 1, {}};
  for (double x : v) put(a.bytes, x);
  return a;
}

Array ints(const char* name, const std::vector<int>& v) {
  Array a{name, "Int32", 1, {}};
  for (int x : v) put(a.bytes, static_cast<std::int32_t>(x));
  return a;
}

// Cells of `corners` points each, numbered in order: connectivity, offsets.
std::pair<Array, Array> cells(long long count, int corners) {
  Array connectivity{"connectivity", "Int64", 1, {}}, offsets{"offsets", "Int64", 1, {}};
  for (long long c = 0; c < count; ++c) {
    for (int k = 0; k < corners; ++k) put(connectivity.bytes, static_cast<std::int64_t>(c * corners + k));
    put(offsets.bytes, static_cast<std::int64_t>((c + 1) * corners));
  }
  return {connectivity, offsets};
}

// A PolyData piece of one kind of cell ("Verts", "Lines" or "Polys").
struct Piece {
  std::vector<Vec3> points;
  const char* topology = "Verts";
  int corners = 1;
  std::vector<Array> point_data, cell_data;
};

std::string number(double v) { return format_number("%.17g", v); }

std::string document(const Piece& p, double time) {
  std::string blob;
  const auto element = [&](const Array& a) {
    std::ostringstream e;
    e << "        <DataArray type=\"" << a.type << "\" Name=\"" << a.name << "\" NumberOfComponents=\""
      << a.components << "\" format=\"appended\" offset=\"" << blob.size() << "\"/>\n";
    put(blob, static_cast<std::uint64_t>(a.bytes.size()));
    blob += a.bytes;
    return e.str();
  };
  const long long n_cells = static_cast<long long>(p.points.size()) / p.corners;
  std::ostringstream x;
  x << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"" << kByteOrder
    << "\" header_type=\"UInt64\">\n  <PolyData>\n    <FieldData>\n"
    << "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">"
    << number(time) << "</DataArray>\n    </FieldData>\n";
  x << "    <Piece NumberOfPoints=\"" << p.points.size() << "\"";
  for (const char* t : {"Verts", "Lines", "Strips", "Polys"})
    x << " NumberOf" << t << "=\"" << (std::string(t) == p.topology ? n_cells : 0) << "\"";
  x << ">\n      <PointData>\n";
  for (const Array& a : p.point_data) x << element(a);
  x << "      </PointData>\n      <CellData>\n";
  for (const Array& a : p.cell_data) x << element(a);
  x << "      </CellData>\n      <Points>\n" << element(vec3s("Points", p.points)) << "      </Points>\n";
  const auto [connectivity, offsets] = cells(n_cells, p.corners);
  x << "      <" << p.topology << ">\n" << element(connectivity) << element(offsets) << "      </"
    << p.topology << ">\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n_";
  return x.str() + blob + "\n  </AppendedData>\n</VTKFile>\n";
}

Vec3 add(const Vec3& a, const Vec3& b, double s = 1) { return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; }
Vec3 unit(const Vec3& a) {
  const double l = norm(a);
  return l > 0 ? scale(1 / l, a) : Vec3{0, 0, 0};
}

// The beads' bounding box: its centre and half its diagonal (1 cm without beads).
std::pair<Vec3, double> bead_bounds(const ParticleSnapshot& b) {
  if (b.position.empty()) return {Vec3{0, 0, 0}, 0.01};
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i < b.position.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], b.position[i][k] - b.radius[i]);
      hi[k] = std::max(hi[k], b.position[i][k] + b.radius[i]);
    }
  const Vec3 centre = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
  const Vec3 half = add(hi, centre, -1);
  return {centre, std::sqrt(dot(half, half))};
}

// The quad drawn for wall w at `point`: a rectangle whole, a plane over the beads.
std::array<Vec3, 4> wall_quad(const Wall& w, const Vec3& point, const ParticleSnapshot& beads) {
  Vec3 centre = point, u = w.axis_u, v;
  double hu = w.half_u, hv = w.half_v;
  if (w.shape != WallShape::Rectangle) {
    const auto [c, reach] = bead_bounds(beads);
    centre = add(c, w.normal, -dot(add(c, point, -1), w.normal));
    u = unit(cross(w.normal, std::abs(w.normal[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    hu = hv = 1.2 * reach;
  }
  v = cross(w.normal, u);
  return {add(add(centre, u, -hu), v, -hv), add(add(centre, u, hu), v, -hv), add(add(centre, u, hu), v, hv),
          add(add(centre, u, -hu), v, hv)};
}

}  // namespace

std::string particles_vtp(const ContactSample& sample, const Scene& scene, double time) {
  const ParticleSnapshot& b = sample.beads;
  Piece p;
  p.points = b.position;
  std::vector<int> grain(b.position.size(), -1);
  for (size_t i = 0; i < grain.size() && i < scene.particles.size(); ++i) grain[i] = scene.particles[i].clump;
  p.point_data = {doubles("radius", b.radius), vec3s("velocity", b.velocity),
                  vec3s("spin", b.angular_velocity), vec3s("force", b.force),
                  ints("contacts", b.contacts),     ints("material", b.material),
                  ints("grain", grain)};
  return document(p, time);
}

std::string walls_vtp(const ContactSample& sample, const Scene& scene, double time) {
  Piece p;
  p.topology = "Polys";
  p.corners = 4;
  const size_t n = scene.walls.size();
  std::vector<Vec3> normal(n), force(n, Vec3{0, 0, 0});
  std::vector<int> index(n);
  for (const ContactForce& c : sample.contacts)
    if (c.b < 0 && size_t(-1 - c.b) < n) force[-1 - c.b] = add(force[-1 - c.b], c.force, -1);
  for (size_t w = 0; w < n; ++w) {
    const Vec3 at = w < sample.wall_points.size() ? sample.wall_points[w] : scene.walls[w].point;
    const Wall& now = w < sample.walls.size() ? sample.walls[w] : scene.walls[w];
    for (const Vec3& q : wall_quad(now, at, sample.beads)) p.points.push_back(q);
    normal[w] = now.normal;
    index[w] = static_cast<int>(w);
  }
  p.cell_data = {ints("wall", index), vec3s("normal", normal), vec3s("force", force)};
  return document(p, time);
}

std::string contacts_vtp(const ContactSample& sample, const Scene& scene, double time) {
  Piece p;
  p.topology = "Lines";
  p.corners = 2;
  const ParticleSnapshot& b = sample.beads;
  std::vector<Vec3> force;
  std::vector<double> normal_force, tangential_force;
  std::vector<int> wall, bead_a, bead_b;
  for (const ContactForce& c : sample.contacts) {
    const Vec3& a = b.position[c.a];
    Vec3 other;
    if (c.b >= 0) {
      other = b.position[c.b];
    } else {
      const size_t w = size_t(-1 - c.b);
      other = wall_closest_point(w < sample.walls.size() ? sample.walls[w] : scene.walls[w],
                                 sample.wall_points[w], a);
    }
    Vec3 n = unit(add(other, a, -1));  // from the first bead towards what it touches
    if (dot(n, n) == 0 && c.b < 0) n = add(Vec3{0, 0, 0}, scene.walls[-1 - c.b].normal, -1);
    const double fn = dot(c.force, n);
    p.points.push_back(a);
    p.points.push_back(other);
    force.push_back(c.force);
    normal_force.push_back(-fn);  // the force on the first bead points away from what presses it
    const Vec3 t = add(c.force, n, -fn);
    tangential_force.push_back(std::sqrt(dot(t, t)));
    wall.push_back(c.b < 0 ? -1 - c.b : -1);
    bead_a.push_back(c.a);
    bead_b.push_back(c.b);
  }
  p.cell_data = {vec3s("force", force), doubles("normal_force", normal_force),
                 doubles("tangential_force", tangential_force), ints("wall", wall), ints("bead_a", bead_a),
                 ints("bead_b", bead_b)};
  return document(p, time);
}

namespace {

std::string step_file(const char* kind, long long step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%09lld.vtp", kind, step);
  return buf;
}

}  // namespace

ParaviewSeries::ParaviewSeries(std::filesystem::path dir, long long resume_step) : dir_(std::move(dir)) {
  std::filesystem::create_directories(dir_);
  if (resume_step < 0) return;
  std::istringstream in(read_text((dir_ / "particles.pvd").string()));
  const std::regex entry(R"re(timestep="([^"]+)".*file="particles_([0-9]+)\.vtp")re");
  std::string line;
  std::smatch m;
  while (std::getline(in, line))
    if (std::regex_search(line, m, entry) && std::stoll(m[2]) <= resume_step)
      entries_.push_back({std::stod(m[1]), std::stoll(m[2])});
}

void ParaviewSeries::write(Simulation& sim) {
  const ContactSample sample = sample_contacts(sim);
  const Scene& scene = sim.scene();
  const long long step = sim.steps();
  const double t = sim.time();
  write_file_atomic((dir_ / step_file("particles", step)).string(), particles_vtp(sample, scene, t));
  write_file_atomic((dir_ / step_file("walls", step)).string(), walls_vtp(sample, scene, t));
  write_file_atomic((dir_ / step_file("contacts", step)).string(), contacts_vtp(sample, scene, t));
  while (!entries_.empty() && entries_.back().step >= step) entries_.pop_back();
  entries_.push_back({t, step});
  write_collections();
}

void ParaviewSeries::write_collections() const {
  for (const char* kind : kKinds) {
    std::ostringstream x;
    x << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"" << kByteOrder
      << "\">\n  <Collection>\n";
    for (const Entry& e : entries_)
      x << "    <DataSet timestep=\"" << number(e.time) << "\" group=\"\" part=\"0\" file=\""
        << step_file(kind, e.step) << "\"/>\n";
    x << "  </Collection>\n</VTKFile>\n";
    write_file_atomic((dir_ / (std::string(kind) + ".pvd")).string(), x.str());
  }
}

}  // namespace simsols
