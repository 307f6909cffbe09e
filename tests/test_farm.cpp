// prism farm's pieces: splitting work, Slurm's scripts and reports, the plan file, running programs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "core/work_split.h"
#include "io/errors.h"
#include "io/farm_plan.h"
#include "io/slurm.h"
#include "io/subprocess.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

TEST(WorkSplit, SampleRangesAreConsecutiveAndCoverEverySampleOnce) {
  for (uint64_t spp : {1u, 7u, 64u, 1000u, 4097u})
    for (int parts : {1, 2, 3, 4, 7, 16}) {
      if (uint64_t(parts) > spp) {
        EXPECT_TRUE(split_samples(spp, parts).empty());
        continue;
      }
      const std::vector<SampleRange> r = split_samples(spp, parts);
      ASSERT_EQ(r.size(), size_t(parts));
      uint64_t next = 0, smallest = spp, largest = 0;
      for (const SampleRange& s : r) {
        EXPECT_EQ(s.first, next);
        EXPECT_GE(s.count, 1u);
        next = s.first + s.count;
        smallest = std::min(smallest, s.count);
        largest = std::max(largest, s.count);
      }
      EXPECT_EQ(next, spp);
      EXPECT_LE(largest - smallest, 1u) << spp << " spp in " << parts;
    }
  EXPECT_TRUE(split_samples(16, 0).empty());
}

TEST(WorkSplit, TilesPartitionTheImageIntoNearlySquareTiles) {
  struct Case {
    int width, height, parts, columns, rows;
  };
  for (const Case& c : {Case{96, 72, 4, 2, 2}, Case{512, 512, 16, 4, 4}, Case{1920, 1080, 8, 4, 2},
                        Case{1920, 1080, 7, 7, 1}, Case{100, 1000, 5, 1, 5}, Case{3, 3, 9, 3, 3}, Case{64, 48, 1, 1, 1}}) {
    const std::vector<PixelWindow> tiles = split_tiles(c.width, c.height, c.parts);
    ASSERT_EQ(tiles.size(), size_t(c.parts)) << c.width << "x" << c.height << " in " << c.parts;
    std::vector<int> covered(size_t(c.width) * size_t(c.height), 0);
    std::set<int> x0s, y0s;
    for (const PixelWindow& t : tiles) {
      EXPECT_FALSE(t.empty());
      EXPECT_TRUE((PixelWindow{0, 0, c.width, c.height}).contains(t));
      x0s.insert(t.x0);
      y0s.insert(t.y0);
      for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) ++covered[size_t(y) * size_t(c.width) + size_t(x)];
    }
    for (int n : covered) ASSERT_EQ(n, 1) << "every pixel in exactly one tile";
    EXPECT_EQ(x0s.size(), size_t(c.columns));
    EXPECT_EQ(y0s.size(), size_t(c.rows));
  }
  EXPECT_TRUE(split_tiles(3, 3, 7).empty()) << "no 7-tile grid fits 3x3";
  EXPECT_TRUE(split_tiles(4, 4, 17).empty());
}

TEST(WorkSplit, FramesFormConsecutiveGroups) {
  const auto groups = split_frames(10, 4);
  ASSERT_EQ(groups.size(), 4u);
  size_t next = 0;
  for (const auto& g : groups) {
    EXPECT_TRUE(g.size() == 2 || g.size() == 3);
    for (size_t i : g) EXPECT_EQ(i, next++);
  }
  EXPECT_EQ(next, 10u);
  EXPECT_TRUE(split_frames(3, 4).empty());
}

