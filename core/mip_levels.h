// MIP levels: an image's successively halved copies, box-filtered in linear values, for texture
// lookups whose footprint covers many texels (Williams 1983, "Pyramidal parametrics").
#pragma once

#include <string>

#include "core/image_desc.h"
#include "core/scene_desc.h"

namespace prism {

// Fills image.mips: level k+1 is max(1, w/2) x max(1, h/2) and each of its texels is the mean of
// the 2x2 (3 wide or high where a size is odd) texels of level k it covers, averaged in linear
// values, down to 1x1. Levels of an image held as 8- or 16-bit codes are held as codes again, each
// the code whose decoded value is nearest the mean (each level from the rounded one before: an 8K
// image's first level in floats alone would take 200 MiB); every other image's levels are floats.
void build_mip_levels(ImageDesc& image);

// Builds the MIP levels of every image a material reads through a filtered texture slot (all but
// the emissive one, which is read at full size). Checks the memory they add first: throws
// MemoryLimitError naming `source` when the images with their levels would exceed the limit.
void build_texture_mips(SceneDesc& scene, const std::string& source);

// The 8-bit code whose decoded value in `codes` (a rising table: kSrgbCodes or kLinearCodes) is
// nearest to v.
uint8_t nearest_code(const std::array<float, 256>& codes, float v);

}  // namespace prism
