// Geometry at the extremes: degenerate and sliver triangles, duplicate vertices, zero, flipped and
// disagreeing normals, coplanar overlaps and very thin slabs. Each has a stated behaviour
// (docs/NUMERICS.md) that these tests hold prism to.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "core/pcg32.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "integrators/whitted_integrator.h"
#include "lit_plane.h"
#include "radiance_stats.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

using test::kNoRoulette;

Vec3 on_grid(Pcg32& rng, float extent) {  // a point of the 1/8 grid in [-extent, extent]^3
  auto c = [&] { return std::round((rng.next_float() * 2 - 1) * extent * 8) / 8; };
  return Vec3(c(), c(), c());
}

// Triangles with no area in float, a third of each kind: a repeated index, two corners at one
// position, and three corners on a line that floats hold exactly (a, a + d, a + 2d on the 1/8
// grid). `aims` gets a point on each, to shoot at.
PrimitiveDesc degenerate_triangles(Pcg32& rng, int per_kind, float extent, int material, std::vector<Vec3>& aims) {
  PrimitiveDesc prim;
  prim.material = material;
  for (int kind = 0; kind < 3; ++kind) {
    for (int i = 0; i < per_kind; ++i) {
      const Vec3 a = on_grid(rng, extent);
      Vec3 d = on_grid(rng, 0.25f * extent);
      if (d == Vec3(0.0f)) d = Vec3(0.125f, 0, 0);
      const auto base = static_cast<uint32_t>(prim.positions.size());
      if (kind == 0) {
        prim.positions.insert(prim.positions.end(), {a, a + d});
        prim.indices.insert(prim.indices.end(), {base, base, base + 1});
      } else {
        prim.positions.insert(prim.positions.end(), {a, kind == 1 ? a : a + d, a + d * 2.0f});
        prim.indices.insert(prim.indices.end(), {base, base + 1, base + 2});
      }
      aims.push_back(a + d * rng.next_float());
    }
  }
  return prim;
}

// Stated: a triangle whose corners are collinear in float has no area; Embree never reports it
// (its determinant is exactly 0), it carries no light power, is never picked, and its pdf is 0,
// not 1/0.
TEST(GeometryExtremes, DegenerateTrianglesAreNeverHitNorLights) {
  Pcg32 rng(2026, 5);
  SceneDesc desc;
  const int glow = test::add_material(desc, Rgb(0.5f), Rgb(1e4f));
  std::vector<Vec3> aims;
  test::add_mesh(desc, degenerate_triangles(rng, 500, 2.0f, glow, aims));
  const int degenerate = static_cast<int>(desc.instances.size()) - 1;
  test::add_quad(desc, Vec3(-1, -1, 40), Vec3(2, 0, 0), Vec3(0, 2, 0), glow);  // one real light, far off
  const Scene scene(std::move(desc));
  ASSERT_EQ(scene.origin(), Vec3(0.0f));  // a move would round the corners off their line
  int hits = 0;
  for (const Vec3& aim : aims) {
    for (int j = 0; j < 20; ++j) {
      const Vec3 dir = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      SurfaceHit hit;
      hits += scene.intersect(Ray(aim - scene.origin() - dir * 8.0f, dir, 0.0f, 16.0f), hit);
    }
  }
  EXPECT_EQ(hits, 0) << "of " << aims.size() * 20 << " rays aimed at points on degenerate triangles";
  const Emitters& emitters = scene.emitters();
  for (uint32_t t = 0; t < 1500; ++t) {
    const int emitter = emitters.triangle_emitter(degenerate, 0, t);
    ASSERT_GE(emitter, 0);
    EXPECT_EQ(emitters.power_pick_probability(emitter), 0.0f);
    EXPECT_EQ(emitters.pdf(emitter, Vec3(0, 0, 5), Vec3(), aims[t] - scene.origin(), Vec3(0, 0, 1)), 0.0f);
  }
  // The quad (its two triangles one emitter) has all the power.
  const int quad = emitters.triangle_emitter(degenerate + 1, 0, 0);
  EXPECT_EQ(emitters.triangle_emitter(degenerate + 1, 0, 1), quad);
  EXPECT_FLOAT_EQ(emitters.power_pick_probability(quad), 1.0f);
}

