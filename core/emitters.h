// Emitters: every light of a scene (emissive triangles, quads and spheres as area lights, punctual
// and the environment), chosen by a light tree or in proportion to emitted power.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/distribution_1d.h"
#include "core/environment_light.h"
#include "core/environment_portals.h"
#include "core/light_tree.h"
#include "core/scene_desc.h"
#include "core/spherical_triangle.h"

namespace prism {

// A point sampled on an emitter, seen from a reference point.
struct EmitterSample {
  Vec3 p;        // point on the emitter
  Vec3 p_error;  // error bound of p, for offsetting the shadow ray's far end
  Vec3 n;        // unit front-face normal of the emitter at p
  Vec2 uv;       // texture coordinates at p, for emissive textures
  int material = -1;
  int emitter = -1;
  // Area lights: solid-angle density at the reference point, including the choice of emitter.
  // Punctual lights: the probability of choosing this light.
  float pdf = 0;
  bool delta = false;     // a punctual light: no surface to hit, no MIS
  bool infinite = false;  // the environment: nothing to hit but the sky
  Vec3 wi;                // punctual and environment: unit direction toward the light
  float distance = 0;     // punctual: to the light (+inf for directional and environment)
  // Punctual: irradiance at a surface facing the light. Environment: radiance along -wi.
  Rgb incident;
};

// How next-event estimation chooses a light. Power: in proportion to emitted power, the same
// everywhere. Tree: lights with a position go down a light tree by their importance at the shading
// point (distance, orientation, the surface's normal); lights at infinity by power.
enum class LightSampling { Power, Tree };

class Emitters {
 public:
  Emitters() = default;
  // Collects emitters from `desc`, which must outlive this object. An emitter's power is area x pi
  // x the luminance of mean_emission (x2 if double-sided). The light tree is built only for
  // LightSampling::Tree: choosing by power does not pay for it.
  explicit Emitters(const SceneDesc& desc, LightSampling how = LightSampling::Tree);

  bool empty() const { return pick_.size() == 0; }
  // Area emitters: spheres, triangles, and quads (two triangles of a primitive, one after the
  // other, that share an edge and form a parallelogram: one light, sampled as a whole).
  size_t size() const { return emitters_.size(); }

  // A light chosen for a shading point: an emitter, then punctual lights, then the environment.
  struct Pick {
    size_t index = 0;
    float pmf = 0;
    float remapped = 0;  // u rescaled to [0, 1) within the chosen emitter's share of it
  };
  // Whether choosing the lights of several shading points together (pick_many) pays: where the
  // light depends on the point (a light tree) and the tree is larger than the caches, so that the
  // walks wait for their nodes together. On a tree that fits in them (16,384 lights take 1.6 MB of
  // nodes) a walk waits for little, and the shading around each walk hides its chain of square roots.
  bool picks_ahead() const { return tree_pays() && tree_.node_bytes() >= kPickAheadBytes; }
  static constexpr size_t kPickAheadBytes = size_t(4) << 20;
  // The light sample(ref[i], ref_n[i], ., u) chooses where u.x = u_x[i], for count shading points
  // at once: on a light tree their walks go together (LightTree::sample_many), and the chosen
  // emitters are asked for from memory before any is sampled.
  void pick_many(const Vec3* ref, const Vec3* ref_n, const float* u_x, int count, std::optional<Pick>* out) const;

