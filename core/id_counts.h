// Per-pixel sample counts of ids (Cryptomatte's float ids, as bits): coverage = count / samples.
#pragma once

#include <cstdint>
#include <vector>

namespace prism {

struct IdCount {
  uint32_t id;
  uint32_t count;
};
using PixelIdCounts = std::vector<IdCount>;

// Counts `count` more samples of `id`; a pixel sees few ids, so a linear search is cheapest.
inline void add_id_count(PixelIdCounts& pixel, uint32_t id, uint32_t count) {
  for (IdCount& c : pixel)
    if (c.id == id) {
      c.count += count;
      return;
    }
  pixel.push_back({id, count});
}

inline void add_id_sample(PixelIdCounts& pixel, uint32_t id) { add_id_count(pixel, id, 1); }

}  // namespace prism