TEST(Slurm, ParsesScontrolRecordsOfAnArrayAndItsPendingRange) {
  const std::string text =
      "JobId=13 ArrayJobId=12 ArrayTaskId=0 JobName=prism-job UserId=root(0) JobState=COMPLETED Reason=None "
      "Dependency=(null) ExitCode=0:0 RunTime=00:00:01\n"
      "JobId=14 ArrayJobId=12 ArrayTaskId=2 JobState=FAILED Reason=NonZeroExitCode ExitCode=4:0\n"
      "JobId=12 ArrayJobId=12 ArrayTaskId=3-5%2 JobState=PENDING Reason=JobArrayTaskLimit ExitCode=0:0\n"
      "JobId=20 JobName=prism-job-merge JobState=CANCELLED Reason=DependencyNeverSatisfied Dependency=afterok:12_*(failed) "
      "ExitCode=0:0\n"
      "not a record\n";
  const std::vector<SlurmJob> jobs = parse_scontrol_jobs(text);
  ASSERT_EQ(jobs.size(), 6u);
  EXPECT_EQ(jobs[0].job_id, "12");
  EXPECT_EQ(*jobs[0].array_task, 0);
  EXPECT_EQ(jobs[0].state, "COMPLETED");
  EXPECT_EQ(*jobs[1].array_task, 2);
  EXPECT_EQ(jobs[1].state, "FAILED");
  EXPECT_EQ(jobs[1].exit_code, "4:0");
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(*jobs[size_t(2 + i)].array_task, 3 + i);
    EXPECT_EQ(jobs[size_t(2 + i)].state, "PENDING");
  }
  EXPECT_EQ(jobs[5].job_id, "20");
  EXPECT_FALSE(jobs[5].array_task);
  EXPECT_EQ(jobs[5].reason, "DependencyNeverSatisfied");
}

TEST(Slurm, JobIdsArraySpecsAndQuoting) {
  EXPECT_EQ(*parse_sbatch_job_id("42\n"), "42");
  EXPECT_EQ(*parse_sbatch_job_id("42;cluster\n"), "42");
  EXPECT_FALSE(parse_sbatch_job_id("sbatch: error: Batch job submission failed\n"));
  EXPECT_FALSE(parse_sbatch_job_id(""));
  EXPECT_EQ(array_spec({0, 1, 2, 3}), "0-3");
  EXPECT_EQ(array_spec({1, 4, 5, 6, 9}), "1,4-6,9");
  EXPECT_EQ(array_spec({2}), "2");
  EXPECT_EQ(shell_quote("/plain/path-1.exr"), "/plain/path-1.exr");
  EXPECT_EQ(shell_quote("with space"), "'with space'");
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
  EXPECT_EQ(shell_quote(""), "''");
}

TEST(Slurm, BatchScriptQuotesArgumentsAndRefusesLineBreaks) {
  SbatchScript s;
  s.job_name = "prism-box";
  s.output = "/plans/box farm/logs/task-%A_%a.log";
  s.directory = "/plans/box farm";
  s.options = {"--cpus-per-task=8", "--mem=16G"};
  s.command = {"/opt/prism/bin/prism", "farm", "task", "/plans/box farm", "$SLURM_ARRAY_TASK_ID"};
  const std::string text = sbatch_script_text(s);
  EXPECT_EQ(text,
            "#!/bin/sh\n"
            "#SBATCH --job-name=prism-box\n"
            "#SBATCH --output=/plans/box farm/logs/task-%A_%a.log\n"
            "#SBATCH --chdir=/plans/box farm\n"
            "#SBATCH --cpus-per-task=8\n"
            "#SBATCH --mem=16G\n"
            "exec /opt/prism/bin/prism farm task '/plans/box farm' $SLURM_ARRAY_TASK_ID\n");
  s.options = {"--mem=1G\nrm -rf /"};
  EXPECT_THROW(sbatch_script_text(s), std::invalid_argument);
}

class FarmPlanFile : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("prism_farm_plan_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  FarmPlan sample_plan() const {
    FarmPlan p;
    p.directory = dir_.string();
    p.source = "/jobs/box.json";
    p.by = FarmSplit::Tiles;
    p.prism = "/opt/prism/bin/prism";
    p.slurm.cpus_per_task = 4;
    p.slurm.memory = "8G";
    p.slurm.options = {"--account=vfx"};
    FarmOutput& o = p.outputs.emplace_back();
    o.where = "$";
    o.output = "/out/box.exr";
    o.preview = "/out/box.png";
    for (int k = 0; k < 2; ++k) {
      o.parts.push_back(dir_.string() + "/parts/part00" + std::to_string(k) + ".exr");
      p.tasks.push_back(FarmTask{{FarmSlice{0, o.parts.back(), PixelWindow{k * 32, 0, k * 32 + 32, 48}, std::nullopt}}});
    }
    p.tasks.push_back(FarmTask{{FarmSlice{0, "/out/x.exr", std::nullopt, SampleRange{16, 48}}}});
    return p;
  }
  void write(const std::string& text) const { std::ofstream(dir_ / "plan.json") << text; }

  fs::path dir_;
};

