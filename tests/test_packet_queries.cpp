// Packet queries (Scene::intersect_packet / occluded_packet) answer exactly what the one-ray
// queries answer, lane by lane, through every kind of geometry and callback prism gives Embree:
// baked and instanced meshes, spheres (user geometry), alpha MASK and BLEND filters, and rays that
// skip the triangle they leave.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include "core/arctangent.h"
#include "core/cpu_features.h"
#include "core/embree_rays.h"
#include "core/pcg32.h"
#include "core/sobol_sampler.h"
#include "integrators/lane_spherical_triangle.h"
#include "integrators/path_integrator.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "core/spawn.h"
#include "materials/bsdf.h"
#include "materials/material_eval.h"
#include "scene_builders.h"

namespace prism {
namespace {

SceneDesc packet_test_scene() {
  SceneDesc desc;
  const int wall = test::add_material(desc, Rgb(0.5f));
  test::add_inward_box(desc, Vec3(-2), Vec3(2), wall);
  // One mesh placed twice: instanced, not baked.
  const int block = test::add_box(desc, Vec3(-0.3f), Vec3(0.3f), test::add_material(desc, Rgb(0.3f)));
  desc.instances[size_t(block)].object_to_world = Transform::translate(Vec3(-1, -1, 0));
  InstanceDesc second;
  second.mesh = block;
  second.object_to_world = Transform::translate(Vec3(1, -1, 0.5f)) * Transform::rotate_quaternion(0, 0.38268343, 0, 0.92387953);
  desc.instances.push_back(second);
  // A 50%-opaque BLEND sheet and a sphere behind MASK (cut out) and BLEND alpha.
  const int blend = test::add_material(desc, Rgb(0.2f));
  desc.materials[size_t(blend)].base_alpha = 0.5f;
  desc.materials[size_t(blend)].alpha_mode = MaterialDesc::AlphaMode::Blend;
  test::add_quad(desc, Vec3(-1.5f, 0.5f, -1.5f), Vec3(3, 0, 0), Vec3(0, 0, 3), blend);
  const int masked = test::add_material(desc, Rgb(0.7f));
  desc.materials[size_t(masked)].base_alpha = 0.2f;
  desc.materials[size_t(masked)].alpha_mode = MaterialDesc::AlphaMode::Mask;
  test::add_sphere(desc, Vec3(0.8f, 1.2f, -0.8f), 0.4f, masked);
  test::add_sphere(desc, Vec3(-0.8f, 1.2f, 0.8f), 0.5f, blend);
  test::add_sphere(desc, Vec3(0, -1.2f, -1), 0.5f, wall);
  return desc;
}

void expect_same_hit(const SurfaceHit& a, const SurfaceHit& b) {
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.p, b.p);
  EXPECT_EQ(a.ng, b.ng);
  EXPECT_EQ(a.material, b.material);
  EXPECT_EQ(a.object, b.object);
  EXPECT_EQ(a.triangle.instance, b.triangle.instance);
  EXPECT_EQ(a.triangle.geometry, b.triangle.geometry);
  EXPECT_EQ(a.triangle.primitive, b.triangle.primitive);
}

TEST(PacketQueries, AgreeWithSingleRaysLaneByLane) {
  const Scene scene(packet_test_scene(), &material_alpha);
  Pcg32 rng(21, 22);
  int hits_compared = 0, spawned = 0, blocked = 0;
  for (int round = 0; round < 400; ++round) {
    // Packets of every width, and runs of rays longer than a packet (traced as several), of
    // camera-like rays from inside the box and the rays spawned from their hits (which skip the
    // triangle they leave) and shadow rays between two hits.
    constexpr int kMaxRays = 2 * Scene::kPacketSize + 3;
    const int n = 1 + round % kMaxRays;
    Ray rays[kMaxRays], next[kMaxRays], shadow[kMaxRays];
    for (int k = 0; k < n; ++k)
      rays[k] = Ray{Vec3(3.6f * rng.next_float() - 1.8f, 3.6f * rng.next_float() - 1.8f, 1.9f),
                    sample_uniform_sphere({rng.next_float(), rng.next_float()})};
    SurfaceHit hits[kMaxRays];
    bool found[kMaxRays];
    scene.intersect_packet(rays, n, hits, found, round % 2 == 0);
    for (int k = 0; k < n; ++k) {
      SurfaceHit single;
      ASSERT_EQ(found[k], scene.intersect(rays[k], single)) << "round " << round << " lane " << k;
      next[k] = rays[k];
      shadow[k] = rays[k];
      if (!found[k]) continue;
      expect_same_hit(hits[k], single);
      ++hits_compared;
      const Vec3 n_side = dot(hits[k].ng, rays[k].dir) < 0 ? hits[k].ng : -hits[k].ng;
      next[k] = spawn_ray(hits[k], normalize(n_side + sample_uniform_sphere({rng.next_float(), rng.next_float()})));
      shadow[k] = spawn_ray_between(hits[k], Vec3(0, 1.9f, 0), Vec3(0.0f), Vec3(0, -1, 0));
      spawned += next[k].leaves.valid();
    }
    SurfaceHit next_hits[kMaxRays];
    bool next_found[kMaxRays], occluded[kMaxRays];
    scene.intersect_packet(next, n, next_hits, next_found);
    scene.occluded_packet(shadow, n, occluded);
    for (int k = 0; k < n; ++k) {
      SurfaceHit single;
      ASSERT_EQ(next_found[k], scene.intersect(next[k], single)) << "round " << round << " lane " << k;
      if (next_found[k]) expect_same_hit(next_hits[k], single);
      EXPECT_EQ(occluded[k], scene.occluded(shadow[k])) << "round " << round << " lane " << k;
      blocked += occluded[k];
    }
  }
  // The rays did exercise what they were meant to.
  EXPECT_GT(hits_compared, 1000);
  EXPECT_GT(spawned, 1000);
  EXPECT_GT(blocked, 100);
}

// Every lane of a packet of paths traced in lockstep must come out exactly as the same path traced
// alone, AOVs included; split: the path tracer's continuations per camera sample.
void expect_paths_in_lockstep_match_paths_alone(const Scene& scene, int split = 1) {
  SCOPED_TRACE("split " + std::to_string(split));
  PathIntegrator path(8, 3);
  path.set_split(split);
  Pcg32 rng(31, 32);
  RayCounters packed_counters, alone_counters;
  constexpr int kMaxPaths = Integrator::kPathsInLockstep + 3;  // more than li_packet takes in lockstep
  for (int round = 0; round < 300; ++round) {
    const int n = 1 + round % kMaxPaths;
    Ray rays[kMaxPaths];
    std::vector<SobolSampler> lane_samplers(kMaxPaths, SobolSampler(5));
    Sampler* samplers[kMaxPaths];
    AovSample aov[kMaxPaths];
    AovSample* aovs[kMaxPaths];
    for (int k = 0; k < n; ++k) {
      rays[k] = Ray{Vec3(3.6f * rng.next_float() - 1.8f, 3.6f * rng.next_float() - 1.8f, 1.9f),
                    sample_uniform_sphere({rng.next_float(), rng.next_float()})};
      lane_samplers[k].start_pixel_sample(round, 0, uint64_t(k));
      samplers[k] = &lane_samplers[k];
      aovs[k] = &aov[k];
    }
    RadianceSample out[kMaxPaths];
    path.li_packet(scene, rays, samplers, n, packed_counters, aovs, out);
    for (int k = 0; k < n; ++k) {
      SobolSampler alone_sampler(5);
      alone_sampler.start_pixel_sample(round, 0, uint64_t(k));
      AovSample alone_aov;
      const RadianceSample alone = path.li(scene, rays[k], alone_sampler, alone_counters, &alone_aov);
      ASSERT_EQ(out[k].radiance, alone.radiance) << "round " << round << " lane " << k;
      EXPECT_EQ(out[k].alpha, alone.alpha);
      EXPECT_EQ(aov[k].direct, alone_aov.direct);
      EXPECT_EQ(aov[k].indirect, alone_aov.indirect);
      EXPECT_EQ(aov[k].emission, alone_aov.emission);
      EXPECT_EQ(aov[k].normal, alone_aov.normal);
      EXPECT_EQ(aov[k].object, alone_aov.object);
    }
  }
  EXPECT_EQ(packed_counters.camera, alone_counters.camera);
  EXPECT_EQ(packed_counters.extension, alone_counters.extension);
  EXPECT_EQ(packed_counters.shadow, alone_counters.shadow);
  EXPECT_GT(packed_counters.shadow, 1000u);
  EXPECT_GT(packed_counters.extension, 1000u);
}

// The same paths with part of their vertices' work in SIMD lanes (lane_vertices)
// and without: the same bits, lane by lane, and the same rays counted. Returns how many shadow rays
// were cast. caster_share, split: as the integrator's (0: no bounce is aimed at casters; 1: no
// splitting).
uint64_t expect_lanes_match_scalar_paths(const Scene& scene, int rounds = 200, float caster_share = 0, int split = 1) {
  SCOPED_TRACE("split " + std::to_string(split));
  PathIntegrator lanes(8, 3, -1, 0, caster_share), alone(8, 3, -1, 0, caster_share);
  alone.set_lanes(false);
  lanes.set_split(split);
  alone.set_split(split);
  Pcg32 rng(41, 42);
  RayCounters lane_counters, alone_counters;
  constexpr int kMaxPaths = Integrator::kPathsInLockstep + 3;
  for (int round = 0; round < rounds; ++round) {
    const int n = 1 + round % kMaxPaths;
    Ray rays[kMaxPaths];
    std::vector<SobolSampler> lane_samplers(kMaxPaths, SobolSampler(7)), alone_samplers(kMaxPaths, SobolSampler(7));
    Sampler *lane_sampler[kMaxPaths], *alone_sampler[kMaxPaths];
    AovSample lane_aov[kMaxPaths], alone_aov[kMaxPaths];
    AovSample *lane_aovs[kMaxPaths], *alone_aovs[kMaxPaths];
    for (int k = 0; k < n; ++k) {
      rays[k] = Ray{Vec3(3.6f * rng.next_float() - 1.8f, 3.6f * rng.next_float() - 1.8f, 1.9f),
                    sample_uniform_sphere({rng.next_float(), rng.next_float()})};
      lane_samplers[k].start_pixel_sample(round, 1, uint64_t(k));
      alone_samplers[k].start_pixel_sample(round, 1, uint64_t(k));
      lane_sampler[k] = &lane_samplers[k];
      alone_sampler[k] = &alone_samplers[k];
      lane_aovs[k] = &lane_aov[k];
      alone_aovs[k] = &alone_aov[k];
    }
    RadianceSample lane_out[kMaxPaths], alone_out[kMaxPaths];
    lanes.li_packet(scene, rays, lane_sampler, n, lane_counters, lane_aovs, lane_out);
    alone.li_packet(scene, rays, alone_sampler, n, alone_counters, alone_aovs, alone_out);
    for (int k = 0; k < n; ++k) {
      EXPECT_EQ(lane_out[k].radiance, alone_out[k].radiance) << "round " << round << " lane " << k;
      EXPECT_EQ(lane_aov[k].direct, alone_aov[k].direct) << "round " << round << " lane " << k;
      EXPECT_EQ(lane_aov[k].indirect, alone_aov[k].indirect) << "round " << round << " lane " << k;
    }
    if (::testing::Test::HasFailure()) return 0;
  }
  EXPECT_EQ(lane_counters.extension, alone_counters.extension);
  EXPECT_EQ(lane_counters.shadow, alone_counters.shadow);
  return lane_counters.shadow;
}

// Paths in lockstep through glass with absorption (a medium stack), alpha, spheres, an emitter and
// instanced meshes.
SceneDesc lockstep_test_scene() {
  SceneDesc desc = packet_test_scene();
  const int glass = test::add_glass(desc, 1.5f, Rgb(0.6f, 0.8f, 0.9f));
  test::add_sphere(desc, Vec3(0.6f, 0, 0.6f), 0.4f, glass);
  test::add_box(desc, Vec3(-1.2f, 0.2f, 0.9f), Vec3(-0.6f, 0.8f, 1.5f), glass);
  return desc;
}

TEST(PacketQueries, PathsInLockstepMatchPathsAlone) {
  SceneDesc desc = lockstep_test_scene();
  const int light = test::add_material(desc, Rgb(0.0f), Rgb(8.0f));
  test::add_quad(desc, Vec3(-0.5f, 1.99f, -0.5f), Vec3(1, 0, 0), Vec3(0, 0, 1), light);  // facing down
  const Scene scene(std::move(desc), &material_alpha);
  ASSERT_FALSE(scene.emitters().picks_ahead());
  expect_paths_in_lockstep_match_paths_alone(scene);
  expect_paths_in_lockstep_match_paths_alone(scene, 3);
}

// The lanes give the scalar code's bits: Lambertian walls and blocks lit by a quad seen from far
// and near (where it is sampled by solid angle instead) and from behind (nothing to sample), by
// a double-sided triangle, and by a quad whose emission is a texture (left to the scalar code);
// paths through glass with absorption and past alpha-blended sheets and spheres (not the lanes'
// case) in the same packets.
SceneDesc lanes_test_scene() {
  SceneDesc desc = lockstep_test_scene();
  const int lamp = test::add_material(desc, Rgb(0.0f), Rgb(8.0f, 6.0f, 4.0f));
  test::add_quad(desc, Vec3(-0.5f, 1.99f, -0.5f), Vec3(1, 0, 0), Vec3(0, 0, 1), lamp);  // facing down
  const int both_faces = test::add_material(desc, Rgb(0.0f), Rgb(1.0f, 3.0f, 2.0f), true);
  PrimitiveDesc triangle;
  triangle.positions = {Vec3(1.9f, -1.5f, -1.5f), Vec3(1.9f, -1.5f, -0.5f), Vec3(1.5f, -0.7f, -1.0f)};
  triangle.indices = {0, 1, 2};
  triangle.material = both_faces;
  test::add_mesh(desc, std::move(triangle));
  ImageDesc& stripes = desc.images.emplace_back();  // two texels: orange and blue
  stripes.width = 2;
  stripes.height = 1;
  stripes.channels = 3;
  stripes.texels = {4, 2, 0.5f, 0.5f, 1, 4};
  desc.textures.push_back({.image = int(desc.images.size()) - 1, .nearest = true});
  const int painted = test::add_material(desc, Rgb(0.0f), Rgb(1.0f), true);
  desc.materials[size_t(painted)].emissive_texture.texture = int(desc.textures.size()) - 1;
  test::add_quad(desc, Vec3(-1.95f, -1.0f, -1.5f), Vec3(0, 1, 0), Vec3(0, 0, 1), painted);
  return desc;
}

TEST(Lanes, GiveTheScalarPathsBitsLaneByLane) {
  const Scene scene(lanes_test_scene(), &material_alpha);
  ASSERT_GT(scene.emitters().size(), 2u);
  EXPECT_GT(expect_lanes_match_scalar_paths(scene), 2000u);
}

// A batch's light samples taken in AVX2 (where the CPU has it) and in SSE pairs.
struct LightLanes {
  explicit LightLanes(const LaneVertexBatch& batch) {
    LaneBounce unasked[LaneVertexBatch::kLanes];
    lane_vertices(batch, avx2, unasked);
    lane_vertices(batch, sse, unasked, false);
  }
  LaneLightResult avx2[LaneVertexBatch::kLanes], sse[LaneVertexBatch::kLanes];
};

// The lanes' shadow rays are spawn_ray_between's, bit for bit, wherever the points are: at and near
// zero (where the offset steps from -0 and crosses signs), far from the origin, with normals along
// an axis (offsets of zero) and in general directions, lit from either side; with AVX2 and without.
TEST(Lanes, ShadowRaysAreSpawnRayBetweens) {
  Pcg32 rng(43, 44);
  const float magnitudes[] = {0.0f, 1e-30f, 1e-3f, 1.0f, 3e4f};
  const auto coordinate = [&] {
    const float m = magnitudes[rng.next_u32() % 5];
    return (rng.next_float() < 0.5f ? -m : m) * (rng.next_float() < 0.2f ? 1.0f : rng.next_float());
  };
  const auto point = [&] { return Vec3(coordinate(), coordinate(), coordinate()); };
  const auto direction = [&] {
    if (rng.next_float() < 0.5f) {
      Vec3 axis(0.0f);
      axis[int(rng.next_u32() % 3)] = rng.next_float() < 0.5f ? -1.0f : 1.0f;
      return axis;
    }
    return sample_uniform_sphere({rng.next_float(), rng.next_float()});
  };
  int compared = 0;
  for (int round = 0; round < 2000; ++round) {
    const int n = 1 + round % LaneVertexBatch::kLanes;
    LaneVertexBatch batch;
    Emitters::Emitter light[LaneVertexBatch::kLanes];
    Emitters::TriangleDraw draw[LaneVertexBatch::kLanes];
    Emitters::LaneRecord record[LaneVertexBatch::kLanes];
    SurfaceHit from[LaneVertexBatch::kLanes];
    for (int k = 0; k < n; ++k) {
      from[k].p = point();
      from[k].p_error = abs(point()) * 1e-6f;
      from[k].ng = direction();
      from[k].triangle = {1, 2, uint32_t(k)};
      Emitters::Emitter& e = light[k];
      e.p0 = point();
      e.p1 = e.p0 + Vec3(rng.next_float(), 0, 0);
      e.p2 = e.p0 + Vec3(0, 0, rng.next_float());
      e.normal = Vec3(0, rng.next_float() < 0.5f ? -1.0f : 1.0f, 0);
      e.quad_slack = rng.next_float() < 0.5f ? 0.0f : 1e-7f;
      e.area = 1;
      e.double_sided = true;
      record[k] = Emitters::lane_record(e, Rgb(1.0f));
      draw[k] = {.light = &e, .record = &record[k], .u = {rng.next_float(), rng.next_float()}, .pmf = 1.0f};
      // A surface that sees the light: its shading normal toward the light's first corner, wo along it.
      const Vec3 to = e.p0 - from[k].p;
      const Vec3 toward = length(to) > 0 ? normalize(to) : Vec3(0, 1, 0);
      const int lane = batch.add({toward, from[k].ng, toward, Rgb(1.0f)}, from[k].p, from[k].p_error);
      batch.request_light(lane, from[k].triangle, Rgb(1.0f), draw[k]);
    }
    const LightLanes both(batch);
    const LaneLightResult *out = both.avx2, *sse = both.sse;
    for (int k = 0; k < n; ++k) {
      // Without AVX2 (SSE pairs), the same bits.
      ASSERT_EQ(out[k].cast, sse[k].cast);
      if (!out[k].cast) continue;
      EXPECT_EQ(out[k].contribution, sse[k].contribution);
      EXPECT_EQ(out[k].ray.origin, sse[k].ray.origin);
      EXPECT_EQ(out[k].ray.dir, sse[k].ray.dir);
      const Emitters::TriangleDraw& l = draw[k];
      // Emitters::triangle_point's point and error bound (half A of a triangle) at the draw by area.
      Barycentrics b;
      Emitters::area_point_draw(*l.light, l.u, b);
      const Vec3 p = l.light->p0 * b.b0 + l.light->p1 * b.b1 + l.light->p2 * b.b2;
      const Vec3 p_error =
          (abs(l.light->p0 * b.b0) + abs(l.light->p1 * b.b1) + abs(l.light->p2 * b.b2)) * kHitRelativeError +
          Vec3(l.light->quad_slack);
      const Ray expected = spawn_ray_between(from[k], p, p_error, l.light->normal);
      const Ray& got = out[k].ray;
      for (int a = 0; a < 3; ++a) {
        ASSERT_EQ(std::bit_cast<uint32_t>(got.origin[a]), std::bit_cast<uint32_t>(expected.origin[a]))
            << "round " << round << " lane " << k << " axis " << a << ": " << got.origin[a] << " for " << expected.origin[a];
        ASSERT_EQ(std::bit_cast<uint32_t>(got.dir[a]), std::bit_cast<uint32_t>(expected.dir[a]))
            << "round " << round << " lane " << k << " axis " << a;
      }
      EXPECT_EQ(got.t_max, expected.t_max);
      EXPECT_EQ(got.leaves.primitive, expected.leaves.primitive);
      ++compared;
    }
  }
  EXPECT_GT(compared, 5000);
}

// The lanes' shadow rays toward a direction are spawn_ray_toward's, bit for bit, for finite and
// infinite distances, and their contributions direct_light's (the lobe's value through a Bsdf, the
// power heuristic or, for a punctual light, none), with AVX2 and without, for Lambertian lanes and,
// every other round, coated ones among them (Bsdf::coated_only: dielectric, metal and mixed layers
// with relative indices above and below 1).
TEST(Lanes, ShadowRaysTowardADirectionAreSpawnRayTowards) {
  Pcg32 rng(45, 46);
  int compared = 0, coated_compared = 0;
  for (int round = 0; round < 2000; ++round) {
    const int n = 1 + round % LaneVertexBatch::kLanes;
    LaneVertexBatch batch;
    SurfaceHit from[LaneVertexBatch::kLanes];
    EmitterSample light[LaneVertexBatch::kLanes];
    Vec3 wo[LaneVertexBatch::kLanes];
    SurfaceParams params[LaneVertexBatch::kLanes];
    float eta[LaneVertexBatch::kLanes];
    const Rgb f(0.2f, 0.1f, 0.05f), beta(0.9f, 0.7f, 0.5f);
    for (int k = 0; k < n; ++k) {
      from[k].p = Vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 100.0f - Vec3(50.0f);
      from[k].p_error = abs(from[k].p) * 1e-6f;
      from[k].ng = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      from[k].ns = from[k].ng;
      from[k].triangle = {1, 2, uint32_t(k)};
      wo[k] = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      EmitterSample& l = light[k];
      l.wi = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      l.delta = rng.next_float() < 0.3f;
      l.infinite = !l.delta;
      l.distance = l.delta && rng.next_float() < 0.5f ? 0.5f + 10 * rng.next_float() : kInfinity;
      l.pdf = l.delta ? 0.25f : 0.1f + rng.next_float();
      l.incident = Rgb(rng.next_float(), 2 * rng.next_float(), 0.5f);
      // A Lambertian surface of albedo pi f, or a coated one.
      SurfaceParams& surface = params[k];
      surface.base_color = f * kPi;
      surface.metallic = 0;
      surface.specular = 0;
      eta[k] = 1.0f;
      const bool coated = round % 2 == 1 && rng.next_float() < 0.7f;
      if (coated) {
        surface.base_color = Rgb(rng.next_float(), rng.next_float(), rng.next_float());
        surface.specular = 1;
        surface.roughness = 0.04f + 0.96f * rng.next_float();
        eta[k] = rng.next_float() < 0.2f ? 0.6f + 0.35f * rng.next_float() : 1.05f + rng.next_float();
        const float metal = rng.next_float();
        surface.metallic = metal < 0.5f ? 0.0f : metal < 0.75f ? 1.0f : rng.next_float();
        // Half the directions toward the light in wo's hemisphere, where the glossy lobe lives.
        if (rng.next_float() < 0.5f && dot(l.wi, from[k].ns) * dot(wo[k], from[k].ns) < 0) l.wi = -l.wi;
      }
      ASSERT_EQ(Bsdf::coated_only(surface, eta[k]), coated);
      const LambertianSurface lambertian{from[k].ns, from[k].ng, wo[k], Lambertian{surface.base_color}.f()};
      const int lane = coated ? batch.add(lambertian, from[k].p, from[k].p_error, CoatedSurface::of(surface, eta[k]))
                              : batch.add(lambertian, from[k].p, from[k].p_error);
      batch.request_light_toward(lane, from[k].triangle, beta, l);
    }
    const LightLanes both(batch);
    const LaneLightResult *out = both.avx2, *sse = both.sse;
    for (int k = 0; k < n; ++k) {
      ASSERT_EQ(out[k].cast, sse[k].cast);
      // direct_light's steps for this sample.
      const Bsdf bsdf(params[k], from[k].ns, from[k].ng, wo[k], eta[k]);
      const Bsdf::Value v = bsdf.evaluate(light[k].wi);
      const bool expected_cast = !is_black(light[k].incident) && !is_black(v.f_cos);
      ASSERT_EQ(out[k].cast, expected_cast) << "round " << round << " lane " << k;
      if (!out[k].cast) continue;
      const float weight = light[k].delta ? 1.0f : power_heuristic(light[k].pdf, v.pdf);
      const Rgb contribution = beta * (v.f_cos * light[k].incident * (weight / light[k].pdf));
      const Ray expected = spawn_ray_toward(from[k], light[k].wi, light[k].distance);
      for (const LaneLightResult* r : {&out[k], &sse[k]}) {
        EXPECT_EQ(r->contribution, contribution) << "round " << round << " lane " << k;
        EXPECT_EQ(r->ray.origin, expected.origin);
        EXPECT_EQ(r->ray.dir, expected.dir);
        EXPECT_EQ(r->ray.t_max, expected.t_max);
        EXPECT_EQ(r->ray.leaves.primitive, expected.leaves.primitive);
      }
      ++compared;
      coated_compared += eta[k] != 1.0f;
    }
  }
  EXPECT_GT(compared, 10000);
  EXPECT_GT(coated_compared, 2000);
}

// The lanes' bounces are Bsdf::sample's for a Lambertian lobe and for the coated mixture (every
// other round's batches mix both), and their rays' origins spawn_ray's, bit for bit, with AVX2 and
// without, the lobe's frame made in lanes from the Bsdf constructor's inputs: shading normals
// leaning off the face (bent toward a grazing wo, mirrored, or facing into the surface), seen from
// either side and along the face's plane, with draws on the square's edges and at its centre.
TEST(Lanes, BouncesAreBsdfSamplesAndSpawnedRays) {
  Pcg32 rng(45, 46);
  const float edges[] = {0.0f, 0.5f, 0x1.fffffep-1f};
  int compared = 0, refused = 0, bent = 0, in_plane = 0, coated_lanes = 0;
  for (int round = 0; round < 3000; ++round) {
    const int n = 1 + round % LaneVertexBatch::kLanes;
    LaneVertexBatch batch;
    SurfaceHit hits[LaneVertexBatch::kLanes];
    std::optional<Bsdf> bsdfs[LaneVertexBatch::kLanes];
    Vec3 wos[LaneVertexBatch::kLanes];
    Vec2 draws[LaneVertexBatch::kLanes];
    float lobe_draws[LaneVertexBatch::kLanes];
    bool asked[LaneVertexBatch::kLanes];
    for (int k = 0; k < n; ++k) {
      SurfaceHit& hit = hits[k];
      hit.p = Vec3(rng.next_float() - 0.5f, 100.0f * rng.next_float(), -3.0f) * (rng.next_float() < 0.5f ? 1e-3f : 1e3f);
      hit.p_error = abs(hit.p) * 1e-6f;
      hit.ng = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      hit.ns = normalize(hit.ng + sample_uniform_sphere({rng.next_float(), rng.next_float()}) * 0.6f);
      if (rng.next_float() < 0.1f) hit.ns = -hit.ns;  // facing into the surface: the lobe turns it out
      Vec3& wo = wos[k];
      wo = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      if (rng.next_float() < 0.05f) {  // wo exactly along the face's plane: no lobe
        hit.ng = Vec3(0, 0, 1);
        wo = Vec3(0, 1, 0);
      }
      SurfaceParams params;
      params.base_color = Rgb(rng.next_float(), rng.next_float(), rng.next_float());
      params.specular = 0;
      // Some lanes coated (Bsdf::coated_only): relative indices above 1, and below (inside glass).
      const bool coated = round % 2 == 1 && rng.next_float() < 0.7f;
      float eta = 1.0f;
      if (coated) {
        params.specular = 1;
        params.roughness = 0.04f + 0.96f * rng.next_float();
        eta = rng.next_float() < 0.2f ? 0.6f + 0.35f * rng.next_float() : 1.05f + rng.next_float();
        const float metal = rng.next_float();  // half dielectric, a quarter metal, a quarter mixed
        params.metallic = metal < 0.5f ? 0.0f : metal < 0.75f ? 1.0f : rng.next_float();
      }
      bsdfs[k].emplace(params, hit.ns, hit.ng, wo, eta);
      draws[k] = rng.next_float() < 0.2f ? Vec2{edges[rng.next_u32() % 3], edges[rng.next_u32() % 3]}
                                         : Vec2{rng.next_float(), rng.next_float()};
      lobe_draws[k] = rng.next_float();
      // A lane that asks for no bounce beside those that do (it would ask for its light sample alone).
      const LambertianSurface surface{hit.ns, hit.ng, wo, Lambertian{params.base_color}.f()};
      ASSERT_EQ(Bsdf::coated_only(params, eta), coated);
      const int lane = coated ? batch.add(surface, hit.p, hit.p_error, CoatedSurface::of(params, eta))
                              : batch.add(surface, hit.p, hit.p_error);
      asked[k] = rng.next_float() < 0.8f;
      if (asked[k]) batch.request_bounce(lane, draws[k], lobe_draws[k]);
      coated_lanes += coated && asked[k];
    }
    LaneBounce out[LaneVertexBatch::kLanes], sse[LaneVertexBatch::kLanes];
    LaneLightResult unasked[LaneVertexBatch::kLanes];
    lane_vertices(batch, unasked, out);
    lane_vertices(batch, unasked, sse, false);
    for (int k = 0; k < n; ++k) {
      if (!asked[k]) continue;  // its result is not to be read
      const LaneBounce& got = out[k];
      const LaneBounce& other = sse[k];
      const std::optional<BsdfSample> expected = bsdfs[k]->sample(lobe_draws[k], draws[k]);
      ASSERT_EQ(got.sampled, expected.has_value()) << "round " << round << " lane " << k;
      ASSERT_EQ(other.sampled, got.sampled);
      const Vec3& n_used = bsdfs[k]->normal();
      if (!(n_used == hits[k].ns || n_used == -hits[k].ns)) ++bent;
      if (dot(wos[k], hits[k].ng) == 0) ++in_plane;
      if (!expected) {
        ++refused;
        continue;
      }
      const Vec3 origin = spawn_ray(hits[k], expected->wi).origin;
      for (int a = 0; a < 3; ++a) {
        ASSERT_EQ(std::bit_cast<uint32_t>(got.wi[a]), std::bit_cast<uint32_t>(expected->wi[a])) << "round " << round;
        ASSERT_EQ(std::bit_cast<uint32_t>(got.f_cos[a]), std::bit_cast<uint32_t>(expected->f_cos[a]));
        ASSERT_EQ(std::bit_cast<uint32_t>(got.origin[a]), std::bit_cast<uint32_t>(origin[a]));
      }
      ASSERT_EQ(got.pdf, expected->pdf);
      EXPECT_EQ(other.wi, got.wi);
      EXPECT_EQ(other.origin, got.origin);
      EXPECT_EQ(other.f_cos, got.f_cos);
      EXPECT_EQ(other.pdf, got.pdf);
      ++compared;
    }
  }
  EXPECT_GT(compared, 20000);
  EXPECT_GT(coated_lanes, 20000);
  EXPECT_GT(refused, 0);  // draws the checks turn down were among them
  EXPECT_GT(bent, 100);
  EXPECT_GT(in_plane, 100);
}

// fill_packet_avx2 writes every byte of the packet and its valid mask as the lane-by-lane form
// does, for each number of rays a packet may hold (lanes past n repeat ray 0).
TEST(PacketQueries, TransposedFillIsTheLaneByLaneOne) {
  if (!cpu_has_avx2()) GTEST_SKIP() << "no AVX2 on this CPU";
  Pcg32 rng(71, 72);
  Ray rays[kEmbreePacketSize];
  for (Ray& r : rays) {
    r = Ray({rng.next_float(), -rng.next_float(), 3 * rng.next_float()}, {rng.next_float() - 0.5f, 1, -2},
            rng.next_float(), 10 + rng.next_float(), {1, 2, 3});
    r.cone_width = 0.25f;
  }
  for (int n = 1; n <= kEmbreePacketSize; ++n) {
    alignas(32) RTCRay8 transposed, lanes;
    alignas(32) int valid_transposed[kEmbreePacketSize], valid_lanes[kEmbreePacketSize];
    std::memset(&transposed, 0xab, sizeof transposed);  // any byte left unwritten shows
    std::memset(&lanes, 0xcd, sizeof lanes);
    fill_packet_avx2(transposed, valid_transposed, rays, n);
    fill_packet_lanes(lanes, valid_lanes, rays, n);
    EXPECT_EQ(std::memcmp(&transposed, &lanes, sizeof lanes), 0) << n << " rays";
    EXPECT_EQ(std::memcmp(valid_transposed, valid_lanes, sizeof valid_lanes), 0) << n << " rays";
  }
}

// transpose (core/float8.h) turns eight records into rows of lanes: lane k of row j is record k's float j.
TEST(Lanes, TransposeTurnsRecordsIntoRows) {
  float records[lanes::kLanes][24];
  const float* pointers[lanes::kLanes];
  for (int k = 0; k < lanes::kLanes; ++k) {
    for (int j = 0; j < 24; ++j) records[k][j] = float(100 * k + j);
    pointers[lanes::kLanes - 1 - k] = records[k];  // in no particular order in memory
  }
  for (int offset = 0; offset < 24; offset += 8) {
    lanes::F8 rows[8];
    transpose(pointers, offset, rows);
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < lanes::kLanes; ++k)
        ASSERT_EQ(rows[j][k], pointers[k][offset + j]) << "offset " << offset << " row " << j << " lane " << k;
  }
}