// The same, rendered: a sunlit plane with 750 bright degenerate triangles lying in it and 750
// above it still reads its closed form in every pixel.
TEST(GeometryExtremes, DegenerateTrianglesLeaveALitPlaneExact) {
  Pcg32 rng(2026, 6);
  SceneDesc desc = test::lit_plane(1.0f, Vec3(0.0f));
  const int glow = test::add_material(desc, Rgb(0.5f), Rgb(1e4f), /*double_sided=*/true);
  std::vector<Vec3> aims;
  PrimitiveDesc in_plane = degenerate_triangles(rng, 250, 2.0f, glow, aims), above = in_plane;
  for (Vec3& p : in_plane.positions) p.z = 0;     // still collinear: x and y are
  for (Vec3& p : above.positions) p.z += 3.5f;    // exact on the 1/8 grid
  test::add_mesh(desc, std::move(in_plane));
  test::add_mesh(desc, std::move(above));
  const double expected = test::sunlit_radiance(0.5);
  const test::PixelCheck c = test::check_pixels(test::view_lit_plane(std::move(desc), 1.0f, Vec3(0.0f)), expected, expected);
  EXPECT_EQ(c.covered, 32 * 32);
  EXPECT_EQ(c.outside, 0);
}

// Stated: a sliver (corners nearly collinear: a, a + k1 d, a + k2 d rounded to float) is the thin
// triangle its float corners span, hit as such, with the normal of that plane: computed in double
// (core/face_normal.h), it is perpendicular to both edges to float rounding. In float the cross
// product cancelled: the worst of 4025 hits was 0.95 off perpendicular, the median 0.025.
TEST(GeometryExtremes, SliverTrianglesTakeTheNormalOfTheirFloatCorners) {
  Pcg32 rng(7, 3);
  int hits = 0;
  double worst = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3 a(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1);
    const Vec3 d(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1);
    const float k1 = rng.next_float(), k2 = rng.next_float() * 2;
    const std::array<Vec3, 3> tri = {a, a + d * k1, a + d * k2};
    SceneDesc desc;
    const int m = test::add_material(desc, Rgb(0.5f));
    PrimitiveDesc prim;
    prim.material = m;
    prim.positions.assign(tri.begin(), tri.end());
    prim.indices = {0, 1, 2};
    test::add_mesh(desc, std::move(prim));
    for (float c : {-5.0f, 5.0f}) test::add_sphere(desc, Vec3(c), 1e-3f, m);  // keep the origin: corners unmoved
    const Scene scene(std::move(desc));
    ASSERT_EQ(scene.origin(), Vec3(0.0f));
    for (int j = 0; j < 300; ++j) {
      const Vec3 target = a + d * (k2 * rng.next_float());
      const Vec3 dir = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      SurfaceHit hit;
      if (!scene.intersect(Ray(target - dir * 3.0f, dir, 0.0f, 6.0f), hit)) continue;
      ++hits;
      EXPECT_NEAR(length(hit.ng), 1.0f, 2e-7f);
      for (int e = 1; e < 3; ++e) {
        const long double ex = (long double)tri[e].x - tri[0].x, ey = (long double)tri[e].y - tri[0].y,
                          ez = (long double)tri[e].z - tri[0].z;
        const long double along = std::abs(ex * hit.ng.x + ey * hit.ng.y + ez * hit.ng.z);
        worst = std::max(worst, double(along / std::sqrt(ex * ex + ey * ey + ez * ez)));
      }
    }
  }
  EXPECT_GT(hits, 2000);  // rays aimed at the line through a sliver do hit it (4025 measured)
  EXPECT_LE(worst, 0x1p-23) << "cosine between the hit normal and an edge";  // 3.3e-8 measured
}

