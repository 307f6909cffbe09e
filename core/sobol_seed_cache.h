// SobolSeedCache: the per-dimension Owen-Sobol seeds of a few pixels, shared by the samplers of a packet's lanes.
#pragma once

#include <cstdint>
#include <vector>

#include "core/hash.h"
#include "core/owen_sobol.h"

namespace prism {

// A dimension's seeds depend on the pixel and the sampler seed, never on the sample index, so
// every sample of a pixel draws the same ones. A packet's lanes take consecutive samples, mostly
// of one pixel: sharing one cache lets the lane that first reaches a dimension hash its seeds for
// all of them (at 16 spp, once per pixel instead of once per lane every other packet). Each entry
// holds one pixel's seeds, filled lazily in dimension order, as arrays owen_sobol_vertex loads
// directly. An entry is counted while a sampler uses it, and only an unused one is given to a
// new pixel, so a cache with as many entries as samplers sharing it never runs short.
class SobolSeedCache {
 public:
  static constexpr uint32_t kDimensions = 64;
  static constexpr uint32_t kPadding = 8;  // owen_sobol_vertex reads eight seeds from a run's start

  struct Entry {
    int x = -1, y = -1;
    uint64_t pixel_hash = 0;
    uint32_t cached = 0;  // dimensions [0, cached) are filled in
    int users = 0;
    uint64_t last_start = 0;  // when a sampler last took it: the least recent unused entry goes first
    uint32_t index[kDimensions + kPadding] = {};
    uint32_t value0[kDimensions + kPadding] = {};
    uint32_t value1[kDimensions + kPadding] = {};
  };

  SobolSeedCache(uint64_t seed, int entries) : seed_(seed), entries_(size_t(entries < 1 ? 1 : entries)) {}

  // The entry of pixel (x, y) for a sampler that held `current` (-1 for none), which it releases.
  int take(int current, int x, int y) {
    if (current >= 0) {
      Entry& e = entries_[size_t(current)];
      if (e.x == x && e.y == y) return current;
      --e.users;
    }
    ++starts_;
    // Consecutive samples are mostly of one pixel: the entry taken last first.
    if (last_ >= 0 && entries_[size_t(last_)].x == x && entries_[size_t(last_)].y == y) return claim(last_);
    int unused = -1;
    for (size_t i = 0; i < entries_.size(); ++i) {
      Entry& e = entries_[i];
      if (e.x == x && e.y == y) return claim(int(i));
      if (e.users == 0 && (unused < 0 || e.last_start < entries_[size_t(unused)].last_start)) unused = int(i);
    }
    if (unused < 0) {  // more samplers than entries: grow (the entries' addresses are not kept)
      entries_.emplace_back();
      unused = int(entries_.size() - 1);
    }
    Entry& e = entries_[size_t(unused)];
    e.x = x;
    e.y = y;
    e.pixel_hash = hash_values(static_cast<uint64_t>(x), static_cast<uint64_t>(y), seed_, 0x50b01ull);
    e.cached = 0;
    return claim(unused);
  }

  void release(int current) {
    if (current >= 0) --entries_[size_t(current)].users;
  }

  Entry& entry(int i) { return entries_[size_t(i)]; }
  uint64_t seed() const { return seed_; }

  // Dimension d's seeds for the entry's pixel. The next dimension not yet cached is stored;
  // dimensions past the cache are hashed each time.
  SobolSeeds seeds(Entry& e, uint32_t d) const {
    if (d < e.cached) return {e.index[d], e.value0[d], e.value1[d]};
    const uint64_t h = hash_combine(e.pixel_hash, d);
    const SobolSeeds s{uint32_t(h), uint32_t(h >> 32), uint32_t(mix64(h))};
    if (d == e.cached && d < kDimensions) {
      e.index[d] = s.index;
      e.value0[d] = s.value0;
      e.value1[d] = s.value1;
      ++e.cached;
    }
    return s;
  }

 private:
  int claim(int i) {
    Entry& e = entries_[size_t(i)];
    ++e.users;
    e.last_start = starts_;
    last_ = i;
    return i;
  }

  uint64_t seed_;
  std::vector<Entry> entries_;
  uint64_t starts_ = 0;
  int last_ = -1;  // the entry claimed last
};

}  // namespace prism
