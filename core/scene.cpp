#include "core/scene.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/constants.h"
#include "core/embree_device.h"
#include "core/embree_rays.h"
#include "core/face_normal.h"
#include "core/hash.h"
#include "core/render_origin.h"
#include "core/spawn.h"
#include "core/sphere_geometry.h"
#include "core/tsan_annotations.h"
#include "core/tangents.h"

namespace prism {

void validate_scene_desc(const SceneDesc& desc) {
  auto fail = [&](const std::string& what) { throw std::invalid_argument(desc.source + ": " + what); };
  const int n_materials = static_cast<int>(desc.materials.size());
  for (size_t m = 0; m < desc.meshes.size(); ++m) {
    for (size_t p = 0; p < desc.meshes[m].primitives.size(); ++p) {
      const PrimitiveDesc& prim = desc.meshes[m].primitives[p];
      const std::string where = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      if (prim.material < -1 || prim.material >= n_materials) fail(where + ": material index out of range");
      if (prim.indices.size() % 3 != 0) fail(where + ": index count is not a multiple of 3");
      if (!prim.normals.empty() && prim.normals.size() != prim.positions.size())
        fail(where + ": normal count differs from position count");
      if (!prim.uvs.empty() && prim.uvs.size() != prim.positions.size())
        fail(where + ": uv count differs from position count");
      if (!prim.tangents.empty() &&
          (prim.tangents.size() != prim.positions.size() || prim.tangent_signs.size() != prim.positions.size()))
        fail(where + ": tangent count differs from position count");
      for (uint32_t i : prim.indices)
        if (i >= prim.positions.size()) fail(where + ": vertex index " + std::to_string(i) + " out of range");
      for (const Vec3& v : prim.positions)
        if (!is_finite(v)) fail(where + ": non-finite vertex position");
    }
  }
  for (size_t i = 0; i < desc.instances.size(); ++i) {
    const InstanceDesc& inst = desc.instances[i];
    if (inst.mesh < 0 || inst.mesh >= static_cast<int>(desc.meshes.size()))
      fail("instance " + std::to_string(i) + ": mesh index out of range");
    if (!inst.object_to_world.is_invertible()) fail("instance " + std::to_string(i) + ": singular transform");
  }
  for (size_t s = 0; s < desc.spheres.size(); ++s) {
    const SphereDesc& sph = desc.spheres[s];
    if (sph.material < -1 || sph.material >= n_materials)
      fail("sphere " + std::to_string(s) + ": material index out of range");
    if (!(sph.radius > 0) || !std::isfinite(sph.radius) || !is_finite(sph.center))
      fail("sphere " + std::to_string(s) + ": radius must be positive and centre finite");
  }
  for (const TextureDesc& t : desc.textures)
    if (t.image < 0 || t.image >= static_cast<int>(desc.images.size())) fail("texture image index out of range");
  for (const MaterialDesc& m : desc.materials)
    for (const TextureRef* r : m.texture_slots())
      if (r->texture >= static_cast<int>(desc.textures.size()))
        fail("material '" + m.name + "': texture index out of range");
}

void Scene::bake_single_use_meshes() {
  std::vector<int> uses(desc_.meshes.size(), 0);
  for (const InstanceDesc& inst : desc_.instances) ++uses[inst.mesh];
  for (InstanceDesc& inst : desc_.instances) {
    if (uses[inst.mesh] != 1 || inst.object_to_world.is_identity()) continue;
    const Transform& xf = inst.object_to_world;
    for (PrimitiveDesc& prim : desc_.meshes[inst.mesh].primitives) {
      for (Vec3& p : prim.positions) p = xf.point(p);
      for (Vec3& n : prim.normals) n = xf.normal(n);
      for (Vec3& t : prim.tangents) t = xf.vector(t);
      if (xf.flips_handedness())
        for (float& w : prim.tangent_signs) w = -w;
      // glTF 2.0 §3.7.4: under a negative determinant the front face is clockwise; swapping two
      // corners keeps "front = counter-clockwise" true in world space.
      if (xf.flips_handedness())
        for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) std::swap(prim.indices[t + 1], prim.indices[t + 2]);
    }
    inst.object_to_world = Transform();
  }
}

