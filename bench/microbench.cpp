// Microbenchmarks of the hot pieces: sampling, BSDF and emitter sampling, and Embree ray queries on
// the Cornell box (the ceiling prism's own Mrays/s is measured against). Prints figures; asserts nothing.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "core/constants.h"
#include "core/distribution_2d.h"
#include "core/light_tree.h"
#include "core/pcg32.h"
#include "core/sampler.h"
#include "core/sobol_sampler.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "bench/ray_workload.h"
#include "core/spawn.h"
#include "io/gltf_loader.h"
#include "materials/bsdf.h"
#include "materials/texture_lookup.h"

namespace prism {
namespace {

// A scene of scenes/, loaded once for each light sampler (benchmarks run one at a time).
const Scene& scene_asset(const std::string& relative, LightSampling how) {
  static std::map<std::pair<std::string, LightSampling>, std::unique_ptr<Scene>> loaded;
  std::unique_ptr<Scene>& scene = loaded[{relative, how}];
  if (!scene) {
    Diagnostics diag;
    scene = std::make_unique<Scene>(load_gltf(PRISM_SOURCE_DIR "/scenes/" + relative, diag), nullptr, how);
  }
  return *scene;
}

const Scene& cornell_box(LightSampling how = LightSampling::Tree) {
  return scene_asset("cornell-box/cornell-box.gltf", how);
}
const Scene& many_lights(LightSampling how = LightSampling::Tree) {
  return scene_asset("many-lights/many-lights.gltf", how);
}

// Rays from random points inside the box in uniformly random directions.
std::vector<Ray> random_rays(size_t n) {
  Pcg32 rng(1, 2);
  std::vector<Ray> rays(n);
  for (Ray& r : rays) {
    r.origin = Vec3(0.05f + 0.45f * rng.next_float(), 0.05f + 0.45f * rng.next_float(), 0.05f + 0.45f * rng.next_float());
    r.dir = sample_uniform_sphere({rng.next_float(), rng.next_float()});
  }
  return rays;
}

// One path's worth of draws in the integrator's pattern: pixel jitter, then per bounce an emitter
// pick, a point on it, a lobe, a direction and a roulette decision (four bounces), drawn one at a
// time (range 0) or a vertex at once (range 1, as the path tracer does).
template <typename SamplerType>
void BM_SamplerPath(benchmark::State& state) {
  SamplerType s(7);
  const bool by_vertex = state.range(0) != 0;
  uint64_t i = 0;
  for (auto _ : state) {
    s.start_pixel_sample(int((i >> 6) & 511), int((i >> 15) & 511), i & 63);
    auto add = [](Vec2 v) { return v.x + v.y; };
    float sum = add(s.next_2d());
    for (int bounce = 0; bounce < 4; ++bounce) {
      if (by_vertex) {
        const VertexSamples v = s.next_vertex();
        sum += v.light_spare + add(v.light_point) + v.lobe + add(v.direction) + v.roulette;
        continue;
      }
      sum += s.next_1d();
      sum += add(s.next_2d());
      sum += s.next_1d();
      sum += add(s.next_2d());
      sum += s.next_1d();
    }
    benchmark::DoNotOptimize(sum);
    ++i;
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * 21);  // dimensions drawn
}
BENCHMARK(BM_SamplerPath<IndependentSampler>)->Arg(0)->Arg(1);
BENCHMARK(BM_SamplerPath<SobolSampler>)->Arg(0)->Arg(1);

// A packet's worth of vertex draws: eight lanes' samplers, each at its own pixel, draw their next
// vertex one after another, as the path tracer does at each bounce (time per packet, for 8 vertices).
template <typename SamplerType>
void BM_SamplerPacketVertices(benchmark::State& state) {
  std::vector<SamplerType> lanes(8, SamplerType(7));
  uint64_t i = 0;
  for (auto _ : state) {
    if (i % 4 == 0)  // a new sample every four bounces
      for (int k = 0; k < 8; ++k) lanes[size_t(k)].start_pixel_sample(k, int((i >> 8) & 511), (i >> 2) & 63);
    float sum = 0;
    for (SamplerType& s : lanes) {
      const VertexSamples v = s.next_vertex();
      sum += v.light_spare + v.light_point.x + v.light_point.y + v.lobe + v.direction.x + v.direction.y + v.roulette;
    }
    benchmark::DoNotOptimize(sum);
    ++i;
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * 8);  // vertices drawn
}
BENCHMARK(BM_SamplerPacketVertices<IndependentSampler>);
BENCHMARK(BM_SamplerPacketVertices<SobolSampler>);

// The glTF BSDF for a given material, at a fixed shading frame and outgoing direction.
void bsdf_sample_benchmark(benchmark::State& state, const SurfaceParams& params) {
  Pcg32 rng(3, 4);
  const Bsdf bsdf(params, normalize(Vec3(0.1f, 0.2f, 1.0f)), Vec3(0, 0, 1), normalize(Vec3(0.3f, -0.1f, 1.0f)), 1.5f);
  for (auto _ : state) benchmark::DoNotOptimize(bsdf.sample(rng.next_float(), {rng.next_float(), rng.next_float()}));
  state.SetItemsProcessed(int64_t(state.iterations()));
}

void BM_BsdfSampleRoughPlastic(benchmark::State& state) {
  SurfaceParams p;
  p.base_color = Rgb(0.5f);
  p.roughness = 0.5f;
  bsdf_sample_benchmark(state, p);
}
BENCHMARK(BM_BsdfSampleRoughPlastic);

void BM_BsdfSampleRoughMetal(benchmark::State& state) {
  SurfaceParams p;
  p.metallic = 1;
  p.roughness = 0.3f;
  bsdf_sample_benchmark(state, p);
}
BENCHMARK(BM_BsdfSampleRoughMetal);

void BM_BsdfSampleRoughGlass(benchmark::State& state) {
  SurfaceParams p;
  p.transmission = 1;
  p.thin_walled = false;
  p.roughness = 0.3f;
  bsdf_sample_benchmark(state, p);
}
BENCHMARK(BM_BsdfSampleRoughGlass);

// One bounce's BSDF work in the path tracer's pattern: build the BSDF for a new outgoing direction,
// evaluate it and its pdf toward a light, then sample the next direction.
void bsdf_bounce_benchmark(benchmark::State& state, const SurfaceParams& params, float eta) {
  Pcg32 rng(3, 4);
  const Vec3 n = normalize(Vec3(0.1f, 0.2f, 1.0f)), ng(0, 0, 1);
  for (auto _ : state) {
    const Vec3 wo = normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 1.0f));
    const Vec3 wl = normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 0.5f));
    const Bsdf bsdf(params, n, ng, wo, eta);
    benchmark::DoNotOptimize(bsdf.evaluate(wl));
    benchmark::DoNotOptimize(bsdf.sample(rng.next_float(), {rng.next_float(), rng.next_float()}));
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
}

