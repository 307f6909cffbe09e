// The layers of a rendered EXR: the beauty, the AOVs asked for, and the Cryptomatte layers, from a
// film, with the per-layer pixel types compositors expect.
#pragma once

#include <vector>

#include "core/film.h"
#include "core/scene_desc.h"
#include "io/exr_image.h"

namespace prism {

// The layer each averaged AOV (Film::kAveraged) is written as: its name, its three channel
// suffixes, and whether it holds light (and so takes the beauty's pixel type).
struct AveragedLayer {
  Aov aov;
  const char* layer;
  const char* components;
  bool light;
};
inline constexpr AveragedLayer kAveragedLayers[] = {
    {Aov::Albedo, "albedo", "RGB", false},     {Aov::Normal, "N", "XYZ", false},
    {Aov::Position, "P", "XYZ", false},        {Aov::Emission, "emission", "RGB", true},
    {Aov::Direct, "direct", "RGB", true},      {Aov::Indirect, "indirect", "RGB", true}};

struct LayerOptions {
  // The beauty (R, G, B, A) and the light layers (emission, direct, indirect). Data layers
  // (albedo, N, P, Z, variance, spp, ids, Cryptomatte) are always float.
  ExrPixelType beauty = ExrPixelType::Half;
  int cryptomatte_ranks = 6;
};

// Channel names: R G B A; albedo.R/G/B; N.X/Y/Z; Z; P.X/Y/Z; emission, direct, indirect and
// variance .R/G/B; spp.V; object_id.V and material_id.V (the nearest hit's index as a float, -1
// where nothing was hit); CryptoObjectNN and CryptoMaterialNN .R/G/B/A. An spp layer is also
// written whenever pixels have different counts. Attributes: the Cryptomatte manifests.
// With a null scene the Cryptomatte manifests are left to the caller (prism merge copies them).
void add_render_layers(const Film& film, const SceneDesc* scene, const LayerOptions& options, ExrImage& image);

// Cryptomatte ids of every object and material (SceneDesc::object_name, material_name), for
// Film::set_cryptomatte_ids.
std::vector<uint32_t> object_cryptomatte_ids(const SceneDesc& scene);
std::vector<uint32_t> material_cryptomatte_ids(const SceneDesc& scene);

}  // namespace prism