namespace {

// A baked (world-space) primitive's unit face normals, exactly as reconstruct_triangle_hit would
// compute them at each hit.
std::vector<Vec3> face_normals(const PrimitiveDesc& prim) {
  std::vector<Vec3> normals(prim.triangle_count());
  for (size_t t = 0; t < normals.size(); ++t) {
    const uint32_t* idx = &prim.indices[3 * t];
    normals[t] = face_normal(prim.positions[idx[0]], prim.positions[idx[1]], prim.positions[idx[2]]).normal;
  }
  return normals;
}

// Embree triangle geometry over a primitive's own arrays (no copy).
RTCGeometry triangle_geometry(RTCDevice device, PrimitiveDesc& prim) {
  // Embree loads vertices 16 bytes at a time: make room past the last float3.
  prim.positions.reserve(prim.positions.size() + 1);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, prim.positions.data(), 0,
                             sizeof(Vec3), prim.positions.size());
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, prim.indices.data(), 0,
                             3 * sizeof(uint32_t), prim.triangle_count());
  rtcCommitGeometry(geom);
  return geom;
}

}  // namespace

void Scene::alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* data = static_cast<const AlphaFilterData*>(args->geometryUserPtr);
  const SceneDesc& desc = data->scene->desc_;
  const PrimitiveDesc& prim = desc.meshes[data->mesh].primitives[data->primitive];
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) continue;
    const uint32_t tri = RTCHitN_primID(args->hit, N, i);
    const float b1 = RTCHitN_u(args->hit, N, i), b2 = RTCHitN_v(args->hit, N, i), b0 = 1.0f - b1 - b2;
    Vec2 uv{0, 0};
    if (!prim.uvs.empty()) {
      const uint32_t* idx = &prim.indices[3 * size_t(tri)];
      const Vec2 &t0 = prim.uvs[idx[0]], &t1 = prim.uvs[idx[1]], &t2 = prim.uvs[idx[2]];
      uv = {t0.x * b0 + t1.x * b1 + t2.x * b2, t0.y * b0 + t1.y * b1 + t2.y * b2};
    }
    const auto bits = float_bits;
    RTCRayN* r = args->ray;  // Embree 3 declares the accessors on non-const rays
    const uint64_t h = hash_values(bits(RTCRayN_org_x(r, N, i)), bits(RTCRayN_org_y(r, N, i)), bits(RTCRayN_org_z(r, N, i)),
                                   bits(RTCRayN_dir_x(r, N, i)), bits(RTCRayN_dir_y(r, N, i)), bits(RTCRayN_dir_z(r, N, i)),
                                   uint64_t(tri), bits(b1), bits(b2));
    if (!data->scene->keeps_hit(prim.material, uv, h)) args->valid[i] = 0;
  }
}

bool Scene::keeps_hit(int material, Vec2 uv, uint64_t hash) const {
  const MaterialDesc& m = desc_.material(material);
  const float alpha = alpha_(desc_, material, uv);
  if (m.alpha_mode == MaterialDesc::AlphaMode::Mask) return alpha >= m.alpha_cutoff;
  // Stochastic transparency, a pure function of this ray meeting this point: the same camera ray
  // makes the same choice on every run and thread.
  return float(hash >> 40) * 0x1p-24f < alpha;
}

bool Scene::sphere_keeps_hit(const void* owner, int sphere, Vec2 uv, const Ray& ray, float t) {
  const auto* scene = static_cast<const Scene*>(owner);
  const int material = scene->desc_.spheres[sphere].material;
  if (!scene->desc_.material(material).has_alpha()) return true;
  const auto bits = float_bits;
  const uint64_t h = hash_values(bits(ray.origin.x), bits(ray.origin.y), bits(ray.origin.z), bits(ray.dir.x),
                                 bits(ray.dir.y), bits(ray.dir.z), uint64_t(sphere), bits(t));
  return scene->keeps_hit(material, uv, h);
}

void Scene::attach_alpha_filter(RTCGeometry geom, int mesh, int primitive) {
  if (!alpha_ || !desc_.material(desc_.meshes[mesh].primitives[primitive].material).has_alpha()) return;
  alpha_filters_.push_back(std::make_unique<AlphaFilterData>(AlphaFilterData{this, mesh, primitive}));
  rtcSetGeometryUserData(geom, alpha_filters_.back().get());
  rtcSetGeometryIntersectFilterFunction(geom, alpha_filter);
  rtcSetGeometryOccludedFilterFunction(geom, alpha_filter);
}

