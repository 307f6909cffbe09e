// PathIntegrator: unidirectional path tracing with next-event estimation, MIS and Russian roulette.
#pragma once

#include "core/integrator.h"
#include "integrators/lane_vertices.h"
#include "integrators/medium_stack.h"
#include "materials/bsdf.h"

namespace prism {

class PathIntegrator final : public Integrator {
 public:
  // max_depth: bounces (0 = directly visible emission only); Russian roulette starts at
  // bounce rr_start_depth; max_diffuse_depth limits non-delta bounces (-1: no limit of its own);
  // clamp_indirect > 0 scales each sample's indirect light (after two or more scattering events)
  // down to that maximum component, trading bias for fewer fireflies. caster_share > 0 aims that
  // share of the bounce directions at reflecting surfaces toward the scene's caustic casters
  // (smooth metal and glass, core/caustic_casters.h) where there are any in view. How next-event
  // estimation chooses a light is the scene's (its Emitters were built for one light sampler).
  PathIntegrator(int max_depth, int rr_start_depth, int max_diffuse_depth = -1, float clamp_indirect = 0,
                 float caster_share = 0)
      : max_depth_(max_depth),
        rr_start_depth_(rr_start_depth),
        max_diffuse_depth_(max_diffuse_depth),
        clamp_indirect_(clamp_indirect),
        caster_share_(caster_share) {}

  RadianceSample li(const Scene& scene, const Ray& camera_ray, Sampler& sampler, RayCounters& counters,
                    AovSample* aov = nullptr) const override;
  // Traces the lanes' paths in lockstep, bounce by bounce: their extension rays and their shadow
  // rays go to Embree as packets. Each lane's result is bit for bit what li gives it.
  void li_packet(const Scene& scene, const Ray* camera_rays, Sampler* const* samplers, int n, RayCounters& counters,
                 AovSample* const* aovs, RadianceSample* out) const override;
  // Whether li_packet does part of the work of Lambertian vertices and of glTF's opaque
  // metallic-roughness mixture (Bsdf::coated_only) in SIMD lanes (lane_vertices): next-event
  // estimation toward untextured triangles and quads, punctual lights and the sky (its direction
  // drawn by the scalar code), and the bounce. On by default; either way the images are the same
  // bits, so off serves tests and measurements.
  void set_lanes(bool on) { lanes_ = on; }
  // Splits every path at its first vertex into `continuations` paths from there on, whose mean is
  // the camera sample's estimate (li_split); 1: no splitting.
  void set_split(int continuations) { split_ = continuations; }

 private:
  struct Path;
  struct ShadowQuery;
  struct Bounce;
  struct Arrival;
  // What li_split hands each continuation of its camera samples: what the camera rays found, the
  // draws of the first vertex's light sample, and its weight (split_ in the continuation that
  // takes the sample, 0 in the others).
  struct CameraHits {
    SurfaceHit hits[kPathsInLockstep];
    bool found[kPathsInLockstep];
    VertexSamples light_draws[kPathsInLockstep];
    float light_weight = 1;
  };