  // Samples a point on an emitter for shading point `ref` on a surface with unit normal `ref_n`
  // (zero: none); pdf 0 when nothing can be sampled. u chooses the emitter and the point on it;
  // u_spare stands in for u.x where the emitter's share of u.x is too narrow to place the point.
  // sky: environment_.sample(*environment_map_draw(u_spare, u)) when the caller drew it already
  // (a batch of draws at once), else null. portal_view: portals().view(ref), where the caller made
  // it already (portal_views, for a batch of points at once), else null.
  EmitterSample sample(const Vec3& ref, const Vec3& ref_n, float u_spare, Vec2 u,
                       const EnvironmentLight::Sample* sky = nullptr,
                       const EnvironmentPortals::View* portal_view = nullptr) const;
  // sample() where the light was chosen already: `chosen` is pick_many's choice for (ref, ref_n, u.x).
  EmitterSample sample_light(const std::optional<Pick>& chosen, const Vec3& ref, float u_spare, Vec2 u,
                             const EnvironmentLight::Sample* sky = nullptr,
                             const EnvironmentPortals::View* portal_view = nullptr) const;
  // An area light as sample_light samples it.
  struct Emitter {
    bool sphere = false;
    bool quad = false;   // p0 + u (p1 - p0) + v (p2 - p0) over the unit square: halves A and B
    int instance = -1;   // triangles: instance and primitive, to look up vertex attributes
    int primitive = -1;
    uint32_t index = 0;  // triangle (a quad's half A) within the primitive, or sphere index
    uint32_t index_b = 0;  // quads: the triangle that is half B
    int material = -1;
    // World-space corners, front face counter-clockwise (winding x handedness). Half A is
    // (p0, p1, p2); a quad's half B is (p1, p3, p2), p3 its own fourth corner, within quad_slack
    // of p1 + p2 - p0.
    Vec3 p0, p1, p2, p3;
    float quad_slack = 0;
    uint8_t corner[6] = {0, 1, 2, 0, 1, 2};  // the file's corner (0-2) of each half's corners, A then B
    Vec3 normal;         // triangles and quads: unit front-face normal
    float area = 0;
    float longest_edge2 = 0;  // triangles and quads: squared length of a half's longest edge
    bool textured = false;  // the emission varies over the surface: uvs are needed
    bool double_sided = false;  // triangles and quads: emits from the back face too
    // Half A's (0) or half B's (1) corners, in the order barycentrics weigh them.
    const Vec3& corner0(int half) const { return half == 0 ? p0 : p1; }
    const Vec3& corner1(int half) const { return half == 0 ? p1 : p3; }
    const Vec3& corner2(int) const { return p2; }
  };

  // An untextured triangle or quad light's constants as SIMD kernels load them (lanes::direct_light):
  // three loads of eight floats each, which eight lights' records transpose into rows of lanes.
  struct LaneRecord {
    enum Field { kP0 = 0, kP1 = 3, kP2 = 6, kP3 = 9, kNormal = 12, kEmission = 15, kSlack = 18, kPdfArea, kQuad,
                 kDoubleSided, kLongestEdge2, kFields };
    static constexpr int kFloats = 24;
    static_assert(kFields <= kFloats);
    alignas(32) float v[kFloats] = {};
  };
  // Light e's record, with the radiance it emits (0 where it emits nothing).
  static LaneRecord lane_record(const Emitter& e, const Rgb& emission);
  // The light sample_light would choose, and the point draw it would use, on an untextured triangle
  // or quad with an area, for next-event estimation in SIMD lanes (lanes::direct_light,
  // integrators/lane_direct_light.h). They finish the sample bit for bit as sample_light does: no
  // sample from the light's back (faces), by solid angle where the vertex is near (near_enough) and
  // the solid angle pays (SolidAngleView), else the point by area (area_point_draw).
  struct TriangleDraw {
    const Emitter* light = nullptr;
    const LaneRecord* record = nullptr;  // the light's
    Vec2 u;           // the point's draw (u.x rescaled, point_draw)
    float pmf = 0;    // of choosing the light
  };
  // The half (0: A, 1: B) and barycentrics a draw u places a point at by area.
  static int area_point_draw(const Emitter& e, Vec2 u, Barycentrics& b);
  enum class Draw {
    kNothing,     // sample_light's pdf is 0: no light, or one with no area
    kOnTriangle,  // `out` holds the draw
    kToward,      // a punctual light or the environment: sample_light gives a direction toward it
    kOther,       // another kind of sample (a sphere, a textured emitter): sample_light makes it
  };
  // Solid angles under kMinSolidAngle (a grazing view) or near 2 pi (ref almost on the triangle)
  // stay with area sampling, as in pbrt-v4, where the spherical construction loses precision.
  static constexpr float kMinSolidAngle = 3e-4f;
  static constexpr float kMaxSolidAngle = 6.22f;
  // What sample_light(chosen, ref, u_spare, u) makes of this draw; `chosen` null: the light that
  // sample(ref, ref_n, u_spare, u) would choose.
  Draw triangle_draw(const std::optional<Pick>* chosen, const Vec3& ref, const Vec3& ref_n, float u_spare, Vec2 u,
                     TriangleDraw& out) const;

