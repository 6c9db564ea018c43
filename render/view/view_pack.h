// ViewPacker: the solver side of the renderer's data path.
//
// The renderer draws beads as sphere impostors coloured by a field and the
// contact forces as segments (force chains). ViewPacker writes what it needs
// into compact float buffers ON THE DEVICE, with the small program of
// kernels/render_pack.cl. That program is built on the first pack (or by
// build()), with the solver's options, so a run that never draws never
// compiles it. The output is any cl_mem of the simulation's context: a plain
// OpenCL buffer, read back once per frame (PoCL, or devices without
// cl_khr_gl_sharing), or a buffer created from a GL buffer, which the caller
// acquires before packing and releases afterwards. ViewPacker knows nothing
// of OpenGL.
//
// Precision: GPUs draw in float, so positions are written relative to a view
// origin near the specimen (by default the centre of the initial packing).
// In float runs the compensated positions (hi + lo) become one float only
// after the origin is taken off, so the packed positions keep float's
// relative precision over the specimen, not over the distance to the model's
// float frame origin. Field values are float, in SI units.
//
// Determinism: the field's min/max and the contact statistics come from
// fixed-order work-group partials, combined on the host (sums in double);
// only the order of the segments, compacted with an atomic counter, may vary
// from one call to the next.
//
// What is packed is the state after the last step: positions, velocities and
// the forces of the last force evaluation (as contact_list() in observe.h).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "solver/core/cl_program.h"
#include "solver/core/simulation.h"

namespace simsols {

// What colours the beads. Values are in SI units (unit_of), per bead:
//   Size          radius
//   Layer         floor((z_ref - z0) / band + 0.5): the horizontal band the
//                 bead's reference position falls in (0, 1, 2...)
//   Speed         |v|
//   Displacement  |x - x_ref|
//   Contacts      touching neighbours and walls
//   Rotation      |omega|
//   Grain         the grain the bead belongs to: c for the members of clump
//                 c (Scene::clumps), C + i for a free sphere i (C = the
//                 number of clumps), so every grain has its own number and
//                 the members of a clump share theirs. Exact in float up to
//                 C + i = 2^24.
//   NonAffine     |u - (A (x_ref - c) + u_mean)|, u = x - x_ref: the
//                 displacement less the affine field that fits all beads'
//                 displacements best (least squares over the beads; c the
//                 reference centroid; affine_fit below). What the
//                 specimen's homogeneous strain does not explain: a shear
//                 band, a sliding block, a rattler.
enum class ColorField { Size, Layer, Speed, Displacement, Contacts, Rotation, Grain, NonAffine };
inline constexpr ColorField kColorFields[] = {
    ColorField::Size,     ColorField::Layer,    ColorField::Speed, ColorField::Displacement,
    ColorField::Contacts, ColorField::Rotation, ColorField::Grain, ColorField::NonAffine};

const char* to_string(ColorField f);  // "size", "layer", "speed", ...
// The field named `s` (as to_string writes it, any case); nullopt otherwise.
std::optional<ColorField> parse_color_field(std::string_view s);
const char* unit_of(ColorField f);    // "m", "", "m/s", "m", "", "rad/s", "", "m" (for legends)
// "size, layer, speed, displacement, contacts, rotation, grain, nonaffine"
// for help and errors; with '|', "size|layer|...|nonaffine" (the lab's script).
std::string color_field_names(char separator = ',');
// The colouring a scene is drawn with when none is asked for: grain for
// scenes with clumps (each grain in its own colour), layer otherwise.
ColorField default_color_field(const Scene& scene);

// The affine displacement field u(x_ref) = A (x_ref - centre) + mean that
// fits displacements u_i = current_i - reference_i best in least squares
// (A by the normal equations, a pseudo-inverse when the reference points
// are coplanar). Both lists absolute, the same length (std::invalid_argument
// otherwise, or when empty).
struct AffineFit {
  double a[3][3] = {};  // A, row-major
  Vec3 centre{}, mean{};
};
AffineFit affine_fit(const std::vector<Vec3>& reference, const std::vector<Vec3>& current);

class ViewPacker {
 public:
  explicit ViewPacker(Simulation& sim);
  ViewPacker(const ViewPacker&) = delete;
  ViewPacker& operator=(const ViewPacker&) = delete;

