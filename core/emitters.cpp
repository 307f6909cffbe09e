#include "core/emitters.h"

#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "core/constants.h"
#include "core/face_normal.h"
#include "core/frame.h"
#include "core/punctual_light.h"
#include "core/sampling.h"
#include "core/spawn.h"
#include "core/sphere_geometry.h"

namespace prism {
namespace {

// A reference point this close to a sphere's surface (in squared-radius units) samples it by
// area, as from inside: the cone of directions degenerates to a hemisphere there.
constexpr float kInsideSphere = 1.00001f;

// Converts an area density at p (unit normal n) to a solid-angle density seen from ref:
// pdf_area * dist^2 / |cos theta_p| (Veach's thesis, eq. 8.10).
float area_to_solid_angle(float pdf_area, const Vec3& ref, const Vec3& p, const Vec3& n) {
  const Vec3 d = p - ref;
  const float dist2 = length_squared(d);
  const float cos_p = std::abs(dot(n, d)) / std::sqrt(dist2);
  return cos_p > 0 ? pdf_area * dist2 / cos_p : 0.0f;
}

}  // namespace

Rgb mean_emission(const SceneDesc& desc, const MaterialDesc& m) {
  Rgb e = m.emissive * m.emissive_strength;
  const TextureRef& ref = m.emissive_texture;
  if (!ref.present() || ref.texture >= static_cast<int>(desc.textures.size())) return e;
  const int image = desc.textures[ref.texture].image;
  if (image < 0 || image >= static_cast<int>(desc.images.size())) return e;
  const ImageDesc& img = desc.images[image];
  if (img.channels <= 0 || img.texel_count() == 0) return e;
  double sum[3] = {0, 0, 0};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Rgb t = img.texel(x, y).rgb;
      for (int c = 0; c < 3; ++c) sum[c] += t[c];
    }
  const double n = double(img.texel_count());
  return e * Rgb(float(sum[0] / n), float(sum[1] / n), float(sum[2] / n));
}

Emitters::Emitter Emitters::make_triangle(const InstanceDesc& inst, int instance, const PrimitiveDesc& prim,
                                           int primitive, uint32_t t) const {
  const MaterialDesc& mat = desc_->material(prim.material);
  Emitter e;
  e.instance = instance;
  e.primitive = primitive;
  e.index = t;
  e.material = prim.material;
  e.p0 = world_corner(inst, prim, t, 0);
  e.p1 = world_corner(inst, prim, t, 1);
  e.p2 = world_corner(inst, prim, t, 2);
  if (inst.object_to_world.flips_handedness()) {  // keep the front face counter-clockwise in world space
    std::swap(e.p1, e.p2);
    std::swap(e.corner[1], e.corner[2]);
  }
  const FaceNormal face = face_normal(e.p0, e.p1, e.p2);
  e.area = face.area;
  e.normal = face.normal;
  e.longest_edge2 = std::max({length_squared(e.p1 - e.p0), length_squared(e.p2 - e.p1), length_squared(e.p0 - e.p2)});
  e.textured = mat.emissive_texture.present();
  e.double_sided = mat.double_sided;
  return e;
}