  // Where the draw (u_spare, u) chooses a map's sky, and the sky has no portals, the draw it hands
  // the map: a light is chosen before the shading point is known only there (lights at infinity
  // are chosen by power). So a packet's sky samples can be drawn together, ahead of shading.
  std::optional<Vec2> environment_map_draw(float u_spare, Vec2 u) const;
  // Solid-angle pdf of sample() choosing point p (normal n) on emitter `index` from `ref`.
  float pdf(int index, const Vec3& ref, const Vec3& ref_n, const Vec3& p, const Vec3& n) const;

  // Emitter index of a triangle of primitive (instance, primitive), or -1 when it emits nothing.
  int triangle_emitter(int instance, int primitive, uint32_t triangle) const {
    const int* emitters = triangle_emitters(instance, primitive);
    return emitters ? emitters[triangle] : -1;
  }
  // Primitive (instance, primitive)'s emitter index per triangle (-1: emits nothing), or null when
  // none of its triangles emits.
  const int* triangle_emitters(int instance, int primitive) const {
    if (prim_triangle_base_.empty()) return nullptr;
    const int base = prim_triangle_base_[size_t(instance_prim_base_[size_t(instance)] + primitive)];
    return base >= 0 ? &triangle_emitter_[size_t(base)] : nullptr;
  }
  // Emitter index of sphere `s`, or -1.
  int sphere_emitter(int s) const { return sphere_emitter_[s]; }
  const EnvironmentLight& environment() const { return environment_; }
  // Density of sample() choosing direction w toward the environment from `ref`, including the
  // choice (it depends on ref where portals lead to the sky); map_pdf is the environment's own
  // density of w (EnvironmentLight::seen).
  float environment_pdf(const Vec3& ref, const Vec3& w, float map_pdf) const;
  const EnvironmentPortals& portals() const { return portals_; }
  // The probability of choosing light `index` (an emitter, then punctual lights, then the
  // environment) from `ref`.
  float pick_probability(int index, const Vec3& ref, const Vec3& ref_n) const;
  // The same by power alone, which does not depend on where the light is seen from.
  float power_pick_probability(int index) const { return pick_.pmf(index); }
  const LightTree& tree() const { return tree_; }  // empty unless sampling by tree
  LightSampling light_sampling() const { return how_; }

 private:
  // sample_light's sky where it has portals, seen as `view` from ref: its direction, radiance and
  // density (the mixture of portals and map); false where the draw gives none.
  bool sky_sample(const EnvironmentPortals::View& view, const Vec3& ref, Vec2 u, Vec3& wi,
                  EnvironmentLight::Seen& seen, float& pdf_dir) const;
  Emitter make_triangle(const InstanceDesc& inst, int instance, const PrimitiveDesc& prim, int primitive,
                        uint32_t t) const;
  // Makes `a` the quad of a and the triangle b that follows it, when they form one.
  static bool merge_into_quad(Emitter& a, const Emitter& b);
  // The spherical triangles a triangle or quad is sampled by near ref, where near_enough and it pays.
  struct SolidAngleView;
  static bool near_enough(const Emitter& e, float plane_distance);