Scene::Scene(SceneDesc desc, AlphaFunction alpha, LightSampling lights) : desc_(std::move(desc)), alpha_(alpha) {
  const auto start = std::chrono::steady_clock::now();
  validate_scene_desc(desc_);
  origin_ = choose_render_origin(desc_);
  move_origin(desc_, origin_);
  features_ = desc_.features();
  bake_single_use_meshes();
  RTCDevice device = embree_device();

  std::vector<int> uses(desc_.meshes.size(), 0);
  for (const InstanceDesc& inst : desc_.instances) ++uses[inst.mesh];
  top_ = rtcNewScene(device);
  rtcSetSceneFlags(top_, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);  // skip_left_triangle
  auto attach_top = [&](RTCGeometry geom, TopGeometry ref) {
    rtcAttachGeometryByID(top_, geom, static_cast<unsigned>(top_geometries_.size()));
    rtcReleaseGeometry(geom);
    top_geometries_.push_back(std::move(ref));
  };

  mesh_scenes_.assign(desc_.meshes.size(), nullptr);
  for (size_t i = 0; i < desc_.instances.size(); ++i) {
    const InstanceDesc& inst = desc_.instances[i];
    auto& prims = desc_.meshes[inst.mesh].primitives;
    if (uses[inst.mesh] == 1) {
      for (size_t p = 0; p < prims.size(); ++p) {
        if (prims[p].triangle_count() == 0) continue;
        RTCGeometry geom = triangle_geometry(device, prims[p]);
        attach_alpha_filter(geom, inst.mesh, static_cast<int>(p));
        rtcCommitGeometry(geom);
        attach_top(geom, {static_cast<int>(i), static_cast<int>(p), face_normals(prims[p]),
                          desc_.material(prims[p].material).is_thin_sheet(), {}});
      }
      continue;
    }
    RTCScene& mesh_scene = mesh_scenes_[inst.mesh];
    if (!mesh_scene) {
      mesh_scene = rtcNewScene(device);
      rtcSetSceneFlags(mesh_scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
      for (size_t p = 0; p < prims.size(); ++p) {
        if (prims[p].triangle_count() == 0) continue;
        RTCGeometry geom = triangle_geometry(device, prims[p]);
        attach_alpha_filter(geom, inst.mesh, static_cast<int>(p));
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(mesh_scene, geom, static_cast<unsigned>(p));  // geomID = primitive
        rtcReleaseGeometry(geom);
      }
      rtcCommitScene(mesh_scene);
    }
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geom, mesh_scene);
    const std::array<float, 12> m = inst.object_to_world.matrix_float();
    rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, m.data());
    rtcCommitGeometry(geom);
    attach_top(geom, {static_cast<int>(i), -1, {}, false, {}});
  }
  for (const SphereDesc& sphere : desc_.spheres)
    if (desc_.material(sphere.material).is_thin_sheet()) sees_every_sheet_ = false;
  if (!desc_.spheres.empty()) {
    sphere_geom_id_ = static_cast<unsigned>(top_geometries_.size());
    sphere_geometry_.spheres = &desc_.spheres;
    sphere_geometry_.owner = this;
    if (alpha_) sphere_geometry_.keep = &Scene::sphere_keeps_hit;
    attach_spheres(device, top_, sphere_geometry_, sphere_geom_id_);
    top_geometries_.push_back({});
  }
  rtcCommitScene(top_);
  tsan_acquire(&sphere_geometry_);  // the build threads' sphere_bounds calls are over
  throw_on_embree_error("building the scene of " + desc_.source);
  emitters_ = Emitters(desc_, lights);
  for (TopGeometry& g : top_geometries_)
    if (g.primitive >= 0) g.baked = hit_primitive(g.instance, g.primitive, g.face_normals.data());
  casters_ = CausticCasters(desc_);
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Scene::~Scene() {
  if (top_) rtcReleaseScene(top_);
  for (RTCScene s : mesh_scenes_)
    if (s) rtcReleaseScene(s);
}

uint64_t Scene::triangle_count() const {
  uint64_t n = 0;
  for (const InstanceDesc& inst : desc_.instances)
    for (const PrimitiveDesc& prim : desc_.meshes[size_t(inst.mesh)].primitives) n += prim.indices.size() / 3;
  return n;
}