TEST_F(FarmPlanFile, RoundTripsAndKeepsItsId) {
  const FarmPlan p = sample_plan();
  write(farm_plan_json(p));
  const FarmPlan q = read_farm_plan(dir_.string());
  EXPECT_EQ(q.id(), p.id());
  EXPECT_EQ(farm_plan_json(q), farm_plan_json(p));
  ASSERT_EQ(q.tasks.size(), 3u);
  EXPECT_EQ(*q.tasks[1].slices[0].crop, (PixelWindow{32, 0, 64, 48}));
  EXPECT_EQ(*q.tasks[2].slices[0].samples, (SampleRange{16, 48}));
  EXPECT_EQ(*q.slurm.memory, "8G");
  EXPECT_EQ(*q.outputs[0].preview, "/out/box.png");
  EXPECT_EQ(q.task_log("12", 3), dir_.string() + "/logs/task-12_3.log");
  // The id digests what the tasks render: another split is another plan.
  FarmPlan r = p;
  r.tasks[0].slices[0].crop->x1 = 31;
  EXPECT_NE(r.id(), p.id());
}

TEST_F(FarmPlanFile, RefusesAnEditedOrDamagedPlanNamingTheElement) {
  std::string text = farm_plan_json(sample_plan());
  text.replace(text.find("\"/out/box.exr\""), 14, "\"/out/bax.exr\"");
  write(text);
  try {
    read_farm_plan(dir_.string());
    FAIL() << "an edited plan was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("$.id"), std::string::npos) << e.what();
  }
  write(R"({"version": 1, "source": "/j.json", "source_digest": "0", "batch": false, "by": "slices"})");
  try {
    read_farm_plan(dir_.string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("$.by"), std::string::npos) << e.what();
  }
  fs::remove(dir_ / "plan.json");
  EXPECT_THROW(read_farm_plan(dir_.string()), InputError);
}

TEST_F(FarmPlanFile, RecordsSubmissionsInOrder) {
  const FarmPlan p = sample_plan();
  EXPECT_TRUE(read_farm_submissions(p).empty());
  record_farm_submission(p, {"12", {0, 1, 2}, "13"});
  record_farm_submission(p, {"", {}, "20"});
  const std::vector<FarmSubmission> s = read_farm_submissions(p);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].array_job, "12");
  EXPECT_EQ(s[0].tasks, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(s[1].array_job, "");
  EXPECT_EQ(s[1].merge_job, "20");
}

TEST(Subprocess, CapturesBothStreamsAndTheExitStatus) {
  const std::optional<CommandResult> r = run_command({"sh", "-c", "echo out; echo err >&2; exit 3"});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->exit_code, 3);
  EXPECT_EQ(r->out, "out\n");
  EXPECT_EQ(r->err, "err\n");
  EXPECT_EQ(r->message(), "err");  // stderr, without its newline
  const std::optional<CommandResult> quiet = run_command({"sh", "-c", "echo only-out; exit 1"});
  ASSERT_TRUE(quiet);
  EXPECT_EQ(quiet->message(), "only-out");  // stdout when stderr is empty
  // More than a pipe holds on both streams at once must not block.
  const std::optional<CommandResult> big =
      run_command({"sh", "-c", "head -c 200000 /dev/zero; head -c 200000 /dev/zero >&2"});
  ASSERT_TRUE(big);
  EXPECT_EQ(big->out.size(), 200000u);
  EXPECT_EQ(big->err.size(), 200000u);
  EXPECT_FALSE(run_command({"prism-no-such-program-here"}));
  EXPECT_FALSE(program_on_path("prism-no-such-program-here"));
  EXPECT_TRUE(program_on_path("sh"));
}

}  // namespace
}  // namespace prism
