#include "checkpoint.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "errors.h"
#include "scene_toml.h"

namespace simsols {
namespace {

constexpr char kMagic[12] = {'S', 'I', 'M', 'S', 'O', 'L', 'S', '-', 'C', 'K', 'P', 'T'};
constexpr std::uint32_t kVersion = 3;

class Writer {
 public:
  explicit Writer(std::ofstream& out) : out_(out) {}
  template <typename T> void pod(const T& v) { out_.write(reinterpret_cast<const char*>(&v), sizeof v); }
  void bytes(const void* p, size_t n) { pod<std::uint64_t>(n); out_.write(static_cast<const char*>(p), n); }
  void str(const std::string& s) { bytes(s.data(), s.size()); }

 private:
  std::ofstream& out_;
};

class Reader {
 public:
  Reader(std::ifstream& in, std::string path) : in_(in), path_(std::move(path)) {}
  template <typename T> T pod() {
    T v{};
    in_.read(reinterpret_cast<char*>(&v), sizeof v);
    if (!in_) fail("truncated file");
    return v;
  }
  std::vector<char> bytes() {
    const auto n = pod<std::uint64_t>();
    if (n > (std::uint64_t(1) << 40)) fail("corrupt block size");
    std::vector<char> b(n);
    in_.read(b.data(), static_cast<std::streamsize>(n));
    if (!in_) fail("truncated file");
    return b;
  }
  std::string str() { auto b = bytes(); return std::string(b.begin(), b.end()); }
  [[noreturn]] void fail(const std::string& what) {
    throw SceneError("bad_checkpoint", path_, 0, "", "not a usable SimSols checkpoint: " + what);
  }

 private:
  std::ifstream& in_;
  std::string path_;
};

}  // namespace

void save_checkpoint(Simulation& sim, const std::string& path, const std::string& extra) {
  sim.check();  // never a checkpoint of a state past a runaway (guard.h)
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw DeviceError("cannot write checkpoint " + tmp);
    Writer w(out);
    out.write(kMagic, sizeof kMagic);
    w.pod(kVersion);
    w.str(to_toml(sim.scene()));
    State& s = sim.state();
    w.pod<std::int64_t>(s.step);
    w.pod<std::int64_t>(s.list_builds);
    w.pod<std::int64_t>(s.next_check);
    w.pod<std::int64_t>(s.late_builds);
    w.pod<std::int32_t>(s.cap);
    std::vector<char> data;
    for (auto& [name, buf] : s.dynamic_buffers()) {
      data.resize(buf->bytes);
      sim.model().device().read(buf->get(), buf->bytes, data.data());
      w.str(name);
      w.bytes(data.data(), data.size());
    }
    w.str(extra);
    out.flush();
    if (!out) throw DeviceError("failed writing checkpoint " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

std::unique_ptr<Simulation> load_checkpoint(std::shared_ptr<Device> device, const std::string& path,
                                            std::string* extra) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError("io", path, 0, "", "cannot open checkpoint");
  Reader r(in, path);
  char magic[sizeof kMagic];
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0) r.fail("wrong magic");
  if (r.pod<std::uint32_t>() != kVersion) r.fail("unsupported version");
  const std::string text = r.str();
  Scene scene = parse_scene(text, path + " (embedded scene)");
  auto sim = std::make_unique<Simulation>(std::move(device), scene);
  State& s = sim->state();
  s.step = r.pod<std::int64_t>();
  s.time = s.step * sim->dt();
  s.list_builds = r.pod<std::int64_t>();
  s.next_check = r.pod<std::int64_t>();
  s.late_builds = r.pod<std::int64_t>();
  const int cap = r.pod<std::int32_t>();
  if (cap != s.cap) s.resize_lists(sim->model(), cap);
  for (auto& [name, buf] : s.dynamic_buffers()) {
    if (r.str() != name) r.fail("buffer '" + name + "' missing");
    const std::vector<char> data = r.bytes();
    // flags grew from 4 to 8 ints (the runaway mark, guard.h): an older
    // file's 4 keep the new ones at their initial values
    const bool older_flags = name == "flags" && data.size() == 16 && buf->bytes == 32;
    // before the effect slots, every scene kept a tangential spring per list
    // and wall slot; a scene whose slots need no history now has a 16-byte
    // stand-in, and the older file's (zero, unused) springs are dropped
    const bool unused_history =
        (name == "spring" || name == "wall_spring") && buf->bytes == 16 && data.size() > 16 &&
        sim->model().config().history_planes() == 0;
    if (unused_history) continue;
    if (data.size() != buf->bytes && !older_flags)
      r.fail("buffer '" + name + "' has the wrong size");
    sim->model().device().write(buf->get(), data.size(), data.data());
  }
  derive_state(sim->model(), sim->state());
  sim->state_replaced();
  const std::string rest = r.str();
  if (extra) *extra = rest;
  return sim;
}

}  // namespace simsols
