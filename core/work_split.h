// Splitting one render into parts for many machines: sample ranges, image tiles, groups of frames.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/pixel_window.h"

namespace prism {

struct SampleRange {
  uint64_t first = 0, count = 0;
  bool operator==(const SampleRange&) const = default;
};

// `parts` consecutive ranges covering samples 0 .. spp-1, their sizes differing by at most one.
// Requires 1 <= parts <= spp.
std::vector<SampleRange> split_samples(uint64_t spp, int parts);

// `parts` tiles covering a width x height image exactly, in rows top to bottom, each row left to
// right: the grid of columns x rows = parts whose tiles are closest to square (a prime count gives
// strips along the longer side). Requires 1 <= parts <= width * height.
std::vector<PixelWindow> split_tiles(int width, int height, int parts);

// `parts` groups of consecutive indices 0 .. count-1 (frames of a batch), sizes differing by at
// most one. Requires 1 <= parts <= count.
std::vector<std::vector<size_t>> split_frames(size_t count, int parts);

}  // namespace prism