namespace {

// An intersection context that names the triangle each ray leaves, by the ray's id (its lane in
// a packet; 0 for a single ray). Embree passes the context to the filter, so it must come first.
struct LeavingContext {
  RTCIntersectContext context;
  TriangleId leaves[kEmbreePacketSize];
};

// Embree's test sees a triangle through its float normal, which on a needle is off by up to
// 2^-24 / sin(angle) (the cross product cancels): near the origin of a ray spawned from it, the
// triangle's plane can appear on the wrong side of the offset origin, so the ray hits the face it
// just left. No ray meets a plane twice, so such hits are dropped (Cycles skips its own primitive too).
void skip_left_triangle(const RTCFilterFunctionNArguments* args) {
  const TriangleId* leaves = reinterpret_cast<const LeavingContext*>(args->context)->leaves;  // by ray id
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) continue;
    const TriangleId& left = leaves[RTCRayN_id(args->ray, N, i)];
    if (RTCHitN_primID(args->hit, N, i) == left.primitive && RTCHitN_geomID(args->hit, N, i) == left.geometry &&
        RTCHitN_instID(args->hit, N, i, 0) == left.instance)
      args->valid[i] = 0;
  }
}

// The context for n <= kEmbreePacketSize rays with ids 0..n-1; the filter runs only when some
// ray leaves a triangle, and `filter` is set.
LeavingContext leaving_context(const Ray* rays, int n, bool coherent, bool filter = true) {
  LeavingContext c;
  rtcInitIntersectContext(&c.context);
  if (coherent) c.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  for (int k = 0; k < n; ++k) {
    c.leaves[k] = rays[k].leaves;
    if (c.leaves[k].valid() && filter) c.context.filter = skip_left_triangle;
  }
  return c;
}

// Whether Embree's closest hit is the triangle the ray leaves.
bool hits_left_triangle(const EmbreeHit& hit, const TriangleId& left) {
  return left.valid() && hit.prim == left.primitive && hit.geom == left.geometry && hit.inst == left.instance;
}

}  // namespace

// Closest-hit queries run without skip_left_triangle: a call per candidate hit costs more than
// tracing again, with the filter, the rare ray whose closest hit is the triangle it leaves. Its
// other hits are the filtered query's (a ray meets the left triangle's plane once), so the answer
// is the same. Occlusion queries report no hit to check, and keep the filter.
RTCRayHit Scene::intersect_one(const Ray& ray, bool coherent, bool filter) const {
  LeavingContext c = leaving_context(&ray, 1, coherent, filter);
  RTCRayHit rh = to_embree(ray);
  rtcIntersect1(top_, &c.context, &rh);
  return rh;
}

bool Scene::intersect(const Ray& ray, SurfaceHit& hit, bool coherent) const {
  EmbreeHit found = embree_hit(intersect_one(ray, coherent, false));
  if (hits_left_triangle(found, ray.leaves)) found = embree_hit(intersect_one(ray, coherent, true));
  return resolve_hit(ray, found, hit);
}

bool Scene::occluded(const Ray& ray) const {
  bool blocked = false;
  occluded8(&ray, 1, &blocked);
  return blocked;
}

void Scene::intersect_packet(const Ray* rays, int n, SurfaceHit* hits, bool* found, bool coherent) const {
  for (int first = 0; first < n; first += kPacketSize)
    intersect8(rays + first, std::min(n - first, kPacketSize), hits + first, found + first, coherent);
}

void Scene::occluded_packet(const Ray* rays, int n, bool* occluded) const {
  for (int first = 0; first < n; first += kPacketSize)
    occluded8(rays + first, std::min(n - first, kPacketSize), occluded + first);
}

void Scene::intersect8(const Ray* rays, int n, SurfaceHit* hits, bool* found, bool coherent) const {
  if (n == 1) {  // a one-lane packet costs more than the one-ray query
    found[0] = intersect(rays[0], hits[0], coherent);
    return;
  }
  LeavingContext c = leaving_context(rays, n, coherent, false);  // see Scene::intersect
  alignas(32) RTCRayHit8 rh;
  alignas(32) int valid[kPacketSize];
  fill_packet(rh, valid, rays, n);
  rtcIntersect8(valid, top_, &c.context, &rh);
  for (int k = 0; k < n; ++k) {
    const EmbreeHit one = embree_hit(rh, k);
    found[k] = resolve_hit(rays[k],
                           hits_left_triangle(one, rays[k].leaves) ? embree_hit(intersect_one(rays[k], coherent, true))
                                                                   : one,
                           hits[k]);
  }
}

