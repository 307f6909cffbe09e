// Quad emitters: two triangles that form a parallelogram are one light, sampled as a whole.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/emitters.h"
#include "core/pcg32.h"
#include "core/transform.h"
#include "chi_square.h"
#include "scene_builders.h"
#include "solid_angle.h"
#include "statistics.h"

namespace prism {
namespace {

using test::triangle_solid_angle;

// One emissive primitive with these corners and triangles (and uvs, when given, which make the
// emission textured: a texture index with no image behind it is enough for the sampler).
SceneDesc light_scene(std::vector<Vec3> positions, std::vector<uint32_t> indices, std::vector<Vec2> uvs = {},
                      const Transform& xf = Transform(), bool double_sided = false) {
  SceneDesc scene;
  const int light = test::add_material(scene, Rgb(0.0f), Rgb(1.0f), double_sided);
  if (!uvs.empty()) scene.materials[size_t(light)].emissive_texture.texture = 0;
  PrimitiveDesc prim;
  prim.material = light;
  prim.positions = std::move(positions);
  prim.indices = std::move(indices);
  prim.uvs = std::move(uvs);
  test::add_mesh(scene, std::move(prim), xf);
  return scene;
}

TEST(QuadEmitters, TwoTrianglesOfAParallelogramAreOneLight) {
  const Vec3 o(0, 0, 1), u(1, 0, 0), v(0.4f, 0.7f, 0);  // a parallelogram, not a rectangle
  const std::vector<Vec3> corners = {o, o + u, o + u + v, o + v};
  struct Case {
    const char* what;
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices;
    size_t emitters;
  };
  const Case cases[] = {
      {"split along 0-2", corners, {0, 1, 2, 0, 2, 3}, 1},
      {"split along 1-3", corners, {0, 1, 3, 1, 2, 3}, 1},
      {"second triangle's corners turned", corners, {0, 1, 2, 3, 0, 2}, 1},
      {"unwelded: the diagonal's corners twice", {o, o + u, o + u + v, o, o + u + v, o + v}, {0, 1, 2, 3, 4, 5}, 1},
      {"a kite: the fourth corner 1% off", {o, o + u, o + u + v, o + v * 1.01f}, {0, 1, 2, 0, 2, 3}, 2},
      {"wound the other way", corners, {0, 1, 2, 0, 3, 2}, 2},
      {"not one after the other", {o, o + u, o + u + v, o + v, o + Vec3(5, 0, 0), o + Vec3(6, 0, 0), o + Vec3(5, 1, 0)},
       {0, 1, 2, 4, 5, 6, 0, 2, 3}, 3},
      {"two quads", {o, o + u, o + u + v, o + v, o + u * 2, o + u * 2 + v}, {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2}, 2},
  };
  for (const Case& c : cases) {
    const SceneDesc scene = light_scene(c.positions, c.indices);
    const Emitters emitters(scene);
    EXPECT_EQ(emitters.size(), c.emitters) << c.what;
    if (c.emitters == 1) EXPECT_EQ(emitters.triangle_emitter(0, 0, 0), emitters.triangle_emitter(0, 0, 1)) << c.what;
  }
}

// Sampled from near (by solid angle, the two halves in proportion to theirs), from afar (by area,
// the unit square mapped linearly onto the parallelogram) and at a grazing angle, a quad's points
// must fall on it with the density pdf() reports: each of 4 x 4 cells of the parallelogram gets
// the pdf integrated over it (on 8 x 8 sub-cells), by a chi-square test, and E[1 / pdf] is the
// solid angle of the whole. A mirrored instance and a double-sided quad seen from behind as well.
TEST(QuadEmitters, SamplesFollowTheirPdfOverTheWholeQuad) {
  const Vec3 o(-0.5f, -0.3f, 1.0f), u(1.0f, 0, 0), v(0.4f, 0.7f, 0);
  const std::vector<Vec3> corners = {o, o + v, o + u + v, o + u};  // front face toward -z
  struct Case {
    Vec3 ref;
    Transform xf;
    bool double_sided;
  };
  const Transform mirror = Transform::scale(Vec3(-1, 1, 1));
  const Case cases[] = {{Vec3(0.1f, 0.1f, 0.6f), Transform(), false},   {Vec3(0.1f, 0.2f, -3.0f), Transform(), false},
                        {Vec3(2.5f, 0.2f, 0.9f), Transform(), false},   {Vec3(-0.1f, 0.1f, 0.7f), mirror, false},
                        {Vec3(-0.1f, 0.1f, -4.0f), mirror, false},      {Vec3(0.2f, 0.3f, 1.3f), Transform(), true},
                        {Vec3(3.0f, 0.1f, -0.7f), Transform(), false},  // far, but the corners' distances differ
                        {Vec3(0.1f, 0.1f, 0.999f), Transform(), false}};  // nearly on it: not by solid angle
  for (const Case& c : cases) {
    const SceneDesc scene = light_scene(corners, {0, 1, 2, 0, 2, 3}, {}, c.xf, c.double_sided);
    const Emitters emitters(scene);
    ASSERT_EQ(emitters.size(), 1u);
    // The parallelogram in world space: corner wo, edges wu and wv.
    const Vec3 wo = c.xf.point(o), wu = c.xf.vector(u), wv = c.xf.vector(v);
    const Vec3 light_normal = normalize(cross(wu, wv));
    constexpr int kCells = 4, kSub = 8, n = 160000;
    std::vector<double> expected(kCells * kCells, 0.0), counts(kCells * kCells, 0.0);
    double total = 0;
    const Vec3 du = wu / (kCells * kSub), dv = wv / (kCells * kSub);
    const double sub_area = length(cross(du, dv));
    for (int cell = 0; cell < kCells * kCells; ++cell)
      for (int sub = 0; sub < kSub * kSub; ++sub) {
        const int i = (cell % kCells) * kSub + sub % kSub, j = (cell / kCells) * kSub + sub / kSub;
        const Vec3 lo = wo + du * float(i) + dv * float(j);
        const double solid_angle = triangle_solid_angle(lo - c.ref, lo + du - c.ref, lo + du + dv - c.ref) +
                                   triangle_solid_angle(lo - c.ref, lo + du + dv - c.ref, lo + dv - c.ref);
        total += solid_angle;
        // In area measure, where the density is smooth even right under ref: pdf x cos / d^2.
        const Vec3 centre = lo + (du + dv) * 0.5f, to = centre - c.ref;
        const double d2 = length_squared(to), cosine = std::abs(dot(light_normal, to)) / std::sqrt(d2);
        expected[size_t(cell)] += n * emitters.pdf(0, c.ref, Vec3(), centre, light_normal) * cosine / d2 * sub_area;
      }
    // Where a point falls in the parallelogram's own coordinates (a, b): p = wo + a wu + b wv.
    const Vec3 normal = cross(wu, wv);
    Pcg32 rng(21, 22);
    test::RunningStats inverse_pdf;
    for (int i = 0; i < n; ++i) {
      const EmitterSample s = emitters.sample(c.ref, Vec3(), rng.next_float(), {rng.next_float(), rng.next_float()});
      ASSERT_GT(s.pdf, 0.0f) << "ref " << c.ref.x << " " << c.ref.z;
      ASSERT_NEAR(emitters.pdf(s.emitter, c.ref, Vec3(), s.p, s.n), s.pdf, 1e-4f * s.pdf);
      const Vec3 d = s.p - wo;
      ASSERT_NEAR(dot(d, normal), 0.0f, 1e-5f);
      const float a = dot(cross(d, wv), normal) / dot(normal, normal);
      const float b = dot(cross(wu, d), normal) / dot(normal, normal);
      ASSERT_GE(a, -1e-5f);
      ASSERT_LE(a, 1 + 1e-5f);
      ASSERT_GE(b, -1e-5f);
      ASSERT_LE(b, 1 + 1e-5f);
      counts[size_t(std::clamp(int(b * kCells), 0, kCells - 1) * kCells + std::clamp(int(a * kCells), 0, kCells - 1))] += 1;
      inverse_pdf.add(1.0 / s.pdf);
    }
    EXPECT_LT(test::chi2(counts, expected), test::chi2_critical(kCells * kCells - 1)) << "ref " << c.ref.x << " " << c.ref.z;
    EXPECT_NEAR(inverse_pdf.mean(), total, test::kSigmas * inverse_pdf.standard_error() + 1e-5 * total)
        << "ref " << c.ref.x << " " << c.ref.z;
  }
}

// A textured quad's samples carry the uvs of the triangle they fall in, interpolated over that
// triangle's own vertices in the file's order: here the second triangle's vertices are its own
// (unwelded) with uvs 10 apart from the first's, so a point given the other half's uvs, or the
// corners' uvs in the wrong order, shows. Plain and mirrored, near (by solid angle) and far (by area).
Vec2 weigh(Vec2 t0, float w0, Vec2 t1, float w1, Vec2 t2, float w2) {
  return {t0.x * w0 + t1.x * w1 + t2.x * w2, t0.y * w0 + t1.y * w1 + t2.y * w2};
}

TEST(QuadEmitters, TexturedSamplesCarryTheirTrianglesUvs) {
  const Vec3 o(-0.5f, -0.3f, 1.0f), u(1.0f, 0, 0), v(0.4f, 0.7f, 0);
  const std::vector<Vec3> positions = {o, o + v, o + u + v, o + u + v, o + u, o};
  const std::vector<Vec2> uvs = {{0, 0}, {0, 1}, {1, 1}, {11, 11}, {11, 10}, {10, 10}};
  const std::vector<uint32_t> indices = {0, 1, 2, 3, 4, 5};
  for (const Transform& xf : {Transform(), Transform::scale(Vec3(-1, 1, 1))}) {
    const SceneDesc scene = light_scene(positions, indices, uvs, xf);
    const Emitters emitters(scene);
    ASSERT_EQ(emitters.size(), 1u);
    for (const Vec3 ref : {Vec3(0.0f, 0.2f, 0.5f), Vec3(0.0f, 0.2f, -5.0f)}) {
      Pcg32 rng(7, 8);
      int in_second = 0;
      for (int i = 0; i < 2000; ++i) {
        const EmitterSample s = emitters.sample(xf.point(Vec3(ref.x, ref.y, 0)) + Vec3(0, 0, ref.z), Vec3(),
                                                rng.next_float(), {rng.next_float(), rng.next_float()});
        ASSERT_GT(s.pdf, 0.0f);
        // Back in object space: which triangle holds the point, and its barycentrics there.
        const Vec3 p = xf.inverse().point(s.p);
        const Vec3 local = p - o;  // = a v + b u for triangle 1 (o, o+v, o+u+v): b <= a
        const float b = local.x - local.y * (v.x / v.y), a = local.y / v.y;
        const bool second = b > a;
        in_second += second;
        Vec2 expected;
        if (!second) {  // (o, o+v, o+u+v): weights 1 - a, a - b, b
          expected = weigh(uvs[0], 1 - a, uvs[1], a - b, uvs[2], b);
        } else {  // (o+u+v, o+u, o): weights a, b - a, 1 - b
          expected = weigh(uvs[3], a, uvs[4], b - a, uvs[5], 1 - b);
        }
        ASSERT_NEAR(s.uv.x, expected.x, 1e-4f) << "sample " << i;
        ASSERT_NEAR(s.uv.y, expected.y, 1e-4f) << "sample " << i;
      }
      EXPECT_GT(in_second, 500);  // both halves sampled
      EXPECT_LT(in_second, 1500);
    }
  }
}

}  // namespace
}  // namespace prism