// lanes::atan2_fast is atan2_fast, bit for bit, in every quadrant and on the axes: signed zeros,
// infinities, NaNs, equal magnitudes (the reduction's edge) and ratios across tan(pi/8).
TEST(Lanes, Atan2IsTheScalarOnesBits) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> values = {0.0f, -0.0f, inf, -inf, nan, 1.0f, -1.0f, 0.41421356f, 1e-30f, -3e30f, 0x1p-149f};
  Pcg32 rng(49, 50);
  for (int k = 0; k < 400; ++k)
    values.push_back((rng.next_float() - 0.5f) * std::exp2(float(int(rng.next_u32() % 40) - 20)));
  int compared = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    float ys[8], xs[8];
    for (size_t j = 0; j < values.size(); j += 8) {
      for (size_t k = 0; k < 8; ++k) {
        ys[k] = values[i];
        xs[k] = values[(j + k) % values.size()];
      }
      const lanes::F8 got = lanes::atan2_fast(lanes::load(ys, 0), lanes::load(xs, 0));
      for (int k = 0; k < 8; ++k) {
        const float expected = atan2_fast(ys[k], xs[k]);
        if (std::isnan(expected)) {
          EXPECT_TRUE(std::isnan(got[k])) << ys[k] << ", " << xs[k];
        } else {
          ASSERT_EQ(std::bit_cast<uint32_t>(got[k]), std::bit_cast<uint32_t>(expected)) << ys[k] << ", " << xs[k];
        }
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 150000);
}