// The 12 triangles of a closed room, as `add_inward_box` lays them out (4 corners per face), with
// every triangle given its own 3 corners, and welded to the 8 distinct corners.
std::array<PrimitiveDesc, 3> room_three_ways(int material) {
  SceneDesc tmp;
  test::add_inward_box(tmp, Vec3(-1), Vec3(1), material);
  PrimitiveDesc per_face = tmp.meshes[0].primitives[0];
  per_face.uvs.clear();  // a weld cannot keep per-face uvs; an untextured material needs none
  PrimitiveDesc per_triangle, welded;
  per_triangle.material = welded.material = material;
  std::map<std::tuple<float, float, float>, uint32_t> corner;
  for (uint32_t i : per_face.indices) {
    const Vec3& p = per_face.positions[i];
    per_triangle.indices.push_back(static_cast<uint32_t>(per_triangle.positions.size()));
    per_triangle.positions.push_back(p);
    const auto [it, added] = corner.try_emplace({p.x, p.y, p.z}, static_cast<uint32_t>(welded.positions.size()));
    if (added) welded.positions.push_back(p);
    welded.indices.push_back(it->second);
  }
  EXPECT_EQ(welded.positions.size(), 8u);
  EXPECT_EQ(per_triangle.positions.size(), 36u);
  return {per_face, per_triangle, welded};
}

// Stated: vertices are only positions; duplicating or welding them changes nothing. A room lit
// by a point light renders the same bits with 24, 36 and 8 vertices.
TEST(GeometryExtremes, DuplicateVerticesRenderLikeTheWeldedMesh) {
  std::vector<std::vector<float>> images;
  for (int layout = 0; layout < 3; ++layout) {
    SceneDesc desc;
    const int wall = test::add_material(desc, Rgb(0.7f, 0.5f, 0.3f));
    test::add_mesh(desc, room_three_ways(wall)[size_t(layout)]);
    PunctualLightDesc lamp;
    lamp.position = Vec3(0.3f, -0.2f, 0.6f);
    lamp.intensity = Rgb(5.0f);
    desc.lights.push_back(lamp);
    images.push_back(test::render_view(std::move(desc), Vec3(-0.6f), Vec3(1.0f), 4, 32, 8).resolve_rgba());
  }
  EXPECT_EQ(images[1], images[0]) << "one vertex per triangle corner";
  EXPECT_EQ(images[2], images[0]) << "welded";
}

// The lit plane's quad (corners 0..3, front +z) with vertex normals and winding varied.
struct NormalCase {
  const char* name;
  bool has_normals = false;
  std::array<Vec3, 4> normals;
  bool reversed = false;  // winding reversed: front face -z
};

const NormalCase kNormalCases[] = {
    {"no normals", false, {}},
    {"all zero length", true, {Vec3(0.0f), Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)}},
    {"two zero length", true, {Vec3(0.0f), Vec3(0, 0, 1), Vec3(0.0f), Vec3(0, 0, 1)}},
    {"flipped", true, {Vec3(0, 0, -1), Vec3(0, 0, -1), Vec3(0, 0, -1), Vec3(0, 0, -1)}},
    {"cancelling along y = 0", true, {Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(0, 0, -1)}},
    {"not unit", true, {Vec3(0, 0, 5), Vec3(0, 0, 1e-20f), Vec3(0, 0, 3e20f), Vec3(0, 0, 1)}},
    {"winding reversed, no normals", false, {}, true},
    {"winding reversed, normals up", true, {Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1)}, true},
};

