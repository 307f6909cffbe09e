// prism's rays in Embree's layouts: one ray (RTCRayHit) and eight-wide packets (RTCRay8, RTCRayHit8).
#pragma once

#include <embree3/rtcore.h>

#include "core/cpu_features.h"
#include "core/ray.h"

namespace prism {

constexpr int kEmbreePacketSize = 8;

// One ray with no hit yet.
inline RTCRayHit to_embree(const Ray& ray) {
  RTCRayHit rh;
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.dir.x;
  rh.ray.dir_y = ray.dir.y;
  rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = ray.t_min;
  rh.ray.tfar = ray.t_max;
  rh.ray.time = 0.0f;
  rh.ray.mask = ~0u;  // a zero mask misses everything
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// What a closest-hit query answered, as Scene::resolve_hit reads it: read field by field from the
// query's layout, not copied whole (rtcGetRayHitFromRayHitN copies all twenty fields of a packet's
// lane, for the six read here).
struct EmbreeHit {
  unsigned geom = RTC_INVALID_GEOMETRY_ID, prim = RTC_INVALID_GEOMETRY_ID, inst = RTC_INVALID_GEOMETRY_ID;
  float u = 0, v = 0;  // barycentrics of vertices 1 and 2
  float t = 0;         // the hit's distance (tfar)
};

inline EmbreeHit embree_hit(const RTCRayHit& rh) {
  return {rh.hit.geomID, rh.hit.primID, rh.hit.instID[0], rh.hit.u, rh.hit.v, rh.ray.tfar};
}

inline EmbreeHit embree_hit(const RTCRayHit8& rh, int lane) {
  return {rh.hit.geomID[lane], rh.hit.primID[lane], rh.hit.instID[0][lane], rh.hit.u[lane], rh.hit.v[lane],
          rh.ray.tfar[lane]};
}

// fill_packet for CPUs with AVX2 (cpu_has_avx2): each ray's first eight floats (origin, direction,
// t_min, t_max) turned into the packet's rows by one 8x8 transpose (core/float8.h), the constant
// fields stored a row at a time. The lanes hold the very values the scalar form writes. Filling the
// Cornell box's packets took 59M of its 2.13G instructions lane by lane, 28M so (PERFORMANCE.md).
void fill_packet_avx2(RTCRay8& p, int (&valid)[kEmbreePacketSize], const Ray* rays, int n);

// Lanes [0, n) of a W-wide packet hold `rays`, with ray id = lane; the other lanes are switched
// off in `valid` (which Embree wants aligned as the packet) and repeat ray 0. One lane at a time.
template <int W, typename Packet>
void fill_packet_lanes(Packet& p, int (&valid)[W], const Ray* rays, int n) {
  for (int k = 0; k < W; ++k) {
    const Ray& r = rays[k < n ? k : 0];
    valid[k] = k < n ? -1 : 0;
    p.org_x[k] = r.origin.x, p.org_y[k] = r.origin.y, p.org_z[k] = r.origin.z;
    p.dir_x[k] = r.dir.x, p.dir_y[k] = r.dir.y, p.dir_z[k] = r.dir.z;
    p.tnear[k] = r.t_min;
    p.tfar[k] = r.t_max;
    p.time[k] = 0.0f;
    p.mask[k] = ~0u;
    p.id[k] = unsigned(k);
    p.flags[k] = 0;
  }
}

// The same for prism's eight-wide packets, by a transpose where the CPU has AVX2.
inline void fill_packet(RTCRay8& p, int (&valid)[kEmbreePacketSize], const Ray* rays, int n) {
  if (cpu_has_avx2()) return fill_packet_avx2(p, valid, rays, n);
  fill_packet_lanes(p, valid, rays, n);
}

// The same for a packet with hits, each lane's hit cleared (no geometry, primitive or instance).
inline void fill_packet(RTCRayHit8& p, int (&valid)[kEmbreePacketSize], const Ray* rays, int n) {
  fill_packet(p.ray, valid, rays, n);
  for (int k = 0; k < kEmbreePacketSize; ++k)
    p.hit.geomID[k] = p.hit.primID[k] = p.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
}

}  // namespace prism
