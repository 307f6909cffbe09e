// prism bench's figures: the text a child passes its parent, medians over repetitions, CSV rows.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "io/bench_runs.h"

namespace prism {
namespace {

BenchRun run_of(double render_seconds, uint64_t samples) {
  BenchRun r;
  r.triangles = 32;
  r.bvh_seconds = 0.001;
  r.render_seconds = render_seconds;
  r.samples = samples;
  r.camera_rays = samples;
  r.extension_rays = 2 * samples;
  r.shadow_rays = 3 * samples;
  return r;
}

TEST(BenchRuns, TextRoundTripsExactly) {
  BenchRun r = run_of(0.1 + 0.2, 123456789012345ull);  // a double with no short decimal form
  r.bvh_seconds = 1.0 / 3.0;
  r.peak_mb = 28.7109375;
  r.rel_mse = 1.316e-3;
  const std::optional<BenchRun> back = bench_run_from_text(to_text(r));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->triangles, r.triangles);
  EXPECT_EQ(back->bvh_seconds, r.bvh_seconds);
  EXPECT_EQ(back->render_seconds, r.render_seconds);
  EXPECT_EQ(back->samples, r.samples);
  EXPECT_EQ(back->camera_rays, r.camera_rays);
  EXPECT_EQ(back->extension_rays, r.extension_rays);
  EXPECT_EQ(back->shadow_rays, r.shadow_rays);
  EXPECT_EQ(back->peak_mb, r.peak_mb);
  EXPECT_EQ(back->rel_mse, r.rel_mse);
  // Without a reference the error stays unmeasured on the other side too.
  const std::optional<BenchRun> unmeasured = bench_run_from_text(to_text(run_of(1.0, 100)));
  ASSERT_TRUE(unmeasured);
  EXPECT_FALSE(unmeasured->has_error());
}

TEST(BenchRuns, OtherTextIsRejected) {
  const std::string good = to_text(run_of(1.0, 100));
  EXPECT_FALSE(bench_run_from_text(""));
  EXPECT_FALSE(bench_run_from_text("prism: error: scene.gltf: cannot open"));
  EXPECT_FALSE(bench_run_from_text(good.substr(0, good.size() - 2)  + " x"));
  EXPECT_FALSE(bench_run_from_text(good + " 7"));
  EXPECT_TRUE(bench_run_from_text(good));
}

TEST(BenchRuns, MedianOfOddAndEvenCounts) {
  EXPECT_EQ(median({3.0}), 3.0);
  EXPECT_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 100.0}), 3.5);
  EXPECT_THROW(median({}), std::invalid_argument);
}

TEST(BenchRuns, SummaryTakesEachFiguresMedianAndTheRange) {
  // Rates are medians of each run's rate, not the rate of the median time: with one slow run
  // among three they agree; the slow run moves neither.
  std::vector<BenchRun> runs = {run_of(2.0, 2'000'000), run_of(9.0, 2'000'000), run_of(1.0, 2'000'000)};
  runs[0].peak_mb = 40;
  runs[1].peak_mb = 42;
  runs[2].peak_mb = 41;
  const BenchSummary s = summarize(runs);
  EXPECT_EQ(s.runs, 3);
  EXPECT_EQ(s.render_seconds, 2.0);
  EXPECT_EQ(s.render_seconds_min, 1.0);
  EXPECT_EQ(s.render_seconds_max, 9.0);
  EXPECT_DOUBLE_EQ(s.mpaths, 1.0);  // 2M paths in 2 s
  EXPECT_DOUBLE_EQ(s.mrays, 6.0);
  EXPECT_DOUBLE_EQ(s.camera_mrays, 1.0);
  EXPECT_DOUBLE_EQ(s.extension_mrays, 2.0);
  EXPECT_DOUBLE_EQ(s.shadow_mrays, 3.0);
  EXPECT_EQ(s.peak_mb, 42);
  EXPECT_FALSE(s.rel_mse >= 0);  // no run measured its error
  EXPECT_THROW(summarize({}), std::invalid_argument);
}

TEST(BenchRuns, EfficiencyIsOneOverErrorTimesSeconds) {
  BenchRun r = run_of(4.0, 1000);
  EXPECT_EQ(r.efficiency(), 0.0);  // unmeasured
  r.rel_mse = 0.5;
  EXPECT_DOUBLE_EQ(r.efficiency(), 0.5);
  r.rel_mse = 0;
  EXPECT_TRUE(std::isinf(r.efficiency()));  // the reference itself
  // The summary's efficiency is the median of the runs' (the same image, three times).
  std::vector<BenchRun> runs = {run_of(1.0, 10), run_of(2.0, 10), run_of(8.0, 10)};
  for (BenchRun& x : runs) x.rel_mse = 0.25;
  const BenchSummary s = summarize(runs);
  EXPECT_EQ(s.rel_mse, 0.25);
  EXPECT_DOUBLE_EQ(s.efficiency, 2.0);
  // One run without an error figure leaves the summary without one.
  runs[1].rel_mse = -1;
  EXPECT_FALSE(summarize(runs).rel_mse >= 0);
}

TEST(BenchRuns, CsvRowsQuoteWhatNeedsIt) {
  const BenchSettingsText settings{16, "512x512", "sobol", 8, 2, 3};
  const std::string header = bench_csv_header();
  const std::string row = bench_csv_row("a,\"b\".gltf", 2, run_of(2.0, 2'000'000), settings);
  BenchRun measured = run_of(2.0, 2'000'000);
  measured.rel_mse = 0.25;
  const std::string measured_row = bench_csv_row("box.gltf", 1, measured, settings);
  EXPECT_EQ(row.rfind("\"a,\"\"b\"\".gltf\",2,16,512x512,8,sobol,2,3,32,", 0), 0u) << row;
  // As many fields as the header names, once the quoted one counts as one.
  auto fields = [](const std::string& line) {
    int n = 1;
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted) ++n;
    }
    return n;
  };
  EXPECT_EQ(fields(row), fields(header));
  EXPECT_EQ(fields(measured_row), fields(header));
  EXPECT_NE(measured_row.find(",0.25,2\n"), std::string::npos) << measured_row;  // relmse, efficiency
  EXPECT_NE(row.find(",,\n"), std::string::npos) << row;  // both empty
  EXPECT_EQ(row.back(), '\n');
}

}  // namespace
}  // namespace prism
