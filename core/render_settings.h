// RenderSettings: everything that decides the image besides the scene and camera.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/aov.h"
#include "core/pixel_window.h"

namespace prism {

// The most continuations a path may split into at its first vertex (RenderSettings::split): past a
// few the camera sample's own noise (its pixel filter, the first vertex) dominates anyway.
inline constexpr int kMaxSplit = 64;
// RenderSettings::allocation's default: every pixel gets the same count.
inline constexpr const char* kUniformAllocation = "uniform";

struct RenderSettings {
  int width = 0, height = 0;   // 0 = from the camera's aspect ratio (see default_resolution)
  int spp = 64;                // samples per pixel; the most any pixel gets under a time or noise budget
  int max_depth = 8;           // bounces; 0 = emitted light seen directly only
  int max_diffuse_depth = -1;  // non-delta (diffuse and glossy) bounces; -1 = no limit of its own,
                               // 0 = direct light only on such surfaces (mirrors and glass go on)
  int rr_start_depth = 4;      // Russian roulette from this bounce on
  int split = 1;               // continuations of each camera sample past its first vertex (1: none)
  float clamp_indirect = 0;    // > 0: each sample's indirect light is scaled down to this maximum
                               // component (biased, removes fireflies); 0 = off
  // The share of bounce directions at reflecting surfaces aimed at caustic casters (smooth metal
  // and glass) in view, MIS-weighted with the BSDF's own (unbiased); 0 = off.
  float caster_share = 0.25f;
  std::string sampler = "sobol";
  std::string light_sampler = "tree";  // how next-event estimation picks a light: tree or power
  // How textures are read: "bilinear" (the full-size image at every lookup) or "trilinear" (MIP
  // levels chosen by each lookup's ray-cone footprint).
  std::string texture_filter = "bilinear";
  // Budgets beyond a fixed spp, stopping at whichever is met first (0 = not set):
  double time_budget = 0;      // seconds of rendering: progressive passes until spent
  double noise_target = 0;     // relative standard error per pixel: adaptive sampling
  int min_spp = 16;            // samples every pixel gets before the noise target is judged, or
                               // before samples are shared by error
  // How a pass's samples are shared among pixels: "uniform" (the same count each) or "error" (in
  // proportion to each pixel's estimated share of the relMSE, core/error_allocation.h; spp is then
  // the mean).
  std::string allocation = kUniformAllocation;
  uint64_t seed = 0;
  int tile_size = 16;
  int threads = 0;             // 0 = all hardware threads
  double pass_seconds = 0;     // > 0: split a fixed-spp render into passes of about this long (the
                               // bits do not change), so a checkpoint can be written between them
  std::string integrator = "path";
  std::string camera;          // name or index; "" = the first in node order
  // The part of the image rendered (a crop); empty = all of it.
  PixelWindow crop;
  // Sample indices first_sample .. first_sample + spp - 1 of every pixel (a slice of a render
  // split by samples, see prism merge); each pixel's random numbers depend on the index alone.
  uint64_t first_sample = 0;
  AovSet aovs;

  // Whether pixels' sample counts follow the render's own progress (a time budget, a noise target
  // or samples shared by error), so that no fixed slice of sample indices stands for them.
  bool counts_follow_the_render() const {
    return time_budget > 0 || noise_target > 0 || allocation != kUniformAllocation;
  }
};

// Settings given by a job file or on the command line; unset fields leave the settings alone.
struct RenderSettingsOverride {
  std::optional<int> width, height, spp, max_depth, max_diffuse_depth, rr_start_depth, min_spp, threads, split;
  std::optional<float> clamp_indirect, caster_share;
  std::optional<double> time_budget, noise_target;
  std::optional<uint64_t> seed;
  std::optional<std::string> camera, integrator, sampler, light_sampler, allocation, texture_filter;
  std::optional<PixelWindow> crop;
  std::optional<uint64_t> first_sample;
  std::optional<AovSet> aovs;

  void apply_to(RenderSettings& s) const {
    if (width) s.width = *width;
    if (height) s.height = *height;
    if (spp) s.spp = *spp;
    if (max_depth) s.max_depth = *max_depth;
    if (max_diffuse_depth) s.max_diffuse_depth = *max_diffuse_depth;
    if (rr_start_depth) s.rr_start_depth = *rr_start_depth;
    if (min_spp) s.min_spp = *min_spp;
    if (split) s.split = *split;
    if (clamp_indirect) s.clamp_indirect = *clamp_indirect;
    if (caster_share) s.caster_share = *caster_share;
    if (time_budget) s.time_budget = *time_budget;
    if (noise_target) s.noise_target = *noise_target;
    if (threads) s.threads = *threads;
    if (sampler) s.sampler = *sampler;
    if (light_sampler) s.light_sampler = *light_sampler;
    if (texture_filter) s.texture_filter = *texture_filter;
    if (allocation) s.allocation = *allocation;
    if (seed) s.seed = *seed;
    if (camera) s.camera = *camera;
    if (integrator) s.integrator = *integrator;
    if (crop) s.crop = *crop;
    if (first_sample) s.first_sample = *first_sample;
    if (aovs) s.aovs = *aovs;
  }
};

}  // namespace prism
