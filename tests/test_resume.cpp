// Stopping and resuming: a render split into passes, stopped at any sample, saved with its film
// state and continued reaches the bits of one uninterrupted render.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <functional>

#include "aov_scene.h"
#include "core/renderer.h"
#include "core/scene.h"
#include "gltf_writer.h"
#include "integrators/path_integrator.h"
#include "io/exr_reader.h"
#include "io/exr_writer.h"
#include "io/film_state.h"
#include "io/render_layers.h"

namespace prism {
namespace {

constexpr int kSize = 24;

RenderSettings resume_settings() {
  RenderSettings s;
  s.width = s.height = kSize;
  s.spp = 12;
  s.seed = 11;
  s.aovs = parse_aovs("all");
  return s;
}

Film empty_film(const Scene& scene, const RenderSettings& s) {
  Film film(s.width, s.height, s.aovs);
  film.set_cryptomatte_ids(object_cryptomatte_ids(scene.desc()), material_cryptomatte_ids(scene.desc()));
  return film;
}

// The path tracer, asking the render to stop once it has begun `limit` samples: a stop in the
// middle of a pass that always happens, wherever the threads then are.
class StopAfter : public Integrator {
 public:
  StopAfter(uint64_t limit, RenderProgress& progress) : limit_(limit), progress_(progress) {}
  RadianceSample li(const Scene& scene, const Ray& ray, Sampler& sampler, RayCounters& counters,
                    AovSample* aov) const override {
    if (begun_.fetch_add(1) + 1 == limit_) progress_.stop = true;
    return path_.li(scene, ray, sampler, counters, aov);
  }