// The lanes' spherical triangles are SphericalTriangle's, bit for bit: solid angles and sampled
// barycentrics of triangles seen from near and far, slivers, triangles filling nearly a
// hemisphere (their corners relabelled), a reference point on a corner, and draws at the ends of
// the square.
TEST(Lanes, SphericalTrianglesAreTheScalarOnesBits) {
  using namespace lanes;
  Pcg32 rng(47, 48);
  const auto unit = [&] { return Vec3(rng.next_float(), rng.next_float(), rng.next_float()) - Vec3(0.5f); };
  const float ends[] = {0.0f, 0.5f, kOneMinusEpsilon};
  int compared = 0, drawn = 0, relabelled = 0;
  for (int round = 0; round < 4000; ++round) {
    float ref[3][8], p[3][3][8], u[2][8];
    Vec3 refs[8], corners[8][3];
    Vec2 draws[8];
    for (int k = 0; k < 8; ++k) {
      Vec3 c[3] = {unit(), unit(), unit()};
      const int kind = int(rng.next_u32() % 5);
      if (kind == 1) c[2] = c[0] + (c[1] - c[0]) * rng.next_float() + unit() * 1e-4f;  // a sliver
      const float scale = kind == 2 ? 1e4f : kind == 3 ? 1e-3f : 1.0f;
      Vec3 r = unit() * 4.0f * scale;
      if (kind == 4) {  // just off the triangle's middle: nearly a hemisphere, or its corner
        r = rng.next_float() < 0.2f ? c[0] : (c[0] + c[1] + c[2]) / 3.0f + cross(c[1] - c[0], c[2] - c[0]) * 1e-3f;
      }
      for (Vec3& v : c) v = v * scale;
      if (kind == 4) r = r * scale;
      refs[k] = r;
      draws[k] = rng.next_float() < 0.2f ? Vec2{ends[rng.next_u32() % 3], ends[rng.next_u32() % 3]}
                                         : Vec2{rng.next_float(), rng.next_float()};
      for (int a = 0; a < 3; ++a) {
        ref[a][k] = r[a];
        for (int i = 0; i < 3; ++i) p[i][a][k] = c[i][a];
      }
      for (int i = 0; i < 3; ++i) corners[k][i] = c[i];
      u[0][k] = draws[k].x;
      u[1][k] = draws[k].y;
    }
    const auto vec = [](float (&v)[3][8]) { return V8{load(v[0], 0), load(v[1], 0), load(v[2], 0)}; };
    const V8 r8 = vec(ref);
    const SphericalTriangle8 t = spherical_triangle(r8, see(r8, vec(p[0])), see(r8, vec(p[1])), see(r8, vec(p[2])));
    const Barycentrics8 b = sample(t, load(u[0], 0), load(u[1], 0));
    for (int k = 0; k < 8; ++k) {
      const SphericalTriangle expected(refs[k], corners[k][0], corners[k][1], corners[k][2]);
      ASSERT_EQ(std::bit_cast<uint32_t>(t.solid_angle[k]), std::bit_cast<uint32_t>(expected.solid_angle()))
          << "round " << round << " lane " << k;
      const std::optional<Barycentrics> e = expected.sample(draws[k]);
      ASSERT_EQ(b.drawn[k] != 0, e.has_value()) << "round " << round << " lane " << k;
      if (dot(normalize(corners[k][0] - refs[k]), normalize(corners[k][1] - refs[k])) < SphericalTriangle::kRelabelCos)
        ++relabelled;
      ++compared;
      if (!e) continue;
      ASSERT_EQ(std::bit_cast<uint32_t>(b.b0[k]), std::bit_cast<uint32_t>(e->b0)) << "round " << round << " lane " << k;
      ASSERT_EQ(std::bit_cast<uint32_t>(b.b1[k]), std::bit_cast<uint32_t>(e->b1));
      ASSERT_EQ(std::bit_cast<uint32_t>(b.b2[k]), std::bit_cast<uint32_t>(e->b2));
      ++drawn;
    }
  }
  EXPECT_EQ(compared, 32000);
  EXPECT_GT(drawn, 25000);
  EXPECT_GT(relabelled, 500);
}

