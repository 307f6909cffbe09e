#include "bench/ray_workload.h"

#include <filesystem>
#include <map>
#include <mutex>

#include "core/embree_device.h"
#include "core/embree_rays.h"
#include "core/frame.h"
#include "core/pcg32.h"
#include "core/render_origin.h"
#include "core/sampling.h"
#include "core/spawn.h"
#include "io/diagnostics.h"
#include "io/scene_source.h"

namespace prism::bench {
namespace {

RTCIntersectContext context_for(bool coherent) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  return context;
}

RTCScene build_raw(const SceneDesc& desc) {
  std::vector<float> vertices;
  std::vector<uint32_t> indices;
  for (const InstanceDesc& inst : desc.instances)
    for (const PrimitiveDesc& prim : desc.meshes[size_t(inst.mesh)].primitives) {
      const auto base = uint32_t(vertices.size() / 3);
      for (const Vec3& p : prim.positions) {
        const Vec3 w = inst.object_to_world.point(p);
        vertices.insert(vertices.end(), {w.x, w.y, w.z});
      }
      for (uint32_t i : prim.indices) indices.push_back(base + i);
    }
  RTCScene scene = rtcNewScene(embree_device());
  RTCGeometry geom = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), vertices.size() / 3 + 1));
  std::copy(vertices.begin(), vertices.end(), v);
  auto* ix = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), indices.size() / 3));
  std::copy(indices.begin(), indices.end(), ix);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  return scene;
}

RayWorkload make_workload(const Scene& scene, const CameraDesc& cam_desc) {
  RayWorkload w;
  const int size = 256;
  const Camera camera(cam_desc, size, size);
  Pcg32 rng(11, 12);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const Ray ray = camera.generate_ray(float(x) + rng.next_float(), float(y) + rng.next_float());
      w.camera.push_back(ray);
      SurfaceHit hit;
      if (!scene.intersect(ray, hit)) continue;
      const Vec3 n = dot(hit.ng, ray.dir) < 0 ? hit.ng : -hit.ng;
      const Frame frame = Frame::from_normal(n);
      w.bounce.push_back(spawn_ray(hit, frame.to_world(sample_cosine_hemisphere({rng.next_float(), rng.next_float()}))));
      if (scene.emitters().empty()) continue;
      const EmitterSample ls = scene.emitters().sample(hit.p, n, rng.next_float(), {rng.next_float(), rng.next_float()});
      if (!(ls.pdf > 0) || ls.delta || ls.infinite) continue;
      w.shadow.push_back(spawn_ray_between(hit, ls.p, ls.p_error, ls.n));
    }
  return w;
}

}  // namespace

const BenchScene& bench_scene(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<BenchScene>> cache;
  std::lock_guard lock(mutex);
  auto& entry = cache[path];
  if (entry) return *entry;
  entry = std::make_unique<BenchScene>();
  if (!std::filesystem::exists(path)) {
    entry->skip_reason = path + " is absent (scripts/bench generates it)";
    return *entry;
  }
  Diagnostics diag;
  LoadedScene loaded = load_scene_source(path, diag, {});
  // The raw ceiling traces the same coordinates prism renders in.
  move_origin(loaded.scene, choose_render_origin(loaded.scene));
  const CameraDesc cam = select_camera(loaded.scene, "");
  entry->raw = build_raw(loaded.scene);
  entry->scene = std::make_unique<Scene>(std::move(loaded.scene));
  entry->rays = make_workload(*entry->scene, cam);
  return *entry;
}

bool raw_intersect(RTCScene scene, const Ray& ray, bool coherent) {
  RTCIntersectContext context = context_for(coherent);
  RTCRayHit rh = to_embree(ray);
  rtcIntersect1(scene, &context, &rh);
  return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

bool raw_occluded(RTCScene scene, const Ray& ray) {
  RTCIntersectContext context = context_for(false);
  RTCRay r = to_embree(ray).ray;
  rtcOccluded1(scene, &context, &r);
  return r.tfar < 0;
}

int raw_intersect8(RTCScene scene, const Ray* rays, bool coherent) {
  RTCIntersectContext context = context_for(coherent);
  alignas(32) RTCRayHit8 rh;
  alignas(32) int valid[kEmbreePacketSize];
  fill_packet(rh, valid, rays, kEmbreePacketSize);
  rtcIntersect8(valid, scene, &context, &rh);
  int hits = 0;
  for (int k = 0; k < kEmbreePacketSize; ++k) hits += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
  return hits;
}

int raw_occluded8(RTCScene scene, const Ray* rays, bool coherent) {
  RTCIntersectContext context = context_for(coherent);
  alignas(32) RTCRay8 r;
  alignas(32) int valid[kEmbreePacketSize];
  fill_packet(r, valid, rays, kEmbreePacketSize);
  rtcOccluded8(valid, scene, &context, &r);
  int hits = 0;
  for (int k = 0; k < kEmbreePacketSize; ++k) hits += r.tfar[k] < 0;
  return hits;
}

int raw_intersect16(RTCScene scene, const Ray* rays, bool coherent) {
  RTCIntersectContext context = context_for(coherent);
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[16];
  fill_packet_lanes(rh.ray, valid, rays, 16);
  for (int k = 0; k < 16; ++k) rh.hit.geomID[k] = rh.hit.primID[k] = rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect16(valid, scene, &context, &rh);
  int hits = 0;
  for (int k = 0; k < 16; ++k) hits += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
  return hits;
}

int raw_occluded16(RTCScene scene, const Ray* rays, bool coherent) {
  RTCIntersectContext context = context_for(coherent);
  alignas(64) RTCRay16 r;
  alignas(64) int valid[16];
  fill_packet_lanes(r, valid, rays, 16);
  rtcOccluded16(valid, scene, &context, &r);
  int hits = 0;
  for (int k = 0; k < 16; ++k) hits += r.tfar[k] < 0;
  return hits;
}

int raw_intersect_stream(RTCScene scene, const Ray* rays, unsigned n, bool coherent) {
  RTCIntersectContext context = context_for(coherent);
  thread_local std::vector<RTCRayHit> rh;
  rh.resize(n);
  for (unsigned i = 0; i < n; ++i) rh[i] = to_embree(rays[i]);
  rtcIntersect1M(scene, &context, rh.data(), n, sizeof(RTCRayHit));
  int hits = 0;
  for (unsigned i = 0; i < n; ++i) hits += rh[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
  return hits;
}

int raw_occluded_stream(RTCScene scene, const Ray* rays, unsigned n, bool coherent) {
  RTCIntersectContext context = context_for(coherent);
  thread_local std::vector<RTCRay> r;
  r.resize(n);
  for (unsigned i = 0; i < n; ++i) r[i] = to_embree(rays[i]).ray;
  rtcOccluded1M(scene, &context, r.data(), n, sizeof(RTCRay));
  int hits = 0;
  for (unsigned i = 0; i < n; ++i) hits += r[i].tfar < 0;
  return hits;
}

}  // namespace prism::bench
