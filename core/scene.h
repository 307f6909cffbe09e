// Scene: the Embree acceleration structure over a SceneDesc, with hit reconstruction, emitters and
// caustic casters.
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include "core/caustic_casters.h"
#include "core/embree_rays.h"
#include "core/emitters.h"
#include "core/ray.h"
#include "core/scene_desc.h"
#include "core/sphere_geometry.h"
#include "core/surface_hit.h"

namespace prism {

// Coverage (glTF alpha: base colour factor x texture alpha) of material `material` at uv. Core
// cannot evaluate materials itself; the caller hands this in (materials/ provides one).
using AlphaFunction = float (*)(const SceneDesc& scene, int material, Vec2 uv);

class Scene {
 public:
  // Validates `desc` (indices in range; throws std::invalid_argument naming the element) and
  // builds the BVH. A mesh placed once is transformed to world space and goes straight into
  // the top-level BVH; a mesh placed several times gets its own BVH, instanced per placement
  // (instancing costs a ray transform per visit, so only scenes that reuse meshes pay it).
  // All spheres share one user geometry. A scene far from its file's origin is moved to a render
  // origin first (core/render_origin.h): everything the scene hands out or takes in (desc(),
  // rays, hits, emitter samples) is relative to origin().
  // With `alpha`, primitives whose material has alphaMode MASK or BLEND get Embree filter
  // functions: MASK rejects hits below the cutoff; BLEND keeps a hit with probability alpha,
  // decided by a hash of the ray and the hit so every run makes the same choice. Without it
  // every surface is opaque. `lights` is how next-event estimation will choose among the
  // emitters (the light tree is built only when it is asked for).
  explicit Scene(SceneDesc desc, AlphaFunction alpha = nullptr, LightSampling lights = LightSampling::Tree);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // Nearest hit in (t_min, t_max). `coherent` marks camera rays for Embree's packet heuristics.
  bool intersect(const Ray& ray, SurfaceHit& hit, bool coherent = false) const;
  // True when anything blocks the ray within (t_min, t_max).
  bool occluded(const Ray& ray) const;
  // The same queries for n rays at once, traced as Embree's eight-wide packets (kPacketSize rays
  // each): entry k gives what intersect / occluded give for rays[k]. Coherent rays (camera rays,
  // shadow rays from neighbouring paths toward one light) are traced several times faster than
  // one by one.
  static constexpr int kPacketSize = kEmbreePacketSize;
  void intersect_packet(const Ray* rays, int n, SurfaceHit* hits, bool* found, bool coherent = false) const;
  void occluded_packet(const Ray* rays, int n, bool* occluded) const;
  // The thin-sheet triangles an occlusion query looked past, for one ray: where it met each, enough
  // to rebuild the hit (sheet_hit).
  struct SheetsCrossed {
    static constexpr int kKept = 16;  // as many as a path crosses straight (kMaxSheetCrossings)
    struct Crossing {  // left uninitialised: count says which are set
      unsigned geom, inst, prim;
      float u, v, t;
    };
    // Distinct crossings met, in no particular order; a triangle met twice, or two met at the same
    // distance (a shared edge), count once. Only the first kKept are kept.
    int count = 0;
    Crossing met[kKept];
  };
  // Occlusion that looks past thin sheets (MaterialDesc::is_thin_sheet): blocked[k] when something
  // else blocks rays[k]; crossed[k] the sheets within its range (count 0 for rays blocked). One
  // packet query answers the shadow rays of a scene with glass panes, those through a window too:
  // only the panes' transmittance is left to work out. Requires sees_every_sheet().
  void occluded_past_sheets(const Ray* rays, int n, bool* blocked, SheetsCrossed* crossed) const;
  // The hit a crossing stands for, as intersect() would give it for `ray`.
  void sheet_hit(const Ray& ray, const SheetsCrossed::Crossing& crossing, SurfaceHit& hit) const;
  // Whether occluded_past_sheets can tell every sheet apart: false when a sphere is one (the
  // spheres' own intersection code runs no filters).
  bool sees_every_sheet() const { return sees_every_sheet_; }

  const SceneDesc& desc() const { return desc_; }
  // The world position of the coordinates' origin: world = scene coordinates + origin().
  const Vec3& origin() const { return origin_; }
  const Emitters& emitters() const { return emitters_; }
  const CausticCasters& casters() const { return casters_; }
  const SceneFeatures& features() const { return features_; }
  double build_seconds() const { return build_seconds_; }
  // Triangles in the world, counting each instance of a mesh.
  uint64_t triangle_count() const;