// Two triangles make a quad when they share an edge (the same world-space corners, run in opposite
// directions, so the two face the same way) and the corner of b off that edge completes a
// parallelogram with a's three, to within 1e-5 of the longest edge (float corners written out by
// an exporter are off by about 1e-7). Half B's points are placed on b's own corners, and
// quad_slack widens their error bound, so a shadow ray never ends beyond the real surface.
bool Emitters::merge_into_quad(Emitter& a, const Emitter& b) {
  if (!(a.area > 0 && b.area > 0) || dot(a.normal, b.normal) <= 0) return false;
  const Vec3 pa[3] = {a.p0, a.p1, a.p2}, pb[3] = {b.p0, b.p1, b.p2};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // a's edge i -> i + 1 is b's edge j + 1 -> j.
      if (!(pa[i] == pb[(j + 1) % 3] && pa[(i + 1) % 3] == pb[j])) continue;
      const Vec3 o = pa[(i + 2) % 3], s1 = pa[i], s2 = pa[(i + 1) % 3], d = pb[(j + 2) % 3];
      const float slack = length(o + d - s1 - s2);
      const float longest2 = std::max(a.longest_edge2, b.longest_edge2);
      if (!(slack * slack <= 1e-10f * longest2)) return false;
      Emitter q = a;
      q.quad = true;
      q.index_b = b.index;
      // Half A is (o, s1, s2), a's corners turned to start at o; half B is (s1, d, s2).
      q.p0 = o;
      q.p1 = s1;
      q.p2 = s2;
      q.p3 = d;
      q.quad_slack = slack;
      const uint8_t* ca = a.corner;
      const uint8_t* cb = b.corner;
      const uint8_t corners[6] = {ca[(i + 2) % 3], ca[i], ca[(i + 1) % 3], cb[(j + 1) % 3], cb[(j + 2) % 3], cb[j]};
      std::copy(corners, corners + 6, q.corner);
      q.area = 2 * a.area;  // the parallelogram the samples are drawn in; its half's longest edge is a's
      if (!std::isfinite(q.area)) return false;
      a = q;
      return true;
    }
  return false;
}

Emitters::Emitters(const SceneDesc& desc, LightSampling how) : desc_(&desc), how_(how) {
  std::vector<double> power;
  instance_prim_base_.resize(desc.instances.size(), 0);
  for (size_t i = 0; i < desc.instances.size(); ++i) {
    const InstanceDesc& inst = desc.instances[i];
    const MeshDesc& mesh = desc.meshes[inst.mesh];
    instance_prim_base_[i] = static_cast<int>(prim_triangle_base_.size());
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const PrimitiveDesc& prim = mesh.primitives[p];
      const MaterialDesc& mat = desc.material(prim.material);
      if (!mat.is_emissive() || prim.triangle_count() == 0) {
        prim_triangle_base_.push_back(-1);
        continue;
      }
      prim_triangle_base_.push_back(static_cast<int>(triangle_emitter_.size()));
      const float radiance = luminance(mean_emission(desc, mat)) * (mat.double_sided ? 2.0f : 1.0f);
      const auto count = static_cast<uint32_t>(prim.triangle_count());
      std::optional<Emitter> made;  // triangle t, made already as the one after a triangle it did not join
      for (uint32_t t = 0; t < count; ++t) {
        Emitter e = made ? *made : make_triangle(inst, int(i), prim, int(p), t);
        made.reset();
        triangle_emitter_.push_back(static_cast<int>(emitters_.size()));
        if (t + 1 < count) {
          const Emitter b = make_triangle(inst, int(i), prim, int(p), t + 1);
          if (merge_into_quad(e, b)) {
            triangle_emitter_.push_back(static_cast<int>(emitters_.size()));
            ++t;
          } else {
            made = b;
          }
        }
        emitters_.push_back(e);
        power.push_back(double(radiance) * e.area * kPi);
      }
    }
  }
  sphere_emitter_.assign(desc.spheres.size(), -1);
  for (size_t s = 0; s < desc.spheres.size(); ++s) {
    const MaterialDesc& mat = desc.material(desc.spheres[s].material);
    if (!mat.is_emissive()) continue;
    sphere_emitter_[s] = static_cast<int>(emitters_.size());
    Emitter e;
    e.sphere = true;
    e.index = static_cast<uint32_t>(s);
    const float r = desc.spheres[s].radius;
    e.area = 4.0f * kPi * r * r;
    emitters_.push_back(e);
    power.push_back(double(luminance(mean_emission(desc, mat))) * (mat.double_sided ? 2.0 : 1.0) * e.area * kPi);
  }
  const Bounds3 bounds = scene_bounds(desc);
  const float radius = bounds.empty() ? 1.0f : 0.5f * length(bounds.diagonal());
  for (const PunctualLightDesc& l : desc.lights) power.push_back(punctual_power(l, radius));
  environment_ = EnvironmentLight(desc);
  if (environment_.present()) {
    portals_ = EnvironmentPortals(desc);  // windows the sky comes through, if any
    // What a disc of the scene's size receives from the sky: pi r^2 x pi L.
    environment_index_ = static_cast<int>(power.size());
    power.push_back(double(kPi) * kPi * double(radius) * radius * environment_.mean_luminance());
  }
  pick_ = Distribution1D(power);
  if (how_ == LightSampling::Tree) build_tree(desc, power);
  for (const Emitter& e : emitters_)
    lane_records_.push_back(lane_record(e, desc.material(e.material).emission_factor()));
}