// The same where a light tree chooses the lights, ahead of shading (Emitters::pick_many).
TEST(Lanes, GiveTheScalarPathsBitsUnderALightTree) {
  SceneDesc desc = packet_test_scene();
  int lamp[3];
  for (int k = 0; k < 3; ++k) lamp[k] = test::add_material(desc, Rgb(0.0f), Rgb(2.0f + float(k), 3.0f, 4.0f - float(k)));
  for (int k = 0; k < 60; ++k) {
    const float x = -1.8f + 0.06f * float(k);
    test::add_quad(desc, Vec3(x, 1.99f, -1.8f + 0.05f * float(k % 7)), Vec3(0.04f, 0, 0), Vec3(0, 0, 0.3f), lamp[k % 3]);
  }
  const Scene scene(std::move(desc), &material_alpha);
  ASSERT_EQ(scene.emitters().light_sampling(), LightSampling::Tree);
  EXPECT_GT(expect_lanes_match_scalar_paths(scene), 2000u);
}

// A floor, a back wall, a block and a sphere open to a sky map, lit by it, by a point light, a spot,
// the sun and a lamp on the wall; with `pane`, a thin glass sheet above them, through which the sky is also sampled
// (EnvironmentPortals), else the sky samples are drawn ahead for a packet (environment_map_draw).
SceneDesc open_to_the_sky(bool pane) {
  SceneDesc desc;
  const int wall = test::add_material(desc, Rgb(0.6f, 0.5f, 0.4f));
  test::add_quad(desc, Vec3(-4, -2, -4), Vec3(0, 0, 8), Vec3(8, 0, 0), wall);  // floor, facing up
  test::add_quad(desc, Vec3(-4, -2, -2), Vec3(8, 0, 0), Vec3(0, 4, 0), wall);  // back wall, facing +z
  const int block = test::add_box(desc, Vec3(-0.3f), Vec3(0.3f), test::add_material(desc, Rgb(0.3f, 0.7f, 0.5f)));
  desc.instances[size_t(block)].object_to_world = Transform::translate(Vec3(-1, -1.5f, 0));
  test::add_sphere(desc, Vec3(1, -1.4f, -0.5f), 0.6f, wall);
  // A lamp on the back wall: blocks of lanes mix points on it with directions.
  test::add_quad(desc, Vec3(-0.5f, 0.5f, -1.99f), Vec3(1, 0, 0), Vec3(0, 0.5f, 0),
                 test::add_material(desc, Rgb(0.0f), Rgb(3.0f, 2.0f, 1.0f)));
  if (pane) test::add_quad(desc, Vec3(-1.5f, 1.5f, -1.5f), Vec3(3, 0, 0), Vec3(0, 0, 3),
                           test::add_glass(desc, 1.5f, Rgb(1.0f), 1.0f, /*thin_walled=*/true));
  ImageDesc& sky = desc.images.emplace_back();  // a dim sky with one bright texel
  sky.width = 8;
  sky.height = 4;
  sky.channels = 3;
  for (int i = 0; i < 8 * 4; ++i)
    for (float c : {0.3f + 0.01f * float(i), 0.4f, 0.7f}) sky.texels.push_back(i == 10 ? 50.0f * c : c);
  desc.environment.present = true;
  desc.environment.image = int(desc.images.size()) - 1;
  PunctualLightDesc point, spot, sun;
  point.position = Vec3(1, 1, 1);
  point.intensity = Rgb(5, 4, 3);
  spot.type = LightType::Spot;
  spot.position = Vec3(-1, 1.5f, 0);
  spot.direction = Vec3(0, -1, 0);
  spot.intensity = Rgb(20);
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3(-0.3f, -1, -0.2f));
  sun.intensity = Rgb(2);
  desc.lights = {point, spot, sun};
  return desc;
}

