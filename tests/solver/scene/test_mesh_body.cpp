// Surface meshes (solver/scene/mesh_body.h): read from STL (ASCII, binary)
// and OBJ files the test writes, their volume against closed forms, and
// their voxel bodies against that volume.
//
// The test meshes have whole-number corners, which every format and
// Assimp's single-precision reading keep exactly, so the enclosed volume is
// exact to round-off: a cube of side 2 (8), the regular tetrahedron with
// corners (+-1, +-1, +-1), an even number of minus signs (8/3), the
// octahedron with corners on the axes at +-1 (4/3). A voxel body's volume
// is off by the cells cut by the surface, about (surface area) x (cell) x
// (a fraction that averages out), so its error falls as the cells shrink;
// the tolerances below are about ten times the errors measured
// (listed above VoxelVolumeConverges).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "solver/scene/mesh_body.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

// A folder of its own under the system's temporary folder, removed at the end.
class TempFolder {
 public:
  TempFolder() {
    const auto tick = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = fs::temp_directory_path() / ("simsols_mesh_body_" + std::to_string(tick));
    fs::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

// Flips the triangles of a convex mesh that face its centre.
SurfaceMesh oriented_outward(SurfaceMesh mesh) {
  Vec3 centre{};
  for (const Vec3& v : mesh.vertices) centre = {centre[0] + v[0], centre[1] + v[1], centre[2] + v[2]};
  centre = scale(1.0 / static_cast<double>(mesh.vertices.size()), centre);
  for (auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    if (dot(cross(sub(b, a), sub(c, a)), sub(a, centre)) < 0) std::swap(t[1], t[2]);
  }
  return mesh;
}

// The cube [lo, lo + side]^3 as six quads, counter-clockwise from outside;
// corner x + 2 y + 4 z.
std::vector<std::array<int, 4>> cube_quads() {
  return {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
}
SurfaceMesh cube(const Vec3& lo, double side) {
  SurfaceMesh mesh;
  for (int n = 0; n < 8; ++n) {
    mesh.vertices.push_back(
        {lo[0] + side * (n & 1), lo[1] + side * ((n >> 1) & 1), lo[2] + side * ((n >> 2) & 1)});
  }
  for (const auto& q : cube_quads()) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}
SurfaceMesh tetrahedron() {
  return oriented_outward(
      {{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}, {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}});
}
SurfaceMesh octahedron() {
  SurfaceMesh mesh{{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}, {}};
  for (int x : {0, 1})
    for (int y : {2, 3})
      for (int z : {4, 5}) mesh.triangles.push_back({x, y, z});
  return oriented_outward(mesh);
}
// An icosahedron's faces split `levels` times into four, corners pushed onto the unit sphere.
SurfaceMesh icosphere(int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  SurfaceMesh mesh{{{-1, g, 0},
                    {1, g, 0},
                    {-1, -g, 0},
                    {1, -g, 0},
                    {0, -1, g},
                    {0, 1, g},
                    {0, -1, -g},
                    {0, 1, -g},
                    {g, 0, -1},
                    {g, 0, 1},
                    {-g, 0, -1},
                    {-g, 0, 1}},
                   {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                    {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}}};
  for (Vec3& v : mesh.vertices) v = scale(1 / norm(v), v);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto found = middle.find(key);
      if (found != middle.end()) return found->second;
      const Vec3& p = mesh.vertices[a];
      const Vec3& q = mesh.vertices[b];
      const Vec3 m{p[0] + q[0], p[1] + q[1], p[2] + q[2]};
      mesh.vertices.push_back(scale(1 / norm(m), m));
      return middle[key] = static_cast<int>(mesh.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& t : mesh.triangles) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    mesh.triangles = std::move(finer);
  }
  return oriented_outward(mesh);
}

// --- writers --------------------------------------------------------------

Vec3 normal_of(const SurfaceMesh& m, const std::array<int, 3>& t) {
  const Vec3 n = cross(sub(m.vertices[t[1]], m.vertices[t[0]]), sub(m.vertices[t[2]], m.vertices[t[0]]));
  return scale(1 / norm(n), n);
}
void write_ascii_stl(const std::string& path, const SurfaceMesh& m) {
  std::ofstream out(path);
  out.precision(17);
  out << "solid test\n";
  for (const auto& t : m.triangles) {
    const Vec3 n = normal_of(m, t);
    out << " facet normal " << n[0] << ' ' << n[1] << ' ' << n[2] << "\n  outer loop\n";
    for (int v : t)
      out << "   vertex " << m.vertices[v][0] << ' ' << m.vertices[v][1] << ' ' << m.vertices[v][2] << '\n';
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid test\n";
}
void write_binary_stl(const std::string& path, const SurfaceMesh& m) {
  std::ofstream out(path, std::ios::binary);
  std::string header = "binary STL written by test_mesh_body";
  header.resize(80, ' ');
  out.write(header.data(), 80);
  const auto count = static_cast<std::uint32_t>(m.triangles.size());
  out.write(reinterpret_cast<const char*>(&count), 4);
  const auto put = [&out](const Vec3& v) {
    for (double x : v) {
      const auto f = static_cast<float>(x);
      out.write(reinterpret_cast<const char*>(&f), 4);
    }
  };
  for (const auto& t : m.triangles) {
    put(normal_of(m, t));
    for (int v : t) put(m.vertices[v]);
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char*>(&attributes), 2);
  }
}
void write_obj(const std::string& path, const SurfaceMesh& m) {
  std::ofstream out(path);
  out.precision(17);
  for (const Vec3& v : m.vertices) out << "v " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
  for (const auto& t : m.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

double relative_error(double value, double exact) { return std::abs(value - exact) / exact; }

TEST(MeshBody, ReadsAsciiStlBinaryStlAndObj) {
  const TempFolder folder;
  struct Case {
    const char* name;
    SurfaceMesh mesh;
    double volume;
  };
  const std::vector<Case> cases = {{"cube", cube({1, 2, 3}, 2), 8}, {"tetrahedron", tetrahedron(), 8.0 / 3}};
  for (const Case& c : cases) {
    const std::string ascii = folder.file(std::string(c.name) + "_ascii.stl");
    const std::string binary = folder.file(std::string(c.name) + "_binary.stl");
    const std::string obj = folder.file(std::string(c.name) + ".obj");
    write_ascii_stl(ascii, c.mesh);
    write_binary_stl(binary, c.mesh);
    write_obj(obj, c.mesh);
    for (const std::string& path : {ascii, binary, obj}) {
      SCOPED_TRACE(path);
      const SurfaceMesh read = load_surface_mesh(path);
      EXPECT_EQ(read.triangles.size(), c.mesh.triangles.size());
      EXPECT_EQ(read.vertices.size(), c.mesh.vertices.size());  // an STL's corners joined
      EXPECT_NEAR(enclosed_volume(read), c.volume, 1e-12 * c.volume);
      const Box3 box = bounding_box(read);
      const Box3 expected = bounding_box(c.mesh);
      for (int d = 0; d < 3; ++d) {
        EXPECT_EQ(box.lo[d], expected.lo[d]);
        EXPECT_EQ(box.hi[d], expected.hi[d]);
      }
    }
  }
}

TEST(MeshBody, ObjQuadsAreTriangulated) {
  const TempFolder folder;
  const std::string path = folder.file("cube_quads.obj");
  {
    std::ofstream out(path);
    for (const Vec3& v : cube({0, 0, 0}, 2).vertices)
      out << "v " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
    for (const auto& q : cube_quads())
      out << "f " << q[0] + 1 << ' ' << q[1] + 1 << ' ' << q[2] + 1 << ' ' << q[3] + 1 << '\n';
  }
  const SurfaceMesh read = load_surface_mesh(path);
  EXPECT_EQ(read.triangles.size(), 12u);
  EXPECT_NEAR(enclosed_volume(read), 8, 1e-12 * 8);
}

// A cube whose box is the grid's core: its faces lie on cell faces, so the
// voxel body is exact, and the margin of one cell all round is empty.
TEST(MeshBody, GridCoversTheBoxWithAMargin) {
  const VoxelBody body = voxelize(cube({1, 2, 3}, 2), 32);
  EXPECT_EQ(body.nx, 34);
  EXPECT_EQ(body.ny, 34);
  EXPECT_EQ(body.nz, 34);
  EXPECT_DOUBLE_EQ(body.cell, 2.0 / 32);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(body.origin[d], 1 + d - body.cell, 1e-15);
  EXPECT_NEAR(body.volume(), 8, 1e-12);
  for (int k = 0; k < body.nz; ++k) {
    for (int j = 0; j < body.ny; ++j) {
      for (int i = 0; i < body.nx; ++i) {
        const bool margin =
            i == 0 || j == 0 || k == 0 || i == body.nx - 1 || j == body.ny - 1 || k == body.nz - 1;
        ASSERT_EQ(body.inside[body.index(i, j, k)], margin ? 0 : 1) << i << ' ' << j << ' ' << k;
      }
    }
  }
  // a flat box: the short sides get as many cells as they need, centred
  SurfaceMesh flat = cube({0, 0, 0}, 1);
  for (Vec3& v : flat.vertices) v = {4 * v[0], 2 * v[1], 0.9 * v[2]};
  const VoxelBody slab = voxelize(flat, 40);
  EXPECT_EQ(slab.nx, 42);
  EXPECT_EQ(slab.ny, 22);
  EXPECT_EQ(slab.nz, 11);  // 0.9 / 0.1 = 9 cells, + 2
  EXPECT_NEAR(slab.origin[2], -0.1, 1e-12);
  EXPECT_NEAR(slab.volume(), 4 * 2 * 0.9, 1e-12);
}

// The errors measured, relative to the exact volume (the icosphere's: its
// enclosed volume), at 16, 32, 64, 128, 256 cells:
//   tetrahedron  7.8e-3  2.0e-3  4.9e-4  1.2e-4  3.1e-5
//   octahedron   1.6e-2  3.9e-3  9.8e-4  2.4e-4  6.1e-5
//   icosphere(3) 2.3e-2  1.8e-3  7.3e-4  3.7e-4  9.3e-5
// The plane faces of the first two meet the regular grid in a regular way,
// so their errors fall as cell^2; the icosphere's less regularly.
TEST(MeshBody, VoxelVolumeConverges) {
  struct Case {
    const char* name;
    SurfaceMesh mesh;
    double volume;  // 0: the enclosed volume
    double tolerance64, tolerance128;
  };
  for (const Case& c : {Case{"tetrahedron", tetrahedron(), 8.0 / 3, 5e-3, 1.2e-3},
                        Case{"octahedron", octahedron(), 4.0 / 3, 1e-2, 2.5e-3},
                        Case{"icosphere", icosphere(3), 0, 7e-3, 4e-3}}) {
    SCOPED_TRACE(c.name);
    const double exact = c.volume > 0 ? c.volume : enclosed_volume(c.mesh);
    EXPECT_NEAR(enclosed_volume(c.mesh), exact, 1e-12 * exact);
    const double error32 = relative_error(voxelize(c.mesh, 32).volume(), exact);
    const double error64 = relative_error(voxelize(c.mesh, 64).volume(), exact);
    const double error128 = relative_error(voxelize(c.mesh, 128).volume(), exact);
    printf("%s: relative voxel volume error %.2e at 32 cells, %.2e at 64, %.2e at 128\n", c.name, error32,
           error64, error128);
    EXPECT_LT(error64, c.tolerance64);
    EXPECT_LT(error128, c.tolerance128);
    EXPECT_LT(error128, error32);
  }
  // the polyhedron inscribed in the unit sphere holds a little less than the sphere
  const double of_sphere = enclosed_volume(icosphere(3)) / (4 * std::acos(-1.0) / 3);
  EXPECT_LT(of_sphere, 1);
  EXPECT_GT(of_sphere, 0.99);
}

// An icosphere through a binary STL (single precision): it reads back
// closed, with the corners its triangles share joined.
TEST(MeshBody, IcosphereReadsBackClosed) {
  const TempFolder folder;
  const SurfaceMesh sphere = icosphere(3);
  const std::string path = folder.file("icosphere.stl");
  write_binary_stl(path, sphere);
  const SurfaceMesh read = load_surface_mesh(path);
  EXPECT_EQ(read.vertices.size(), sphere.vertices.size());
  EXPECT_EQ(read.triangles.size(), sphere.triangles.size());
  EXPECT_NEAR(enclosed_volume(read), enclosed_volume(sphere),
              1e-6 * enclosed_volume(sphere));  // floats: 6e-8 a coordinate
  EXPECT_NEAR(voxelize(read, 64).volume(), voxelize(sphere, 64).volume(), 1e-2 * enclosed_volume(sphere));
}

// Rays that hit a vertex and run through an edge exactly count one
// crossing: a cube whose top face is cut into six triangles around two
// corners P and Q placed exactly on two rays of one row (so the edge PQ
// lies on that row's rays) gives the same voxels as the plain cube. The
// rays' positions are the cells' centres shifted by the nudge mesh_body.h
// documents, 1e-6 (sqrt 2, sqrt 3) cells, computed as voxelize does.
TEST(MeshBody, RaysThroughVerticesAndEdgesCountOnce) {
  const SurfaceMesh plain = cube({-1, -1, -1}, 2);
  const VoxelBody expected = voxelize(plain, 16);
  const double h = expected.cell;
  const auto ray = [&](int i, int j) {
    return Vec3{expected.origin[0] + h * (i + 0.5 + 1.4142135623730951e-6),
                expected.origin[1] + h * (j + 0.5 + 1.7320508075688772e-6), 1.0};
  };
  SurfaceMesh cut;
  cut.vertices = plain.vertices;       // corner x + 2 y + 4 z: the top face is 4, 5, 7, 6
  cut.vertices.push_back(ray(4, 6));   // P = 8
  cut.vertices.push_back(ray(11, 6));  // Q = 9
  for (std::size_t t = 0; t < plain.triangles.size(); ++t) {
    if (t != 2 && t != 3) cut.triangles.push_back(plain.triangles[t]);  // all but the top face's two
  }
  // below P-Q: 4 5 9 8; above: 5 7 6 4 8 9 in turn, fanned from 7 and 6
  for (const std::array<int, 3>& t :
       std::vector<std::array<int, 3>>{{4, 5, 9}, {4, 9, 8}, {5, 7, 9}, {7, 8, 9}, {7, 6, 8}, {6, 4, 8}}) {
    cut.triangles.push_back(t);
  }
  ASSERT_NEAR(enclosed_volume(cut), 8, 1e-12);
  const VoxelBody body = voxelize(cut, 16);
  ASSERT_EQ(body.inside.size(), expected.inside.size());
  EXPECT_EQ(body.inside, expected.inside);
  EXPECT_NEAR(body.volume(), 8, 1e-12);
}

TEST(MeshBody, VoxelizeIsFast) {
  const SurfaceMesh sphere = icosphere(4);
  const auto start = std::chrono::steady_clock::now();
  const VoxelBody body = voxelize(sphere, 128);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  printf("voxelize: %zu triangles at 128 cells in %.3f s\n", sphere.triangles.size(), seconds);
  EXPECT_LT(seconds, 1.0);
  EXPECT_NEAR(body.volume(), enclosed_volume(sphere), 1e-3 * enclosed_volume(sphere));
}

// The message of what `read` throws, "" when it returns.
template <class Exception, class F>
std::string thrown(F read) {
  try {
    read();
  } catch (const Exception& e) {
    return e.what();
  }
  return "";
}

TEST(MeshBody, BadFilesAreRefusedByName) {
  const TempFolder folder;
  const std::string missing = folder.file("no_such_grain.stl");
  EXPECT_EQ(thrown<std::runtime_error>([&] { load_surface_mesh(missing); }), missing + ": no such file");

  // a cube without its top: the top's four sides belong to one triangle each
  SurfaceMesh open = cube({0, 0, 0}, 1);
  open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4);
  const std::string open_path = folder.file("open_cube.stl");
  write_ascii_stl(open_path, open);
  EXPECT_EQ(thrown<std::runtime_error>([&] { load_surface_mesh(open_path); }),
            open_path +
                ": the surface is not closed: 4 edges belong to one triangle only; a grain mesh must be "
                "watertight");

  // one triangle turned over: its three edges each join triangles facing opposite ways
  SurfaceMesh flipped = cube({0, 0, 0}, 1);
  std::swap(flipped.triangles[5][1], flipped.triangles[5][2]);
  const std::string flipped_path = folder.file("flipped.obj");
  write_obj(flipped_path, flipped);
  const std::string flipped_message = thrown<std::runtime_error>([&] { load_surface_mesh(flipped_path); });
  EXPECT_NE(
      flipped_message.find(flipped_path +
                           ": the surface is not closed: 3 edges join two triangles facing opposite ways"),
      std::string::npos)
      << flipped_message;

  // three triangles on one edge: a fin glued onto the cube
  SurfaceMesh finned = cube({0, 0, 0}, 1);
  finned.vertices.push_back({0.5, -1, 0.5});
  finned.triangles.push_back({0, 1, 8});
  const std::string finned_path = folder.file("finned.obj");
  write_obj(finned_path, finned);
  const std::string finned_message = thrown<std::runtime_error>([&] { load_surface_mesh(finned_path); });
  EXPECT_NE(finned_message.find("1 edge is shared by more than two triangles"), std::string::npos)
      << finned_message;
  EXPECT_NE(finned_message.find("2 edges belong to one triangle only"), std::string::npos) << finned_message;

  // not a mesh at all, and a mesh of points only
  const std::string garbage = folder.file("garbage.stl");
  std::ofstream(garbage) << "these are not the facets you are looking for\n";
  const std::string garbage_message = thrown<std::runtime_error>([&] { load_surface_mesh(garbage); });
  EXPECT_EQ(garbage_message.rfind(garbage + ": ", 0), 0u) << garbage_message;
  const std::string points = folder.file("points.obj");
  std::ofstream(points) << "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n";
  const std::string points_message = thrown<std::runtime_error>([&] { load_surface_mesh(points); });
  EXPECT_EQ(points_message.rfind(points + ": ", 0), 0u) << points_message;

  EXPECT_EQ(thrown<std::runtime_error>([&] { load_surface_mesh(folder.file("")); }).find("is a directory"),
            folder.file("").size() + 2);
}

TEST(MeshBody, CellsOutOfRangeAreRefused) {
  const SurfaceMesh mesh = tetrahedron();
  for (int cells : {3, 513, 0, -8}) {
    const std::string message = thrown<std::invalid_argument>([&] { voxelize(mesh, cells); });
    EXPECT_NE(message.find("from 4 to 512"), std::string::npos) << message;
    EXPECT_NE(message.find("not " + std::to_string(cells)), std::string::npos) << message;
  }
  EXPECT_NO_THROW(voxelize(mesh, 4));
  EXPECT_NO_THROW(voxelize(mesh, 512));
  EXPECT_THROW(voxelize(SurfaceMesh{}, 32), std::invalid_argument);
}

// The grain meshes of assets/grains: closed, of the size and volume their
// README states (computed exactly from the coordinates as written; Assimp
// reads them in single precision, a relative 6e-8 a coordinate).
TEST(MeshBody, AssetGrainsMatchTheirReadme) {
  struct Asset {
    const char* file;
    std::size_t triangles;
    double volume;  // m^3, assets/grains/README.md
  };
  for (const Asset& a :
       {Asset{"sand_grain.stl", 46, 2.0679308490e-10}, Asset{"tetrahedron.obj", 4, 1.0 / 24e9}}) {
    SCOPED_TRACE(a.file);
    const SurfaceMesh mesh = load_surface_mesh(std::string(SIMSOLS_SOURCE_DIR) + "/assets/grains/" + a.file);
    EXPECT_EQ(mesh.triangles.size(), a.triangles);
    const double volume = enclosed_volume(mesh);
    printf("%s: volume %.10e m^3, relative to the README %.1e\n", a.file, volume,
           relative_error(volume, a.volume));
    EXPECT_NEAR(volume, a.volume, 1e-6 * a.volume);
    const Box3 box = bounding_box(mesh);
    for (int d = 0; d < 3; ++d) {
      EXPECT_GT(box.hi[d] - box.lo[d], 4e-4);  // about a millimetre, in metres
      EXPECT_LT(box.hi[d] - box.lo[d], 1.2e-3);
    }
    EXPECT_NEAR(voxelize(mesh, 64).volume(), volume, 1e-2 * volume);
  }
}

}  // namespace
}  // namespace simsols
