#include "core/sphere_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/constants.h"

namespace prism {

double intersect_sphere(const Vec3& center, float radius, const Ray& ray) {
  const double ox = double(ray.origin.x) - center.x, oy = double(ray.origin.y) - center.y,
               oz = double(ray.origin.z) - center.z;
  const double dx = ray.dir.x, dy = ray.dir.y, dz = ray.dir.z;
  const double a = dx * dx + dy * dy + dz * dz;
  const double b = ox * dx + oy * dy + oz * dz;  // half the linear coefficient
  const double r = radius;
  const double fx = ox - b / a * dx, fy = oy - b / a * dy, fz = oz - b / a * dz;
  const double disc = r * r - (fx * fx + fy * fy + fz * fz);  // = (b^2 - a c) / a
  if (!(disc >= 0) || a == 0) return -1.0;
  const double c = ox * ox + oy * oy + oz * oz - r * r;
  const double q = -(b + std::copysign(std::sqrt(a * disc), b));
  double t0 = q != 0 ? c / q : 0.0;
  double t1 = q / a;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > ray.t_min && t0 < ray.t_max) return t0;
  if (t1 > ray.t_min && t1 < ray.t_max) return t1;
  return -1.0;
}

Vec2 sphere_uv(const Vec3& n) {
  const float phi = std::atan2(n.x, n.z);
  return {0.5f + phi * kInvTwoPi, std::acos(std::clamp(n.y, -1.0f, 1.0f)) * kInvPi};
}

namespace {

const std::vector<SphereDesc>& spheres_of(void* user) { return *static_cast<const std::vector<SphereDesc>*>(user); }

void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const SphereDesc& s = spheres_of(args->geometryUserPtr)[args->primID];
  // Widen by a few ulps so float rounding of centre +- radius never clips the sphere.
  const float pad = 4.0f * std::numeric_limits<float>::epsilon();
  const Vec3 extent = Vec3(s.radius) * (1.0f + pad) + abs(s.center) * pad;
  args->bounds_o->lower_x = s.center.x - extent.x;
  args->bounds_o->lower_y = s.center.y - extent.y;
  args->bounds_o->lower_z = s.center.z - extent.z;
  args->bounds_o->upper_x = s.center.x + extent.x;
  args->bounds_o->upper_y = s.center.y + extent.y;
  args->bounds_o->upper_z = s.center.z + extent.z;
}

Ray ray_of(const RTCRay& r) {
  return Ray{{r.org_x, r.org_y, r.org_z}, {r.dir_x, r.dir_y, r.dir_z}, r.tnear, r.tfar};
}

// rtcIntersect1 / rtcOccluded1 call these with N == 1.
void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;
  auto* rayhit = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const SphereDesc& s = spheres_of(args->geometryUserPtr)[args->primID];
  const double t = intersect_sphere(s.center, s.radius, ray_of(rayhit->ray));
  if (t < 0) return;
  const auto tf = static_cast<float>(t);
  if (!(tf > rayhit->ray.tnear && tf < rayhit->ray.tfar)) return;
  rayhit->ray.tfar = tf;
  rayhit->hit.u = 0;
  rayhit->hit.v = 0;
  rayhit->hit.Ng_x = rayhit->ray.org_x + tf * rayhit->ray.dir_x - s.center.x;
  rayhit->hit.Ng_y = rayhit->ray.org_y + tf * rayhit->ray.dir_y - s.center.y;
  rayhit->hit.Ng_z = rayhit->ray.org_z + tf * rayhit->ray.dir_z - s.center.z;
  rayhit->hit.primID = args->primID;
  rayhit->hit.geomID = args->geomID;
  rayhit->hit.instID[0] = args->context->instID[0];
}

void sphere_occluded(const RTCOccludedFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;
  auto* ray = reinterpret_cast<RTCRay*>(args->ray);
  const SphereDesc& s = spheres_of(args->geometryUserPtr)[args->primID];
  const double t = intersect_sphere(s.center, s.radius, ray_of(*ray));
  if (t < 0) return;
  const auto tf = static_cast<float>(t);
  if (tf > ray->tnear && tf < ray->tfar) ray->tfar = -std::numeric_limits<float>::infinity();
}

}  // namespace

void attach_spheres(RTCDevice device, RTCScene scene, const std::vector<SphereDesc>& spheres, unsigned id) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(spheres.size()));
  void* user = const_cast<std::vector<SphereDesc>*>(&spheres);
  rtcSetGeometryUserData(geom, user);
  rtcSetGeometryBoundsFunction(geom, sphere_bounds, user);
  rtcSetGeometryIntersectFunction(geom, sphere_intersect);
  rtcSetGeometryOccludedFunction(geom, sphere_occluded);
  rtcCommitGeometry(geom);
  rtcAttachGeometryByID(scene, geom, id);
  rtcReleaseGeometry(geom);
}

}  // namespace prism
