// Ray workloads for the Embree microbenchmarks: camera, bounce and shadow rays drawn from a real
// scene, and the same scene as one flat raw Embree BVH (the ceiling prism's own queries approach).
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/ray.h"
#include "core/scene.h"

namespace prism::bench {

struct RayWorkload {
  std::vector<Ray> camera;  // jittered through every pixel of a 256x256 image from the scene's camera
  std::vector<Ray> bounce;  // from camera-ray hits, cosine-distributed about the normal (extension rays)
  std::vector<Ray> shadow;  // from those hits to points drawn on the emitters, as next-event estimation casts
};

struct BenchScene {
  std::unique_ptr<Scene> scene;  // prism's scene (instancing, hit reconstruction, alpha, spheres)
  RTCScene raw = nullptr;        // every triangle baked to world space in one geometry, no callbacks
  RayWorkload rays;
  std::string skip_reason;       // non-empty when the scene file is absent
};

// Loads and prepares a scene once per process; later calls return the cached one.
const BenchScene& bench_scene(const std::string& path);

// Raw Embree queries as prism issues them (rtcIntersect1 / rtcOccluded1, one ray at a time).
bool raw_intersect(RTCScene scene, const Ray& ray, bool coherent);
bool raw_occluded(RTCScene scene, const Ray& ray);
// The same queries eight rays at a time (rtcIntersect8 / rtcOccluded8): how much a wavefront
// design that traces paths in packets could gain. Returns how many of the eight rays hit.
int raw_intersect8(RTCScene scene, const Ray* rays, bool coherent);
int raw_occluded8(RTCScene scene, const Ray* rays, bool coherent);
// Sixteen at a time (rtcIntersect16 / rtcOccluded16), the width of Embree's AVX-512 kernels.
int raw_intersect16(RTCScene scene, const Ray* rays, bool coherent);
int raw_occluded16(RTCScene scene, const Ray* rays, bool coherent);
// A stream of n rays in one call (rtcIntersect1M / rtcOccluded1M), Embree's own reordering.
int raw_intersect_stream(RTCScene scene, const Ray* rays, unsigned n, bool coherent);
int raw_occluded_stream(RTCScene scene, const Ray* rays, unsigned n, bool coherent);

}  // namespace prism::bench