Emitters::LaneRecord Emitters::lane_record(const Emitter& e, const Rgb& emission) {
  LaneRecord r;
  const auto put = [&](int field, const Vec3& v) {
    for (int i = 0; i < 3; ++i) r.v[field + i] = v[i];
  };
  put(LaneRecord::kP0, e.p0);
  put(LaneRecord::kP1, e.p1);
  put(LaneRecord::kP2, e.p2);
  put(LaneRecord::kP3, e.p3);
  put(LaneRecord::kNormal, e.normal);
  put(LaneRecord::kEmission, emission);
  r.v[LaneRecord::kSlack] = e.quad_slack;
  r.v[LaneRecord::kPdfArea] = 1.0f / e.area;
  r.v[LaneRecord::kQuad] = e.quad ? 1.0f : 0.0f;
  r.v[LaneRecord::kDoubleSided] = e.double_sided ? 1.0f : 0.0f;
  r.v[LaneRecord::kLongestEdge2] = e.longest_edge2;
  return r;
}

void Emitters::build_tree(const SceneDesc& desc, const std::vector<double>& power) {
  std::vector<LightBounds> bounded(power.size());
  std::vector<double> top_power(1, 0.0);
  unbounded_.assign(1, -1);
  top_slot_.assign(power.size(), -1);
  for (size_t i = 0; i < power.size(); ++i) {
    LightBounds& b = bounded[i];
    if (i < emitters_.size() && !emitters_[i].sphere) {
      const Emitter& e = emitters_[i];
      b.box.extend(e.p0);
      b.box.extend(e.p1);
      b.box.extend(e.p2);
      if (e.quad) b.box.extend(e.p3);
      b.normals = {e.normal, 1.0f};
      b.two_sided = e.double_sided;
    } else if (i < emitters_.size()) {
      const SphereDesc& sph = desc.spheres[emitters_[i].index];
      b.box.extend(sph.center - Vec3(sph.radius));
      b.box.extend(sph.center + Vec3(sph.radius));
      b.normals = DirectionCone::every_direction();
    } else if (static_cast<int>(i) != environment_index_ &&
               desc.lights[i - emitters_.size()].type != LightType::Directional) {
      const PunctualLightDesc& l = desc.lights[i - emitters_.size()];
      b.box.extend(l.position);
      b.normals = DirectionCone::every_direction();
      if (l.type == LightType::Spot) {
        // Full intensity inside the inner cone (theta_o), falling to nothing at the outer one
        // (theta_o + theta_e), as pbrt-v4 bounds its spot lights.
        const float inner = std::acos(std::clamp(l.cos_inner, -1.0f, 1.0f));
        const float outer = std::acos(std::clamp(l.cos_outer, -1.0f, 1.0f));
        b.normals = {l.direction, std::cos(std::min(inner, outer))};
        b.cos_emit = std::cos(std::max(0.0f, outer - inner));
      }
    } else {
      // At infinity: chosen beside the tree, by power.
      top_slot_[i] = static_cast<int>(unbounded_.size());
      unbounded_.push_back(static_cast<int>(i));
      top_power.push_back(power[i]);
      continue;
    }
    b.power = power[i] > 0 && std::isfinite(power[i]) ? power[i] : 0.0;
  }
  tree_ = LightTree(std::move(bounded));
  top_power[0] = tree_.power();
  top_ = Distribution1D(top_power);
}

