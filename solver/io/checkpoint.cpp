#include "solver/io/checkpoint.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "solver/common/errors.h"
#include "solver/common/input_file.h"
#include "solver/io/scene_toml.h"

namespace simsols {
namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw SceneError("bad_checkpoint", path, 0, "", "not a usable SimSols checkpoint: " + what);
}

std::uint32_t crc_update(std::uint32_t crc, const void* p, size_t n) {
  const auto* b = static_cast<const Bytef*>(p);
  while (n > 0) {  // zlib takes uInt lengths
    const uInt chunk = static_cast<uInt>(std::min<size_t>(n, 1u << 30));
    crc = static_cast<std::uint32_t>(crc32(crc, b, chunk));
    b += chunk;
    n -= chunk;
  }
  return crc;
}

// Streams the payload into the file, keeping its size and checksum.
class Writer {
 public:
  explicit Writer(std::ofstream& out) : out_(out) {}
  template <typename T> void pod(const T& v) { raw(&v, sizeof v); }
  void bytes(const void* p, size_t n) { pod<std::uint64_t>(n); raw(p, n); }
  void str(const std::string& s) { bytes(s.data(), s.size()); }
  std::uint64_t size() const { return size_; }
  std::uint32_t crc() const { return crc_; }

 private:
  void raw(const void* p, size_t n) {
    out_.write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
    crc_ = crc_update(crc_, p, n);
    size_ += n;
  }
  std::ofstream& out_;
  std::uint64_t size_ = 0;
  std::uint32_t crc_ = 0;
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
  [[noreturn]] void fail(const std::string& what) { refuse(path_, what); }

 private:
  std::ifstream& in_;
  std::string path_;
};

struct Header {
  std::uint32_t version = 0;
  std::uint64_t payload = 0;
  std::uint32_t crc = 0;
};

// Reads and checks magic and version; leaves `in` at the payload.
Header read_header(std::ifstream& in, const std::string& path) {
  char magic[sizeof kCheckpointMagic];
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kCheckpointMagic, sizeof kCheckpointMagic) != 0)
    refuse(path, "it does not start with SIMSOLS-CKPT");
  Reader r(in, path);
  Header h;
  h.version = r.pod<std::uint32_t>();
  if (h.version == 3 || h.version == 4)
    refuse(path, "format version " + std::to_string(h.version) +
                     ", written before the sliced neighbour lists; this build reads version " +
                     std::to_string(kCheckpointVersion) + ": rerun the run from its scene");
  if (h.version > kCheckpointVersion || h.version < 5)
    refuse(path, "format version " + std::to_string(h.version) + ", this build reads version " +
                     std::to_string(kCheckpointVersion));
  h.payload = r.pod<std::uint64_t>();
  h.crc = r.pod<std::uint32_t>();
  return h;
}

void write_payload(Writer& w, Simulation& sim, const std::string& extra) {
  w.str(to_toml(sim.scene()));
  State& s = sim.state();
  w.pod<std::int64_t>(s.step);
  w.pod<std::int64_t>(s.list_builds);
  w.pod<std::int64_t>(s.next_check);
  w.pod<std::int64_t>(s.late_builds);
  w.pod<std::int32_t>(s.up_slots);
  w.pod<std::int32_t>(s.lo_slots);
  w.pod<std::int32_t>(s.wall_slots);
  std::vector<char> data;
  for (auto& [name, buf] : s.dynamic_buffers()) {
    data.resize(buf->bytes);
    sim.model().device().read(buf->get(), buf->bytes, data.data());
    w.str(name);
    w.bytes(data.data(), data.size());
  }
  // The shares of the last step: not state (every step writes them before
  // reading them), but what the contact forces are read from (contact_list,
  // the force chains), so a loaded run shows the forces it was saved with.
  data.resize(s.share_bytes(sim.model()));
  sim.model().device().read(s.share.get(), data.size(), data.data());
  w.str("share");
  w.bytes(data.data(), data.size());
  w.str(extra);
}

// Versions 5 and 6 stored each history record whole (x, y, z, w of a slot
// together); since version 7 a slice's records go by component (SLOT_REAL in
// common.cl). Regroups every plane of `slots` records; slots past the last
// whole slice are spare and stay zero.
std::vector<char> regroup_slot_records(const std::vector<char>& in, size_t slots, int slice,
                                       size_t real) {
  const size_t plane = 4 * slots * real;  // bytes
  if (slots == 0 || in.size() < plane) return in;  // the stand-in of a run without history
  std::vector<char> out(in.size(), 0);
  for (size_t p = 0; p + plane <= in.size(); p += plane)
    for (size_t s = 0; s < slots; ++s)
      for (int c = 0; c < 4; ++c) {
        const size_t to = slot_real(s, slice, c);
        if (to < 4 * slots) std::memcpy(&out[p + to * real], &in[p + (4 * s + c) * real], real);
      }
  return out;
}

