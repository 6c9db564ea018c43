#include "solver/core/kernel_cache_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace simsols {
namespace {

const char* env(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && v[0] != '\0' ? v : nullptr;
}

}  // namespace

std::string pocl_compile_lock_path() {
  namespace fs = std::filesystem;
  fs::path dir;
  if (const char* d = env("POCL_CACHE_DIR")) {
    dir = d;
  } else {
    const char* kcache = env("POCL_KERNEL_CACHE");
    const char* sub = kcache != nullptr && std::string(kcache) == "0" ? "pocl/uncached" : "pocl/kcache";
    if (const char* x = env("XDG_CACHE_HOME"))
      dir = fs::path(x) / sub;
    else if (const char* h = env("HOME"))
      dir = fs::path(h) / ".cache" / sub;
    else
      dir = fs::path("/tmp") / sub;
  }
  std::error_code ec;
  fs::create_directories(dir, ec);  // PoCL would create it at its first build
  return (dir / ".simsols-compile.lock").string();
}

KernelCacheLock::KernelCacheLock(const std::string& path) {
  if (path.empty()) return;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) return;
  int rc = 0;
  do rc = ::flock(fd_, LOCK_EX);
  while (rc != 0 && errno == EINTR);
  if (rc != 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

KernelCacheLock::~KernelCacheLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the descriptor releases the lock
}

}  // namespace simsols
