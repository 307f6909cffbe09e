// AOVs (arbitrary output variables): the layers beside the beauty that a render can write, and
// what one camera path reports for them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace prism {

enum class Aov : uint32_t {
  Albedo,      // base colour at the first hit
  Normal,      // world-space shading normal at the first hit
  Depth,       // planar camera-space depth of the nearest first hit in the pixel
  Position,    // world-space position of the first hit
  Emission,    // light emitted by what the camera sees directly (surfaces and the sky)
  Direct,      // light reaching the camera after one scattering event
  Indirect,    // light reaching the camera after two or more
  Variance,    // per-channel variance of the beauty's mean
  Spp,         // samples per pixel
  ObjectId,    // index of the nearest first-hit object (-1: none)
  MaterialId,  // index of the nearest first-hit material (-1: none; the default material after the scene's)
  CryptoObject,    // Cryptomatte for objects (node names)
  CryptoMaterial,  // Cryptomatte for materials (material names)
  Count
};

// The depth written where a pixel sees nothing: the EXR holds no infinities (the value Blender
// uses for its own background depth).
inline constexpr float kBackgroundDepth = 1e10f;

class AovSet {
 public:
  bool has(Aov a) const { return bits_ & bit(a); }
  void add(Aov a) { bits_ |= bit(a); }
  bool empty() const { return bits_ == 0; }
  // Any AOV the integrator must report per sample (Variance and Spp come from the film alone).
  bool needs_path_data() const { return bits_ & ~(bit(Aov::Variance) | bit(Aov::Spp)); }
  bool operator==(const AovSet&) const = default;

 private:
  static uint32_t bit(Aov a) { return 1u << uint32_t(a); }
  uint32_t bits_ = 0;
};

// The names --aovs and job files use, in Aov order.
const std::vector<std::string>& aov_names();
const std::string& aov_name(Aov a);
// Parses a comma-separated list ("albedo,normal,depth"; "all" for every AOV). Throws
// std::invalid_argument naming an unknown entry and listing the known ones.
AovSet parse_aovs(const std::string& list);

// What one camera path reports about itself beyond its radiance. The integrator fills it only
// when asked (a non-null pointer), so renders without AOVs pay nothing.
struct AovSample {
  Rgb albedo, emission, direct, indirect;  // emission + direct + indirect = the sample's radiance
  Vec3 normal, position;                   // scene (render-origin) coordinates; zero on a miss
  bool hit = false;
  int object = -1, material = -1;
};

}  // namespace prism