void Scene::occluded8(const Ray* rays, int n, bool* occluded) const {
  LeavingContext c = leaving_context(rays, n, false);
  occluded8(rays, n, occluded, &c.context);
}

void Scene::occluded8(const Ray* rays, int n, bool* occluded, RTCIntersectContext* context) const {
  if (n == 1) {  // a one-lane packet costs more than the one-ray query
    RTCRay r = to_embree(rays[0]).ray;
    rtcOccluded1(top_, context, &r);
    occluded[0] = r.tfar < 0;  // Embree sets tfar to -inf on a hit
    return;
  }
  alignas(32) RTCRay8 r;
  alignas(32) int valid[kPacketSize];
  fill_packet(r, valid, rays, n);
  rtcOccluded8(valid, top_, context, &r);
  for (int k = 0; k < n; ++k) occluded[k] = r.tfar[k] < 0;
}

namespace {

// occluded_past_sheets' context: the leaving triangles, and where the filter notes the sheets it
// lets rays through.
struct SheetContext {
  LeavingContext leaving;
  const Scene* scene;
  Scene::SheetsCrossed* crossed;  // by ray id
};

}  // namespace

bool Scene::is_sheet_hit(unsigned geom, unsigned inst) const {
  if (inst == RTC_INVALID_GEOMETRY_ID) return geom < top_geometries_.size() && top_geometries_[geom].sheet;
  // An instanced mesh: geom is the primitive within it.
  const InstanceDesc& instance = desc_.instances[size_t(top_geometries_[inst].instance)];
  return desc_.material(desc_.meshes[size_t(instance.mesh)].primitives[geom].material).is_thin_sheet();
}

void Scene::sheet_filter(const RTCFilterFunctionNArguments* args) {
  skip_left_triangle(args);
  const auto* c = reinterpret_cast<const SheetContext*>(args->context);
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    const unsigned geom = RTCHitN_geomID(args->hit, N, i), inst = RTCHitN_instID(args->hit, N, i, 0);
    if (!args->valid[i] || !c->scene->is_sheet_hit(geom, inst)) continue;
    args->valid[i] = 0;  // not a blocker: look on past it
    SheetsCrossed& seen = c->crossed[RTCRayN_id(args->ray, N, i)];
    const unsigned prim = RTCHitN_primID(args->hit, N, i);
    const float t = RTCRayN_tfar(args->ray, N, i);  // the candidate hit's distance (Embree's filter contract)
    bool again = false;
    for (int j = 0; j < std::min(seen.count, SheetsCrossed::kKept); ++j) {
      const SheetsCrossed::Crossing& m = seen.met[j];
      // Rounding separates one point's distances on two triangles by an ulp or so; two sheets
      // closer than this are one surface to a walk, whose next segment starts past both.
      again |= (m.geom == geom && m.inst == inst && m.prim == prim) || std::abs(m.t - t) <= 1e-6f * std::max(m.t, t);
    }
    if (again) continue;
    if (seen.count < SheetsCrossed::kKept)
      seen.met[seen.count] = {geom, inst, prim, RTCHitN_u(args->hit, N, i), RTCHitN_v(args->hit, N, i), t};
    ++seen.count;
  }
}

void Scene::occluded_past_sheets(const Ray* rays, int n, bool* blocked, SheetsCrossed* crossed) const {
  for (int first = 0; first < n; first += kPacketSize) {
    const int m = std::min(n - first, kPacketSize);
    SheetContext c{leaving_context(rays + first, m, false), this, crossed + first};
    c.leaving.context.filter = sheet_filter;
    for (int k = 0; k < m; ++k) crossed[first + k].count = 0;
    occluded8(rays + first, m, blocked + first, &c.leaving.context);
    for (int k = 0; k < m; ++k)
      if (blocked[first + k]) crossed[first + k].count = 0;
  }
}

void Scene::sheet_hit(const Ray& ray, const SheetsCrossed::Crossing& crossed, SurfaceHit& hit) const {
  resolve_hit(ray, {crossed.geom, crossed.prim, crossed.inst, crossed.u, crossed.v, crossed.t}, hit);
}