// The lanes' light samples toward a direction (Emitters::Draw::kToward: the sky, punctual lights)
// give the scalar code's bits, under an open sky and through a window.
TEST(Lanes, GiveTheScalarPathsBitsUnderTheSkyAndPunctualLights) {
  for (const bool pane : {false, true}) {
    const Scene scene(open_to_the_sky(pane), &material_alpha);
    ASSERT_EQ(scene.emitters().portals().empty(), !pane);
    EXPECT_GT(expect_lanes_match_scalar_paths(scene), 2000u) << "pane " << pane;
  }
}

// Where casters aim part of the bounces, the lanes' light samples are weighed against that mixture
// after their run: the same bits as the scalar code's, for points on lights (the glass sphere and
// box of lanes_test_scene are the casters) and for directions (a mirror sphere under the sky).
TEST(Lanes, GiveTheScalarPathsBitsWhereCastersAimTheBounce) {
  const Scene lit(lanes_test_scene(), &material_alpha);
  ASSERT_FALSE(lit.casters().empty());
  EXPECT_GT(expect_lanes_match_scalar_paths(lit, 200, 0.25f), 2000u);
  EXPECT_GT(expect_lanes_match_scalar_paths(lit, 100, 0.25f, 2), 2000u);
  SceneDesc open = open_to_the_sky(false);
  const int mirror = test::add_material(open, Rgb(0.9f));
  open.materials[size_t(mirror)].metallic = 1;
  open.materials[size_t(mirror)].roughness = 0;
  test::add_sphere(open, Vec3(-1.5f, -1.5f, 1), 0.5f, mirror);
  const Scene sky(std::move(open), &material_alpha);
  ASSERT_FALSE(sky.casters().empty());
  EXPECT_GT(expect_lanes_match_scalar_paths(sky, 200, 0.25f), 2000u);
  EXPECT_GT(expect_lanes_match_scalar_paths(sky, 200, 0.25f, 2), 2000u);
}

