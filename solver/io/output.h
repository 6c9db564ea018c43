// Output: files a run leaves for people and for ParaView.
//
//   particles_<step>.csv         one row per particle (radius, position,
//                                velocity, angular velocity, force,
//                                contacts, material); ParaView's series
//                                are paraview.h's
//   series.csv                   one row per output step (TimeSeries)
//
// Every file is written to a temporary name and renamed, so no reader (and
// no kill) ever sees half a file. series.csv is kept in memory and written
// whole at least every 10 s of wall time, at every checkpoint and at the
// end; a resumed run keeps its rows up to the checkpoint's step.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "solver/common/atomic_file.h"  // write_file_atomic
#include "solver/core/observe.h"

namespace simsols {

// One number through a printf conversion ("%.3f", "%g"): the tables and
// labels of every report share it.
std::string format_number(const char* printf_format, double value);
// One CSV line's fields; a field in double quotes may hold commas.
std::vector<std::string> split_csv_line(const std::string& line);
// The whole file as text; empty when it cannot be read.
std::string read_text(const std::string& path);
void write_particles_csv(const std::string& path, const ParticleSnapshot& p);

class TimeSeries {
 public:
  // Opens `path`; when `resume_step` >= 0 keeps the rows up to that step,
  // otherwise starts a new file.
  TimeSeries(const std::string& path, const std::vector<std::string>& wall_names,
             long long resume_step = -1);
  ~TimeSeries();  // writes what is not written yet (errors ignored)
  void append(double time, long long step, const Observables& o,
              const std::vector<WallReaction>& walls, const std::vector<Vec3>& wall_points);
  void flush();  // writes the file now (atomically)

 private:
  std::string path_, text_;
  bool dirty_ = false;
  std::chrono::steady_clock::time_point written_;
};

}  // namespace simsols
