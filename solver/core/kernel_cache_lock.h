// KernelCacheLock: kernel compilation serialised between processes on PoCL.
//
// PoCL compiles a program at clBuildProgram, and each kernel's work-group
// function at its first launch for a size, into an on-disk kernel cache
// (POCL_CACHE_DIR, else $XDG_CACHE_HOME/pocl/kcache, else
// ~/.cache/pocl/kcache). Version 3.1 (Debian 12) locks that cache between a
// process's threads but not between processes, and two processes compiling
// the same kernel at the same moment can crash (pocl issues #430 and #1480);
// the test suite runs in parallel over one cache, and so do campaigns on one
// machine. So on PoCL both compilations run under an exclusive flock(2) on
// `.simsols-compile.lock` in the cache directory: clBuildProgram (Program)
// and a kernel's first launch at each size, which is waited for before the
// lock is let go (enqueue_kernel, cl_program.h). Other drivers keep their
// caches safe themselves: there the path is empty and the lock does
// nothing. A lock file that cannot be opened or locked leaves the lock a
// no-op as well; PoCL reports its own error if its cache is unusable.
#pragma once

#include <string>

namespace simsols {

// The lock file in the cache directory PoCL uses, found from the
// environment as PoCL finds it.
std::string pocl_compile_lock_path();

class KernelCacheLock {
 public:
  explicit KernelCacheLock(const std::string& path);  // "": no lock
  ~KernelCacheLock();
  KernelCacheLock(const KernelCacheLock&) = delete;
  KernelCacheLock& operator=(const KernelCacheLock&) = delete;
  bool held() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

}  // namespace simsols
