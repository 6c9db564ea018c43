#include "app/cli/video.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <vector>

extern char** environ;

namespace simsols {
namespace {

// ffmpeg's path in PATH, or empty.
std::string find_ffmpeg() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/ffmpeg";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

std::vector<std::string> ffmpeg_args(const std::string& frames_dir, const std::string& output, int fps) {
  return {"ffmpeg", "-y", "-loglevel", "error", "-framerate", std::to_string(fps), "-pattern_type", "glob",
          "-i", frames_dir + "/frame_*.png", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264",
          "-pix_fmt", "yuv420p", "-f", "mp4", output};
}

// Runs `program` with `args` and waits: its exit status, or -1 when it
// could not start or did not exit normally.
int run_and_wait(const std::string& program, const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid;
  if (::posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::string ffmpeg_command_text(const std::string& frames_dir, const std::string& video_path, int fps) {
  std::string text;
  for (const std::string& a : ffmpeg_args(frames_dir, video_path, fps)) {
    const bool quote = a.find_first_of("*() ") != std::string::npos;
    text += (text.empty() ? "" : " ") + (quote ? "'" + a + "'" : a);
  }
  return text;
}

VideoOutcome encode_video(const std::string& frames_dir, const std::string& video_path, int fps) {
  const std::string ffmpeg = find_ffmpeg();
  if (ffmpeg.empty())
    return {false, "ffmpeg not found in PATH: the frames are kept in " + frames_dir +
                       "; install it (apt-get install ffmpeg) and run: " +
                       ffmpeg_command_text(frames_dir, video_path, fps)};
  const std::string part = video_path + ".part";
  const int status = run_and_wait(ffmpeg, ffmpeg_args(frames_dir, part, fps));
  std::error_code ec;
  if (status == 0 && std::filesystem::exists(part, ec)) {
    std::filesystem::rename(part, video_path, ec);
    if (!ec) return {true, "video " + video_path + " (" + std::to_string(fps) + " frames per second)"};
  }
  std::filesystem::remove(part, ec);
  return {false, "ffmpeg (" + ffmpeg + ") failed with status " + std::to_string(status) +
                     ": no video; the frames are kept in " + frames_dir};
}

}  // namespace simsols