  // Whether a path scatters at the surface its ray finds (or only gathers its emission there).
  bool scatters_next(const Path& path) const;
  // One bounce of a path where its ray arrived (a surface or the sky): gathers emission, queues
  // the next-event estimation's shadow ray in `shadow`, samples the next direction. False when
  // the path ends here.
  // What advance leaves a path to: it ends, it goes on, or it waits for lane_vertices to draw its
  // bounce (li_packet then finishes it with scatter).
  enum class Step { kEnds, kGoesOn, kInLanes };
  // lanes: where a Lambertian or coated vertex takes a lane of it (the last one added), from which its
  // next-event estimation (ShadowQuery::queued) and its bounce (Step::kInLanes) may be asked
  // instead of direct_light and Bsdf::sample; null: neither. kAimsAtCasters: casters may take a
  // share of the bounces (caster_share_ > 0 and the scene has some); without them, the code that
  // weighs the lanes' work against that share is left out.
  template <bool kAimsAtCasters>
  Step advance(const Scene& scene, Path& path, const Arrival& at, ShadowQuery& shadow, RayCounters& counters,
               LaneVertexBatch* lanes = nullptr) const;
  // li_packet for at most kPathsInLockstep paths; camera_hits: what the camera rays find, where
  // known already (null: traced here, and counted).
  template <bool kAimsAtCasters>
  void li_lockstep(const Scene& scene, const Ray* camera_rays, Sampler* const* samplers, int n,
                   RayCounters& counters, AovSample* const* aovs, RadianceSample* out,
                   const CameraHits* camera_hits) const;
  // li_lockstep for the scene: with or without the work for caustic casters.
  void lockstep(const Scene& scene, const Ray* camera_rays, Sampler* const* samplers, int n, RayCounters& counters,
                AovSample* const* aovs, RadianceSample* out, const CameraHits* camera_hits) const;
  // li_packet for at most kPathsInLockstep camera rays, each path split at its first vertex.
  void li_split(const Scene& scene, const Ray* camera_rays, Sampler* const* samplers, int n, RayCounters& counters,
                AovSample* const* aovs, RadianceSample* out) const;
  // The rest of a bounce once its direction is drawn (bs): the throughput, the path's record of the
  // vertex, the next ray (from `origin` where lane_vertices offset it already) and Russian roulette.
  // False when the path ends.
  bool scatter(Path& path, const SurfaceHit& hit, const BsdfSample& bs, const MaterialDesc& material, bool from_front,
               float u_roulette, RayCounters& counters, const Vec3* origin = nullptr) const;
  // Next-event estimation in lane `lane` of `lanes` (lane_vertices) at a vertex with a Lambertian
  // lobe, where the vertex and its light draw allow it: asks the lane for it (true, shadow.queued)
  // or finds there is no light to sample (true); false: direct_light's case.
  template <bool kAimsAtCasters>
  bool queue_direct_light(const Scene& scene, const SurfaceHit& hit, const Bounce& bounce, const Path& path,
                          const MaterialDesc& material, const VertexSamples& u, const Arrival& at, ShadowQuery& shadow,
                          LaneVertexBatch& lanes, int lane) const;
  // Light from one sampled light through the BSDF, before its visibility is known: the shadow ray
  // to test and what it adds when unoccluded (the medium's attenuation and MIS weight included).
  // sky, light, portal_view: the light sample's sky direction, the light and the sky's portals seen
  // from the hit, when the caller made them (Emitters::sample, Emitters::pick_many, portal_views).
  ShadowQuery direct_light(const Scene& scene, const SurfaceHit& hit, const Bsdf& bsdf, const Bounce& bounce,
                           const MediumStack& media, const MaterialDesc& material, bool from_front,
                           const VertexSamples& u, const EnvironmentLight::Sample* sky,
                           const std::optional<Emitters::Pick>* light,
                           const EnvironmentPortals::View* portal_view) const;
  // How the vertex at `hit` draws its next direction: from the BSDF alone, or also aimed at casters.
  // Fills `out` in place (a view of the casters is a few hundred bytes, made at every vertex).
  void choose_bounce(const Scene& scene, const SurfaceHit& hit, const Bsdf& bsdf, Bounce& out) const;
  // choose_bounce's aim at the casters in view from p, for a BSDF of normal n that reflects only
  // and is not a delta lobe.
  void aim_bounce(const Scene& scene, const Vec3& p, const Vec3& n, Bounce& out) const;
  RadianceSample finish(Path& path) const;
  // Sends the path on from `hit` along wi, after a bounce or a straight crossing of a thin sheet.
  // origin: the ray's, where the caller offset it already.
  static void leave_surface(Path& path, const SurfaceHit& hit, const Vec3& wi, const Vec3* origin = nullptr);
  // Russian roulette after the path's bounce number `depth` (none before rr_start_depth), with draw u;
  // false when the path ends, else the survivor's throughput is reweighted.
  bool survives_roulette(Path& path, int depth, float u) const;

  int max_depth_;
  int rr_start_depth_;
  int max_diffuse_depth_;
  float clamp_indirect_;
  float caster_share_;
  bool lanes_ = true;
  int split_ = 1;
};

}  // namespace prism