  // Triangles and quads: by solid angle where near_enough and SolidAngleView::pays(), else by area.
  EmitterSample sample_triangle(const Emitter& e, const Vec3& ref, Vec2 u) const;
  // plane_distance is dot(ref - p0, normal): positive on the front side.
  static bool faces(const Emitter& e, float plane_distance);
  // The point at barycentrics b of half A (0) or B (1).
  EmitterSample triangle_point(const Emitter& e, int half, const Barycentrics& b) const;
  float triangle_pdf(const Emitter& e, const Vec3& ref, const Vec3& p, const Vec3& n) const;
  EmitterSample sample_sphere(const Emitter& e, const Vec3& ref, Vec2 u) const;
  float sphere_pdf(const Emitter& e, const Vec3& ref, const Vec3& p, const Vec3& n) const;

  void build_tree(const SceneDesc& desc, const std::vector<double>& power);
  std::optional<Pick> pick(const Vec3& ref, const Vec3& ref_n, float u) const;
  // The light a walk down the tree, after pick_first() chose it, ends at.
  static std::optional<Pick> down_the_tree(const Pick& first, const std::optional<LightTree::Pick>& leaf) {
    if (!leaf) return std::nullopt;
    return Pick{size_t(leaf->item), first.pmf * leaf->pmf, leaf->remapped};
  }
  // The step of pick() that does not depend on the shading point: by power among all lights, or
  // between the tree (index kDownTheTree, to go on with `remapped`) and each light at infinity.
  static constexpr size_t kDownTheTree = ~size_t(0);
  std::optional<Pick> pick_first(float u) const;
  // The draw that places the point on the light chosen by `chosen`: u.x rescaled within the
  // light's share, or u_spare where that share is too narrow (see sample()).
  static float point_draw(const Pick& chosen, float u_spare) {
    return chosen.pmf >= 0x1p-8f ? chosen.remapped : u_spare;
  }

  const SceneDesc* desc_ = nullptr;
  LightSampling how_ = LightSampling::Tree;
  std::vector<Emitter> emitters_;
  std::vector<LaneRecord> lane_records_;  // per emitter (those of spheres and textured lights unused)
  Distribution1D pick_;
  // Tree sampling: first among the tree as a whole (slot 0, when it has lights) and the lights at
  // infinity, by power; then down the tree. unbounded_[slot] is the light a slot stands for.
  LightTree tree_;
  Distribution1D top_;
  std::vector<int> unbounded_;
  std::vector<int> top_slot_;  // light -> its slot in top_, -1 for lights in the tree
  // A tree that is one leaf (one light, or lights it cannot tell apart) chooses by power alone.
  bool tree_pays() const { return how_ == LightSampling::Tree && tree_.depth() > 0; }
  std::vector<int> instance_prim_base_;   // per instance: offset into prim_triangle_base_
  std::vector<int> prim_triangle_base_;   // per (instance, primitive): offset into triangle_emitter_, or -1
  std::vector<int> triangle_emitter_;     // per emissive triangle: its emitter
  std::vector<int> sphere_emitter_;
  EnvironmentLight environment_;
  // Where a scene has thin glass sheets, the environment is sampled through them as well as by
  // its own density: kPortalShare of its samples, wherever a portal is in view (0.75: in a room
  // lit through glass 0.65x the error of 0.5, with an open doorway as well 1.05x; PERFORMANCE.md).
  EnvironmentPortals portals_;
  static constexpr float kPortalShare = 0.75f;
  // The environment's own density (map_pdf, at w) and the portals' mixed, at direction w from ref.
  float environment_direction_pdf(const EnvironmentPortals::View* view, const Vec3& ref, const Vec3& w, float map_pdf,
                                  int drawn_in = -1) const;
  // Punctual lights follow the area emitters in pick_ (light k is item size() + k); the
  // environment, when present, is the last item.
  int environment_index_ = -1;
};

// Mean of a material's emitted radiance over its texture (factor x strength x mean texel).
Rgb mean_emission(const SceneDesc& desc, const MaterialDesc& m);

}  // namespace prism