void apply(const NormalCase& c, PrimitiveDesc& quad) {
  if (c.has_normals) quad.normals.assign(c.normals.begin(), c.normals.end());
  if (c.reversed)
    for (size_t t = 0; t + 2 < quad.indices.size(); t += 3) std::swap(quad.indices[t + 1], quad.indices[t + 2]);
}

// Stated: the shading normal is the interpolated vertex normal, normalised; where it has zero
// length (or is not finite) the face normal stands in; one that points into the surface is turned
// to the side of the face normal (materials/bsdf.cpp). The front face is the winding's (glTF
// §3.7.4), whatever the normals say. So every case shades a plane lit by the sun exactly as a flat
// plane: every pixel is the closed form, and every hit has a unit shading normal.
TEST(GeometryExtremes, ZeroFlippedAndDisagreeingNormalsShadeLikeTheFace) {
  const double expected = test::sunlit_radiance(0.5);
  for (const NormalCase& c : kNormalCases) {
    SCOPED_TRACE(c.name);
    SceneDesc desc = test::lit_plane(1.0f, Vec3(0.0f));
    apply(c, desc.meshes[0].primitives[0]);
    {
      const Scene scene(desc);
      Pcg32 rng(11, 2);
      for (int i = 0; i < 2000; ++i) {
        const Vec3 target((rng.next_float() * 2 - 1) * 100, (rng.next_float() * 2 - 1) * 100, 0);
        SurfaceHit hit;
        ASSERT_TRUE(scene.intersect(Ray(target - scene.origin() + Vec3(0, 0, 1), Vec3(0, 0, -1)), hit));
        ASSERT_NEAR(length(hit.ns), 1.0f, 1e-6f);
        ASSERT_EQ(hit.ng.z, c.reversed ? -1.0f : 1.0f);
      }
    }
    const test::PixelCheck pixels = test::check_pixels(test::view_lit_plane(std::move(desc), 1.0f, Vec3(0.0f)), expected, expected);
    EXPECT_EQ(pixels.covered, 32 * 32);
    EXPECT_EQ(pixels.outside, 0);
  }
}

// Stated: a single-sided emitter emits from its winding's front face; its normals do not move it.
// Seen from the front every pixel is Le, from the back 0; double-sided, Le from both.
TEST(GeometryExtremes, EmittersShineFromTheirWindingWhateverTheNormals) {
  const float le = 3.0f;
  for (const NormalCase* c : {&kNormalCases[0], &kNormalCases[3], &kNormalCases[7]}) {
    for (bool double_sided : {false, true}) {
      for (bool from_front : {true, false}) {
        SCOPED_TRACE(std::string(c->name) + (double_sided ? ", double-sided" : "") + (from_front ? ", front" : ", back"));
        SceneDesc desc;
        const int m = test::add_material(desc, Rgb(0.0f), Rgb(le), double_sided);
        test::add_quad(desc, Vec3(-100, -100, 0), Vec3(200, 0, 0), Vec3(0, 200, 0), m);
        apply(*c, desc.meshes[0].primitives[0]);
        const bool front_is_up = !c->reversed;
        const Vec3 eye(0.3f, -0.5f, from_front == front_is_up ? 2.0f : -2.0f);
        const double seen = double_sided || from_front ? le : 0.0;
        const test::PixelCheck p = test::check_pixels(test::render_view(std::move(desc), eye, Vec3(0.0f), 1), seen, seen);
        EXPECT_EQ(p.covered, 32 * 32);
        EXPECT_EQ(p.outside, 0);
      }
    }
  }
}

