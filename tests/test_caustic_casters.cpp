// Caustic casters: which objects are aimed at, the density of the aimed directions, and that a
// path tracer aiming at them keeps every mean where it was.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/caustic_casters.h"
#include "core/constants.h"
#include "core/pcg32.h"
#include "core/sampling.h"
#include "furnace_scene.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

int add_metal(SceneDesc& desc, float roughness) {
  MaterialDesc m;
  m.name = "metal " + std::to_string(desc.materials.size());
  m.base_color = Rgb(0.9f);
  m.metallic = 1;
  m.roughness = roughness;
  desc.materials.push_back(m);
  return static_cast<int>(desc.materials.size()) - 1;
}

// Directions from the origin toward a caster of centre c: the pdf is positive along c and zero
// straight away from it.
bool aims_at(const CausticCasters& casters, const Vec3& c) {
  CasterView v;
  casters.view(Vec3(0.0f), normalize(c), v);
  return v.pdf(normalize(c)) > 0 && v.pdf(-normalize(c)) == 0;
}

TEST(CausticCasters, AreSmoothOrGlossyMetalAndSmoothGlassPlacedInTheWorld) {
  SceneDesc desc;
  test::add_quad(desc, Vec3(-5, -5, -1), Vec3(10, 0, 0), Vec3(0, 10, 0), test::add_material(desc, Rgb(0.5f)));
  test::add_sphere(desc, Vec3(0, 0, 5), 0.5f, add_metal(desc, 0.0f));          // a mirror: caster
  test::add_sphere(desc, Vec3(5, 0, 0), 0.5f, add_metal(desc, 0.6f));          // rough metal: not
  test::add_sphere(desc, Vec3(0, 0, -5), 0.5f, add_metal(desc, 0.5f));         // glossy metal: caster
  const int rough_glass = test::add_glass(desc, 1.5f, Rgb(1.0f), 1.0f, false, 0.5f);
  test::add_sphere(desc, Vec3(0, 5, 0), 0.5f, rough_glass);                    // rough glass: not
  // A glass box about the origin, placed at (0, -6, 0) by its instance: a caster there.
  const int glass = test::add_glass(desc, 1.5f);
  test::add_box(desc, Vec3(-0.5f), Vec3(0.5f), glass);
  desc.instances.back().object_to_world = Transform::translate(Vec3(0, -6, 0));
  const CausticCasters casters(desc);
  EXPECT_EQ(casters.size(), 3u);
  EXPECT_TRUE(aims_at(casters, Vec3(0, 0, 5)));
  EXPECT_TRUE(aims_at(casters, Vec3(0, 0, -5)));
  EXPECT_TRUE(aims_at(casters, Vec3(0, -6, 0)));
  EXPECT_FALSE(aims_at(casters, Vec3(5, 0, 0)));
  EXPECT_FALSE(aims_at(casters, Vec3(0, 5, 0)));
  EXPECT_FALSE(aims_at(casters, Vec3(-5, 0, -1)));
  EXPECT_TRUE(CausticCasters::is_caster(desc, desc.material(glass)));
  // A thin pane passes light straight on, to shadow rays too: nothing to aim at.
  EXPECT_FALSE(CausticCasters::is_caster(desc, desc.material(test::add_glass(desc, 1.5f, Rgb(1.0f), 1.0f, true))));
}

// A metal of factors 1 whose metallic-roughness texture (B metallic, G roughness) is `texels`, one
// row of RGB floats.
int add_textured_metal(SceneDesc& desc, const std::vector<Rgb>& texels) {
  ImageDesc img;
  img.width = int(texels.size());
  img.height = 1;
  img.channels = 3;
  for (const Rgb& t : texels) img.texels.insert(img.texels.end(), {t.x, t.y, t.z});
  desc.images.push_back(img);
  TextureDesc tex;
  tex.image = int(desc.images.size()) - 1;
  desc.textures.push_back(tex);
  const int m = add_metal(desc, 1.0f);
  desc.materials[size_t(m)].metallic_roughness_texture.texture = int(desc.textures.size()) - 1;
  return m;
}

