// EnvironmentLight: radiance from infinitely far away (constant or an equirectangular map),
// importance-sampled by luminance x sin(theta) so bright sky regions get the samples.
#pragma once

#include "core/distribution_2d.h"
#include "core/scene_desc.h"

namespace prism {

class EnvironmentLight {
 public:
  EnvironmentLight() = default;
  // `desc` must outlive this object.
  explicit EnvironmentLight(const SceneDesc& desc);

  bool present() const { return present_; }
  // Radiance arriving along -w (w points from the scene toward the sky).
  Rgb radiance(const Vec3& w) const;
  // The radiance along -w and the solid-angle density of sample() drawing w, from one mapping of
  // w onto the map (an atan2 and an acos): next-event estimation and MIS need both.
  struct Seen {
    Rgb radiance;
    float pdf = 0;
  };
  Seen seen(const Vec3& w) const;
  // The same, for a map's sky, at the map coordinates of w (direction_to_uv(w)).
  Seen seen_at(Vec2 uv) const { return {map_radiance(uv), map_pdf(uv)}; }
  // True when the sky is an image (not one constant colour).
  bool has_map() const { return image_ != nullptr; }
  // For a map's sky: the map coordinates of the unit vector w, with the texel and the density
  // seen_at() will read there already asked of the cache (their misses overlap other work).
  Vec2 prefetch(const Vec3& w) const;
  // The map's radiance at uv (has_map() only).
  Rgb map_radiance(Vec2 uv) const;
  // A direction toward the sky, and what is seen along it.
  struct Sample {
    Vec3 wi;
    Seen seen;
  };
  Sample sample(Vec2 u) const {
    Sample s;
    sample(&u, 1, &s);
    return s;
  }
  // sample() for each of the n draws u[i], into out[i]: a map's draws go together, stage by stage,
  // so that their cache misses on its density and texels overlap (Distribution2D::sample).
  void sample(const Vec2* u, int n, Sample* out) const;
  float pdf(const Vec3& w) const;
  // Mean radiance luminance over the sphere, for choosing among lights.
  double mean_luminance() const { return mean_luminance_; }

  // Map coordinates of a direction and back (rotation included).
  Vec2 direction_to_uv(const Vec3& w) const;
  Vec3 uv_to_direction(Vec2 uv) const;

 private:
  // The solid-angle density of sampling the map at uv.
  float map_pdf(Vec2 uv) const;

  const ImageDesc* image_ = nullptr;
  Rgb scale_{1, 1, 1};
  float cos_rot_ = 1, sin_rot_ = 0;
  bool present_ = false;
  Distribution2D distribution_;
  double mean_luminance_ = 0;
};

}  // namespace prism