bool Scene::resolve_hit(const Ray& ray, const EmbreeHit& found, SurfaceHit& hit) const {
  if (found.geom == RTC_INVALID_GEOMETRY_ID) return false;
  hit.t = found.t;
  if (found.inst != RTC_INVALID_GEOMETRY_ID) {
    // An instanced mesh: Embree's geomID is the primitive within the mesh.
    reconstruct_triangle_hit(
        hit_primitive(top_geometries_[found.inst].instance, static_cast<int>(found.geom), nullptr), ray, found, hit);
  } else if (found.geom == sphere_geom_id_) {
    reconstruct_sphere_hit(ray, found, hit);
  } else {
    reconstruct_triangle_hit(top_geometries_[found.geom].baked, ray, found, hit);
  }
  return true;
}

Scene::HitPrimitive Scene::hit_primitive(int instance, int primitive, const Vec3* face_normals) const {
  const InstanceDesc& inst = desc_.instances[instance];
  HitPrimitive h;
  h.prim = &desc_.meshes[inst.mesh].primitives[primitive];
  h.material = &desc_.material(h.prim->material);
  h.object_to_world = inst.object_to_world.is_identity() ? nullptr : &inst.object_to_world;
  h.face_normals = face_normals;
  h.emitters = emitters_.triangle_emitters(instance, primitive);
  h.instance = instance;
  return h;
}

void Scene::reconstruct_triangle_hit(const HitPrimitive& source, const Ray& ray, const EmbreeHit& found,
                                     SurfaceHit& hit) const {
  const PrimitiveDesc& prim = *source.prim;
  const Transform* xf = source.object_to_world;
  const bool world_space = !xf;  // baked meshes need no transform
  const float handedness = xf && xf->flips_handedness() ? -1.0f : 1.0f;
  const Vec3* face_normals = source.face_normals;
  const uint32_t* idx = &prim.indices[3 * size_t(found.prim)];
  const float b1 = found.u, b2 = found.v, b0 = 1.0f - b1 - b2;

  const Vec3 p0 = world_space ? prim.positions[idx[0]] : xf->point(prim.positions[idx[0]]);
  const Vec3 p1 = world_space ? prim.positions[idx[1]] : xf->point(prim.positions[idx[1]]);
  const Vec3 p2 = world_space ? prim.positions[idx[2]] : xf->point(prim.positions[idx[2]]);
  hit.p = p0 * b0 + p1 * b1 + p2 * b2;
  hit.p_error = (abs(p0 * b0) + abs(p1 * b1) + abs(p2 * b2)) * kHitRelativeError;

  // glTF 2.0 §3.7.4: a negative determinant makes the front face clockwise.
  const Vec3 ng = face_normals ? face_normals[found.prim] : face_normal(p0, p1, p2).normal * handedness;
  if (ng != Vec3(0.0f)) {
    hit.ng = ng;
  } else {
    // Degenerate in float after the transform: face the incoming ray.
    hit.ng = normalize(-ray.dir);
  }

  hit.ns = hit.ng;
  if (!prim.normals.empty()) {
    const Vec3 n = prim.normals[idx[0]] * b0 + prim.normals[idx[1]] * b1 + prim.normals[idx[2]] * b2;
    const Vec3 nw = world_space ? n : xf->normal(n);
    const float nlen = length(nw);
    if (nlen > 0 && std::isfinite(nlen)) hit.ns = nw / nlen;
  }
  hit.uv = {0, 0};
  hit.uv_per_length = 0;
  hit.cone_width = 0;
  hit.tangent = Vec3(0.0f);
  hit.tangent_sign = 1.0f;
  if (!prim.uvs.empty()) {
    const Vec2 &t0 = prim.uvs[idx[0]], &t1 = prim.uvs[idx[1]], &t2 = prim.uvs[idx[2]];
    hit.uv = {t0.x * b0 + t1.x * b1 + t2.x * b2, t0.y * b0 + t1.y * b1 + t2.y * b2};
    const MaterialDesc& material = *source.material;
    if (features_.mip_levels && material.has_textures()) {
      // Twice the triangle's area in uv and in space (Akenine-Moller et al. 2019, "Texture level
      // of detail strategies for real-time ray tracing", eq. 3: the texel-to-area ratio).
      const float uv_area = std::abs((t1.x - t0.x) * (t2.y - t0.y) - (t2.x - t0.x) * (t1.y - t0.y));
      const float area = length(cross(p1 - p0, p2 - p0));
      const float ratio = area > 0 ? std::sqrt(uv_area / area) : 0.0f;
      hit.uv_per_length = std::isfinite(ratio) ? ratio : 0.0f;
    }
    // Tangent frames serve normal maps only: other materials skip the work.
    const bool wants_frame = material.normal_texture.present();
    if (wants_frame && !prim.tangents.empty()) {
      // A mirroring transform reverses the frame's handedness (bitangents map by M, but
      // cross(M^-T n, M t) flips with det M).
      const Vec3 t = prim.tangents[idx[0]] * b0 + prim.tangents[idx[1]] * b1 + prim.tangents[idx[2]] * b2;
      hit.tangent = world_space ? t : xf->vector(t);
      hit.tangent_sign = prim.tangent_signs[idx[0]] * handedness;
    } else if (wants_frame) {
      // No per-vertex frames: the triangle's own (already in world space).
      const TangentFrame f = triangle_tangent_frame(p0, p1, p2, t0, t1, t2);
      if (f.valid) {
        hit.tangent = f.tangent;
        hit.tangent_sign = dot(cross(hit.ns, f.tangent), f.up_image) < 0 ? -1.0f : 1.0f;
      }
    }
    if (wants_frame) {
      const float tangent_len = length(hit.tangent);
      hit.tangent = tangent_len > 0 && std::isfinite(tangent_len) ? hit.tangent / tangent_len : Vec3(0.0f);
    }
  }
  hit.material = prim.material;
  hit.object = source.instance;
  hit.triangle = {found.inst, found.geom, found.prim};
  hit.emitter = source.emitters ? source.emitters[found.prim] : -1;
}

