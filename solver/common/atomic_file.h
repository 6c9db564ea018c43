// Files written whole or not at all: the content goes to `path.tmp`, which
// is then renamed over `path`, so no reader (and no kill) ever sees half a
// file. On failure the temporary file is removed and IoError names the
// path. Every result file (CSV, TOML, PNG, VTK, checkpoints) goes through it.
#pragma once

#include <string>

namespace simsols {

void write_file_atomic(const std::string& path, const std::string& content);

}  // namespace simsols
