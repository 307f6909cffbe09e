#include "integrators/path_integrator.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/spawn.h"
#include "integrators/first_hit_aovs.h"
#include "integrators/lane_portal_views.h"
#include "integrators/medium_stack.h"
#include "integrators/sheet_crossing.h"
#include "materials/material_eval.h"
#include "materials/medium.h"

namespace prism {

// A path in flight: its next ray, what it has gathered, and what the next bounce needs to know.
struct PathIntegrator::Path {
  Ray ray;
  Sampler* sampler = nullptr;
  AovSample* aov = nullptr;
  // Light seen directly, after one scattering event, and after more.
  Rgb emitted{0.0f}, direct{0.0f}, indirect{0.0f}, beta{1.0f};
  float eta_scale = 1.0f;  // undoes the 1/eta^2 radiance scaling in Russian roulette decisions
  // The last scattering vertex, for MIS against next-event estimation: straight crossings of thin
  // sheets (integrators/sheet_crossing.h) leave these as they are, since a shadow ray crosses them too.
  float prev_bsdf_pdf = 0;  // solid-angle pdf of the direction that led to the current hit
  bool prev_delta = true;   // the camera ray counts as a delta event: no MIS for what it sees
  Vec3 prev_p;
  Vec3 prev_n;  // the normal the previous vertex chose its light for (pick_normal), for light-pick pmfs
  Vec3 segment_start;  // where the current ray left a surface (a crossing included), for absorption
  MediumStack media;
  int depth = 0;     // scattering events so far
  int vertices = 0;  // surfaces met so far, straight crossings included
  int crossings = 0;  // thin sheets crossed straight since the last scattering event
  int diffuse_depth = 0;
  bool last_vertex = false;  // the diffuse-bounce limit is reached: only emission (MIS) is left
  float alpha = 0;

  // The sum that light reaching the camera after `scatterings` scattering events belongs to.
  Rgb& light_after(int scatterings) { return scatterings == 0 ? emitted : scatterings == 1 ? direct : indirect; }
};

// A shadow ray and the light it lets through to `target` (one of the path's sums) when unoccluded.
struct PathIntegrator::ShadowQuery {
  Ray ray;
  Rgb contribution;
  bool cast = false;      // false: there is no shadow ray to trace
  bool queued = false;    // the query waits for lane_vertices, which sets ray, contribution and cast
  Rgb* target = nullptr;
  float medium_ior = 1;  // of the medium the ray travels in, for the sheets it may cross
};

// How a vertex draws its next direction: from the BSDF, or with probability `share` (at most
// --caster-share) aimed at one of the caustic casters in view, so that paths through smooth metal
// and glass to a light (which next-event estimation cannot reach) are found far more often. The
// two are combined by one-sample MIS with the balance heuristic (Veach 1997, §9.2.4): whichever
// drew it, a direction is weighted by the mixture's density, which stays unbiased and keeps each
// strategy's strengths.
struct PathIntegrator::Bounce {
  std::optional<CasterView> casters;
  float share = 0;  // 0: the BSDF alone