// The Cornell box's walls: metallic 0, roughness 1, ior 1 (no specular layer), i.e. Lambertian.
void BM_BsdfBounceLambert(benchmark::State& state) {
  SurfaceParams p;
  p.base_color = Rgb(0.725f, 0.71f, 0.68f);
  p.ior = 1.0f;
  bsdf_bounce_benchmark(state, p, 1.0f);
}
BENCHMARK(BM_BsdfBounceLambert);

// glTF's default dielectric: a GGX specular layer (ior 1.5) over the diffuse base.
void BM_BsdfBounceRoughPlastic(benchmark::State& state) {
  SurfaceParams p;
  p.base_color = Rgb(0.5f);
  p.roughness = 0.5f;
  bsdf_bounce_benchmark(state, p, 1.5f);
}
BENCHMARK(BM_BsdfBounceRoughPlastic);

// The light sampler a benchmark's argument names: 0 tree, 1 power.
LightSampling light_sampler_argument(const benchmark::State& state) {
  return state.range(0) == 0 ? LightSampling::Tree : LightSampling::Power;
}

// Next-event estimation's light choice and point from shading point ref (surface normal n).
void emitter_sample_benchmark(benchmark::State& state, const Vec3& ref, const Vec3& n, const Scene& scene) {
  Pcg32 rng(5, 6);
  for (auto _ : state)
    benchmark::DoNotOptimize(scene.emitters().sample(ref, n, rng.next_float(), {rng.next_float(), rng.next_float()}));
  state.SetItemsProcessed(int64_t(state.iterations()));
}

// From the floor.
void BM_EmitterSample(benchmark::State& state) {
  emitter_sample_benchmark(state, Vec3(0.3f, 0.1f, 0.2f), Vec3(0, 1, 0), cornell_box(light_sampler_argument(state)));
}
BENCHMARK(BM_EmitterSample)->Arg(0)->Arg(1);