TEST(CausticCasters, TexturedMetalIsJudgedByItsTexels) {
  SceneDesc desc;
  const Rgb polished(0, 0.1f, 1), rough(0, 0.9f, 1), polished_dielectric(0, 0.1f, 0);
  auto caster = [&](const std::vector<Rgb>& texels) {
    return CausticCasters::is_caster(desc, desc.material(add_textured_metal(desc, texels)));
  };
  // Roughness factor 1, but the texture polishes it: a caster; and the reverse is none.
  EXPECT_TRUE(caster({polished, polished}));
  EXPECT_FALSE(caster({rough, rough}));
  // Metallic factor 1, but the texture says no metal anywhere.
  EXPECT_FALSE(caster({polished_dielectric, polished_dielectric}));
  // A quarter of the texels polished metal is enough; a fifth is not.
  EXPECT_TRUE(caster({polished, rough, rough, rough}));
  EXPECT_FALSE(caster({polished, rough, rough, rough, rough}));
  // The texture scales the factors: roughness 0.6 x 1 is past the limit (0.5), 0.6 x 0.8 is not.
  const int scaled = add_textured_metal(desc, {Rgb(0, 0.6f, 1)});
  EXPECT_FALSE(CausticCasters::is_caster(desc, desc.material(scaled)));
  desc.materials[size_t(scaled)].roughness = 0.8f;
  EXPECT_TRUE(CausticCasters::is_caster(desc, desc.material(scaled)));
  // The scene finds it as the factors alone would not.
  test::add_sphere(desc, Vec3(0, 0, 5), 0.5f, add_textured_metal(desc, {polished}));
  EXPECT_EQ(CausticCasters(desc).size(), 1u);
}

TEST(CasterView, TakesConesThatAreNarrowAndAboveTheSurface) {
  SceneDesc desc;
  test::add_sphere(desc, Vec3(0, 0, 2), 0.5f, add_metal(desc, 0.0f));
  const CausticCasters casters(desc);
  auto cones = [&](const Vec3& p, const Vec3& n) {
    CasterView v;
    casters.view(p, n, v);
    return v.size();
  };
  EXPECT_EQ(cones(Vec3(0, 0, 0), Vec3(0, 0, 1)), 1);     // sin^2 = 1/16
  EXPECT_EQ(cones(Vec3(0, 0, 1.25f), Vec3(0, 0, 1)), 1);  // sin^2 = 0.44: under 45 degrees
  EXPECT_EQ(cones(Vec3(0, 0, 1.35f), Vec3(0, 0, 1)), 0);  // sin^2 = 0.59: wide enough for the BSDF
  EXPECT_EQ(cones(Vec3(0, 0, 1.8f), Vec3(0, 0, 1)), 0);  // inside the sphere
  EXPECT_EQ(cones(Vec3(0, 0, 0), Vec3(0, 0, -1)), 0);    // wholly below the tangent plane
  EXPECT_EQ(cones(Vec3(0, 0, 0), Vec3(1, 0, 0)), 1);     // half above it
}

TEST(CasterView, DensityIntegratesToOneAndMatchesWhereItsSamplesFall) {
  SceneDesc desc;
  const int mirror = add_metal(desc, 0.0f);
  test::add_sphere(desc, Vec3(0, 0, 2), 0.6f, mirror);
  test::add_sphere(desc, Vec3(0.5f, 0.2f, 2.5f), 0.4f, mirror);  // its cone overlaps the first
  test::add_sphere(desc, Vec3(-3, 1, 0.5f), 0.3f, mirror);
  const CausticCasters casters(desc);
  CasterView v;
  casters.view(Vec3(0.0f), Vec3(0, 0, 1), v);
  ASSERT_EQ(v.size(), 3);
  // Region R: directions with x > 0.1. P(sample in R) must equal the integral of pdf over R.
  auto in_region = [](const Vec3& w) { return w.x > 0.1f; };
  Pcg32 rng(11, 12);
  test::RunningStats total, region_integral, region_hits;
  const int n = 1 << 20;
  int rim = 0;  // samples the cone test alone puts outside every cone: rounding at a rim
  for (int i = 0; i < n; ++i) {
    const Vec3 u = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    const double f = 4.0 * kPi * v.pdf(u);
    total.add(f);
    region_integral.add(in_region(u) ? f : 0.0);
    int cone = -1;
    const Vec3 w = v.sample(rng.next_float(), {rng.next_float(), rng.next_float()}, &cone);
    ASSERT_NEAR(length(w), 1.0f, 1e-5f);
    ASSERT_TRUE(cone >= 0 && cone < v.size());
    ASSERT_GT(v.pdf(w, cone), 0.0f);
    if (v.pdf(w) == 0) ++rim;
    region_hits.add(in_region(w) ? 1.0 : 0.0);
  }
  EXPECT_NEAR(total.mean(), 1.0, test::kSigmas * total.standard_error());
  EXPECT_LE(rim, n / 10000) << "more samples outside their cone than rounding explains";
  const double se = std::hypot(region_integral.standard_error(), region_hits.standard_error());
  EXPECT_GT(region_hits.mean(), 0.05);
  EXPECT_NEAR(region_hits.mean(), region_integral.mean(), test::kSigmas * se);
}

