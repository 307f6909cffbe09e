#include "materials/bsdf.h"

namespace prism {

Bsdf::Bsdf(const Vec3& ns, const Vec3& ng, const Vec3& wo, const Rgb& albedo) : lobe_{albedo} {
  const float side = dot(wo, ng);
  valid_ = side != 0;
  ng_ = side < 0 ? -ng : ng;
  frame_ = Frame::from_normal(side < 0 ? -ns : ns);
}

Rgb Bsdf::eval(const Vec3& wi) const {
  if (!valid_ || dot(wi, ng_) <= 0) return {};
  const float cos_i = dot(wi, frame_.n);
  return cos_i > 0 ? lobe_.f() * cos_i : Rgb{};
}

float Bsdf::pdf(const Vec3& wi) const {
  if (!valid_ || dot(wi, ng_) <= 0) return 0;
  return Lambertian::pdf(frame_.to_local(wi));
}

std::optional<BsdfSample> Bsdf::sample(Vec2 u) const {
  if (!valid_) return std::nullopt;
  const Vec3 local = Lambertian::sample(u);
  const Vec3 wi = frame_.to_world(local);
  const float pdf = Lambertian::pdf(local);
  if (pdf <= 0 || dot(wi, ng_) <= 0) return std::nullopt;
  return BsdfSample{wi, lobe_.f() * local.z, pdf};
}

}  // namespace prism
