// Packing host doubles into device records.
//
// Device buffers hold `real` (float or double, chosen at kernel build) and,
// for float runs, float compensation terms. RealPacker appends values in the
// device's precision; put_float always appends a float.
#pragma once

#include <cstring>
#include <vector>

namespace simsols {

// What a float cannot hold of x, as a float: x - float(x), the compensation
// term of float runs (kernels/common.cl). Not inlined on purpose: GCC 12's
// SLP vectorizer (-O2 and above) folded the float round trip of the inline
// expression `x - static_cast<float>(x)` to 0 for pairs of components, so
// beads far from the float frame's origin lost up to half a float step of
// their initial position (found by the stability suite, docs/stability.md).
[[gnu::noinline]] inline float float_remainder(double x) {
  const float hi = static_cast<float>(x);
  return static_cast<float>(x - static_cast<double>(hi));
}

class RealPacker {
 public:
  explicit RealPacker(bool as_double) : dbl_(as_double) {}
  void put(double v) { dbl_ ? append(v) : append(static_cast<float>(v)); }
  void put4(double a, double b, double c, double d) { put(a); put(b); put(c); put(d); }
  void put_float4(double a, double b, double c, double d) {
    for (double v : {a, b, c, d}) append(static_cast<float>(v));
  }
  const std::vector<unsigned char>& bytes() const { return bytes_; }
  const unsigned char* data() const { return bytes_.data(); }
  size_t size() const { return bytes_.size(); }

 private:
  template <typename T> void append(T v) {
    const size_t at = bytes_.size();
    bytes_.resize(at + sizeof v);
    std::memcpy(bytes_.data() + at, &v, sizeof v);
  }
  bool dbl_;
  std::vector<unsigned char> bytes_;
};

}  // namespace simsols
