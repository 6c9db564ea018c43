// What a file given to a command is, from its first bytes: a checkpoint
// (checkpoint.h, its magic present), text that may be a scene (TOML), or
// neither. Commands that take "a scene or a checkpoint" ask first, so an
// empty file, ten bytes of a checkpoint or a PNG is refused as what it is,
// not with a TOML error about a missing field.
#pragma once

#include <string>

namespace simsols {

// The first bytes of every checkpoint (checkpoint.h writes them).
inline constexpr char kCheckpointMagic[12] = {'S', 'I', 'M', 'S', 'O', 'L',
                                              'S', '-', 'C', 'K', 'P', 'T'};

enum class InputKind {
  Checkpoint,           // starts with the checkpoint magic (checked in full on load)
  TruncatedCheckpoint,  // shorter than the magic, but the start of it
  SceneText,            // text: parsed as a scene
  Empty,                // no bytes, or only white space
  Binary,               // control bytes, not a checkpoint
};

// Throws SceneError("io") when the file cannot be read.
InputKind classify_input(const std::string& path);

// Throws SceneError naming `path` unless it is a checkpoint or text; the
// message says what the file is and what was expected (`expected`, e.g.
// "a scene (TOML) or a checkpoint").
InputKind require_scene_or_checkpoint(const std::string& path, const std::string& expected);

}  // namespace simsols
