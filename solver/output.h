// Output: files a run leaves for people and for ParaView.
//
//   particles_<step>.csv / .vtk  one row / point per particle (legacy binary
//                                VTK polydata: radius, velocity, angular
//                                velocity, force, contacts, material)
//   series.csv                   one row per output step (TimeSeries)
//
// Every file except series.csv is written to a temporary name and renamed,
// so no reader ever sees half a file. series.csv is appended row by row and
// flushed; a resumed run truncates it back to its checkpoint.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "observe.h"

namespace simsols {

void write_file_atomic(const std::string& path, const std::string& content);
void write_particles_csv(const std::string& path, const ParticleSnapshot& p);
void write_particles_vtk(const std::string& path, const ParticleSnapshot& p, double time);

class TimeSeries {
 public:
  // Opens `path`; when `resume_step` >= 0 keeps the rows up to that step,
  // otherwise starts a new file.
  TimeSeries(const std::string& path, const std::vector<std::string>& wall_names,
             long long resume_step = -1);
  void append(double time, long long step, const Observables& o,
              const std::vector<WallReaction>& walls, const std::vector<Vec3>& wall_points);

 private:
  std::ofstream out_;
};

}  // namespace simsols
