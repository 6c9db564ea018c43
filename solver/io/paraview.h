// ParaView time series: what a run looks like, step by step, for people
// who scrub through it in ParaView (or read it with VTK).
//
// Each dump writes three VTK XML PolyData files (.vtp, raw binary data
// appended after the XML, native byte order declared) into the run's
// `paraview/` folder, and rewrites three collection files (.pvd) that index
// them by simulated time, so ParaView opens one .pvd and plays the run:
//
//   particles.pvd  particles_<step>.vtp  one vertex per bead: radius (m),
//                  velocity (m/s), spin (rad/s), force (N), contacts,
//                  material, grain (its clump, -1 for a free bead)
//   walls.pvd      walls_<step>.vtp      one quad per wall where it is now
//                  (a plane drawn over the specimen, a rectangle whole):
//                  wall index, normal, force the beads exert on it (N)
//   contacts.pvd   contacts_<step>.vtp   one line per touching contact,
//                  bead centre to bead centre, or to the wall's nearest
//                  point: force on the first bead (N), normal force
//                  (compression positive) and tangential force (N), wall
//                  (-1 for two beads), the beads' indices
//
// Every file carries its simulated time as the field TimeValue. Each file
// is written whole under a temporary name and renamed (atomic_file.h); a
// .pvd is rewritten after its .vtp, so it never names a missing file. A
// resumed run keeps the entries up to its checkpoint's step and drops the
// later ones (they belong to the abandoned future).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "solver/core/stress.h"
#include "solver/scene/scene.h"

namespace simsols {

class Simulation;

// The three documents of one dump (see above), from the state `sample`
// read, the scene's walls and grains, at simulated time `time`.
std::string particles_vtp(const ContactSample& sample, const Scene& scene, double time);
std::string walls_vtp(const ContactSample& sample, const Scene& scene, double time);
std::string contacts_vtp(const ContactSample& sample, const Scene& scene, double time);

class ParaviewSeries {
 public:
  // The series in `dir` (created when needed); with resume_step >= 0 the
  // entries its .pvd files already list up to that step are kept.
  explicit ParaviewSeries(std::filesystem::path dir, long long resume_step = -1);

  // Writes the state now as the next dump (once per step: a second call
  // at the same step rewrites it).
  void write(Simulation& sim);

  const std::filesystem::path& dir() const { return dir_; }

 private:
  struct Entry {
    double time = 0;
    long long step = 0;
  };
  void write_collections() const;

  std::filesystem::path dir_;
  std::vector<Entry> entries_;
};

}  // namespace simsols