std::optional<Emitters::Pick> Emitters::pick_first(float u) const {
  float remapped = 0;
  if (!tree_pays()) {
    if (pick_.size() == 0) return std::nullopt;
    if (pick_.size() == 1) return Pick{0, 1.0f, std::min(u, kOneMinusEpsilon)};  // one light: no choice to make
    const size_t i = pick_.sample(u, &remapped);
    return Pick{i, pick_.pmf(i), remapped};
  }
  if (top_.size() == 0) return std::nullopt;
  const size_t slot = top_.sample(u, &remapped);
  return Pick{slot > 0 ? size_t(unbounded_[slot]) : kDownTheTree, top_.pmf(slot), remapped};
}

std::optional<Emitters::Pick> Emitters::pick(const Vec3& ref, const Vec3& ref_n, float u) const {
  const std::optional<Pick> first = pick_first(u);
  if (!first || first->index != kDownTheTree) return first;
  return down_the_tree(*first, tree_.sample(ref, ref_n, first->remapped));
}

void Emitters::pick_many(const Vec3* ref, const Vec3* ref_n, const float* u_x, int count,
                         std::optional<Pick>* out) const {
  constexpr int kBatch = 8;
  if (count > kBatch) {
    for (int first = 0; first < count; first += kBatch)
      pick_many(ref + first, ref_n + first, u_x + first, std::min(count - first, kBatch), out + first);
    return;
  }
  Vec3 p[kBatch], n[kBatch];
  float u[kBatch];
  int lane[kBatch], down = 0;
  for (int i = 0; i < count; ++i) {
    out[i] = pick_first(u_x[i]);
    if (out[i] && out[i]->index == kDownTheTree) {
      p[down] = ref[i];
      n[down] = ref_n[i];
      u[down] = out[i]->remapped;
      lane[down++] = i;
    }
  }
  if (down > 0) {
    std::optional<LightTree::Pick> leaves[kBatch];
    tree_.sample_many(p, n, u, down, leaves);
    for (int j = 0; j < down; ++j) out[lane[j]] = down_the_tree(*out[lane[j]], leaves[j]);
  }
  for (int i = 0; i < count; ++i)
    if (out[i] && out[i]->index < emitters_.size()) {
      const char* e = reinterpret_cast<const char*>(&emitters_[out[i]->index]);
      __builtin_prefetch(e);
      __builtin_prefetch(e + sizeof(Emitter) - 1);
    }
}

std::optional<Vec2> Emitters::environment_map_draw(float u_spare, Vec2 u) const {
  if (environment_index_ < 0 || !environment_.has_map() || !portals_.empty()) return std::nullopt;
  const std::optional<Pick> first = pick_first(u.x);
  if (!first || first->index != size_t(environment_index_)) return std::nullopt;
  return Vec2{point_draw(*first, u_spare), u.y};
}

float Emitters::pick_probability(int index, const Vec3& ref, const Vec3& ref_n) const {
  if (index < 0 || size_t(index) >= pick_.size()) return 0;
  if (!tree_pays()) return pick_.pmf(size_t(index));
  const int slot = top_slot_[size_t(index)];
  if (slot > 0) return top_.pmf(size_t(slot));
  return top_.pmf(0) * tree_.pmf(index, ref, ref_n);
}

float Emitters::environment_direction_pdf(const EnvironmentPortals::View* view, const Vec3& ref, const Vec3& w,
                                          float map_pdf, int drawn_in) const {
  if (!view || !(view->total > 0)) return map_pdf;
  return (1 - kPortalShare) * map_pdf + kPortalShare * portals_.pdf(*view, ref, w, drawn_in);
}

