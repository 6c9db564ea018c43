// `run --frames DIR --every N --video FILE.mp4`: the run's PNG frames made
// into a video by Debian's ffmpeg, when it is installed.
//
// The frames are the film: they stay in DIR whatever happens. ffmpeg is
// looked up in PATH and run directly (no shell), on the frames in file
// name order (frame_<step>.png sorts by step), H.264 in an MP4 at `fps`
// frames per second, yuv420p with the size padded to even so every player
// reads it. The video is written under a temporary name and renamed, so a
// failed or interrupted encoding leaves no half file. Without ffmpeg the
// run still succeeds and says how to encode the frames later.
#pragma once

#include <string>

namespace simsols {

struct VideoOutcome {
  bool encoded = false;
  std::string message;  // one line for the user: where the video is, or why not
};

// The ffmpeg command line (argv) that encodes `frames_dir`'s frames.
std::string ffmpeg_command_text(const std::string& frames_dir, const std::string& video_path, int fps);

VideoOutcome encode_video(const std::string& frames_dir, const std::string& video_path, int fps);

}  // namespace simsols