// Stated: where two surfaces overlap in one plane, each ray takes whichever Embree reports (the
// same one on every run), and neither shadows the other: a ray leaving one starts off the shared
// plane by the same bound as from a lone surface. So a sunlit plane with a coplanar twin of the
// same material (either winding) reads its closed form in every pixel at every scale, and with a
// twin of another albedo every pixel lies between the two closed forms, the same bits twice.
TEST(GeometryExtremes, CoplanarOverlapsNeitherShadowNorFlicker) {
  for (const auto& [s, offset] : test::placements()) {
    for (bool reversed : {false, true}) {
      SCOPED_TRACE("scale " + std::to_string(s) + " offset " + std::to_string(offset.x) + (reversed ? " reversed" : ""));
      SceneDesc desc = test::lit_plane(s, offset);
      const Vec3 corner = Vec3(-60, -150, 0) * s + offset;
      if (reversed)
        test::add_quad(desc, corner, Vec3(0, 210, 0) * s, Vec3(210, 0, 0) * s, 0);
      else
        test::add_quad(desc, corner, Vec3(210, 0, 0) * s, Vec3(0, 210, 0) * s, 0);
      const double expected = test::sunlit_radiance(0.5);
      const test::PixelCheck c = test::check_pixels(test::view_lit_plane(std::move(desc), s, offset), expected, expected);
      EXPECT_EQ(c.covered, 32 * 32);
      EXPECT_EQ(c.outside, 0);
    }
  }
  std::vector<float> first;
  for (int run = 0; run < 2; ++run) {
    SceneDesc desc = test::lit_plane(1.0f, Vec3(0.0f));
    const int darker = test::add_material(desc, Rgb(0.25f));
    test::add_quad(desc, Vec3(-60, -150, 0), Vec3(210, 0, 0), Vec3(0, 210, 0), darker);
    const Film film = test::view_lit_plane(std::move(desc), 1.0f, Vec3(0.0f));
    const test::PixelCheck c = test::check_pixels(film, test::sunlit_radiance(0.25), test::sunlit_radiance(0.5));
    EXPECT_EQ(c.outside, 0);
    if (run == 0) first = film.resolve_rgba();
    else EXPECT_EQ(film.resolve_rgba(), first);
  }
}

// A square slab 200 s wide and 2e-3 s thick (1e-5 of its size), top face z = 0, turned 35 degrees
// about (1, 2, 0) so that every coordinate feeds the error along its normal, then placed at offset
// by its instance's transform, as a glTF node would: 1e5 from the origin the float spacing is 4
// times the thickness, so vertices written there in float would flatten the slab, while
// transforms compose in double and the scene is rebased before they are applied.
constexpr float kSlabThickness = 2e-3f;
const double kHalfTurn = 17.5 * kPi / 180;
const Transform kSlabTurn = Transform::rotate_quaternion(std::sin(kHalfTurn) / std::sqrt(5.0), std::sin(kHalfTurn) * 2 / std::sqrt(5.0),
                                                         0, std::cos(kHalfTurn));

void add_thin_slab(SceneDesc& desc, float s, const Vec3& offset, int material) {
  const int mesh = test::add_box(desc, Vec3(-100, -100, -kSlabThickness) * s, Vec3(100, 100, 0) * s, material);
  for (Vec3& p : desc.meshes[size_t(mesh)].primitives[0].positions) p = kSlabTurn.point(p);
  desc.instances.back().object_to_world = Transform::translate(offset);
}

// Stated: a slab holds (no leak through it, no acne on it) while it is thicker than the ray
// offset, 32 float spacings of the coordinates along its normal: 2^-19 x 59 s here, where the
// view reaches 59 s from the centre, a tenth of the thickness. Sunlit from above and seen from
// above at 75 degrees, every pixel is the closed form; seen from below, exactly 0 after 8 bounces.
TEST(GeometryExtremes, ThinOpaqueSlabNeitherLeaksNorShadowsItself) {
  const double expected = test::sunlit_radiance(0.5);
  for (const auto& [s, offset] : test::placements()) {
    for (bool from_below : {false, true}) {
      SCOPED_TRACE("scale " + std::to_string(s) + " offset " + std::to_string(offset.x) + (from_below ? " below" : " above"));
      SceneDesc desc;
      add_thin_slab(desc, s, offset, test::add_material(desc, Rgb(0.5f)));
      test::add_sun(desc, kSlabTurn);
      const Film film = test::view_lit_plane(std::move(desc), s, offset, kSlabTurn, from_below, 8);
      const test::PixelCheck c = test::check_pixels(film, from_below ? 0.0 : expected, from_below ? 0.0 : expected);
      EXPECT_EQ(c.covered, 32 * 32);
      EXPECT_EQ(c.outside, 0);
    }
  }
}