// From the top of the left wall, 5 cm under the light's plane: the light (one quad) is sampled
// by solid angle there.
void BM_EmitterSampleNearLight(benchmark::State& state) {
  const Scene& scene = cornell_box(light_sampler_argument(state));
  emitter_sample_benchmark(state, Vec3(0.01f, 0.5f, 0.28f) - scene.origin(), Vec3(1, 0, 0), scene);
}
BENCHMARK(BM_EmitterSampleNearLight)->Arg(0)->Arg(1);

// From the floor of scenes/many-lights, between lamps: the light tree's walk over 64 leaves.
void BM_EmitterSampleManyLights(benchmark::State& state) {
  const Scene& scene = many_lights(light_sampler_argument(state));
  emitter_sample_benchmark(state, Vec3(0.3f, 0.0f, 0.4f) - scene.origin(), Vec3(0, 1, 0), scene);
}
BENCHMARK(BM_EmitterSampleManyLights)->Arg(0)->Arg(1);

// A light tree over small emissive triangles on a wavy sheet (an emissive mesh, as the heavy-mesh
// scene made emissive gives it), picked from random points above the sheet. Args: the sheet's side
// in triangles (1024: a million lights, a tree far larger than the caches; 32: a thousand, one
// that fits them), and how many picks go together (sample_many, as a packet's lanes make them);
// items are picks.
void BM_LightTreePick(benchmark::State& state) {
  const int side = int(state.range(0));
  static std::map<int, LightTree> trees;
  if (!trees.count(side)) {
    std::vector<LightBounds> lights(size_t(side) * size_t(side));
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        LightBounds& b = lights[size_t(y) * size_t(side) + size_t(x)];
        const float h = 0.5f * std::sin(20.0f * float(x) / float(side)) * std::cos(30.0f * float(y) / float(side));
        b.box.extend(Vec3(float(x), 0, float(y)) * (10.0f / float(side)) + Vec3(0, h, 0));
        b.box.extend(Vec3(float(x + 1), 0, float(y + 1)) * (10.0f / float(side)) + Vec3(0, h + 0.01f, 0));
        b.normals = {normalize(Vec3(0.1f * std::cos(20.0f * float(x) / float(side)), 1.0f, 0.0f)), 1.0f};
        b.cos_emit = 0;
        b.power = 1.0 + 0.5 * std::sin(0.1 * x * y);
      }
    trees.emplace(side, LightTree(std::move(lights)));
  }
  const LightTree& tree = trees.at(side);
  const int batch = int(state.range(1));
  Pcg32 rng(7, 8);
  Vec3 p[8], n[8];
  float u[8];
  std::optional<LightTree::Pick> picks[8];
  for (auto _ : state) {
    for (int i = 0; i < batch; ++i) {
      p[i] = {10.0f * rng.next_float(), 1.0f + rng.next_float(), 10.0f * rng.next_float()};
      n[i] = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      u[i] = rng.next_float();
    }
    if (batch == 1)
      picks[0] = tree.sample(p[0], n[0], u[0]);
    else
      tree.sample_many(p, n, u, batch, picks);
    benchmark::DoNotOptimize(picks);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * batch);
  state.counters["node_bytes"] = double(tree.node_bytes());
}
BENCHMARK(BM_LightTreePick)->ArgsProduct({{32, 128, 1024}, {1, 8}});

// An environment map's sampling density, as an HDRI gives it: 2048 x 1024 texels of sky that vary
// by a factor of five, and a sun of 10 x 10 texels 20000 times brighter that takes most of the
// weight. Arg: how many draws go together (Distribution2D::sample's batch, as a packet's lanes
// make them); items are draws (a row, then a texel within it).
void BM_EnvironmentMapSample(benchmark::State& state) {
  constexpr int kWidth = 2048, kHeight = 1024;
  static const Distribution2D map(kWidth, kHeight, [](int y, std::vector<double>& row) {
    Pcg32 rng(uint64_t(y), 3);  // a stream per row: rows are built in parallel
    for (int x = 0; x < kWidth; ++x) {
      const bool sun = x >= 1400 && x < 1410 && y >= 300 && y < 310;
      row[size_t(x)] = (sun ? 20000.0 : 0.2 + 0.8 * rng.next_float()) * std::sin(kPi * (y + 0.5) / kHeight);
    }
  });
  const int batch = int(state.range(0));
  Pcg32 rng(5, 6);
  Vec2 u[8], p[8];
  float pdf[8];
  for (auto _ : state) {
    for (int i = 0; i < batch; ++i) u[i] = {rng.next_float(), rng.next_float()};
    map.sample(u, batch, p, pdf);
    benchmark::DoNotOptimize(p);
    benchmark::DoNotOptimize(pdf);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * batch);
}
BENCHMARK(BM_EnvironmentMapSample)->Arg(1)->Arg(8);