float Emitters::environment_pdf(const Vec3& ref, const Vec3& w, float map_pdf) const {
  if (environment_index_ < 0) return 0;
  const float pick = pick_probability(environment_index_, Vec3(), Vec3());
  if (portals_.empty()) return pick * map_pdf;
  const EnvironmentPortals::View view = portals_.view(ref);
  return pick * environment_direction_pdf(&view, ref, w, map_pdf);
}

// The sky's direction where it has portals: one draw chooses portal or map, then serves the one
// chosen (one-sample MIS: the density of either is the mixture's). False: no direction.
bool Emitters::sky_sample(const EnvironmentPortals::View& view, const Vec3& ref, Vec2 u, Vec3& wi,
                          EnvironmentLight::Seen& seen, float& pdf_dir) const {
  const float share = view.total > 0 ? kPortalShare : 0.0f;
  int drawn_in = -1;
  if (u.x < share) {
    u.x = std::min(u.x / share, 0x1.fffffep-1f);
    const std::optional<EnvironmentPortals::Sample> through = portals_.sample(view, ref, u);
    if (!through) return false;
    wi = through->w;
    drawn_in = through->triangle;
    seen = environment_.seen(wi);
  } else {
    u.x = std::min((u.x - share) / (1 - share), 0x1.fffffep-1f);
    const EnvironmentLight::Sample drawn = environment_.sample(u);
    wi = drawn.wi;
    seen = drawn.seen;
    // In the mixture the map's density is w's own, even where sample() gave the draw none.
    if (!(seen.pdf > 0)) seen.pdf = environment_.pdf(wi);
  }
  pdf_dir = environment_direction_pdf(&view, ref, wi, seen.pdf, drawn_in);
  return true;
}

// The emitter is chosen by u.x, which rescaled within the emitter's share then places the point:
// the 2D draws of a pixel's samples stay stratified over all the triangles of a light together,
// where choosing by a dimension of its own would hand each triangle a random subset of them (Cycles
// reuses its draw the same way). Each rescaling leaves log2(1 / share) fewer bits of u.x, so below
// a share of 2^-8 (16 bits left) the independent u_spare places the point instead: either way the
// point is uniform given the choice, so the density is the same.
// Inlined in sample(), which is what most scenes call.
[[gnu::always_inline]] EmitterSample Emitters::sample_light(const std::optional<Pick>& chosen, const Vec3& ref,
                                                            float u_spare, Vec2 u,
                                                            const EnvironmentLight::Sample* sky,
                                                            const EnvironmentPortals::View* portal_view) const {
  if (!chosen) return {};
  u.x = point_draw(*chosen, u_spare);
  const size_t i = chosen->index;
  if (static_cast<int>(i) == environment_index_) {
    EmitterSample s;
    s.infinite = true;
    s.emitter = static_cast<int>(i);
    EnvironmentLight::Seen seen;
    float pdf_dir = 0;
    if (portals_.empty()) {
      const EnvironmentLight::Sample drawn = sky ? *sky : environment_.sample(u);
      s.wi = drawn.wi;
      seen = drawn.seen;
      pdf_dir = seen.pdf;
    } else {
      const bool drawn = portal_view ? sky_sample(*portal_view, ref, u, s.wi, seen, pdf_dir)
                                     : sky_sample(portals_.view(ref), ref, u, s.wi, seen, pdf_dir);
      if (!drawn) return {};
    }
    s.pdf = chosen->pmf * pdf_dir;
    s.distance = std::numeric_limits<float>::infinity();
    s.incident = seen.radiance;
    return s;
  }
  if (i >= emitters_.size()) {
    const PunctualIncidence in = punctual_incidence(desc_->lights[i - emitters_.size()], ref);
    EmitterSample s;
    s.delta = true;
    s.emitter = static_cast<int>(i);
    s.pdf = chosen->pmf;
    s.wi = in.wi;
    s.distance = in.distance;
    s.incident = in.irradiance;
    return s;
  }
  const Emitter& e = emitters_[i];
  EmitterSample s = e.sphere ? sample_sphere(e, ref, u) : sample_triangle(e, ref, u);
  s.emitter = static_cast<int>(i);
  s.pdf *= chosen->pmf;
  return s;
}