 private:
  // A triangle primitive in its placement, with what reconstruct_triangle_hit reads of it looked up.
  struct HitPrimitive {
    const PrimitiveDesc* prim = nullptr;
    const MaterialDesc* material = nullptr;
    const Transform* object_to_world = nullptr;  // null: the primitive is in world space (baked)
    const Vec3* face_normals = nullptr;  // its triangles' unit world-space face normals, or null to compute
    const int* emitters = nullptr;       // Emitters::triangle_emitters, or null: no triangle emits
    int instance = -1;
  };

  // What a top-level geometry id stands for.
  struct TopGeometry {
    int instance = -1;   // the placement (instances and baked meshes)
    int primitive = -1;  // baked meshes: the primitive; instances: -1 (Embree's geomID says)
    // Baked meshes: each triangle's face_normal, computed once (double precision is dear per hit).
    std::vector<Vec3> face_normals;
    bool sheet = false;  // baked meshes: the primitive's material is a thin sheet
    // Baked meshes: the primitive as hits on it read it, looked up once, when the scene is built.
    HitPrimitive baked;
  };

  // What an alpha filter needs to know about the primitive it guards.
  struct AlphaFilterData {
    const Scene* scene;
    int mesh, primitive;
  };

  // Whether a hit on a material with alphaMode MASK or BLEND is kept: MASK by the cutoff, BLEND
  // with probability alpha drawn from `hash` (a function of the ray and the hit point).
  bool keeps_hit(int material, Vec2 uv, uint64_t hash) const;
  static bool sphere_keeps_hit(const void* owner, int sphere, Vec2 uv, const Ray& ray, float t);

  void bake_single_use_meshes();
  void attach_alpha_filter(RTCGeometry geom, int mesh, int primitive);
  static void alpha_filter(const RTCFilterFunctionNArguments* args);
  // occluded_past_sheets' filter: skips the triangle a ray leaves and passes through sheets.
  static void sheet_filter(const RTCFilterFunctionNArguments* args);
  // Whether Embree's hit (geomID, instID) is on a thin sheet's triangle.
  bool is_sheet_hit(unsigned geom, unsigned inst) const;
  // Fills `hit` from Embree's answer for `ray`; false when the ray hit nothing.
  bool resolve_hit(const Ray& ray, const EmbreeHit& found, SurfaceHit& hit) const;
  // Embree's closest hit for one ray, with or without the filter that skips the triangle it leaves.
  RTCRayHit intersect_one(const Ray& ray, bool coherent, bool filter) const;
  // One packet of n <= kPacketSize rays.
  void intersect8(const Ray* rays, int n, SurfaceHit* hits, bool* found, bool coherent) const;
  void occluded8(const Ray* rays, int n, bool* occluded) const;
  // The same under a given intersection context (its filter decides what blocks).
  void occluded8(const Ray* rays, int n, bool* occluded, RTCIntersectContext* context) const;
  // Primitive `primitive` of instance `instance`, looked up; face_normals as in HitPrimitive.
  HitPrimitive hit_primitive(int instance, int primitive, const Vec3* face_normals) const;
  void reconstruct_triangle_hit(const HitPrimitive& source, const Ray& ray, const EmbreeHit& found,
                                SurfaceHit& hit) const;
  void reconstruct_sphere_hit(const Ray& ray, const EmbreeHit& found, SurfaceHit& hit) const;

  SceneDesc desc_;
  Vec3 origin_{0.0f};
  SceneFeatures features_;
  RTCScene top_ = nullptr;
  std::vector<RTCScene> mesh_scenes_;  // per mesh; null for meshes baked into the top level
  std::vector<TopGeometry> top_geometries_;
  unsigned sphere_geom_id_ = RTC_INVALID_GEOMETRY_ID;
  bool sees_every_sheet_ = true;
  SphereGeometry sphere_geometry_;
  Emitters emitters_;
  CausticCasters casters_;
  AlphaFunction alpha_ = nullptr;
  std::vector<std::unique_ptr<AlphaFilterData>> alpha_filters_;
  double build_seconds_ = 0;
};

// Throws std::invalid_argument if any index in `desc` is out of range.
void validate_scene_desc(const SceneDesc& desc);

}  // namespace prism