void Scene::reconstruct_sphere_hit(const Ray& ray, const EmbreeHit& found, SurfaceHit& hit) const {
  const SphereDesc& s = desc_.spheres[found.prim];
  // Re-project onto the sphere: o + t d carries the error of t; the direction from the centre
  // does not drift off the surface. All in double, so a small sphere far from the ray origin keeps
  // its precision, and from the root solved again: Embree hands t back as a float, whose rounding
  // alone (2^-24 t) tilted the normal of a 1e-5 sphere seen from 1e-2 away by 3e-5 rad. Near the
  // silhouette both roots can round to that float; the first it could stand for wins, as in the
  // intersection callback.
  double t_hit = hit.t, t0, t1;
  if (sphere_roots(s.center, s.radius, ray, t0, t1)) {
    const double slack = std::abs(t_hit) * 0x1p-23;  // twice float rounding
    if (t0 > ray.t_min && std::abs(t0 - t_hit) <= slack) t_hit = t0;
    else if (std::abs(t1 - t_hit) <= slack) t_hit = t1;
  }
  double local[3];
  double len2 = 0;
  for (int i = 0; i < 3; ++i) {
    local[i] = (double(ray.origin[i]) - s.center[i]) + double(ray.dir[i]) * t_hit;
    len2 += local[i] * local[i];
  }
  const double len = std::sqrt(len2);
  const Vec3 n = len > 0 ? Vec3(float(local[0] / len), float(local[1] / len), float(local[2] / len)) : Vec3(0, 1, 0);
  hit.p = s.center + n * s.radius;
  hit.p_error = (abs(s.center) + Vec3(s.radius)) * kHitRelativeError;
  hit.ng = n;
  hit.ns = n;
  hit.uv = sphere_uv(n);
  // u runs once around a circle of radius r sin(theta), v half way around one of radius r: their
  // geometric mean.
  const float sin_theta = std::max(std::sqrt(n.x * n.x + n.z * n.z), 1e-4f);
  hit.uv_per_length = features_.mip_levels && desc_.material(s.material).has_textures()
                          ? 1.0f / (kPi * s.radius * std::sqrt(2.0f * sin_theta))
                          : 0.0f;
  hit.cone_width = 0;
  // dP/du around +Y; -dP/dv points to the north pole, up the image, so the sign is +1.
  const Vec3 t(n.z, 0.0f, -n.x);
  hit.tangent = length_squared(t) > 0 ? normalize(t) : Vec3(1, 0, 0);
  hit.tangent_sign = 1.0f;
  hit.material = s.material;
  hit.object = static_cast<int>(desc_.instances.size() + found.prim);
  hit.triangle = {};  // a ray may meet a sphere twice
  hit.emitter = emitters_.sphere_emitter(static_cast<int>(found.prim));
}

}  // namespace prism