  // drawn_in: the cone an aimed direction was drawn in (CasterView::pdf).
  float pdf(float bsdf_pdf, const Vec3& w, int drawn_in = -1) const {
    return share > 0 ? (1 - share) * bsdf_pdf + share * casters->pdf(w, drawn_in) : bsdf_pdf;
  }
  // Where casters take a share: bs, drawn by either strategy, gets the mixture's density (a delta
  // lobe's direction is one the casters' cones draw with probability 0). False where it carries
  // nothing or cannot be drawn.
  bool mix(BsdfSample& bs, int drawn_in = -1) const {
    bs.pdf = bs.delta ? (1 - share) * bs.pdf : pdf(bs.pdf, bs.wi, drawn_in);
    return !is_black(bs.f_cos) && bs.pdf > 0;
  }
};

// Where a lane's ray arrived, with what li_packet worked out for all lanes before any shades.
struct PathIntegrator::Arrival {
  Vec3 dir;                         // the ray's direction, normalized
  const SurfaceHit* hit = nullptr;  // null: the ray escaped
  const Vec2* sky_uv = nullptr;     // escaped to a map's sky: where it meets the map (EnvironmentLight::prefetch)
  const VertexSamples* draws = nullptr;  // the vertex's draws, where the path scatters (scatters_next)
  const EnvironmentLight::Sample* sky_light = nullptr;  // the light sample, where those draws chose a map's sky
  const std::optional<Emitters::Pick>* light = nullptr;  // the light those draws chose, where li_packet chose it
  const EnvironmentPortals::View* portal_view = nullptr;  // the sky's portals seen from the hit, where made
  // What the vertex's light sample counts for: li_split has one continuation take the first vertex's
  // sample for all of them (weight split_), and the others none (0: advance takes no sample).
  float light_weight = 1;
  // li_packet's slot for how the vertex draws its bounce, where casters may aim bounces (null
  // elsewhere): the lanes' light sample (LaneVertexBatch::weigh_later) and bounce are weighed
  // against it after their run.
  Bounce* bounce = nullptr;
};

// The normal a vertex's light is chosen for (a light tree weighs lights by the cosine about it):
// the hit's shading normal, known before the BSDF is built, so that li_packet can choose the
// lanes' lights together. Its sign does not matter (the tree takes |cos|); the pmf of the pick,
// for MIS, takes the same normal.
static const Vec3& pick_normal(const SurfaceHit& hit) { return hit.ns; }

// Aiming is for surfaces with a non-delta lobe that only reflect: a transmitting one would need its
// crossing (media, eta) worked out for a direction it did not sample.
void PathIntegrator::choose_bounce(const Scene& scene, const SurfaceHit& hit, const Bsdf& bsdf, Bounce& b) const {
  if (!(caster_share_ > 0) || scene.casters().empty() || bsdf.is_delta() || !bsdf.reflects_only()) return;
  aim_bounce(scene, hit.p, bsdf.normal(), b);
}

void PathIntegrator::aim_bounce(const Scene& scene, const Vec3& p, const Vec3& n, Bounce& b) const {
  scene.casters().view(p, n, b.casters.emplace());
  // The full share only where the casters fill about 0.5 sr or more of the view (coverage, the sum
  // of sin^2 of their cones' half-angles, 0.16: one cone of 23 degrees), less in proportion below
  // that: small casters take few of the BSDF's samples, and a quarter of the samples aimed at them
  // costs the rest of the integrand more than their caustics gain (docs/PERFORMANCE.md: 64 small
  // mirror balls). Any share that depends on the vertex alone keeps the estimate unbiased.
  constexpr float kFullShareCoverage = 0.16f;
  b.share = b.casters->empty() ? 0.0f : caster_share_ * std::min(1.0f, b.casters->coverage() / kFullShareCoverage);
}

// Light arriving at `hit` from one sampled light, through the BSDF, attenuated by the medium on
// the light's side of the surface, weighted by MIS against BSDF sampling (area lights); whether
// the light is visible is left to the shadow ray.
PathIntegrator::ShadowQuery PathIntegrator::direct_light(const Scene& scene, const SurfaceHit& hit, const Bsdf& bsdf,
                                                         const Bounce& bounce, const MediumStack& media,
                                                         const MaterialDesc& material, bool from_front,
                                                         const VertexSamples& u,
                                                         const EnvironmentLight::Sample* sky,
                                                         const std::optional<Emitters::Pick>* light,
                                                         const EnvironmentPortals::View* portal_view) const {
  const SceneDesc& desc = scene.desc();
  const Emitters& emitters = scene.emitters();
  ShadowQuery q;
  const Vec2 point = u.light_point;
  const EmitterSample ls = light ? emitters.sample_light(*light, hit.p, u.light_spare, point, sky, portal_view)
                                 : emitters.sample(hit.p, pick_normal(hit), u.light_spare, point, sky, portal_view);
  if (!(ls.pdf > 0)) return q;
  Vec3 wi;
  float dist;
  Rgb incident;
  if (ls.delta || ls.infinite) {
    wi = ls.wi;
    dist = ls.distance;
    incident = ls.incident;
  } else {
    const Vec3 to_light = ls.p - hit.p;
    dist = length(to_light);
    wi = to_light / dist;
    incident = emitted_radiance(desc, ls.material, ls.uv, ls.n, -wi);
  }
  const Bsdf::Value f = bsdf.evaluate(wi);
  if (is_black(incident) || is_black(f.f_cos)) return q;
  q.ray = ls.delta || ls.infinite ? spawn_ray_toward(hit, wi, dist) : spawn_ray_between(hit, ls.p, ls.p_error, ls.n);
  // The shadow ray travels in the medium on wi's side of the surface.
  Rgb sigma = media.sigma_a();
  q.medium_ior = media.ior();
  if ((dot(wi, hit.ng) > 0) != from_front && material.has_volume()) {
    MediumStack beyond = media;
    beyond.cross(material, hit.material, from_front);
    sigma = beyond.sigma_a();
    q.medium_ior = beyond.ior();
  }
  const Rgb tr = beer_lambert(sigma, dist);
  const float weight = ls.delta ? 1.0f : power_heuristic(ls.pdf, bounce.pdf(f.pdf, wi));
  q.contribution = f.f_cos * incident * tr * (weight / ls.pdf);
  q.cast = true;
  return q;
}

// Inlined in advance, its one caller.
template <bool kAimsAtCasters>
[[gnu::always_inline]] inline bool PathIntegrator::queue_direct_light(const Scene& scene, const SurfaceHit& hit,
                                                                      const Bounce& bounce, const Path& path,
                                                                      const MaterialDesc& material,
                                                                      const VertexSamples& u, const Arrival& at,
                                                                      ShadowQuery& shadow, LaneVertexBatch& lanes,
                                                                      int lane) const {
  // lanes::direct_light's case: nothing absorbs on either side of the surface (beer_lambert is 1).
  // Where casters aim the bounce, the MIS weight needs their density toward the light: li_packet
  // applies it after the lanes' run (LaneVertexBatch::weigh_later), from the path's throughput held
  // in shadow.contribution until then.
  if (!path.media.empty() || material.has_volume()) return false;
  bool later = false;  // the sample is weighed after the lanes' run
  const Emitters& emitters = scene.emitters();
  Emitters::TriangleDraw draw;
  switch (emitters.triangle_draw(at.light, hit.p, pick_normal(hit), u.light_spare, u.light_point, draw)) {
    case Emitters::Draw::kNothing: return true;
    case Emitters::Draw::kOther: return false;
    case Emitters::Draw::kOnTriangle:
      lanes.request_light(lane, hit.triangle, path.beta, draw);
      later = kAimsAtCasters && bounce.share > 0;
      break;
    case Emitters::Draw::kToward: {
      // direct_light's sample, whose direction the lanes take on. Without a light tree the light is
      // picked again here (a search of the top-level distribution): handing the sample out of
      // triangle_draw instead cost every triangle draw more (+0.3% on the box, session 45).
      const Vec2 point = u.light_point;
      const EmitterSample ls =
          at.light ? emitters.sample_light(*at.light, hit.p, u.light_spare, point, at.sky_light, at.portal_view)
                   : emitters.sample(hit.p, pick_normal(hit), u.light_spare, point, at.sky_light, at.portal_view);
      if (!(ls.pdf > 0)) return true;
      lanes.request_light_toward(lane, hit.triangle, path.beta, ls);
      later = kAimsAtCasters && bounce.share > 0 && !ls.delta;  // (a punctual light's weight is 1)
      break;
    }
  }
  shadow.queued = true;
  shadow.medium_ior = 1.0f;
  if (kAimsAtCasters && later) {
    lanes.weigh_later(lane);
    shadow.contribution = path.beta;
  }
  return true;
}

bool PathIntegrator::scatters_next(const Path& path) const {
  return path.depth < max_depth_ && !path.last_vertex;
}

// Each vertex that scatters draws, in order: the light sample's spare (1D), the light and the
// point on it (2D), BSDF lobe (1D) and direction (2D), and the Russian-roulette decision (1D), all
// five whether or not it uses them (no light sampling at delta surfaces, no roulette before its
// start depth): a dimension then means the same decision in every sample of a pixel, and stays
// stratified across them (pbrt-v4 does the same). li_packet draws them (at.draws) before the lanes
// shade.
template <bool kAimsAtCasters>
PathIntegrator::Step PathIntegrator::advance(const Scene& scene, Path& path, const Arrival& at, ShadowQuery& shadow,
                                             RayCounters& counters, LaneVertexBatch* lanes) const {
  const SurfaceHit* found = at.hit;
  const Vec2* sky_uv = at.sky_uv;
  const SceneDesc& desc = scene.desc();
  const Emitters& emitters = scene.emitters();
  const int depth = path.depth;
  Rgb& beta = path.beta;
  shadow.cast = shadow.queued = false;
  if (!found) {
    // Escaped to the sky: the environment, MIS-weighted against light sampling after a
    // non-delta bounce; inside an absorbing medium the infinite segment absorbs completely.
    const EnvironmentLight& env = emitters.environment();
    if (env.present()) {
      const Vec3& w = at.dir;
      // The sky seen straight through delta events needs no density (no MIS).
      EnvironmentLight::Seen seen;
      if (sky_uv)
        seen = path.prev_delta ? EnvironmentLight::Seen{env.map_radiance(*sky_uv)} : env.seen_at(*sky_uv);
      else
        seen = path.prev_delta ? EnvironmentLight::Seen{env.radiance(w)} : env.seen(w);
      const float weight = path.prev_delta
                               ? 1.0f
                               : power_heuristic(path.prev_bsdf_pdf, emitters.environment_pdf(path.prev_p, w, seen.pdf));
      path.light_after(depth) += beta * seen.radiance * beer_lambert(path.media.sigma_a(), kInfinity) * weight;
    }
    return Step::kEnds;
  }
  const SurfaceHit& hit = *found;
  const bool first_hit = path.vertices == 0;
  if (first_hit) {
    path.alpha = 1.0f;
    if (path.aov) report_first_hit(desc, hit, *path.aov);
  }
  // Beer-Lambert along the segment, measured between the surface points themselves: the spawned
  // origin sits off its surface by the hit's error bound, which far from the world origin is a
  // visible part of a thin slab's thickness.
  if (!path.media.empty())
    beta *= beer_lambert(path.media.sigma_a(),
                         first_hit ? hit.t * length(path.ray.dir) : length(hit.p - path.segment_start));
  const Vec3 wo = -at.dir;

  // Emission reached by the previous bounce: weighted against next-event estimation by the
  // power heuristic (Veach 1997, ch. 9); unweighted after a delta event.
  if (hit.emitter >= 0) {
    const Rgb Le = emitted_radiance(desc, hit.material, hit.uv, hit.ng, wo);
    if (!is_black(Le)) {
      float w = 1.0f;
      if (!path.prev_delta)
        w = power_heuristic(path.prev_bsdf_pdf,
                            emitters.pdf(hit.emitter, path.prev_p, path.prev_n, hit.p, hit.ng));
      path.light_after(depth) += beta * Le * w;
    }
  }
  const MaterialDesc& material = desc.material(hit.material);
  const bool from_front = dot(wo, hit.ng) > 0;
  if (!scatters_next(path)) {
    // No more scattering, but a straight crossing is none: next-event estimation at the last
    // vertex counted light beyond sheets, so the path must still reach it for its MIS half.
    if (!material.is_thin_sheet() || path.crossings >= kMaxSheetCrossings) return Step::kEnds;
    const Rgb through = straight_through(desc, hit, wo, path.media.interface_eta(material, hit.material, from_front));
    if (is_black(through)) return Step::kEnds;
    beta *= through;
    ++path.crossings;
    leave_surface(path, hit, -wo);
    ++counters.extension;
    return Step::kGoesOn;
  }

  const VertexSamples& u = *at.draws;
  const float eta = path.media.interface_eta(material, hit.material, from_front);
  // The material's parameters at the hit, made only where they are needed: a material whose
  // factors alone say it is Lambertian (lambertian_everywhere) needs its base colour alone.
  std::optional<SurfaceParams> params_at_hit;
  const auto params = [&]() -> const SurfaceParams& {
    if (!params_at_hit) params_at_hit.emplace(surface_params(desc, material, hit.uv, hit.uv_width()));
    return *params_at_hit;
  };
  const Vec3 ns = shading_normal(desc, material, hit);
  // The Lambertian lobe alone, and glTF's opaque metallic-roughness mixture with rough lobes
  // (Bsdf::coated_only), are the lanes' cases: they make the lobes' frame themselves, and the Bsdf is
  // built only where the scalar code below needs it (casters that may aim the bounce, a light
  // sample the lanes do not take).
  std::optional<bool> lambertian;
  if (lanes) lambertian = lambertian_everywhere(material, eta);
  const bool lambertian_lane = lanes && (lambertian ? *lambertian : Bsdf::lambertian_only(params(), eta));
  const bool coated_lane = lanes && !lambertian_lane && Bsdf::coated_only(params(), eta);
  const bool in_lanes = lambertian_lane || coated_lane;
  std::optional<Bsdf> built;
  const auto bsdf = [&]() -> const Bsdf& {
    if (!built) built.emplace(params(), ns, hit.ng, wo, eta);
    return *built;
  };
  const auto albedo = [&] {  // surface_params' base colour, without the rest where it was not made
    return params_at_hit ? params_at_hit->base_color : base_color(desc, material, hit.uv, hit.uv_width());
  };
  int lane = -1;
  if (lambertian_lane) {
    lane = lanes->add({ns, hit.ng, wo, Lambertian{albedo()}.f()}, hit.p, hit.p_error);
  } else if (coated_lane) {
    const SurfaceParams& p = params();
    lane = lanes->add({ns, hit.ng, wo, Lambertian{p.base_color}.f()}, hit.p, hit.p_error, CoatedSurface::of(p, eta));
  }

  // A vertex in the lanes, where casters may aim bounces, makes its strategy in li_packet's slot for
  // it: the lanes' light sample and bounce are weighed against it after their run.
  Bounce own;
  Bounce& bounce = kAimsAtCasters && in_lanes ? *at.bounce : own;
  if (!in_lanes) {
    choose_bounce(scene, hit, bsdf(), bounce);
  } else if constexpr (kAimsAtCasters) {
    // choose_bounce's aim, without the Bsdf (its lobes reflect only, and are not delta lobes).
    aim_bounce(scene, hit.p, Bsdf::reflecting_normal(ns, hit.ng, wo), bounce);
  }

  // Next-event estimation: one light, chosen as the scene's light sampler says; a point on it for area lights.
  if (!emitters.empty() && at.light_weight > 0 && (in_lanes || !bsdf().is_delta())) {
    if (!(in_lanes &&
          queue_direct_light<kAimsAtCasters>(scene, hit, bounce, path, material, u, at, shadow, *lanes, lane))) {
      shadow = direct_light(scene, hit, bsdf(), bounce, path.media, material, from_front, u, at.sky_light, at.light,
                            at.portal_view);
      if (shadow.cast) {
        ++counters.shadow;
        shadow.contribution = beta * shadow.contribution;
      }
    }
    shadow.target = &path.light_after(depth + 1);  // through this bounce's scattering
  }

  // The lobe draw first chooses the strategy, then is rescaled to serve the one chosen. A lanes
  // vertex's bounce, unless aimed at casters, is drawn in lanes; li_packet then finishes it with
  // scatter() (and the mixture's density, where casters take a share).
  const bool aimed = kAimsAtCasters && bounce.share > 0 && u.lobe < bounce.share;  // (no share otherwise)
  const float bsdf_u_lobe = kAimsAtCasters && bounce.share > 0
                                ? std::min((u.lobe - bounce.share) / (1 - bounce.share), 0x1.fffffep-1f)
                                : u.lobe;
  if (in_lanes && !aimed) {
    lanes->request_bounce(lane, u.direction, bsdf_u_lobe);  // (a Lambertian lane ignores the lobe draw)
    return Step::kInLanes;
  }
  std::optional<BsdfSample> bs;
  int cone = -1;  // the caster's cone an aimed direction was drawn in
  if (aimed) {
    bs.emplace();
    bs->wi = bounce.casters->sample(u.lobe / bounce.share, u.direction, &cone);
    const Bsdf::Value v = bsdf().evaluate(bs->wi);
    bs->f_cos = v.f_cos;
    bs->pdf = v.pdf;
  } else {
    bs = bsdf().sample(bsdf_u_lobe, u.direction);
  }
  if (!bs) return Step::kEnds;
  if (bounce.share > 0 && !bounce.mix(*bs, cone)) return Step::kEnds;
  return scatter(path, hit, *bs, material, from_front, u.roulette, counters) ? Step::kGoesOn : Step::kEnds;
}

bool PathIntegrator::scatter(Path& path, const SurfaceHit& hit, const BsdfSample& bs, const MaterialDesc& material,
                             bool from_front, float u_roulette, RayCounters& counters, const Vec3* origin) const {
  const int depth = path.depth;
  path.beta *= bs.f_cos / bs.pdf;
  if (bs.delta && bs.transmission && material.is_thin_sheet()) {
    // Straight through a smooth sheet, as a shadow ray would go: not a scattering event.
    if (path.crossings >= kMaxSheetCrossings) return false;
    ++path.crossings;
  } else {
    path.crossings = 0;
    path.prev_bsdf_pdf = bs.pdf;
    path.prev_delta = bs.delta;
    // Past the diffuse limit the sampled ray still finds the emitter it hits (its MIS half of
    // direct lighting), then the path ends.
    if (!bs.delta && max_diffuse_depth_ >= 0 && ++path.diffuse_depth > max_diffuse_depth_) path.last_vertex = true;
    path.prev_p = hit.p;
    path.prev_n = pick_normal(hit);
    if (bs.transmission) {
      path.media.cross(material, hit.material, from_front);
      if (material.has_volume()) path.eta_scale *= bs.eta * bs.eta;
    }
    path.depth = depth + 1;
  }
  leave_surface(path, hit, bs.wi, origin);
  if (!survives_roulette(path, depth + 1, u_roulette)) return false;
  ++counters.extension;
  return true;
}

void PathIntegrator::leave_surface(Path& path, const SurfaceHit& hit, const Vec3& wi, const Vec3* origin) {
  path.ray = spawn_ray_cone(hit, wi, path.ray, origin);
  path.segment_start = hit.p;
  ++path.vertices;
}

// Russian roulette on the throughput without the radiance scaling of refraction, so paths
// inside glass are not killed for having crossed into it; survivors are reweighted. A path
// survives with probability sqrt(throughput), as in Cycles, not the throughput itself: in the
// closed, bright rooms of scenes/ the linear rule's extra variance outweighed the time it saved
// (docs/PERFORMANCE.md, "Russian roulette").
bool PathIntegrator::survives_roulette(Path& path, int depth, float u) const {
  if (depth < rr_start_depth_) return true;
  const float q = std::max(0.0f, 1.0f - std::sqrt(max_component(path.beta) * path.eta_scale));
  if (u < q) return false;
  path.beta /= 1.0f - q;
  return true;
}

RadianceSample PathIntegrator::finish(Path& path) const {
  if (clamp_indirect_ > 0) {
    const float m = max_component(path.indirect);
    if (m > clamp_indirect_) path.indirect *= clamp_indirect_ / m;
  }
  RadianceSample out;
  out.alpha = path.alpha;
  out.radiance = path.emitted + path.direct + path.indirect;
  if (path.aov) {
    path.aov->emission = path.emitted;
    path.aov->direct = path.direct;
    path.aov->indirect = path.indirect;
  }
  return out;
}

RadianceSample PathIntegrator::li(const Scene& scene, const Ray& camera_ray, Sampler& sampler, RayCounters& counters,
                                  AovSample* aov) const {
  Sampler* samplers[] = {&sampler};
  AovSample* aovs[] = {aov};
  RadianceSample out;
  li_packet(scene, &camera_ray, samplers, 1, counters, aovs, &out);
  return out;
}

void PathIntegrator::li_packet(const Scene& scene, const Ray* camera_rays, Sampler* const* samplers, int n,
                               RayCounters& counters, AovSample* const* aovs, RadianceSample* out) const {
  constexpr int kLanes = kPathsInLockstep;
  for (int first = 0; first < n; first += kLanes) {
    const int m = std::min(n - first, kLanes);
    AovSample* const* lane_aovs = aovs ? aovs + first : nullptr;
    if (split_ > 1 && max_depth_ > 0)
      li_split(scene, camera_rays + first, samplers + first, m, counters, lane_aovs, out + first);
    else
      lockstep(scene, camera_rays + first, samplers + first, m, counters, lane_aovs, out + first, nullptr);
  }
}

void PathIntegrator::lockstep(const Scene& scene, const Ray* camera_rays, Sampler* const* samplers, int n,
                              RayCounters& counters, AovSample* const* aovs, RadianceSample* out,
                              const CameraHits* camera_hits) const {
  if (caster_share_ > 0 && !scene.casters().empty())
    li_lockstep<true>(scene, camera_rays, samplers, n, counters, aovs, out, camera_hits);
  else
    li_lockstep<false>(scene, camera_rays, samplers, n, counters, aovs, out, camera_hits);
}

// Splitting at the first vertex: the camera rays are traced once, and the first vertex takes one
// light sample, drawn at the camera sample's index s (with its jitter, as one net: SobolSampler);
// then each of the split_ continuations c draws its bounce there and the rest of its path from
// sample index s * split_ + c of the pixel. The continuations of a pixel's samples 0 .. N-1 are
// then its samples 0 .. N * split_ - 1, as well stratified as a render with that many, and a
// render split into passes or slices draws the same values. The camera sample's estimate is the
// light sample's (in continuation 0, weighted split_) and the continuations' mean: the light a
// pixel sees through its first bounce gets split_ samples per camera sample, as Arnold's diffuse
// and specular samples give it. With one light sample against split_ bounces the MIS weights
// still sum to one for every direction, so the estimate stays unbiased.
void PathIntegrator::li_split(const Scene& scene, const Ray* camera_rays, Sampler* const* samplers, int n,
                              RayCounters& counters, AovSample* const* aovs, RadianceSample* out) const {
  constexpr int kLanes = kPathsInLockstep;
  CameraHits camera;
  scene.intersect_packet(camera_rays, n, camera.hits, camera.found, true);
  counters.camera += uint64_t(n);
  SamplerPosition after_camera[kLanes];
  for (int k = 0; k < n; ++k) {
    after_camera[k] = samplers[k]->position();
    if (camera.found[k]) samplers[k]->draw_vertex(camera.light_draws[k]);
  }
  AovSample more[kLanes];  // the AOVs of continuations after the first, whose first-hit records repeat its own
  AovSample* more_aovs[kLanes];
  for (int k = 0; k < n; ++k) more_aovs[k] = &more[k];
  RadianceSample part[kLanes];
  for (int c = 0; c < split_; ++c) {
    camera.light_weight = c == 0 ? float(split_) : 0.0f;
    for (int k = 0; k < n; ++k)
      samplers[k]->move_to({after_camera[k].index * uint64_t(split_) + uint64_t(c), after_camera[k].dimension});
    lockstep(scene, camera_rays, samplers, n, counters, aovs ? (c == 0 ? aovs : more_aovs) : nullptr,
             c == 0 ? out : part, &camera);
    if (c == 0) continue;
    for (int k = 0; k < n; ++k) {
      out[k].radiance += part[k].radiance;
      if (!aovs) continue;
      aovs[k]->emission += more[k].emission;
      aovs[k]->direct += more[k].direct;
      aovs[k]->indirect += more[k].indirect;
    }
  }
  const float mean = 1.0f / float(split_);
  for (int k = 0; k < n; ++k) {
    out[k].radiance *= mean;
    if (!aovs) continue;
    aovs[k]->emission *= mean;
    aovs[k]->direct *= mean;
    aovs[k]->indirect *= mean;
  }
}

template <bool kAimsAtCasters>
void PathIntegrator::li_lockstep(const Scene& scene, const Ray* camera_rays, Sampler* const* samplers, int n,
                                 RayCounters& counters, AovSample* const* aovs, RadianceSample* out,
                                 const CameraHits* camera_hits) const {
  constexpr int kLanes = kPathsInLockstep;
  Path paths[kLanes];
  int live[kLanes];  // the paths still in flight, in lane order
  for (int k = 0; k < n; ++k) {
    paths[k].ray = camera_rays[k];
    paths[k].sampler = samplers[k];
    paths[k].aov = aovs ? aovs[k] : nullptr;
    live[k] = k;
  }
  if (!camera_hits) counters.camera += uint64_t(n);
  // One bounce of every live path per round: their rays are traced together, then each path
  // shades its hit, then their shadow rays are traced together. A path's draws do not depend on
  // its shadow ray's answer, so deferring that answer changes nothing but the order of queries.
  Ray rays[kLanes], shadow_rays[kLanes];
  SurfaceHit hits[kLanes];
  ShadowQuery shadows[kLanes];
  bool found[kLanes];
  float shadow_iors[kLanes];
  Rgb through[kLanes];
  int shadow_lane[kLanes];
  static_assert(LaneVertexBatch::kLanes >= kLanes);
  LaneVertexBatch lanes;
  LaneLightResult light_results[kLanes];
  LaneBounce bounce_results[kLanes];
  int vertex_lane[kLanes];  // the path lane of each of the batch's lanes
  // Where casters may aim bounces, each lane's strategy, until the lanes' light sample is weighed.
  struct LaneBounces {
    LaneBounces() {}  // user-provided, so that emplace() does not zero the 14 KiB first
    Bounce lane[kLanes];
  };
  std::optional<LaneBounces> bounces;
  if constexpr (kAimsAtCasters) bounces.emplace();
  Step step[kLanes];
  std::optional<Emitters::Pick> picked[kLanes];  // the lanes' lights, where li_packet chooses them
  const std::optional<Emitters::Pick>* light[kLanes] = {};
  // Each round's per-lane values, set for the round's live lanes before they are read.
  Vec2 sky_uv[kLanes];
  VertexSamples draws[kLanes];
  Vec2 sky_draw[kLanes];
  int sky_draw_lane[kLanes];
  EnvironmentLight::Sample sky_samples[kLanes];
  const EnvironmentLight::Sample* sky_light[kLanes];
  // Where the sky has portals, every light sample that chooses it sees them from its vertex: the
  // views of eight vertices are made at once (portal_views), a block at a time as the lanes shade.
  const EnvironmentPortals& portals = scene.emitters().portals();
  const bool has_portals = !portals.empty();
  constexpr int kViews = 8;
  EnvironmentPortals::View portal_view[kViews];
  for (int m = n; m > 0;) {
    for (int i = 0; i < m; ++i) rays[i] = paths[live[i]].ray;
    const bool camera = paths[live[0]].vertices == 0;  // lanes advance together: all or none are camera rays
    // A continuation's first vertex (li_split): its light sample's draws and weight are the camera sample's.
    const CameraHits* split_vertex = camera ? camera_hits : nullptr;
    const float light_weight = split_vertex ? split_vertex->light_weight : 1.0f;
    if (split_vertex) {
      std::copy(split_vertex->hits, split_vertex->hits + m, hits);
      std::copy(split_vertex->found, split_vertex->found + m, found);
    } else {
      scene.intersect_packet(rays, m, hits, found, camera);
    }
    // The rays' unit directions, made together: one at a time, each lane waited for its square root
    // and division at the top of advance.
    Vec3 unit_dir[kLanes];
    for (int i = 0; i < m; ++i) unit_dir[i] = normalize(rays[i].dir);
    // Ray cones size texture footprints, which only images with MIP levels read (mip_lambda): elsewhere
    // the width, a square root per hit, would go unused.
    if (scene.features().mip_levels)
      for (int i = 0; i < m; ++i)
        if (found[i]) hits[i].cone_width = rays[i].cone_width_at(hits[i].t);
    // Every lane's texels (of its hit's textures, or of the sky map it escaped to) are asked for
    // before the first lane shades: their cache misses, which each lane would otherwise wait out
    // in turn, overlap.
    const Emitters& emitters = scene.emitters();
    const EnvironmentLight& sky = emitters.environment();
    if (scene.features().textures || sky.has_map())
      for (int i = 0; i < m; ++i) {
        if (!found[i])
          sky_uv[i] = sky.has_map() ? sky.prefetch(unit_dir[i]) : Vec2{};
        else if (scene.features().textures)
          prefetch_textures(scene.desc(), scene.desc().material(hits[i].material), hits[i].uv, hits[i].uv_width());
      }
    // The vertices' draws, which do not depend on what a lane finds there, come first too: where
    // they choose a map's sky for the light sample, the lanes' sky samples are drawn together.
    int sky_draws = 0;
    for (int i = 0; i < m; ++i) {
      Path& path = paths[live[i]];
      if (!found[i] || !scatters_next(path)) continue;
      path.sampler->draw_vertex(draws[i]);
      if (split_vertex) {
        draws[i].light_spare = split_vertex->light_draws[i].light_spare;
        draws[i].light_point = split_vertex->light_draws[i].light_point;
      }
      if (!sky.has_map() || light_weight == 0) continue;
      if (const std::optional<Vec2> d = emitters.environment_map_draw(draws[i].light_spare, draws[i].light_point)) {
        sky_draw[sky_draws] = *d;
        sky_draw_lane[sky_draws++] = i;
      }
    }
    std::fill(sky_light, sky_light + m, nullptr);
    if (sky_draws > 0) {
      sky.sample(sky_draw, sky_draws, sky_samples);
      for (int j = 0; j < sky_draws; ++j) sky_light[sky_draw_lane[j]] = &sky_samples[j];
    }
    // Where the light a draw chooses depends on the shading point (a light tree), the lanes' lights
    // are chosen together: their walks down the tree, each a chain of cache misses on a large one,
    // overlap. Lanes whose BSDF turns out to be a delta lobe leave theirs unused.
    if (emitters.picks_ahead() && light_weight > 0) {
      Vec3 pick_p[kLanes], pick_n[kLanes];
      float pick_u[kLanes];
      int pick_lane[kLanes], picks = 0;
      std::fill(light, light + m, nullptr);
      for (int i = 0; i < m; ++i)
        if (found[i] && scatters_next(paths[live[i]])) {
          pick_p[picks] = hits[i].p;
          pick_n[picks] = pick_normal(hits[i]);
          pick_u[picks] = draws[i].light_point.x;
          pick_lane[picks++] = i;
        }
      emitters.pick_many(pick_p, pick_n, pick_u, picks, picked);
      for (int j = 0; j < picks; ++j) light[pick_lane[j]] = &picked[j];
    }

    lanes.clear();
    for (int i = 0; i < m; ++i) {
      if (has_portals && i % kViews == 0) {
        Vec3 refs[kViews];
        const int block = std::min(kViews, m - i);
        for (int k = 0; k < block; ++k) refs[k] = found[i + k] ? hits[i + k].p : Vec3(0.0f);
        portal_views(portals, refs, block, portal_view);
      }
      Arrival at;
      at.dir = unit_dir[i];
      at.light_weight = light_weight;
      if (found[i]) {
        at.hit = &hits[i];
        if constexpr (kAimsAtCasters) at.bounce = &bounces->lane[i];
        at.draws = &draws[i];
        at.sky_light = sky_light[i];
        at.light = light[i];
        if (has_portals) at.portal_view = &portal_view[i % kViews];
      } else if (sky.has_map()) {
        at.sky_uv = &sky_uv[i];
      }
      const int before = lanes.size();
      step[i] = advance<kAimsAtCasters>(scene, paths[live[i]], at, shadows[i], counters, lanes_ ? &lanes : nullptr);
      if (lanes.size() > before) vertex_lane[before] = i;
    }
    // The Lambertian and coated vertices' light samples and bounces, in SIMD lanes.
    lane_vertices(lanes, light_results, bounce_results);
    for (int j = 0; j < lanes.size(); ++j) {
      const int i = vertex_lane[j];
      if (shadows[i].queued) {
        ShadowQuery& q = shadows[i];
        const LaneLightResult& r = light_results[j];
        q.cast = r.cast;
        if (q.cast) {
          q.ray = r.ray;
          if (kAimsAtCasters && lanes.row(LaneVertexBatch::kWeighLater)[j] != 0) {
            // direct_light's weight and products, in its order; q.contribution holds beta.
            const float weight = power_heuristic(r.pdf, bounces->lane[i].pdf(r.bsdf_pdf, r.wi));
            q.contribution = q.contribution * (r.contribution * (weight / r.pdf));
          } else {
            q.contribution = r.contribution;
          }
          ++counters.shadow;
        }
      }
      if (step[i] == Step::kInLanes) {
        const LaneBounce& b = bounce_results[j];
        BsdfSample bs;
        bs.wi = b.wi;
        bs.f_cos = b.f_cos;
        bs.pdf = b.pdf;
        bool sampled = b.sampled;
        if (kAimsAtCasters && sampled && bounces->lane[i].share > 0) sampled = bounces->lane[i].mix(bs);
        // A lanes vertex's bounce reflects: the material and side matter only to transmission.
        step[i] = sampled && scatter(paths[live[i]], hits[i], bs, scene.desc().material(hits[i].material), true,
                                       draws[i].roulette, counters, &b.origin)
                      ? Step::kGoesOn
                      : Step::kEnds;
      }
    }
    int still = 0;
    for (int i = 0; i < m; ++i)
      if (step[i] == Step::kGoesOn) live[still++] = live[i];
    int s = 0;
    for (int i = 0; i < m; ++i)
      if (shadows[i].cast) {
        shadow_rays[s] = shadows[i].ray;
        shadow_iors[s] = shadows[i].medium_ior;
        shadow_lane[s++] = i;
      }
    if (light_weight != 1.0f)
      for (int j = 0; j < s; ++j) shadows[shadow_lane[j]].contribution *= light_weight;
    shadow_transmittance(scene, shadow_rays, shadow_iors, s, through, counters);
    for (int j = 0; j < s; ++j)
      if (!is_black(through[j])) *shadows[shadow_lane[j]].target += shadows[shadow_lane[j]].contribution * through[j];
    m = still;
  }
  for (int k = 0; k < n; ++k) out[k] = finish(paths[k]);
}

}  // namespace prism