  // Builds the packing program now (it is otherwise built on the first
  // pack); throws DeviceError with the build log on failure.
  void build();

  int particles() const { return n_; }

  // Packed positions are float, relative to this point (absolute, m).
  // Default: the centre of the bounding box of the scene's initial centres.
  void set_origin(const Vec3& origin);
  const Vec3& origin() const { return origin_; }

  // Reference positions for Displacement and Layer. Default: the scene's
  // initial positions. set_reference() takes the current state (a copy on
  // the device, exact); the other form takes absolute positions, one per
  // bead (std::invalid_argument otherwise).
  void set_reference();
  void set_reference(const std::vector<Vec3>& absolute_positions);

  // Layer = floor((z_ref - z0) / band + 0.5). Default: z0 = the lowest
  // reference centre (followed when the reference changes), band = the mean
  // diameter. Layered specimens pass their layer spacing; once set, z0 and
  // band stay. band must be > 0 (std::invalid_argument).
  void set_layer_bands(double z0, double band);
  double layer_z0() const { return z0_; }
  double layer_band() const { return band_; }

  struct Range { float min = 0, max = 0; };
  // Writes n float4 (x, y, z relative to origin(), radius) to `beads` and n
  // floats (the field, SI units) to `values`; the buffers must hold that
  // much (std::invalid_argument otherwise). Returns the field's min/max.
  Range pack_beads(ColorField field, cl_mem beads, cl_mem values);

  struct ContactStats {
    size_t count = 0;       // segments written: min(total, capacity)
    size_t total = 0;       // touching contacts (bead pairs once, plus bead-wall contacts)
    double mean_force = 0;  // mean |F_n| over all `total` contacts, N
    double max_force = 0;   // N
  };
  // One segment per touching contact of the last force evaluation, 2 float4
  // each: (a.xyz, |F_n|), (b.xyz, kind) relative to origin(), kind 0 for a
  // bead pair and 1 for a bead-wall contact. A bead pair:
  // a, b the centres of the lower and the higher index, F_n the component of
  // the contact force along b - a. A bead-wall contact (when `walls`): a the
  // centre, b the closest point of the wall, F_n the component along b - a.
  // `segments` must hold 2 * capacity float4; capacity > 0
  // (std::invalid_argument otherwise). Segments past the capacity are
  // counted in `total` and the statistics, not written.
  ContactStats pack_contacts(cl_mem segments, size_t capacity, bool walls = true);

  // Host conveniences: temporary device buffers, pack, read back (tests and
  // the renderer's host-copy path).
  struct HostBeads {
    std::vector<float> xyzr;    // 4 per bead
    std::vector<float> values;  // 1 per bead
    Range range;
  };
  HostBeads pack_beads_host(ColorField field);
  struct HostContacts {
    std::vector<float> segments;  // 8 per segment, stats.count segments
    ContactStats stats;
  };
  HostContacts pack_contacts_host(size_t capacity, bool walls = true);

 private:
  void write_reference(const std::vector<Vec3>& absolute_positions);
  void follow_reference_bottom(const std::vector<Vec3>& absolute_positions);
  // The affine field of the current state against the reference (NonAffine);
  // zero for the other fields.
  AffineFit field_fit(ColorField field);

  Simulation& sim_;
  int n_ = 0;
  std::unique_ptr<Program> program_;
  Kernel pack_beads_, pack_contacts_;
  Vec3 origin_{};
  double z0_ = 0, band_ = 0;
  bool user_bands_ = false;
  // reference positions relative to the model origin (+ float compensation),
  // group partials, the segment counter
  Buffer ref_, ref_lo_, bead_partial_, contact_partial_, counter_;
  std::vector<Vec3> ref_host_;  // the reference positions, absolute (NonAffine's fit)
};

}  // namespace simsols
