// prism command line: parses arguments and dispatches to the commands.
#include <CLI/CLI.hpp>

#include <csignal>

#include "apps/batch_command.h"
#include "apps/bench_command.h"
#include "apps/compare_command.h"
#include "apps/converge_command.h"
#include "apps/exit_codes.h"
#include "apps/farm_command.h"
#include "apps/merge_command.h"
#include "apps/render_command.h"
#include "core/memory_limit.h"

int main(int argc, char** argv) {
  using namespace prism;
  // Past a file-size limit (ulimit -f) a write then fails with EFBIG, which the writers report
  // and clean up after, instead of SIGXFSZ killing prism and leaving its temporary file behind.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"prism " PRISM_VERSION ": a production-style CPU path tracer. glTF 2.0 scenes in, OpenEXR images out."};
  app.set_version_flag("--version", "prism " PRISM_VERSION);
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success, 1 internal error, 2 usage error, 3 bad input (scene, job file, image),\n"
      "4 output not writable, 5 compare: the image misses --threshold, 6 render stopped by SIGINT/SIGTERM (its\n"
      "output holds the samples so far; continue it with --resume), 7 the work would exceed --memory-limit,\n"
      "8 farm: Slurm refused a job, or a task or the merge failed, 9 farm status: not finished yet.\n"
      "Run 'prism COMMAND --help' for the options of a command.");

  std::string memory_limit;
  app.add_option("--memory-limit", memory_limit,
                 "Refuse scenes, textures and images whose estimated memory exceeds this (8G, 512M, bytes), with the "
                 "estimate, before allocating; default: the memory available when prism starts. Any command accepts it")
      ->check([](const std::string& text) {
        return parse_byte_size(text) ? std::string() : "expected a size such as 8G, 512M or a byte count, got '" + text + "'";
      });
  app.fallthrough();

  RenderOptions render;
  CLI::App* cmd = app.add_subcommand("render", "Render a scene to an OpenEXR image (R,G,B,A and the AOVs asked for).");
  cmd->add_option("SCENE", render.scene,
                  "Scene to render: a glTF 2.0 file (.gltf or .glb), or a job file (.json) naming one with settings")
      ->required();
  cmd->add_option("-o,--output", render.output,
                  "Output EXR path (default: the job's \"output\", else SCENE's name with .exr in the current folder)");
  cmd->add_option("--spp", render.settings.spp,
                  "Samples per pixel (default 64, or the job's \"spp\"); with --time or --noise, the most any pixel "
                  "gets (default: no limit with --time, 4096 with --noise)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--time", render.time,
                  "Wall-clock budget for rendering (after loading), e.g. 30s, 2m, 1h30m: progressive passes "
                  "until it is spent; the image is complete after the first pass");
  cmd->add_option("--noise", render.settings.noise_target,
                  "Noise target: adaptive sampling stops each pixel when the relative standard error of its "
                  "luminance is below this (e.g. 0.01); with --allocation error, passes go on until the whole "
                  "image's RMS of it is below this")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--min-spp", render.settings.min_spp,
                  "Samples every pixel gets before --noise judges it (default 16)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--sampler", render.settings.sampler,
                  "Sampler: sobol (default; Owen-scrambled Sobol, lower error) or independent (uniform random)");
  cmd->add_option("--allocation", render.settings.allocation,
                  "How samples are shared among pixels: uniform (default; each pixel the same) or error (after "
                  "--min-spp each, in proportion to each pixel's estimated share of the image's relative MSE, as "
                  "judged from its neighbours; --spp is then the mean; with --time the passes are shared the same "
                  "way; with --noise, by the share of the relative error it bounds, until the whole image's estimated "
                  "error is under the target, no pixel stopped by its own samples (so rare light is barely "
                  "darkened), and --spp is each pixel's ceiling)");
  cmd->add_option("--light-sampler", render.settings.light_sampler,
                  "How next-event estimation picks a light: tree (default; by each light's importance at the shading "
                  "point, from a light tree) or power (in proportion to emitted power, the same everywhere)");
  cmd->add_option("--texture-filter", render.settings.texture_filter,
                  "How textures are read: bilinear (default; the full-size image at every lookup) or trilinear (from "
                  "MIP levels chosen by each lookup's footprint, its pixel's ray cone: less texture noise where a "
                  "pixel spans many texels, e.g. at low spp, for slightly softer textures and about 7% more time)");
  cmd->add_option("--res", render.resolution,
                  "Image size WIDTHxHEIGHT, e.g. 1280x720 (default: 512 high, width from the camera's aspect ratio)");
  cmd->add_option("--camera", render.settings.camera,
                  "Camera by name (the camera's or its node's) or by index in node order (default: the first; with no "
                  "cameras, one that frames the scene)");
  cmd->add_option("--max-depth", render.settings.max_depth,
                  "Maximum bounces; 0 renders only emitters seen directly (default 8)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-diffuse-depth", render.settings.max_diffuse_depth,
                  "Maximum diffuse and glossy bounces within --max-depth; 0 = only direct light on them (default: "
                  "no separate limit)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--rr-start-depth", render.settings.rr_start_depth,
                  "Bounce from which Russian roulette may end paths (default 4; unbiased, trades noise for speed)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--split", render.settings.split,
                  "Continuations of each camera sample past its first vertex (path integrator; unbiased): the light "
                  "seen through the first bounce gets that many samples per camera sample (default 1 = none)")
      ->check(CLI::Range(1, kMaxSplit));
  cmd->add_option("--clamp-indirect", render.settings.clamp_indirect,
                  "Clamp each sample's indirect light to this maximum (biased; removes fireflies; default 0 = off)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--caster-share", render.settings.caster_share,
                  "Largest share of bounce directions at diffuse and glossy surfaces aimed at smooth metal and glass objects "
                  "in view, so light focused through them (caustics) is found; unbiased (MIS); 0 = off (default 0.25)")
      ->check(CLI::Range(0.0f, 0.9f));
  cmd->add_option("--seed", render.settings.seed, "Random seed; the same seed gives the same image bits (default 0)");
  cmd->add_option("--threads", render.settings.threads, "Worker threads; 0 = all cores (default 0). The image does not depend on it")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--integrator", render.settings.integrator,
                  "Integrator: path (default; Monte Carlo path tracing) or whitted (classic recursive ray tracing: "
                  "punctual lights, mirrors, glass)");
  cmd->add_option("--env", render.env,
                  "Environment light: an equirectangular map (EXR/HDR linear, PNG/JPEG sRGB; +Y up, the map's centre "
                  "toward -Z), or R,G,B (or one value) for a constant sky, in nits");
  cmd->add_option("--env-intensity", render.env_intensity, "Multiplier for the environment (default 1)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--env-rotation", render.env_rotation,
                  "Rotation of the environment about +Y in degrees, counter-clockwise seen from above (default 0)");
  cmd->add_option("--preview", render.preview, "Also write an 8-bit sRGB PNG preview to this path");
  cmd->add_option("--pixel-type", render.pixel_type,
                  "How the EXR stores R, G, B, A and the light AOVs: half (default; 16-bit, 11 bits of precision, "
                  "values above 65504 clamped to it with a warning) or float (32-bit). Data AOVs are always float")
      ->check(CLI::IsMember({"float", "half"}));
  cmd->add_option("--aovs", render.aovs,
                  "Layers beside the beauty, comma-separated: albedo, normal (N), depth (Z), position (P), emission, "
                  "direct, indirect, variance, spp, object_id, material_id, crypto_object, crypto_material (Cryptomatte), "
                  "or all");
  cmd->add_option("--compression", render.compression, "EXR compression: zip (default), piz, dwaa or none")
      ->check(CLI::IsMember({"zip", "piz", "dwaa", "none"}));
  cmd->add_flag("--multipart", render.multipart, "Write each layer as its own part of a multi-part EXR (default: one part)");
  cmd->add_option("--crop", render.crop,
                  "Render only pixels x0 <= x < x1, y0 <= y < y1; the EXR's data window holds them inside the full "
                  "display window, so crops composite in place")
      ->expected(4);
  cmd->add_option("--sample-range", render.sample_range,
                  "Render sample indices START .. START+COUNT-1 of every pixel (instead of --spp): a slice of a "
                  "render that 'prism merge' combines with the others")
      ->expected(2);
  cmd->add_flag("--stamp", render.stamp,
                "Record the date (capDate) and the render time (prism/renderSeconds) in the header; without it the "
                "same inputs give the same bytes");
  cmd->add_option("--checkpoint", render.checkpoint,
                  "Write the image so far to the output about this often (e.g. 60, 30s, 5m), resumable with --resume; "
                  "the final image is the same")
      ->type_name("SECONDS");
  cmd->add_option("--resume", render.resume,
                  "Continue a stopped or checkpointed render from its EXR (same scene and settings; --spp may be "
                  "raised): the result has the bits of an uninterrupted render");
  cmd->add_option("--progress", render.progress,
                  "Progress report: bar (default; on a terminal), plain ('progress 42.0%' lines on stdout, for farm "
                  "managers) or none");
  cmd->add_flag("--strict", render.strict,
                "Refuse textures that are missing, unreadable or of an unsupported format (default: warn and "
                "render them magenta)");
  cmd->add_flag("-q,--quiet", render.quiet, "Print nothing but errors (no warnings, progress bar or summary)");

  CompareOptions compare;
  CLI::App* compare_cmd = add_compare_command(app, compare);
  ConvergeOptions converge;
  CLI::App* converge_cmd = add_converge_command(app, converge);
  BenchOptions bench;
  CLI::App* bench_cmd = add_bench_command(app, bench);
  MergeOptions merge;
  CLI::App* merge_cmd = add_merge_command(app, merge);
  BatchOptions batch;
  CLI::App* batch_cmd = add_batch_command(app, batch);
  FarmOptions farm;
  CLI::App* farm_cmd = add_farm_command(app, farm);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }
  if (!memory_limit.empty()) set_memory_limit(*parse_byte_size(memory_limit));
  if (cmd->parsed()) return run_render(render);
  if (compare_cmd->parsed()) return run_compare(compare);
  if (converge_cmd->parsed()) return run_converge(converge);
  if (bench_cmd->parsed()) return run_bench(bench);
  if (merge_cmd->parsed()) return run_merge(merge);
  if (batch_cmd->parsed()) return run_batch(batch);
  if (farm_cmd->parsed()) return run_farm(*farm_cmd, farm);
  return kExitUsage;
}