// A bilinear lookup at random uvs in a 2048 x 2048 RGBA texture, as incoherent bounce rays make
// them: Arg 0 holds its texels as 8-bit codes (what prism keeps for PNG and JPEG), Arg 1 as floats.
// The lookups wait on memory: 16 MiB of codes or 64 MiB of floats, against the caches.
void BM_TextureLookup(benchmark::State& state) {
  constexpr int kSize = 2048;
  SceneDesc desc;
  ImageDesc& img = desc.images.emplace_back();
  img.width = img.height = kSize;
  img.channels = 4;
  Pcg32 fill(7, 8);
  if (state.range(0) == 0) {
    img.srgb = true;
    img.bytes.resize(size_t(kSize) * kSize * 4);
    for (uint8_t& b : img.bytes) b = static_cast<uint8_t>(fill.next_u32());
  } else {
    img.texels.resize(size_t(kSize) * kSize * 4);
    for (float& t : img.texels) t = fill.next_float();
  }
  desc.textures.push_back(TextureDesc{0});
  const TextureRef ref{0};
  Pcg32 rng(5, 6);
  for (auto _ : state) benchmark::DoNotOptimize(lookup_texture(desc, ref, {rng.next_float(), rng.next_float()}));
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_TextureLookup)->Arg(0)->Arg(1);

