// A diffuse plane lit by a sun and seen at a grazing angle, whose every pixel is known exactly; and
// the small path-traced renders the extremes tests look through.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/constants.h"
#include "core/renderer.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "scene_builders.h"

namespace prism::test {

inline constexpr int kNoRoulette = 1 << 20;

// Renders `desc` with the path tracer at max depth `depth` from a camera at eye looking at target
// (`up` up the image); no sample may be non-finite.
inline Film render_view(SceneDesc desc, const Vec3& eye, const Vec3& target, int depth, int size = 32, int spp = 4,
                        const Vec3& up = Vec3(0, 0, 1)) {
  const Scene scene(std::move(desc));
  CameraDesc cam;
  cam.camera_to_world = Transform::look_at(eye, target, up);
  cam.yfov = 0.5f;
  RenderSettings settings;
  settings.width = settings.height = size;
  settings.spp = spp;
  settings.max_depth = depth;
  Film film(size, size);
  const RenderStats stats = render(scene, Camera(cam, size, size), PathIntegrator(depth, kNoRoulette), settings, film);
  EXPECT_EQ(stats.nonfinite_samples, 0u);
  return film;
}

// A sun 60 degrees from +z, delivering kSunLux: on a plane z = const of albedo a, facing up,
// every point reflects a / pi x kSunLux x cos 60 (a delta light and no other surface: no noise).
inline constexpr float kSunLux = 3.0f;

inline void add_sun(SceneDesc& desc, const Transform& turn = Transform()) {
  PunctualLightDesc sun;
  sun.type = LightType::Directional;
  sun.direction = normalize(turn.vector(Vec3(std::sin(kPi / 3), 0.0f, -std::cos(kPi / 3))));
  sun.intensity = Rgb(kSunLux);
  desc.lights.push_back(sun);
}

inline double sunlit_radiance(double albedo) { return albedo / kPi * kSunLux * 0.5; }

// A 200 x 200 plane z = 0 of albedo `albedo` (material 0, mesh 0, front face +z) under the sun,
// scaled by s and moved by offset.
inline SceneDesc lit_plane(float s, const Vec3& offset, float albedo = 0.5f) {
  SceneDesc desc;
  const int m = add_material(desc, Rgb(albedo));
  add_quad(desc, Vec3(-100, -100, 0) * s + offset, Vec3(200, 0, 0) * s, Vec3(0, 200, 0) * s, m);
  add_sun(desc);
  return desc;
}

// The plane seen from 4 s away at 75 degrees off its normal (from below it when `from_below`),
// grazing enough that acne would show; `turn` turns the view with a turned scene.
inline Film view_lit_plane(SceneDesc desc, float s, const Vec3& offset, const Transform& turn = Transform(),
                           bool from_below = false, int depth = 1) {
  const Vec3 eye = turn.vector(Vec3(0.0f, -std::sin(1.309f), std::cos(1.309f) * (from_below ? -1.0f : 1.0f))) * (4.0f * s);
  return render_view(std::move(desc), eye + offset, offset, depth, 32, 4, turn.vector(Vec3(0, 0, 1)));
}

// The scales scale-sensitive cells are tried at, and the far placement: scale 1 moved to kFar,
// where the float spacing is 2^-7.
inline const std::vector<float> kScales = {1e-4f, 1e-2f, 1.0f, 1e2f, 1e4f, 1e6f};
inline const Vec3 kFar(1e5f, -1e5f, 1e5f);

// Every scale, then scale 1 moved far from the origin: {scale, offset}.
inline std::vector<std::pair<float, Vec3>> placements() {
  std::vector<std::pair<float, Vec3>> p;
  for (float s : kScales) p.push_back({s, Vec3(0.0f)});
  p.push_back({1.0f, kFar});
  return p;
}

// Pixels the scene covers, and those of them whose red channel lies outside [lo, hi] widened by
// 1e-5 relative.
struct PixelCheck {
  int covered = 0, outside = 0;
};

inline PixelCheck check_pixels(const Film& film, double lo, double hi) {
  const std::vector<float> rgba = film.resolve_rgba();
  PixelCheck c;
  for (size_t i = 0; i < rgba.size(); i += 4) {
    if (rgba[i + 3] < 1.0f) continue;
    ++c.covered;
    c.outside += rgba[i] < lo * (1 - 1e-5) || rgba[i] > hi * (1 + 1e-5);
  }
  return c;
}

}  // namespace prism::test
