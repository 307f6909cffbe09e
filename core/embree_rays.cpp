#include "core/embree_rays.h"

#include <cstddef>
#include <cstring>

#include "core/float8.h"

namespace prism {

// The transpose reads each ray's first eight floats as Embree's rows name them.
static_assert(offsetof(Ray, origin) == 0 && offsetof(Ray, dir) == 12 && offsetof(Ray, t_min) == 24 &&
              offsetof(Ray, t_max) == 28 && sizeof(Ray) >= 32);

__attribute__((target("avx2"))) void fill_packet_avx2(RTCRay8& p, int (&valid)[kEmbreePacketSize], const Ray* rays,
                                                      int n) {
  static_assert(kEmbreePacketSize == 8);
  const float* records[8];
  for (int k = 0; k < 8; ++k) records[k] = &rays[k < n ? k : 0].origin.x;
  Float8Lanes rows[8];
  transpose(records, 0, rows);
  float* const fields[8] = {p.org_x, p.org_y, p.org_z, p.dir_x, p.dir_y, p.dir_z, p.tnear, p.tfar};
  for (int j = 0; j < 8; ++j) std::memcpy(fields[j], &rows[j], sizeof rows[j]);
  typedef int32_t I32x8 __attribute__((vector_size(32)));
  const I32x8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
  const I32x8 on = lane < n;  // -1 where k < n, as the scalar form's valid
  const I32x8 zero = {}, ones = zero - 1;
  std::memcpy(valid, &on, sizeof on);
  std::memcpy(p.time, &zero, sizeof zero);  // the bits of 0.0f
  std::memcpy(p.mask, &ones, sizeof ones);
  std::memcpy(p.id, &lane, sizeof lane);
  std::memcpy(p.flags, &zero, sizeof zero);
}

}  // namespace prism