void BM_IntersectRandomRays(benchmark::State& state) {
  const Scene& scene = cornell_box();
  const std::vector<Ray> rays = random_rays(1 << 16);
  size_t i = 0;
  SurfaceHit hit;
  for (auto _ : state) {
    benchmark::DoNotOptimize(scene.intersect(rays[i++ & (rays.size() - 1)], hit));
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_IntersectRandomRays)->ThreadRange(1, 2)->UseRealTime();

void BM_OccludedRandomRays(benchmark::State& state) {
  const Scene& scene = cornell_box();
  std::vector<Ray> rays = random_rays(1 << 16);
  for (Ray& r : rays) r.t_max = 0.3f;
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(scene.occluded(rays[i++ & (rays.size() - 1)]));
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_OccludedRandomRays)->ThreadRange(1, 2)->UseRealTime();

// Raw Embree against prism's own queries, per kind of ray, on the canonical scenes: the raw
// figures are the ceiling for prism's Mrays/s (prism adds instancing, hit reconstruction, alpha
// and sphere callbacks). Items are rays; run with 1 and 2 threads.
enum class RayKind { Camera, Bounce, Shadow };

// The workload's rays of one kind, or null once the benchmark is marked skipped (the scene is
// absent, or it has fewer than `at_least` such rays).
const std::vector<Ray>* workload_rays(benchmark::State& state, const bench::BenchScene& b, RayKind kind, size_t at_least) {
  if (!b.skip_reason.empty()) {
    state.SkipWithError(b.skip_reason.c_str());
    return nullptr;
  }
  const std::vector<Ray>& rays = kind == RayKind::Camera ? b.rays.camera : kind == RayKind::Bounce ? b.rays.bounce : b.rays.shadow;
  if (rays.size() < at_least) {
    state.SkipWithError("too few rays of this kind in the scene");
    return nullptr;
  }
  return &rays;
}

void ray_benchmark(benchmark::State& state, const char* scene_path, RayKind kind, bool raw) {
  const bench::BenchScene& b = bench::bench_scene(scene_path);
  const std::vector<Ray>* workload = workload_rays(state, b, kind, 1);
  if (!workload) return;
  const std::vector<Ray>& rays = *workload;
  // Threads start at different offsets and walk the same list.
  size_t i = size_t(state.thread_index()) * rays.size() / 2;
  SurfaceHit hit;
  for (auto _ : state) {
    const Ray& ray = rays[i];
    if (++i == rays.size()) i = 0;
    if (kind == RayKind::Shadow) benchmark::DoNotOptimize(raw ? bench::raw_occluded(b.raw, ray) : b.scene->occluded(ray));
    else
      benchmark::DoNotOptimize(raw ? bench::raw_intersect(b.raw, ray, kind == RayKind::Camera)
                                   : b.scene->intersect(ray, hit, kind == RayKind::Camera));
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
}

// Raw Embree in packets of 8 and 16 and in streams of 64 consecutive rays of the workload (camera rays
// run along image rows and shadow rays follow them, so neighbours are coherent; bounce rays are
// not). Items are rays. Against ray_benchmark's raw figures this is what packet tracing buys.
enum class Batch { Packet8, Packet16, Stream64 };

void ray_batch_benchmark(benchmark::State& state, const char* scene_path, RayKind kind, Batch batch) {
  const bench::BenchScene& b = bench::bench_scene(scene_path);
  const unsigned n = batch == Batch::Packet8 ? 8 : batch == Batch::Packet16 ? 16 : 64;
  const std::vector<Ray>* workload = workload_rays(state, b, kind, n);
  if (!workload) return;
  const std::vector<Ray>& rays = *workload;
  const size_t batches = rays.size() / n;
  size_t i = size_t(state.thread_index()) * batches / 2;
  const bool coherent = kind == RayKind::Camera;
  for (auto _ : state) {
    const Ray* r = &rays[i * n];
    if (++i == batches) i = 0;
    if (batch == Batch::Packet8)
      benchmark::DoNotOptimize(kind == RayKind::Shadow ? bench::raw_occluded8(b.raw, r, coherent) : bench::raw_intersect8(b.raw, r, coherent));
    else if (batch == Batch::Packet16)
      benchmark::DoNotOptimize(kind == RayKind::Shadow ? bench::raw_occluded16(b.raw, r, coherent)
                                                       : bench::raw_intersect16(b.raw, r, coherent));
    else
      benchmark::DoNotOptimize(kind == RayKind::Shadow ? bench::raw_occluded_stream(b.raw, r, n, coherent)
                                                       : bench::raw_intersect_stream(b.raw, r, n, coherent));
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * n);
}

#define PRISM_RAY_BENCHMARKS(name, path)                                                                      \
  BENCHMARK_CAPTURE(ray_benchmark, name##_camera_raw, path, RayKind::Camera, true)->ThreadRange(1, 2)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_benchmark, name##_camera_prism, path, RayKind::Camera, false)->ThreadRange(1, 2)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_benchmark, name##_bounce_raw, path, RayKind::Bounce, true)->ThreadRange(1, 2)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_benchmark, name##_bounce_prism, path, RayKind::Bounce, false)->ThreadRange(1, 2)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_benchmark, name##_shadow_raw, path, RayKind::Shadow, true)->ThreadRange(1, 2)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_benchmark, name##_shadow_prism, path, RayKind::Shadow, false)->ThreadRange(1, 2)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_batch_benchmark, name##_camera_raw8, path, RayKind::Camera, Batch::Packet8)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_batch_benchmark, name##_bounce_raw8, path, RayKind::Bounce, Batch::Packet8)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_batch_benchmark, name##_shadow_raw8, path, RayKind::Shadow, Batch::Packet8)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_batch_benchmark, name##_camera_raw16, path, RayKind::Camera, Batch::Packet16)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_batch_benchmark, name##_bounce_raw16, path, RayKind::Bounce, Batch::Packet16)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_batch_benchmark, name##_shadow_raw16, path, RayKind::Shadow, Batch::Packet16)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_batch_benchmark, name##_camera_stream64, path, RayKind::Camera, Batch::Stream64)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_batch_benchmark, name##_bounce_stream64, path, RayKind::Bounce, Batch::Stream64)->UseRealTime(); \
  BENCHMARK_CAPTURE(ray_batch_benchmark, name##_shadow_stream64, path, RayKind::Shadow, Batch::Stream64)->UseRealTime();

PRISM_RAY_BENCHMARKS(cornell_box, PRISM_SOURCE_DIR "/scenes/cornell-box/cornell-box.gltf")
PRISM_RAY_BENCHMARKS(heavy_mesh, PRISM_SOURCE_DIR "/scenes/heavy-mesh/heavy-mesh.glb")

}  // namespace
}  // namespace prism

BENCHMARK_MAIN();
