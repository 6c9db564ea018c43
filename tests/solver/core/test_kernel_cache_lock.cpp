// Kernel compilation serialised between processes (solver/core/
// kernel_cache_lock.h): the lock excludes another process until it is let
// go, its file lies where PoCL keeps its cache, and on PoCL a kernel's
// first launch at a size waits for the lock while later launches do not.
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/core/cl_program.h"
#include "solver/core/kernel_cache_lock.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

namespace fs = std::filesystem;

std::string temp_lock(const char* name) {
  return (fs::temp_directory_path() / (std::string(name) + std::to_string(getpid()))).string();
}

// Whether another process could take the lock on `path` without waiting.
bool free_in_another_process(const std::string& path) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT, 0644);
    _exit(fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) == 0 ? 0 : 1);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

TEST(KernelCacheLock, ExcludesAnotherProcessUntilLetGo) {
  const std::string path = temp_lock("simsols-lock-test-");
  {
    const KernelCacheLock lock(path);
    ASSERT_TRUE(lock.held());
    EXPECT_FALSE(free_in_another_process(path));
  }
  EXPECT_TRUE(free_in_another_process(path));
  fs::remove(path);
}

TEST(KernelCacheLock, AnEmptyPathLocksNothing) {
  const KernelCacheLock lock("");
  EXPECT_FALSE(lock.held());
}

TEST(KernelCacheLock, TheFileLiesWherePoclKeepsItsCache) {
  const fs::path root = fs::temp_directory_path() / ("simsols-cache-" + std::to_string(getpid()));
  {
    const ScopedVariable dir("POCL_CACHE_DIR", (root / "kc").c_str());
    EXPECT_EQ(pocl_compile_lock_path(), (root / "kc" / ".simsols-compile.lock").string());
  }
  {
    const ScopedVariable dir("POCL_CACHE_DIR", nullptr);
    const ScopedVariable xdg("XDG_CACHE_HOME", (root / "xdg").c_str());
    EXPECT_EQ(pocl_compile_lock_path(),
              (root / "xdg" / "pocl" / "kcache" / ".simsols-compile.lock").string());
    const ScopedVariable off("POCL_KERNEL_CACHE", "0");
    EXPECT_EQ(pocl_compile_lock_path(),
              (root / "xdg" / "pocl" / "uncached" / ".simsols-compile.lock").string());
  }
  EXPECT_TRUE(fs::is_directory(root / "kc"));  // made, as PoCL would
  fs::remove_all(root);
}

const char* kTouch = R"CL(
__kernel void touch(__global int* values) { values[get_global_id(0)] += 1; }
)CL";

// Seconds a call takes.
template <typename F>
double seconds(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

TEST(KernelCacheLock, OnPoclAFirstLaunchPerSizeWaitsForTheLock) {
  const std::shared_ptr<Device> dev = default_device();
  if (dev->compile_lock_path().empty()) GTEST_SKIP() << "not PoCL: " << dev->description();
  EXPECT_EQ(fs::path(dev->compile_lock_path()).filename(), ".simsols-compile.lock");
  const std::vector<KernelFile> files = {{"touch.cl", kTouch}};
  const Program program(*dev, KernelConfig{}, files);
  const Kernel k = program.kernel("touch");
  const ClMem values = dev->alloc(64 * sizeof(int));
  check(clSetKernelArg(k.get(), 0, sizeof(cl_mem), &values), "clSetKernelArg");
  enqueue_kernel(*dev, k, 32, 0);
  enqueue_kernel(*dev, k, 32, 0);
  dev->finish();
  EXPECT_EQ(k.launched, (std::vector<std::array<size_t, 2>>{{32, 0}}));

  // another process holds the lock for 0.6 s
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t pid = fork();
  if (pid == 0) {
    const KernelCacheLock held(dev->compile_lock_path());
    const char c = held.held() ? 'y' : 'n';
    (void)!write(ready[1], &c, 1);
    usleep(600000);
    _exit(0);
  }
  char c = 0;
  ASSERT_EQ(read(ready[0], &c, 1), 1);
  ASSERT_EQ(c, 'y');
  const double known = seconds([&] { enqueue_kernel(*dev, k, 32, 0); dev->finish(); });
  const double first = seconds([&] { enqueue_kernel(*dev, k, 64, 0); });
  waitpid(pid, nullptr, 0);
  close(ready[0]);
  close(ready[1]);
  EXPECT_LT(known, 0.3);
  EXPECT_GT(first, 0.3);
  EXPECT_EQ(k.launched, (std::vector<std::array<size_t, 2>>{{32, 0}, {64, 0}}));
  std::vector<int> out(64);
  dev->read(values.get(), out.size() * sizeof(int), out.data());
  EXPECT_EQ(out[0], 4);
  EXPECT_EQ(out[40], 1);
}

}  // namespace
}  // namespace simsols::testing