EmitterSample Emitters::sample(const Vec3& ref, const Vec3& ref_n, float u_spare, Vec2 u,
                               const EnvironmentLight::Sample* sky, const EnvironmentPortals::View* portal_view) const {
  return sample_light(pick(ref, ref_n, u.x), ref, u_spare, u, sky, portal_view);
}

float Emitters::pdf(int index, const Vec3& ref, const Vec3& ref_n, const Vec3& p, const Vec3& n) const {
  if (index < 0 || index >= static_cast<int>(emitters_.size()) || pick_.size() == 0) return 0;
  const Emitter& e = emitters_[index];
  if (!(e.area > 0)) return 0;  // collinear corners: never sampled (1 / 0 x a pick of 0 is NaN)
  const float pick_pmf = pick_probability(index, ref, ref_n);
  if (!(pick_pmf > 0)) return 0;
  return pick_pmf * (e.sphere ? sphere_pdf(e, ref, p, n) : triangle_pdf(e, ref, p, n));
}

// The back of a single-sided emitter sends nothing (the test emitted_radiance makes): no sample is
// spent there, and the pdf is 0 to match.
bool Emitters::faces(const Emitter& e, float plane_distance) { return e.double_sided || plane_distance > 0; }

// Half A's corners and, for a quad, half B's, seen from ref, and the solid angles of the halves:
// the quad's solid angle is theirs together, and a direction is drawn in one of them in proportion
// to its share. Only the half drawn in is made a SphericalTriangle (half()); a density needs none.
struct Emitters::SolidAngleView {
  SolidAngleView(const Emitter& e, const Vec3& ref)
      : SolidAngleView(e, ref, SphericalTriangle::see(ref, e.p0), SphericalTriangle::see(ref, e.p1),
                       SphericalTriangle::see(ref, e.p2)) {}
  SolidAngleView(const Emitter& e, const Vec3& ref, const SphericalTriangle::Corner& c0,
                 const SphericalTriangle::Corner& c1, const SphericalTriangle::Corner& c2)
      : ref(ref), corners{c0, c1, c2, {}}, quad(e.quad) {
    solid_angle_a = SphericalTriangle::solid_angle(c0, c1, c2);
    if (quad) {
      corners[3] = SphericalTriangle::see(ref, e.p3);
      solid_angle_b = SphericalTriangle::solid_angle(c1, corners[3], c2);
    }
    solid_angle = solid_angle_a + solid_angle_b;
  }
  // Solid angles under kMinSolidAngle or over kMaxSolidAngle are left to area sampling.
  bool pays() const { return solid_angle >= kMinSolidAngle && solid_angle <= kMaxSolidAngle; }
  // Half A (0) or, of a quad, half B (1): (c0, c1, c2) and (c1, c3, c2), as Emitter::corner0..2 order them.
  SphericalTriangle half(int h) const {
    return h == 0 ? SphericalTriangle(ref, corners[0], corners[1], corners[2], solid_angle_a)
                  : SphericalTriangle(ref, corners[1], corners[3], corners[2], solid_angle_b);
  }

  Vec3 ref;
  SphericalTriangle::Corner corners[4];
  bool quad;
  float solid_angle_a = 0, solid_angle_b = 0;
  float solid_angle = 0;
};

// A triangle or quad is sampled uniformly in the solid angle it subtends (Arvo 1995) when ref is
// closer to its plane than a half's longest edge, where the 1 / d^2 and cosine of area sampling vary
// most across it (Cycles' rule), and SolidAngleView::pays(). Farther, the two densities nearly
// agree and area sampling is cheaper.
bool Emitters::near_enough(const Emitter& e, float plane_distance) {
  return e.longest_edge2 > plane_distance * plane_distance;
}

