#pragma once
// The walk every descriptor's band shares (core/description/level_descriptor.hpp): points in raster
// order read rows [y - reach, y + reach] (clipped to [0, rows)), a window sliding down the level. A
// band of `capacity` rows holds rows [top, end); when a point needs a row below it, the points
// before it are described (describe(first, last, top)), and make_rows(top, new_top, kept_end,
// new_end) moves rows [new_top, kept_end), already made, to the band's start and makes rows
// [kept_end, new_end) after them: every row is made once, in a buffer that stays in cache, and rows
// no point reads are not made.
#include <algorithm>
#include <vector>

#include "core/kernels/pixel_point.hpp"

namespace aief {

template <class MakeRows, class Describe>
void describe_through_sliding_band(const PixelPoint* points, int count, int reach, int rows,
                                   int capacity, MakeRows make_rows, Describe describe) {
  int top = 0, end = 0;
  int first = 0;  // first point not yet described
  for (int i = 0; i < count; ++i) {
    const int y = points[i].y;
    if (std::min(rows, y + reach + 1) <= end) continue;
    if (i > first) describe(first, i, top);
    first = i;
    const int new_top = std::max(0, y - reach);
    const int new_end = std::min(rows, new_top + capacity);
    make_rows(top, new_top, std::max(new_top, end), new_end);
    top = new_top;
    end = new_end;
  }
  if (count > first) describe(first, count, top);
}

}  // namespace aief
