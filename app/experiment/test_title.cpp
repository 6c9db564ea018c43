#include "app/experiment/test_title.h"

#include <algorithm>

#include "solver/apparatus/registry.h"
#include "solver/io/output.h"
#include "solver/scene/scene.h"

namespace simsols {
namespace {

std::string number(double v) { return format_number("%.3g", v); }

// "6.35 mm glass beads", "graded glass beads (D50 2 mm)", "sand grains (D50 4.76 mm)"
std::string specimen_words(const Scene& s, const Specimen& sp) {
  const std::string size = number(sp.diameter * 1e3) + " mm";
  if (sp.grain >= 0 && sp.grain < int(s.grains.size()))
    return s.grains[size_t(sp.grain)].name + " grains" + (sp.diameter > 0 ? " (D50 " + size + ")" : "");
  const std::string material =
      sp.material >= 0 && sp.material < int(s.materials.size()) ? s.materials[size_t(sp.material)].name + " " : "";
  if (!s.clumps.empty()) {  // built of clumps (a checkpoint's scene): the grains tell
    const int g = s.clumps.front().grain;
    return (g >= 0 && g < int(s.grains.size()) ? s.grains[size_t(g)].name + " " : std::string()) +
           "grains";
  }
  if (sp.method == Specimen::Method::Given || sp.diameter <= 0) {  // built: the beads tell
    double lo = 1e300, hi = 0;
    for (const Particle& p : s.particles) {
      lo = std::min(lo, p.radius);
      hi = std::max(hi, p.radius);
    }
    if (hi <= 0) return material + "beads";
    if (hi - lo > 1e-9 * hi) return "graded " + material + "beads";
    return number(2 * hi * 1e3) + " mm " + material + "beads";
  }
  if (sp.grading.law == Grading::Law::Single) return size + " " + material + "beads";
  return "graded " + material + "beads (D50 " + size + ")";
}

}  // namespace

std::string test_title(const Scene& s) {
  const ApparatusKind* kind = apparatus_kind(s);
  if (!kind) return s.description.empty() ? s.name : s.description;
  std::string title = kind->title;
  if (const Specimen* sp = s.specimen()) title += ", " + specimen_words(s, *sp);
  const std::string stress = kind->stress_words(s);
  if (!stress.empty()) title += ", " + stress;
  return title;
}

}  // namespace simsols