EmitterSample Emitters::sample_triangle(const Emitter& e, const Vec3& ref, Vec2 u) const {
  const float plane_distance = dot(ref - e.p0, e.normal);
  if (!(e.area > 0) || !faces(e, plane_distance)) return {};
  if (near_enough(e, plane_distance)) {
    const SolidAngleView view(e, ref);
    if (view.pays()) {
      // u.x chooses the half and, rescaled within its share, places the point (as in sample()).
      const float share_a = view.solid_angle_a / view.solid_angle;
      const bool in_b = view.quad && u.x >= share_a;
      if (view.quad) u.x = std::min(in_b ? (u.x - share_a) / (1 - share_a) : u.x / share_a, kOneMinusEpsilon);
      const std::optional<Barycentrics> b = view.half(in_b ? 1 : 0).sample(u);
      if (!b) return {};
      EmitterSample s = triangle_point(e, in_b ? 1 : 0, *b);
      s.pdf = 1.0f / view.solid_angle;
      return s;
    }
  }
  Barycentrics b;
  const int half = area_point_draw(e, u, b);
  EmitterSample s = triangle_point(e, half, b);
  s.pdf = area_to_solid_angle(1.0f / e.area, ref, s.p, s.n);
  return s;
}

// By area: a quad's unit square maps linearly onto it, half A below the diagonal u + v = 1.
int Emitters::area_point_draw(const Emitter& e, Vec2 u, Barycentrics& b) {
  if (!e.quad) {
    const Vec2 t = sample_uniform_triangle(u);
    b = {t.x, t.y, 1.0f - t.x - t.y};
    return 0;
  }
  if (u.x + u.y <= 1) {
    b = {1.0f - u.x - u.y, u.x, u.y};
    return 0;
  }
  b = {1.0f - u.y, u.x + u.y - 1.0f, 1.0f - u.x};
  return 1;
}

Emitters::Draw Emitters::triangle_draw(const std::optional<Pick>* chosen, const Vec3& ref, const Vec3& ref_n,
                                       float u_spare, Vec2 u, TriangleDraw& out) const {
  const std::optional<Pick> picked = chosen ? *chosen : pick(ref, ref_n, u.x);
  if (!picked) return Draw::kNothing;
  if (picked->index >= emitters_.size()) return Draw::kToward;  // punctual or the environment
  const Emitter& e = emitters_[picked->index];
  if (e.sphere || e.textured) return Draw::kOther;
  if (!(e.area > 0)) return Draw::kNothing;
  u.x = point_draw(*picked, u_spare);
  out.light = &e;
  out.record = &lane_records_[picked->index];
  out.u = u;
  out.pmf = picked->pmf;
  return Draw::kOnTriangle;
}

float Emitters::triangle_pdf(const Emitter& e, const Vec3& ref, const Vec3& p, const Vec3& n) const {
  const float plane_distance = dot(ref - e.p0, e.normal);
  if (!faces(e, plane_distance)) return 0;
  if (near_enough(e, plane_distance)) {
    const SolidAngleView view(e, ref);
    if (view.pays()) return 1.0f / view.solid_angle;
  }
  return area_to_solid_angle(1.0f / e.area, ref, p, n);
}