// Turns the scene's opaque dielectrics into glTF's opaque metallic-roughness model with rough lobes
// (Bsdf::coated_only): dielectric (a rough specular layer over the Lambertian lobe), metal, and the
// two mixed, of several roughnesses; but for two kinds the lanes leave to the scalar code: a smooth
// one (delta lobes) and one tinted by KHR_materials_specular.
void coat_the_walls(SceneDesc& desc) {
  for (size_t k = 0; k < desc.materials.size(); ++k) {
    MaterialDesc& m = desc.materials[k];
    if (m.is_emissive() || m.transmission > 0 || m.metallic > 0) continue;
    m.ior = 1.5f;
    m.roughness = k % 4 == 3 ? 0.01f : 0.2f + 0.25f * float(k % 3);
    m.metallic = k % 3 == 1 ? 0.3f : k % 6 == 2 ? 1.0f : 0.0f;
    if (k % 5 == 4) m.specular_color = Rgb(1.0f, 0.6f, 0.3f);
  }
}

// Coated vertices take their light samples and bounces in the lanes: the scalar code's bits, for
// points on triangle lights (near and far), toward the sky and punctual lights (through a window
// too), where casters aim the bounce, and inside glass, where the layer's relative index is below 1
// (total internal reflection at grazing angles).
TEST(Lanes, GiveTheScalarPathsBitsAtCoatedSurfaces) {
  SceneDesc lit = lanes_test_scene();
  coat_the_walls(lit);
  test::add_sphere(lit, Vec3(0.9f, 0.8f, 0.2f), 0.6f, test::add_glass(lit, 1.5f));
  const int inside = test::add_material(lit, Rgb(0.8f, 0.4f, 0.2f));
  lit.materials[size_t(inside)].ior = 1.2f;
  lit.materials[size_t(inside)].roughness = 0.4f;
  test::add_sphere(lit, Vec3(0.9f, 0.8f, 0.2f), 0.3f, inside);
  const Scene lit_scene(std::move(lit), &material_alpha);
  EXPECT_GT(expect_lanes_match_scalar_paths(lit_scene), 2000u);
  EXPECT_GT(expect_lanes_match_scalar_paths(lit_scene, 200, 0.25f), 2000u);
  for (const bool pane : {false, true}) {
    SceneDesc open = open_to_the_sky(pane);
    coat_the_walls(open);
    const Scene sky(std::move(open), &material_alpha);
    EXPECT_GT(expect_lanes_match_scalar_paths(sky), 2000u) << "pane " << pane;
  }
}