// Stated: light crosses a glass slab 1e-5 of its size thick as the closed form says, with its
// interreflections: at normal incidence R = ((n - 1) / (n + 1))^2 per face and internal
// transmittance tau = exp(-sigma d), so T = (1 - R)^2 tau / (1 - R^2 tau^2). Index 1.5, tau = 0.3,
// at every scale: Whitted (deterministic) to 1e-4, the path tracer within 4.5 standard errors;
// and the same with the slab's vertex normals pointing inward.
TEST(GeometryExtremes, ThinGlassSlabTransmitsItsClosedForm) {
  const float le = 2.0f, tau = 0.3f, ior = 1.5f;
  const double r = std::pow((ior - 1.0) / (ior + 1.0), 2);
  const double expected = le * (1 - r) * (1 - r) * tau / (1 - r * r * tau * tau);
  const WhittedIntegrator whitted(16);
  const PathIntegrator path(16, kNoRoulette);
  for (const auto& [s, offset] : test::placements()) {
    for (bool inward_normals : {false, true}) {
      SCOPED_TRACE("scale " + std::to_string(s) + " offset " + std::to_string(offset.x) + (inward_normals ? " inward normals" : ""));
      const float thickness = kSlabThickness * s;
      SceneDesc desc;
      const int light = test::add_material(desc, Rgb(0.0f), Rgb(le));
      test::add_quad(desc, Vec3(-500, -500, -3) * s + offset, Vec3(1000, 0, 0) * s, Vec3(0, 1000, 0) * s, light);
      const int glass = test::add_glass(desc, ior, Rgb(tau), thickness);
      const int slab = test::add_box(desc, Vec3(-100, -100, 0) * s - Vec3(0, 0, thickness), Vec3(100, 100, 0) * s, glass);
      desc.instances.back().object_to_world = Transform::translate(offset);  // as add_thin_slab
      if (inward_normals) {
        PrimitiveDesc& p = desc.meshes[size_t(slab)].primitives[0];
        p.normals.assign(p.positions.size(), Vec3(0.0f));
        for (size_t t = 0; t < p.indices.size(); t += 3) {
          const Vec3 n = normalize(cross(p.positions[p.indices[t + 1]] - p.positions[p.indices[t]],
                                         p.positions[p.indices[t + 2]] - p.positions[p.indices[t]]));
          for (size_t k = 0; k < 3; ++k) p.normals[p.indices[t + k]] = -n;
        }
      }
      const Scene scene(std::move(desc));
      auto ray_at = [&, s = s, offset = offset](int i) {  // clang 14 cannot capture structured bindings
        return Ray(Vec3(0.01f * float(i % 97), -0.02f * float(i % 89), 2.0f) * s + offset - scene.origin(), Vec3(0, 0, -1));
      };
      IndependentSampler sampler(3);
      RayCounters counters;
      for (int i = 0; i < 16; ++i) {
        sampler.start_pixel_sample(0, 0, uint64_t(i));
        EXPECT_NEAR(whitted.li(scene, ray_at(i), sampler, counters).radiance.x, expected, 1e-4 * expected) << "Whitted";
      }
      const test::RunningStats stats = test::radiance_stats(scene, path, 4096, {.seed = 17}, ray_at);
      EXPECT_NEAR(stats.mean(), expected, test::kSigmas * stats.standard_error() + 1e-4 * expected) << "path";
    }
  }
}

}  // namespace
}  // namespace prism
