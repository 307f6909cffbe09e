#include "core/sphere_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/constants.h"
#include "core/tsan_annotations.h"

namespace prism {

bool sphere_roots(const Vec3& center, float radius, const Ray& ray, double& t0, double& t1) {
  const double ox = double(ray.origin.x) - center.x, oy = double(ray.origin.y) - center.y,
               oz = double(ray.origin.z) - center.z;
  const double dx = ray.dir.x, dy = ray.dir.y, dz = ray.dir.z;
  const double a = dx * dx + dy * dy + dz * dz;
  const double b = ox * dx + oy * dy + oz * dz;  // half the linear coefficient
  const double r = radius;
  const double fx = ox - b / a * dx, fy = oy - b / a * dy, fz = oz - b / a * dz;
  const double disc = r * r - (fx * fx + fy * fy + fz * fz);  // = (b^2 - a c) / a
  if (!(disc >= 0) || a == 0) return false;
  const double c = ox * ox + oy * oy + oz * oz - r * r;
  const double q = -(b + std::copysign(std::sqrt(a * disc), b));
  t0 = q != 0 ? c / q : 0.0;
  t1 = q / a;
  if (t0 > t1) std::swap(t0, t1);
  return true;
}

double intersect_sphere(const Vec3& center, float radius, const Ray& ray) {
  double t0, t1;
  if (!sphere_roots(center, radius, ray, t0, t1)) return -1.0;
  if (t0 > ray.t_min && t0 < ray.t_max) return t0;
  if (t1 > ray.t_min && t1 < ray.t_max) return t1;
  return -1.0;
}

Vec2 sphere_uv(const Vec3& n) {
  const float phi = std::atan2(n.x, n.z);
  return {0.5f + phi * kInvTwoPi, std::acos(std::clamp(n.y, -1.0f, 1.0f)) * kInvPi};
}

namespace {

const SphereGeometry& geometry_of(void* user) { return *static_cast<const SphereGeometry*>(user); }

void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  tsan_acquire(args->geometryUserPtr);  // Embree's build threads: see core/tsan_annotations.h
  const SphereDesc& s = (*geometry_of(args->geometryUserPtr).spheres)[args->primID];
  // Widen by a few ulps so float rounding of centre +- radius never clips the sphere.
  const float pad = 4.0f * std::numeric_limits<float>::epsilon();
  const Vec3 extent = Vec3(s.radius) * (1.0f + pad) + abs(s.center) * pad;
  args->bounds_o->lower_x = s.center.x - extent.x;
  args->bounds_o->lower_y = s.center.y - extent.y;
  args->bounds_o->lower_z = s.center.z - extent.z;
  args->bounds_o->upper_x = s.center.x + extent.x;
  args->bounds_o->upper_y = s.center.y + extent.y;
  args->bounds_o->upper_z = s.center.z + extent.z;
  tsan_release(args->geometryUserPtr);  // ...and is done before rtcCommitScene returns
}

// Lane i of a ray packet of size N (Embree's SoA layout; N == 1 is a single RTCRay).
Ray ray_of(RTCRayN* r, unsigned N, unsigned i) {
  return Ray{{RTCRayN_org_x(r, N, i), RTCRayN_org_y(r, N, i), RTCRayN_org_z(r, N, i)},
             {RTCRayN_dir_x(r, N, i), RTCRayN_dir_y(r, N, i), RTCRayN_dir_z(r, N, i)},
             RTCRayN_tnear(r, N, i),
             RTCRayN_tfar(r, N, i)};
}

// The nearest root in the ray's interval that the sphere's coverage keeps, or a negative value.
float nearest_hit(const SphereGeometry& g, unsigned prim, const Ray& ray) {
  const SphereDesc& s = (*g.spheres)[prim];
  double roots[2];
  if (!sphere_roots(s.center, s.radius, ray, roots[0], roots[1])) return -1.0f;
  for (double t : roots) {
    const auto tf = static_cast<float>(t);
    if (!(tf > ray.t_min && tf < ray.t_max)) continue;
    if (g.keep) {
      const Vec3 local = ray.origin + ray.dir * tf - s.center;
      const float len = length(local);
      const Vec2 uv = sphere_uv(len > 0 ? local / len : Vec3(0, 1, 0));
      if (!g.keep(g.owner, static_cast<int>(prim), uv, ray, tf)) continue;
    }
    return tf;
  }
  return -1.0f;
}

// Called with N == 1 by rtcIntersect1 / rtcOccluded1 and with N up to the packet size by
// rtcIntersect8 / rtcOccluded8; lanes whose valid entry is 0 are left alone.
void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  const SphereGeometry& g = geometry_of(args->geometryUserPtr);
  const SphereDesc& s = (*g.spheres)[args->primID];
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const Ray r = ray_of(ray, args->N, i);
    const float tf = nearest_hit(g, args->primID, r);
    if (tf < 0) continue;
    RTCRayN_tfar(ray, args->N, i) = tf;
    RTCHitN_u(hit, args->N, i) = 0;
    RTCHitN_v(hit, args->N, i) = 0;
    RTCHitN_Ng_x(hit, args->N, i) = r.origin.x + tf * r.dir.x - s.center.x;
    RTCHitN_Ng_y(hit, args->N, i) = r.origin.y + tf * r.dir.y - s.center.y;
    RTCHitN_Ng_z(hit, args->N, i) = r.origin.z + tf * r.dir.z - s.center.z;
    RTCHitN_primID(hit, args->N, i) = args->primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
    RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
  }
}

void sphere_occluded(const RTCOccludedFunctionNArguments* args) {
  const SphereGeometry& g = geometry_of(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    if (nearest_hit(g, args->primID, ray_of(args->ray, args->N, i)) >= 0)
      RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
  }
}

}  // namespace

void attach_spheres(RTCDevice device, RTCScene scene, const SphereGeometry& geometry, unsigned id) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(geometry.spheres->size()));
  void* user = const_cast<SphereGeometry*>(&geometry);
  rtcSetGeometryUserData(geom, user);
  rtcSetGeometryBoundsFunction(geom, sphere_bounds, user);
  rtcSetGeometryIntersectFunction(geom, sphere_intersect);
  rtcSetGeometryOccludedFunction(geom, sphere_occluded);
  rtcCommitGeometry(geom);
  tsan_release(user);  // the spheres are complete before Embree's threads read their bounds
  rtcAttachGeometryByID(scene, geom, id);
  rtcReleaseGeometry(geom);
}

}  // namespace prism