EmitterSample Emitters::triangle_point(const Emitter& e, int half, const Barycentrics& b) const {
  const Vec3& c0 = e.corner0(half);
  const Vec3& c1 = e.corner1(half);
  const Vec3& c2 = e.corner2(half);
  EmitterSample s;
  s.p = c0 * b.b0 + c1 * b.b1 + c2 * b.b2;
  s.p_error = (abs(c0 * b.b0) + abs(c1 * b.b1) + abs(c2 * b.b2)) * kHitRelativeError + Vec3(e.quad_slack);
  s.n = e.normal;
  s.material = e.material;
  if (!e.textured) return s;
  const InstanceDesc& inst = desc_->instances[e.instance];
  const PrimitiveDesc& prim = desc_->meshes[inst.mesh].primitives[e.primitive];
  if (!prim.uvs.empty()) {
    // The half's corners in the file's order of its triangle's vertices (see Emitter::corner).
    const size_t first = 3 * size_t(half == 0 ? e.index : e.index_b);
    const uint8_t* corner = e.corner + 3 * half;
    const Vec2& t0 = prim.uvs[prim.indices[first + corner[0]]];
    const Vec2& t1 = prim.uvs[prim.indices[first + corner[1]]];
    const Vec2& t2 = prim.uvs[prim.indices[first + corner[2]]];
    s.uv = {t0.x * b.b0 + t1.x * b.b1 + t2.x * b.b2, t0.y * b.b0 + t1.y * b.b1 + t2.y * b.b2};
  }
  return s;
}

EmitterSample Emitters::sample_sphere(const Emitter& e, const Vec3& ref, Vec2 u) const {
  const SphereDesc& sph = desc_->spheres[e.index];
  EmitterSample s;
  s.material = sph.material;
  const Vec3 to_center = sph.center - ref;
  const float dc2 = length_squared(to_center);
  const float r2 = sph.radius * sph.radius;
  Vec3 n;
  if (dc2 <= r2 * kInsideSphere) {
    // Inside (or on) the sphere: uniform area sampling, converted to solid angle below.
    n = sample_uniform_sphere(u);
    s.p = sph.center + n * sph.radius;
    s.pdf = area_to_solid_angle(1.0f / e.area, ref, s.p, n);
  } else {
    // Outside: sample the cone of directions the sphere subtends, uniformly in solid angle,
    // then find the point through the angle alpha at the centre (pbrt-v4 §6.2.4).
    const float dc = std::sqrt(dc2);
    const float sin2_max = r2 / dc2;
    const float cos_max = std::sqrt(std::max(0.0f, 1.0f - sin2_max));
    const float omc_max = sin2_max / (1.0f + cos_max);  // 1 - cos_max without cancellation
    const float omc = u.x * omc_max;
    const float cos_theta = 1.0f - omc;
    const float sin2_theta = omc * (2.0f - omc);
    const float sin_max = std::sqrt(sin2_max);
    const float cos_alpha = sin2_theta / sin_max + cos_theta * std::sqrt(std::max(0.0f, 1.0f - sin2_theta / sin2_max));
    const float sin_alpha = std::sqrt(std::max(0.0f, 1.0f - cos_alpha * cos_alpha));
    const float phi = kTwoPi * u.y;
    const Frame frame = Frame::from_normal(to_center / dc);
    // The point's normal leans back toward ref: -z in the frame whose +z points to the centre.
    n = frame.to_world(Vec3(sin_alpha * std::cos(phi), sin_alpha * std::sin(phi), -cos_alpha));
    n = normalize(n);
    s.p = sph.center + n * sph.radius;
    s.pdf = 1.0f / (kTwoPi * omc_max);
  }
  s.n = n;
  s.p_error = (abs(sph.center) + Vec3(sph.radius)) * kHitRelativeError;
  s.uv = sphere_uv(n);
  return s;
}

float Emitters::sphere_pdf(const Emitter& e, const Vec3& ref, const Vec3& p, const Vec3& n) const {
  const SphereDesc& sph = desc_->spheres[e.index];
  const float dc2 = length_squared(sph.center - ref);
  const float r2 = sph.radius * sph.radius;
  if (dc2 <= r2 * kInsideSphere) return area_to_solid_angle(1.0f / e.area, ref, p, n);
  const float sin2_max = r2 / dc2;
  const float cos_max = std::sqrt(std::max(0.0f, 1.0f - sin2_max));
  return 1.0f / (kTwoPi * sin2_max / (1.0f + cos_max));
}

}  // namespace prism