// The same under a light tree larger than the caches, where the lanes choose their lights together
// (Emitters::pick_many): a ceiling of 80,000 small emissive triangles, none sharing an edge (so each
// is a light of its own), in four colours.
TEST(PacketQueries, PathsInLockstepMatchPathsAloneUnderALargeLightTree) {
  SceneDesc desc = lockstep_test_scene();
  int lamp[4];
  for (int k = 0; k < 4; ++k) lamp[k] = test::add_material(desc, Rgb(0.0f), Rgb(2.0f + float(k), 3.0f, 4.0f - float(k)));
  constexpr int kSide = 284;
  PrimitiveDesc ceiling[4];
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      PrimitiveDesc& prim = ceiling[(x + 2 * y) % 4];
      const float cell = 3.8f / kSide;
      const Vec3 c(-1.9f + cell * float(x), 1.98f, -1.9f + cell * float(y));
      const uint32_t first = uint32_t(prim.positions.size());
      prim.positions.insert(prim.positions.end(), {c, c + Vec3(0.8f * cell, 0, 0), c + Vec3(0, 0, 0.8f * cell)});
      prim.indices.insert(prim.indices.end(), {first, first + 1, first + 2});  // facing down
    }
  for (int k = 0; k < 4; ++k) {
    ceiling[k].material = lamp[k];
    test::add_mesh(desc, std::move(ceiling[k]));
  }
  const Scene scene(std::move(desc), &material_alpha);
  ASSERT_EQ(scene.emitters().size(), size_t(kSide) * kSide);
  ASSERT_TRUE(scene.emitters().picks_ahead()) << scene.emitters().tree().node_bytes() << " bytes of nodes";
  expect_paths_in_lockstep_match_paths_alone(scene);
  expect_paths_in_lockstep_match_paths_alone(scene, 2);
}

}  // namespace
}  // namespace prism