// Version 5 also held the lower slots' partner ids (nbr_lo), which only the
// list build needs: skipped.
void read_buffers(Reader& r, Simulation& sim, std::uint32_t version) {
  State& s = sim.state();
  for (auto& [name, buf] : s.dynamic_buffers()) {
    std::string seen = r.str();
    if (version == 5 && seen == "nbr_lo") {
      r.bytes();
      seen = r.str();
    }
    if (seen != name) r.fail("buffer '" + name + "' missing");
    std::vector<char> data = r.bytes();
    if (version < 7 && name == "spring")
      data = regroup_slot_records(data, size_t(s.up_slots), sim.model().config().slice,
                                  sim.model().real_size());
    if (data.size() != buf->bytes) r.fail("buffer '" + name + "' has the wrong size");
    sim.model().device().write(buf->get(), data.size(), data.data());
  }
  if (version < 8) return;  // no shares saved: the pair forces are known after a step
  if (r.str() != "share") r.fail("buffer 'share' missing");
  const std::vector<char> shares = r.bytes();
  if (shares.size() != s.share_bytes(sim.model())) r.fail("buffer 'share' has the wrong size");
  sim.model().device().write(s.share.get(), shares.size(), shares.data());
}

}  // namespace

void save_checkpoint(Simulation& sim, const std::string& path, const std::string& extra) {
  sim.check();  // never a checkpoint of a state past a runaway (guard.h)
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError("cannot write checkpoint " + tmp);
    out.write(kCheckpointMagic, sizeof kCheckpointMagic);
    out.write(reinterpret_cast<const char*>(&kCheckpointVersion), 4);
    const char placeholder[12] = {};
    out.write(placeholder, sizeof placeholder);  // payload size and CRC, below
    Writer w(out);
    write_payload(w, sim, extra);
    const std::uint64_t size = w.size();
    const std::uint32_t crc = w.crc();
    out.seekp(sizeof kCheckpointMagic + 4);
    out.write(reinterpret_cast<const char*>(&size), sizeof size);
    out.write(reinterpret_cast<const char*>(&crc), sizeof crc);
    out.flush();
    if (!out) {
      out.close();
      std::filesystem::remove(tmp);
      throw IoError("failed writing checkpoint " + tmp + " (disk full?)");
    }
  }
  std::filesystem::rename(tmp, path);
}

std::uint32_t verify_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError("io", path, 0, "", "cannot open checkpoint");
  const Header h = read_header(in, path);
  std::uint32_t crc = 0;
  std::uint64_t seen = 0;
  std::vector<char> chunk(1 << 20);
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    const auto got = static_cast<size_t>(in.gcount());
    crc = crc_update(crc, chunk.data(), got);
    seen += got;
  }
  if (seen != h.payload)
    refuse(path, "its payload is " + std::to_string(seen) + " bytes, the header says " +
                     std::to_string(h.payload) + " (truncated or damaged file)");
  if (crc != h.crc) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "checksum mismatch (CRC-32 %08x, the header says %08x)", crc,
                  h.crc);
    refuse(path, std::string(buf) + ": the file is damaged");
  }
  return h.version;
}

std::unique_ptr<Simulation> load_checkpoint(std::shared_ptr<Device> device, const std::string& path,
                                            std::string* extra) {
  verify_checkpoint(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError("io", path, 0, "", "cannot open checkpoint");
  const std::uint32_t version = read_header(in, path).version;
  Reader r(in, path);
  const std::string text = r.str();
  Scene scene = parse_scene(text, path + " (embedded scene)");
  auto sim = std::make_unique<Simulation>(std::move(device), scene);
  State& s = sim->state();
  s.step = r.pod<std::int64_t>();
  s.time = s.step * sim->dt();
  s.list_builds = r.pod<std::int64_t>();
  s.next_check = r.pod<std::int64_t>();
  s.late_builds = r.pod<std::int64_t>();
  const int up = r.pod<std::int32_t>();
  const int lo = r.pod<std::int32_t>();
  const int walls = r.pod<std::int32_t>();
  // slots come in whole slices (neighbors.cl), so a scene of a few
  // particles on one particle per work item has a slice's worth
  const std::int64_t padded = std::int64_t(s.slices) * sim->model().config().slice;
  const std::int64_t most = padded * 256;  // MAX_CAP in neighbors.cl
  if (up < 0 || lo < 0 || up > most || lo > most)
    r.fail("neighbour-list capacity " + std::to_string(up) + ", " + std::to_string(lo) +
           " out of range (0 to 256 per particle, particles counted in whole slices)");
  if (walls < 0 || walls > padded * 32)
    r.fail("wall-slot capacity " + std::to_string(walls) +
           " out of range (0 to 32 per particle, particles counted in whole slices)");
  s.resize_slots(sim->model(), up, lo, walls);
  read_buffers(r, *sim, version);
  derive_state(sim->model(), sim->state());
  sim->state_replaced();
  const std::string rest = r.str();
  if (extra) *extra = rest;
  return sim;
}

}  // namespace simsols
