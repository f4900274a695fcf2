#pragma once
// What the x86 and the NEON form of ic_moments share: the disc as their 32-byte row loads see it
// (byte i of row r's load is pixel x + i - 16 of row y + r - kPatchRadius), and the walk over the
// points, with the scalar reference for a point whose load would start left of its row.
#include <cstdint>

#include "core/kernels/ic_moments.hpp"
#include "simd/simd_support.hpp"

AIEF_SIMD_NAMESPACE_BEGIN

inline constexpr int kDiscRows = 2 * kPatchRadius + 1;

// fill(r, i, u, inside) for byte i of row r's load: u = i - 16 is its column relative to the
// point, `inside` whether the disc holds it.
template <class Fill>
inline void for_each_disc_byte(const Fill& fill) {
  const int* umax = orientation_disc_umax();
  for (int r = 0; r < kDiscRows; ++r) {
    const int v = r - kPatchRadius, reach = umax[v < 0 ? -v : v];
    for (int i = 0; i < 32; ++i) fill(r, i, i - 16, i - 16 >= -reach && i - 16 <= reach);
  }
}

// moments(k, top) writes m10[k] and m01[k] of point k from `top`, the start of its first row's
// load (pixel x - 16 of row y - kPatchRadius).
template <class Moments>
inline void for_each_disc_point(ImageView level, const PixelPoint* points, int n, std::int32_t* m10,
                                std::int32_t* m01, const Moments& moments) {
  for (int k = 0; k < n; ++k) {
    const PixelPoint p = points[k];
    if (p.x < 16) {  // the load starts one pixel left of the disc: stay inside the row
      ic_moments_scalar(level, points + k, 1, m10 + k, m01 + k);
      continue;
    }
    moments(k, level.row(p.y - kPatchRadius) + p.x - 16);
  }
}

AIEF_SIMD_NAMESPACE_END