 private:
  PathIntegrator path_{8, 3};
  uint64_t limit_;
  RenderProgress& progress_;
  mutable std::atomic<uint64_t> begun_{0};
};

RenderStats render_into(const Scene& scene, const RenderSettings& s, Film& film, RenderProgress* progress = nullptr,
                        const PassObserver& after_pass = {}, const Integrator* integrator = nullptr) {
  const PathIntegrator path(8, 3);
  return render(scene, Camera(test::top_camera(), s.width, s.height), integrator ? *integrator : path, s, film, progress,
                after_pass);
}

PixelIdCounts sorted(PixelIdCounts c) {
  std::sort(c.begin(), c.end(), [](const IdCount& a, const IdCount& b) { return a.id < b.id; });
  return c;
}

// Every accumulator of the two films is the same, bit for bit.
void expect_same_film(const Film& a, const Film& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Film::Pixel &p = a.pixel(x, y), &q = b.pixel(x, y);
      ASSERT_EQ(p.count, q.count) << x << "," << y;
      for (int c = 0; c < 4; ++c) ASSERT_EQ(p.sum[c], q.sum[c]) << x << "," << y;
      for (int c = 0; c < 3; ++c) ASSERT_EQ(p.sum_sq[c], q.sum_sq[c]) << x << "," << y;
      for (int k = 0; k < a.average_slots(); ++k) ASSERT_EQ(a.average_sums(x, y)[k], b.average_sums(x, y)[k]);
      ASSERT_EQ(a.tracks_halves(), b.tracks_halves());
      if (a.tracks_halves()) {
        const Film::Halves &h = a.halves(x, y), &g = b.halves(x, y);
        ASSERT_TRUE(h.lower == g.lower && h.upper == g.upper && h.lower_count == g.lower_count &&
                    h.upper_count == g.upper_count)
            << x << "," << y;
      }
      ASSERT_EQ(a.nearest_depth(x, y), b.nearest_depth(x, y));
      ASSERT_EQ(a.nearest_object(x, y), b.nearest_object(x, y));
      ASSERT_EQ(a.nearest_material(x, y), b.nearest_material(x, y));
      const size_t i = size_t(y) * a.width() + x;
      const PixelIdCounts oa = sorted(a.crypto_objects()[i]), ob = sorted(b.crypto_objects()[i]);
      ASSERT_EQ(oa.size(), ob.size());
      for (size_t k = 0; k < oa.size(); ++k) ASSERT_TRUE(oa[k].id == ob[k].id && oa[k].count == ob[k].count);
      const PixelIdCounts ma = sorted(a.crypto_materials()[i]), mb = sorted(b.crypto_materials()[i]);
      ASSERT_EQ(ma.size(), mb.size());
      for (size_t k = 0; k < ma.size(); ++k) ASSERT_TRUE(ma[k].id == mb[k].id && ma[k].count == mb[k].count);
    }
}

// Saves the film with its state to an EXR, reads it back as a resumed render would.
Film through_exr(const Scene& scene, const Film& film, const std::string& path) {
  ExrImage image;
  image.display = image.data = {0, 0, film.width(), film.height()};
  image.attributes.push_back({"prism/aovs", std::string("all")});
  add_render_layers(film, &scene.desc(), LayerOptions{}, image);
  add_film_state(film, image);
  write_exr(path, image);
  Film back = film_from_image(read_exr(path), path);
  back.set_cryptomatte_ids(object_cryptomatte_ids(scene.desc()), material_cryptomatte_ids(scene.desc()));
  return back;
}

// Renders `s` whole, which must take at least `min_passes` passes and leave pixels with different
// counts, and again stopped once `stop_after` passes have run, saved into a temporary folder named
// `name`, read back (`check_read_back` sees that film) and continued: the two films must be the
// same, bit for bit.
void expect_continued_between_passes_to_same_bits(const RenderSettings& s, int min_passes, int stop_after,
                                                  const std::string& name,
                                                  const std::function<void(const Film&)>& check_read_back = {}) {
  const Scene scene(test::aov_scene());
  Film whole = empty_film(scene, s);
  const RenderStats one = render_into(scene, s, whole);
  ASSERT_GE(one.passes, min_passes);
  ASSERT_GT(one.spp_max, one.spp_min);

  RenderProgress between;
  Film stopped = empty_film(scene, s);
  int done = 0;
  const RenderStats stats = render_into(scene, s, stopped, &between, [&](const Film&, const RenderStats&) {
    if (++done == stop_after) between.stop = true;
  });
  ASSERT_TRUE(stats.stopped);
  Film resumed = through_exr(scene, stopped, test::make_temp_dir(name) + "/between.exr");
  if (check_read_back) check_read_back(resumed);
  if (::testing::Test::HasFatalFailure()) return;
  render_into(scene, s, resumed);
  expect_same_film(resumed, whole);
}

TEST(Resume, PassesOfAnyLengthGiveTheBitsOfOnePass) {
  const Scene scene(test::aov_scene());
  RenderSettings s = resume_settings();
  Film whole = empty_film(scene, s);
  EXPECT_EQ(render_into(scene, s, whole).passes, 1);
  // A pass length far below one sample's cost: one sample per pixel per pass.
  s.pass_seconds = 1e-12;
  Film passes = empty_film(scene, s);
  int observed = 0;
  const RenderStats stats = render_into(scene, s, passes, nullptr, [&](const Film& f, const RenderStats& so_far) {
    ++observed;
    EXPECT_EQ(so_far.spp_min, uint64_t(observed));  // the film as the pass left it
    EXPECT_EQ(f.sample_count(0, 0), uint64_t(observed));
  });
  EXPECT_EQ(stats.passes, s.spp);
  EXPECT_EQ(observed, s.spp - 1);
  expect_same_film(passes, whole);
}

// Stopped between passes and in the middle of one, saved, read back and continued: the same film
// as one render.
TEST(Resume, AStoppedRenderContinuesToTheSameBits) {
  const Scene scene(test::aov_scene());
  RenderSettings s = resume_settings();
  Film whole = empty_film(scene, s);
  render_into(scene, s, whole);
  const std::string dir = test::make_temp_dir("resume");

  s.pass_seconds = 1e-12;
  RenderProgress between;
  Film stopped = empty_film(scene, s);
  RenderStats stats = render_into(scene, s, stopped, &between, [&](const Film&, const RenderStats& so_far) {
    if (so_far.spp_min == 3) between.stop = true;
  });
  EXPECT_TRUE(stats.stopped);
  EXPECT_EQ(stats.spp_max, 3u);  // the pass planned when the stop came took no sample
  Film resumed = through_exr(scene, stopped, dir + "/between.exr");
  stats = render_into(scene, s, resumed);
  EXPECT_FALSE(stats.stopped);
  expect_same_film(resumed, whole);

  s.pass_seconds = 0;
  RenderProgress midway;
  const StopAfter stop_after(uint64_t(kSize) * kSize * 5, midway);
  Film partial = empty_film(scene, s);
  stats = render_into(scene, s, partial, &midway, {}, &stop_after);
  ASSERT_TRUE(stats.stopped);
  EXPECT_LT(stats.spp_min, uint64_t(s.spp));  // pixels not reached yet
  EXPECT_GE(stats.spp_max, uint64_t(s.spp));  // pixels finished before the stop
  Film continued = through_exr(scene, partial, dir + "/midway.exr");
  render_into(scene, s, continued);
  expect_same_film(continued, whole);
}

// Samples shared by error are planned pass by pass from the film: a render stopped between two
// passes (where checkpoints are written), saved and continued plans the same passes and ends with
// the bits of one render.
TEST(Resume, ErrorAllocationStoppedBetweenPassesContinuesToTheSameBits) {
  RenderSettings s = resume_settings();
  s.allocation = "error";
  s.min_spp = 4;
  s.spp = 16;
  expect_continued_between_passes_to_same_bits(s, 3, 2, "resume-allocation");
}

// Under a noise target with Sobol each pass is planned from the film's halves as well as its sums:
// they travel in the film state, so a render stopped between passes and continued plans the same
// passes and ends with the bits of one render (without them the resumed render judged its pixels
// as if their samples were independent, and took more).
TEST(Resume, NoiseTargetStoppedBetweenPassesContinuesToTheSameBits) {
  RenderSettings s = resume_settings();
  s.sampler = "sobol";
  s.noise_target = 0.05;
  s.spp = 1024;
  expect_continued_between_passes_to_same_bits(s, 4, 3, "resume-noise",
                                               [](const Film& f) { ASSERT_TRUE(f.tracks_halves()); });
}

// A noise target shared by error: each pass is planned from the film's sums, counts and halves.
TEST(Resume, NoiseTargetSharedByErrorStoppedBetweenPassesContinuesToTheSameBits) {
  RenderSettings s = resume_settings();
  s.sampler = "sobol";
  s.allocation = "error";
  s.noise_target = 0.01;
  s.spp = 1024;
  expect_continued_between_passes_to_same_bits(s, 4, 3, "resume-noise-allocation");
}

}  // namespace
}  // namespace prism