// CausticCasters::view and CasterView::pdf take the slots as SIMD lanes, empty slots included. Slot
// by slot in floats, the cone formulas (view's comments) must give the same bits: count, coverage
// and the density toward any direction, with one caster or all kMaxCasters.
TEST(CasterView, LanesGiveTheSlotBySlotBits) {
  struct Sphere {
    Vec3 c;
    float r;
  };
  Pcg32 rng(5, 6);
  for (const int n : {1, 3, CausticCasters::kMaxCasters}) {
    SceneDesc desc;
    const int mirror = add_metal(desc, 0.0f);
    std::vector<Sphere> spheres;
    for (int k = 0; k < n; ++k) {  // radii falling, so that the casters' slots are the spheres' order
      spheres.push_back({Vec3(4 * rng.next_float() - 2, 4 * rng.next_float() - 2, 4 * rng.next_float() - 2),
                         0.5f - 0.05f * float(k)});
      test::add_sphere(desc, spheres.back().c, spheres.back().r, mirror);
    }
    const CausticCasters casters(desc);
    ASSERT_EQ(casters.size(), size_t(n));
    int aimed_views = 0;
    for (int i = 0; i < 2000; ++i) {
      // The first view is from the origin, where the empty slots' sin^2 is 0 / 0.
      Vec3 p(0.0f);
      if (i > 0)
        for (int c = 0; c < 3; ++c) p[c] = 6 * rng.next_float() - 3;
      const Vec3 nrm = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      CasterView v;
      casters.view(p, nrm, v);
      int count = 0;
      float coverage = 0, density[CausticCasters::kMaxCasters], dx[CausticCasters::kMaxCasters],
            dy[CausticCasters::kMaxCasters], dz[CausticCasters::kMaxCasters], edge[CausticCasters::kMaxCasters];
      for (int k = 0; k < n; ++k) {
        const Sphere& s = spheres[size_t(k)];
        dx[k] = s.c.x - p.x, dy[k] = s.c.y - p.y, dz[k] = s.c.z - p.z;
        const float d2 = dx[k] * dx[k] + dy[k] * dy[k] + dz[k] * dz[k], r2 = s.r * s.r, sin2 = r2 / d2;
        edge[k] = d2 - r2;
        const bool aimed = sin2 < 0.5f && sin2 > 1e-12f && dx[k] * nrm.x + dy[k] * nrm.y + dz[k] * nrm.z > -s.r;
        density[k] = aimed ? 1.0f / (kTwoPi * (sin2 / (1.0f + std::sqrt(1.0f - sin2)))) : 0.0f;
        count += aimed;
        coverage += aimed ? sin2 : 0.0f;
      }
      ASSERT_EQ(v.size(), count);
      ASSERT_EQ(std::bit_cast<uint32_t>(v.coverage()), std::bit_cast<uint32_t>(coverage));
      aimed_views += count > 0;
      for (int j = 0; j < 8; ++j) {
        // Toward a caster's centre (inside its cone, where aimed), or anywhere.
        const int toward = j < n ? j : -1;
        const Vec3 w = toward >= 0 ? normalize(Vec3(dx[j], dy[j], dz[j]))
                                   : sample_uniform_sphere({rng.next_float(), rng.next_float()});
        for (const int drawn_in : {-1, toward}) {
          float sum = 0;
          for (int k = 0; k < n; ++k) {
            const float t = w.x * dx[k] + w.y * dy[k] + w.z * dz[k];
            sum += k == drawn_in || (t > 0 && t * t >= edge[k]) ? density[k] : 0.0f;
          }
          const float expected = count > 0 ? sum / float(count) : 0.0f;
          ASSERT_EQ(std::bit_cast<uint32_t>(v.pdf(w, drawn_in)), std::bit_cast<uint32_t>(expected))
              << n << " casters, view " << i << ", direction " << j;
        }
      }
    }
    EXPECT_GT(aimed_views, 200) << "too few views aim at a caster to test them";
  }
}

TEST(CasterAiming, KeepsTheFurnaceExact) {
  // The furnace box (emission 1, albedo 0.5, radiance 2 everywhere) with a perfect mirror sphere
  // and a lossless glass sphere in it: they change no radiance, so every estimate's mean stays 2
  // whatever share of the bounces is aimed at them. Deep paths (Russian roulette from bounce 1)
  // make the depth limit's cut negligible.
  SceneDesc desc = test::furnace_box(1.0, 0.5);
  MaterialDesc mirror;
  mirror.name = "perfect mirror";
  mirror.base_color = Rgb(1.0f);
  mirror.metallic = 1;
  mirror.roughness = 0;
  desc.materials.push_back(mirror);
  test::add_sphere(desc, Vec3(0.45f, 0.1f, -0.8f), 0.25f, int(desc.materials.size()) - 1);
  test::add_sphere(desc, Vec3(-0.3f, 0.35f, -0.9f), 0.3f, test::add_glass(desc, 1.5f));
  ASSERT_EQ(CausticCasters(desc).size(), 2u);
  const int depth = 64;
  for (float share : {0.0f, 0.5f})
    test::expect_furnace(desc, test::furnace_camera(Vec3(0.1f)), 0.5, depth, 1, test::furnace_radiance(1.0, 0.5, depth),
                         share);
}

}  // namespace
}  // namespace prism
