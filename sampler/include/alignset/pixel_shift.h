#pragma once

// The per-pixel recipe for a renderer that uses aligned sets: every pixel
// with the same direction reads the same set, shifted on the torus by its
// own Cranley-Patterson offset, taken from a hash of the pixel (and of a
// frame or pass seed). A toroidal shift leaves a set's periodogram
// |sum_j exp(-2 pi i v.s_j)|^2 exactly as it was at every integer frequency
// v, so each pixel keeps what the set was optimized for, while the errors of
// neighbouring pixels no longer repeat one another. (Realizations,
// SetRequest::realization, decorrelate further at the price of more sets.)
//
// Header-only; the same numbers on every platform.

#include <cstdint>

#include <alignset/point_set.h>

namespace alignset {

namespace pixel_shift_detail {
inline uint64_t Mix(uint64_t z) {  // SplitMix64's finalizer
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
}  // namespace pixel_shift_detail

// The shift of pixel (x, y) under `seed`: two numbers in [0, 1), each with
// 53 random bits.
inline Point2 PixelShift(uint64_t seed, int64_t x, int64_t y) {
  using pixel_shift_detail::Mix;
  const uint64_t h = Mix(Mix(Mix(seed) ^ static_cast<uint64_t>(x)) ^ static_cast<uint64_t>(y));
  return {static_cast<double>(h >> 11) * 0x1.0p-53,
          static_cast<double>(Mix(h) >> 11) * 0x1.0p-53};
}

// p + shift, wrapped into [0, 1) (both inputs in [0, 1)).
inline Point2 ShiftPoint(Point2 p, Point2 shift) {
  double x = p.x + shift.x, y = p.y + shift.y;
  if (x >= 1.0) x -= 1.0;
  if (y >= 1.0) y -= 1.0;
  return {x, y};
}

}  // namespace alignset
