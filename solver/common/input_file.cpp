#include "solver/common/input_file.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>

#include "solver/common/errors.h"

namespace simsols {

InputKind classify_input(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError("io", path, 0, "", "cannot open the file");
  constexpr size_t kMagicBytes = sizeof kCheckpointMagic;
  char head[512];
  in.read(head, sizeof head);
  const size_t n = static_cast<size_t>(in.gcount());
  if (n > 0 && std::memcmp(head, kCheckpointMagic, std::min(n, kMagicBytes)) == 0)
    return n >= kMagicBytes ? InputKind::Checkpoint : InputKind::TruncatedCheckpoint;
  bool blank = true, binary = false;
  for (size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(head[i]);
    if (!std::isspace(c)) blank = false;
    if (c < 32 && c != '\n' && c != '\r' && c != '\t') binary = true;
  }
  return blank ? InputKind::Empty : binary ? InputKind::Binary : InputKind::SceneText;
}

InputKind require_scene_or_checkpoint(const std::string& path, const std::string& expected) {
  const InputKind k = classify_input(path);
  switch (k) {
    case InputKind::Empty:
      throw SceneError("not_a_scene", path, 0, "", "the file is empty; expected " + expected);
    case InputKind::Binary:
      throw SceneError("not_a_scene", path, 0, "",
                       "a binary file that is neither a scene (TOML text) nor a SimSols "
                       "checkpoint; expected " + expected);
    case InputKind::TruncatedCheckpoint:
      throw SceneError("bad_checkpoint", path, 0, "",
                       "only the first bytes of a SimSols checkpoint (truncated file); expected " +
                           expected);
    default: return k;
  }
}

}  // namespace simsols
