#include "solver/core/slots.h"
#include "solver/scene/choices.h"

#include <cstdio>
#include <sstream>

namespace simsols {

std::vector<SlotReport> slot_reports(const Scene& s, const KernelConfig& c) {
  const Effects& e = s.effects;
  std::vector<SlotReport> r;
  r.push_back({"normal", "hertz", true, "", 0});
  r.push_back({"damping", choice_name(e.damping), c.damping,
               e.damping != DampingModel::None && !c.damping ? "every restitution is 1" : "",
               c.damping ? 1 : 0});
  r.push_back({"tangential", choice_name(e.tangential), c.friction,
               e.tangential != TangentialModel::None && !c.friction ? "every sliding_friction is 0"
                                                                    : "",
               c.friction ? (c.micro_slip ? 7 : 3) : 0});
  r.push_back({"rolling", choice_name(e.rolling), c.rolling,
               e.rolling != RollingModel::None && !c.rolling ? "every rolling_friction is 0" : "",
               c.rolling_spring ? 3 : 0});
  r.push_back({"cohesion", choice_name(e.cohesion), c.capillary, "", 0});
  r.push_back({"gravity", s.has_gravity() ? "on" : "none", c.gravity, "", 0});
  r.push_back({"fluid", choice_name(e.fluid), c.fluid, "", 0});
  return r;
}

std::string compiled_slots_line(const Scene& s, const KernelConfig& c) {
  std::string out;
  for (const SlotReport& r : slot_reports(s, c))
    out += r.slot + "=" + (r.compiled ? r.chosen : std::string("none")) + " ";
  out += "history " + std::to_string(c.history_bytes_per_contact()) + " B/contact";
  return out;
}

std::string explain_effects(const Scene& s, const KernelConfig& c) {
  std::ostringstream o;
  o << "effect slots of '" << s.name << "' (" << (c.double_precision ? "double" : "float")
    << "):\n";
  char line[256];
  for (const SlotReport& r : slot_reports(s, c)) {
    const std::string why = r.why.empty() ? "" : "  (" + r.why + ")";
    std::snprintf(line, sizeof line, "  %-11s %-16s %-13s history %d reals/contact%s\n",
                  r.slot.c_str(), r.chosen.c_str(), r.compiled ? "compiled in" : "compiled out",
                  r.history_reals, why.c_str());
    o << line;
  }
  o << "per-contact history: " << c.history_planes() << " record(s) of 4 reals = "
    << c.history_bytes_per_contact() << " bytes per contact (list slot and wall slot; the "
    << "lists keep a previous copy for carrying it over)\n";
  int plane = 0;
  for (const HistoryPlane& h : history_plane_table())
    if (h.compiled(c)) o << "  plane " << plane++ << " (" << h.define << "): " << h.slots << "\n";
  o << "pair coefficient record: " << c.pair_record() << " reals\n";
  o << "kernel build options: " << c.build_options() << "\n";
  return o.str();
}

}  // namespace simsols
