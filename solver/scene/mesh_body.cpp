// Surface meshes read with Assimp and voxelized by parity along z
// (mesh_body.h has the design).
#include "solver/scene/mesh_body.h"
#include "solver/common/errors.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <unordered_map>

namespace simsols {
namespace {

// Joins the corners of every triangle of every mesh of the scene by exact
// position (Assimp joins within a mesh only), dropping triangles with a
// repeated corner: they enclose nothing and would only muddle the edge count.
SurfaceMesh merge_meshes(const aiScene& scene) {
  SurfaceMesh mesh;
  std::map<Vec3, int> index_of;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& am = *scene.mMeshes[m];
    std::vector<int> joined(am.mNumVertices);
    for (unsigned v = 0; v < am.mNumVertices; ++v) {
      const Vec3 p{am.mVertices[v].x, am.mVertices[v].y, am.mVertices[v].z};
      const auto [it, added] = index_of.emplace(p, static_cast<int>(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(p);
      joined[v] = it->second;
    }
    for (unsigned f = 0; f < am.mNumFaces; ++f) {
      const aiFace& face = am.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      const std::array<int, 3> t{joined[face.mIndices[0]], joined[face.mIndices[1]],
                                 joined[face.mIndices[2]]};
      if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
      mesh.triangles.push_back(t);
    }
  }
  return mesh;
}

// Every edge must belong to exactly two triangles that run along it in
// opposite directions; otherwise says how many edges fail and how.
void check_closed(const SurfaceMesh& mesh, const std::string& path) {
  struct Use {
    int count = 0,
        balance = 0;  // triangles on the edge; +1 for each running low -> high index, -1 high -> low
  };
  std::unordered_map<std::uint64_t, Use> edges;
  edges.reserve(mesh.triangles.size() * 2);
  for (const auto& t : mesh.triangles) {
    for (int e = 0; e < 3; ++e) {
      const int a = t[e], b = t[(e + 1) % 3];
      const auto lo = static_cast<std::uint64_t>(std::min(a, b)),
                 hi = static_cast<std::uint64_t>(std::max(a, b));
      Use& use = edges[(lo << 32) | hi];
      ++use.count;
      use.balance += a < b ? 1 : -1;
    }
  }
  std::size_t open = 0, crowded = 0, flipped = 0;
  for (const auto& [key, use] : edges) {
    if (use.count == 1)
      ++open;
    else if (use.count > 2)
      ++crowded;
    else if (use.balance != 0)
      ++flipped;
  }
  if (open + crowded + flipped == 0) return;
  std::string what;
  const auto add = [&what](std::size_t n, const char* one, const char* many) {
    if (n == 0) return;
    if (!what.empty()) what += ", ";
    what += std::to_string(n) + (n == 1 ? one : many);
  };
  add(open, " edge belongs to one triangle only", " edges belong to one triangle only");
  add(crowded, " edge is shared by more than two triangles", " edges are shared by more than two triangles");
  add(flipped, " edge joins two triangles facing opposite ways",
      " edges join two triangles facing opposite ways");
  throw ReadError(path + ": the surface is not closed: " + what +
                           "; a grain mesh must be watertight");
}

// --- the ray test in the xy plane ----------------------------------------

struct Point2 {
  double x, y;
};
bool lex_less(const Point2& a, const Point2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// Twice the signed area of (a, b, p), positive when p is left of a -> b,
// with its sign never 0 for a proper edge: computed from the ends in
// lexicographic order, so every triangle on the edge gets the same answer;
// an exact 0 is resolved as for p shifted by (eps, eps^2), eps -> 0+ (the
// area's derivatives in eps: -(b.y - a.y), then b.x - a.x). 0 only when a
// and b coincide in xy (an edge along z: its triangles are seen edge-on).
struct Side {
  double area;
  int sign;
};
Side side_of(const Point2& a, const Point2& b, const Point2& p) {
  const bool swap = lex_less(b, a);
  const Point2& u = swap ? b : a;
  const Point2& v = swap ? a : b;
  const double w = (v.x - u.x) * (p.y - u.y) - (v.y - u.y) * (p.x - u.x);
  int s = w > 0 ? 1 : w < 0 ? -1 : 0;
  if (s == 0) s = v.y > u.y ? -1 : v.y < u.y ? 1 : v.x > u.x ? 1 : 0;  // u < v: v.x >= u.x
  return swap ? Side{-w, -s} : Side{w, s};
}

// Where the vertical line through p crosses the triangle, if it does.
bool crossing(const Vec3& a, const Vec3& b, const Vec3& c, const Point2& p, double& z) {
  const Point2 pa{a[0], a[1]}, pb{b[0], b[1]}, pc{c[0], c[1]};
  const Side sa = side_of(pb, pc, p), sb = side_of(pc, pa, p), sc = side_of(pa, pb, p);
  if (sa.sign == 0 || sa.sign != sb.sign || sb.sign != sc.sign) return false;
  const double sum = sa.area + sb.area + sc.area;
  z = sum != 0 ? (sa.area * a[2] + sb.area * b[2] + sc.area * c[2]) / sum : (a[2] + b[2] + c[2]) / 3;
  z = std::clamp(z, std::min({a[2], b[2], c[2]}), std::max({a[2], b[2], c[2]}));
  return true;
}

// The rays' offset from the cells' centres, in cells (mesh_body.h).
constexpr double kNudgeX = 1.4142135623730951e-6, kNudgeY = 1.7320508075688772e-6;

// The grid: the box, cells of longest side / cells, one empty cell around.
VoxelBody empty_grid(const Box3& box, int cells) {
  const Vec3 size = sub(box.hi, box.lo);
  const double longest = std::max({size[0], size[1], size[2]});
  VoxelBody body;
  body.cell = longest / cells;
  std::array<int, 3> n{};
  for (int d = 0; d < 3; ++d) {
    const int core = std::max(1, static_cast<int>(std::ceil(size[d] / body.cell - 1e-9)));
    n[d] = core + 2;
    body.origin[d] = box.lo[d] - body.cell - 0.5 * (core * body.cell - size[d]);
  }
  body.nx = n[0];
  body.ny = n[1];
  body.nz = n[2];
  body.inside.assign(static_cast<std::size_t>(body.nx) * body.ny * body.nz, 0);
  return body;
}

// The z of every crossing of every column's ray, column i + nx j: each
// triangle is tried against the columns its xy box covers.
std::vector<std::vector<double>> column_crossings(const SurfaceMesh& mesh, const VoxelBody& body) {
  std::vector<std::vector<double>> columns(static_cast<std::size_t>(body.nx) * body.ny);
  const double h = body.cell;
  // the column index range whose rays' coordinate lies in [lo, hi] (a little wider is harmless)
  const auto range = [h](double lo, double hi, double origin, double nudge, int n) {
    const int first = static_cast<int>(std::floor((lo - origin) / h - 0.5 - nudge));
    const int last = static_cast<int>(std::ceil((hi - origin) / h - 0.5 - nudge));
    return std::array<int, 2>{std::max(first, 0), std::min(last, n - 1)};
  };
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    const auto is =
        range(std::min({a[0], b[0], c[0]}), std::max({a[0], b[0], c[0]}), body.origin[0], kNudgeX, body.nx);
    const auto js =
        range(std::min({a[1], b[1], c[1]}), std::max({a[1], b[1], c[1]}), body.origin[1], kNudgeY, body.ny);
    for (int j = js[0]; j <= js[1]; ++j) {
      for (int i = is[0]; i <= is[1]; ++i) {
        const Point2 p{body.origin[0] + h * (i + 0.5 + kNudgeX), body.origin[1] + h * (j + 0.5 + kNudgeY)};
        double z = 0;
        if (crossing(a, b, c, p, z)) columns[i + static_cast<std::size_t>(body.nx) * j].push_back(z);
      }
    }
  }
  return columns;
}

// Fills each column between its sorted crossings taken in pairs.
void fill_columns(VoxelBody& body, std::vector<std::vector<double>>& columns) {
  const double h = body.cell, z0 = body.origin[2];
  for (int j = 0; j < body.ny; ++j) {
    for (int i = 0; i < body.nx; ++i) {
      std::vector<double>& zs = columns[i + static_cast<std::size_t>(body.nx) * j];
      std::sort(zs.begin(), zs.end());
      for (std::size_t q = 0; q + 1 < zs.size(); q += 2) {
        const int first = std::max(0, static_cast<int>(std::ceil((zs[q] - z0) / h - 0.5)));
        const int last = std::min(body.nz - 1, static_cast<int>(std::floor((zs[q + 1] - z0) / h - 0.5)));
        for (int k = first; k <= last; ++k) body.inside[body.index(i, j, k)] = 1;
      }
    }
  }
}

}  // namespace

SurfaceMesh load_surface_mesh(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw ReadError(path + ": no such file");
  if (std::filesystem::is_directory(status))
    throw ReadError(path + ": is a directory, not a mesh file");
  if (!std::ifstream(path, std::ios::binary))
    throw ReadError(path + ": cannot be opened for reading");
  Assimp::Importer importer;
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_PreTransformVertices | aiProcess_ValidateDataStructure;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (scene == nullptr) {
    throw ReadError(
        path + ": not a mesh file Assimp can read (STL or OBJ expected): " + importer.GetErrorString());
  }
  SurfaceMesh mesh = merge_meshes(*scene);
  if (mesh.triangles.empty()) throw ReadError(path + ": the file holds no triangles");
  check_closed(mesh, path);
  return mesh;
}

Box3 bounding_box(const SurfaceMesh& mesh) {
  if (mesh.vertices.empty()) return {};
  Box3 box{mesh.vertices.front(), mesh.vertices.front()};
  for (const Vec3& v : mesh.vertices) {
    for (int d = 0; d < 3; ++d) {
      box.lo[d] = std::min(box.lo[d], v[d]);
      box.hi[d] = std::max(box.hi[d], v[d]);
    }
  }
  return box;
}

double enclosed_volume(const SurfaceMesh& mesh) {
  // tetrahedra from the box's centre: small lever arms, little cancellation
  const Box3 box = bounding_box(mesh);
  const Vec3 o = scale(0.5, {box.lo[0] + box.hi[0], box.lo[1] + box.hi[1], box.lo[2] + box.hi[2]});
  double six_v = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3 a = sub(mesh.vertices[t[0]], o), b = sub(mesh.vertices[t[1]], o),
               c = sub(mesh.vertices[t[2]], o);
    six_v += dot(a, cross(b, c));
  }
  return std::abs(six_v) / 6;
}

VoxelBody voxelize(const SurfaceMesh& mesh, int cells_along_longest_side) {
  const int cells = cells_along_longest_side;
  if (cells < 4 || cells > 512) {
    throw std::invalid_argument("voxelize: the cells along the longest side must be from 4 to 512, not " +
                                std::to_string(cells));
  }
  if (mesh.triangles.empty()) throw std::invalid_argument("voxelize: the mesh has no triangles");
  const Box3 box = bounding_box(mesh);
  const Vec3 size = sub(box.hi, box.lo);
  if (!(std::max({size[0], size[1], size[2]}) > 0)) {
    throw std::invalid_argument("voxelize: the mesh's bounding box has no size");
  }
  VoxelBody body = empty_grid(box, cells);
  std::vector<std::vector<double>> columns = column_crossings(mesh, body);
  fill_columns(body, columns);
  return body;
}

}  // namespace simsols
