// Cryptomatte (Psyop spec v1.2): name ids, ranked id/coverage EXR layers, metadata, and reading them back.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/id_counts.h"
#include "io/exr_image.h"

namespace prism {


// MurmurHash3_x86_32 of the bytes of key (Austin Appleby's reference algorithm, little-endian blocks).
uint32_t murmur_hash3_32(std::string_view key, uint32_t seed = 0);

// The Cryptomatte id of a name (its UTF-8 bytes) as float bits: MurmurHash3_32 with seed 0, with the
// lowest exponent bit flipped when the exponent is 0 or 255, so the float is finite and normal.
uint32_t cryptomatte_id_bits(std::string_view name);
float cryptomatte_id(std::string_view name);

// The 7-hex-digit metadata key of a layer ("cryptomatte/<key>/name"): the first 7 of the 8 lower-case
// hex digits of the layer name's id bits, as Psyop's reference tools derive it.
std::string cryptomatte_layer_key(std::string_view layer);


// The rank layers <layer>00, <layer>01, ... (ceil(ranks / 2) of them) as Float channels R, G, B, A:
// id of rank 2k, its coverage, id of rank 2k + 1, its coverage. Coverage is count / samples of the
// pixel; ids rank by coverage (descending), then id (ascending); unused ranks and pixels without
// samples are 0. pixels and samples_per_pixel cover the data window, top row first.
// Throws std::invalid_argument if their sizes differ or ranks < 1.
std::vector<ExrChannel> cryptomatte_channels(const std::string& layer, const std::vector<PixelIdCounts>& pixels,
                                             const std::vector<uint64_t>& samples_per_pixel, int ranks = 6);

// The string attributes cryptomatte/<key>/name (= layer), /hash, /conversion and /manifest: a JSON
// object from each name (once, sorted by name) to the 8 lower-case hex digits of its id bits.
std::vector<ExrAttribute> cryptomatte_attributes(const std::string& layer, const std::vector<std::string>& names);

// The inverse of cryptomatte_channels, to merge partial renders: reads every rank layer <layer>NN
// (NN = 00, 01, ... while <layer>NN.R exists) and turns coverage back into counts,
// llround(coverage * samples); ranks with coverage 0 are skipped. One PixelIdCounts per pixel of the
// data window. Only the ranks stored in the file come back, and float32 coverage gives counts below 2^23
// back exactly (larger ones to within about count * 2^-24). Throws std::runtime_error if a rank layer
// lacks a channel or a channel's size is not the data window's, std::invalid_argument if
// samples_per_pixel does not cover the data window.
std::vector<PixelIdCounts> cryptomatte_counts(const ExrImage& image, const std::string& layer,
                                              const std::vector<uint64_t>& samples_per_pixel);

}  // namespace prism
