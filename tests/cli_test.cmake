# End-to-end command-line checks, run with: cmake -DPRISM=... -DSOURCE_DIR=... -DWORK_DIR=... -P cli_test.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(run expected_code)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL expected_code)
    message(FATAL_ERROR "expected exit ${expected_code}, got ${code}: ${ARGN}\nstdout: ${out}\nstderr: ${err}")
  endif()
  set(last_out "${out}" PARENT_SCOPE)
  set(last_err "${err}" PARENT_SCOPE)
endfunction()

# Fails with "<complaint>: <text>" unless text matches regex.
function(expect_match text regex complaint)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "${complaint}: ${text}")
  endif()
endfunction()

set(box "${SOURCE_DIR}/scenes/cornell-box/cornell-box.gltf")

# A small render writes the EXR and the preview, and prints the summary line.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/box.exr" --preview "${WORK_DIR}/box.png" --spp 2 --res 32x24 --threads 2)
foreach(f box.exr box.png)
  if(NOT EXISTS "${WORK_DIR}/${f}")
    message(FATAL_ERROR "render did not write ${f}")
  endif()
endforeach()
expect_match("${last_out}" "32x24, 2 spp, .* s, .* Mpaths/s, .* Mrays/s" "missing summary line")

# A job file supplies settings; command-line flags override them.
file(WRITE "${WORK_DIR}/job.json" "{\"scene\": \"${box}\", \"spp\": 1, \"resolution\": [16, 8], \"output\": \"job.exr\",
  \"spheres\": [{\"center\": [0.3, 0.1, 0.3], \"radius\": 0.05, \"material\": {\"emissive\": [1, 1, 1]}}]}")
run(0 "${PRISM}" render "${WORK_DIR}/job.json" --res 8x4)
if(NOT EXISTS "${WORK_DIR}/job.exr" OR NOT last_out MATCHES "8x4, 1 spp")
  message(FATAL_ERROR "job file render failed: ${last_out}")
endif()

# Half output: a 1e6 emitter is clamped to 65504 (the largest half) with a warning naming the file,
# from the flag and from the job file; an unknown pixel type is a usage error.
file(WRITE "${WORK_DIR}/bright.json" "{\"scene\": \"${box}\", \"spp\": 1, \"resolution\": [16, 16], \"pixel_type\": \"half\",
  \"output\": \"bright_job.exr\", \"spheres\": [{\"center\": [0.0, 0.0, 0.0], \"radius\": 0.3,
  \"material\": {\"emissive\": [1, 1, 1], \"emissive_strength\": 1e6}}]}")
run(0 "${PRISM}" render "${WORK_DIR}/bright.json")
expect_match("${last_err}" "bright_job.exr: [0-9]+ pixel values above 65504, the largest half, were clamped" "no half clamp warning (job)")
run(0 "${PRISM}" render "${WORK_DIR}/bright.json" --pixel-type half -o "${WORK_DIR}/bright.exr")
expect_match("${last_err}" "bright.exr: [0-9]+ pixel values above 65504" "no half clamp warning (flag)")
run(0 "${PRISM}" render "${WORK_DIR}/bright.json" --pixel-type float -o "${WORK_DIR}/bright_float.exr")
if(last_err MATCHES "65504")
  message(FATAL_ERROR "float output warned about half: ${last_err}")
endif()
run(2 "${PRISM}" render "${box}" --pixel-type double -o "${WORK_DIR}/x.exr")
file(WRITE "${WORK_DIR}/bad_type.json" "{\"scene\": \"${box}\", \"pixel_type\": \"double\"}")
run(3 "${PRISM}" render "${WORK_DIR}/bad_type.json")
expect_match("${last_err}" "pixel_type" "unclear pixel_type message")

# --quiet prints nothing.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/quiet.exr" --spp 1 --res 8x8 --quiet)
if(NOT last_out STREQUAL "" OR NOT last_err STREQUAL "")
  message(FATAL_ERROR "--quiet printed: ${last_out}${last_err}")
endif()

# --progress plain prints parseable lines on stdout, ending at 100%; --quiet does not silence it.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/plain.exr" --spp 2 --res 16x16 --progress plain -q)
expect_match("${last_out}" "^(progress [0-9]+\\.[0-9]%\n)*progress 100\\.0%\n$" "plain progress lines")
run(2 "${PRISM}" render "${box}" -o "${WORK_DIR}/x.exr" --progress fancy)
expect_match("${last_err}" "--progress: expected bar, plain or none" "unclear --progress message")
# Checkpoints: from the flag or the job key "checkpoint"; the final file is a complete render that
# keeps its film state (so it can be continued to more samples).
file(WRITE "${WORK_DIR}/checkpointed.json" "{\"scene\": \"${box}\", \"spp\": 4, \"resolution\": [16, 16],
  \"checkpoint\": \"2s\", \"output\": \"checkpointed.exr\"}")
run(0 "${PRISM}" render "${WORK_DIR}/checkpointed.json" -q)
file(STRINGS "${WORK_DIR}/checkpointed.exr" header LIMIT_INPUT 8000)
expect_match("${header}" "prism.state.0hi" "a checkpointed render lost its film state")
expect_match("${header}" "prism/status;string;complete" "a finished render does not say it is complete")
run(0 "${PRISM}" render "${WORK_DIR}/checkpointed.json" -q --spp 8 --resume "${WORK_DIR}/checkpointed.exr"
    -o "${WORK_DIR}/more.exr")
run(0 "${PRISM}" render "${WORK_DIR}/checkpointed.json" -q --spp 8 -o "${WORK_DIR}/eight.exr")
run(0 "${PRISM}" compare "${WORK_DIR}/more.exr" "${WORK_DIR}/eight.exr" --metric maxabs --threshold 0)
run(2 "${PRISM}" render "${box}" -o "${WORK_DIR}/x.exr" --checkpoint soon)
expect_match("${last_err}" "--checkpoint: expected a duration" "unclear --checkpoint message")
file(WRITE "${WORK_DIR}/bad_checkpoint.json" "{\"scene\": \"${box}\", \"checkpoint\": -1}")
run(3 "${PRISM}" render "${WORK_DIR}/bad_checkpoint.json")
expect_match("${last_err}" "checkpoint" "unclear checkpoint key message")
run(3 "${PRISM}" render "${box}" --spp 2 --res 16x16 -o "${WORK_DIR}/x.exr" --resume "${WORK_DIR}/plain.exr")
expect_match("${last_err}" "plain.exr: prism.state channels: missing" "unclear message for a file that cannot be resumed")
run(3 "${PRISM}" render "${box}" -o "${WORK_DIR}/x.exr" --resume "${WORK_DIR}/absent.exr")

# Each class of failure has its exit code and a message naming the culprit.
run(2 "${PRISM}" render "${box}" --spp 0)
run(2 "${PRISM}" render "${box}" --res 12by4 -o "${WORK_DIR}/x.exr")
run(2 "${PRISM}" render "${box}" --integrator magic -o "${WORK_DIR}/x.exr")
run(2 "${PRISM}" frobnicate)
run(3 "${PRISM}" render "${WORK_DIR}/absent.gltf" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "absent.gltf: no such file" "unclear missing-file message")
run(3 "${PRISM}" render "${box}" --camera nope -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "no camera named or numbered 'nope'" "unclear camera message")
run(4 "${PRISM}" render "${box}" -o "${WORK_DIR}/no/such/dir/x.exr" --spp 1 --res 8x8)
expect_match("${last_err}" "does not exist" "unclear output message")
file(GLOB leftovers "${WORK_DIR}/.*tmp*")
if(leftovers)
  message(FATAL_ERROR "temporary files left behind: ${leftovers}")
endif()

# A job with no glTF scene: analytic spheres only, no emitters, so a warning says why it is black.
file(WRITE "${WORK_DIR}/spheres.json" "{\"spheres\": [{\"center\": [0, 0, 0], \"radius\": 1}], \"resolution\": [8, 8], \"spp\": 1}")
run(0 "${PRISM}" render "${WORK_DIR}/spheres.json" -o "${WORK_DIR}/spheres.exr")
expect_match("${last_err}" "no lights" "no warning for a scene without lights")

# An environment light from the command line: a constant sky, or a map that must exist.
run(0 "${PRISM}" render "${WORK_DIR}/spheres.json" -o "${WORK_DIR}/sky.exr" --env 0.5,0.6,0.7 --env-intensity 2)
if(last_err MATCHES "no lights")
  message(FATAL_ERROR "a constant sky should light the scene: ${last_err}")
endif()
run(3 "${PRISM}" render "${WORK_DIR}/spheres.json" -o "${WORK_DIR}/sky.exr" --env "${WORK_DIR}/missing.exr")
expect_match("${last_err}" "missing.exr" "unclear missing-map message")

# Budgets: a time budget and a noise target render complete images and say what they reached.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/timed.exr" --time 0.5s --res 16x16 --sampler independent)
expect_match("${last_out}" "passes, estimated relative error" "no budget summary for --time")
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/adaptive.exr" --noise 0.2 --min-spp 4 --spp 64 --res 16x16)
expect_match("${last_out}" "of pixels under the noise target 0.2" "no noise summary for --noise")
run(2 "${PRISM}" render "${box}" --time soon -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "--time: expected a duration" "unclear --time message")
run(2 "${PRISM}" render "${box}" --sampler magic -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "unknown sampler 'magic'" "unclear --sampler message")

# compare: metrics, a threshold for scripts, difference images, and clear failures.
run(0 "${PRISM}" compare "${WORK_DIR}/timed.exr" "${WORK_DIR}/timed.exr" --threshold 0 --diff "${WORK_DIR}/same.png")
if(NOT last_out MATCHES "relMSE" OR NOT last_out MATCHES "relmse 0 within threshold 0")
  message(FATAL_ERROR "compare of an image with itself: ${last_out}")
endif()
run(5 "${PRISM}" compare "${WORK_DIR}/timed.exr" "${WORK_DIR}/adaptive.exr" --metric rmse --threshold 1e-9
    --diff "${WORK_DIR}/diff.exr")
if(NOT EXISTS "${WORK_DIR}/diff.exr" OR NOT EXISTS "${WORK_DIR}/same.png")
  message(FATAL_ERROR "compare did not write its difference images")
endif()
run(2 "${PRISM}" compare "${WORK_DIR}/timed.exr" "${WORK_DIR}/box.exr")
expect_match("${last_err}" "image sizes differ: 16x16 vs 32x24" "unclear size mismatch message")
run(3 "${PRISM}" compare "${WORK_DIR}/timed.exr" "${WORK_DIR}/absent.exr")
expect_match("${last_err}" "absent.exr" "unclear missing-image message")

# converge: a reference rendered by prism, a CSV row per setting and level, and the plot.
file(MAKE_DIRECTORY "${WORK_DIR}/converge")
run(0 "${PRISM}" converge "${box}" --res 16x16 --reference-spp 32 --spp 1,4 -o "${WORK_DIR}/converge")
file(STRINGS "${WORK_DIR}/converge/convergence.csv" rows)
list(LENGTH rows row_count)
if(NOT row_count EQUAL 5 OR NOT EXISTS "${WORK_DIR}/converge/convergence.svg" OR NOT EXISTS "${WORK_DIR}/converge/reference.exr")
  message(FATAL_ERROR "converge outputs: ${row_count} CSV lines; ${last_out}")
endif()
expect_match("${last_out}" "fitted slopes" "converge printed no slopes")
run(0 "${PRISM}" converge "${box}" --reference "${WORK_DIR}/converge/reference.exr" --spp 2 --samplers independent
    -o "${WORK_DIR}/converge" -q)
run(2 "${PRISM}" converge "${box}" --reference "${WORK_DIR}/converge/reference.exr" --res 8x8 -o "${WORK_DIR}/converge")
expect_match("${last_err}" "is 16x16 but the render is 8x8" "unclear reference size message")
run(2 "${PRISM}" converge "${box}" --spp 1,x -o "${WORK_DIR}/converge")

# bench: one line of figures per scene; a scene that fails is reported and fails the run.
run(0 "${PRISM}" bench "${box}" --res 16x16 --spp 1)
if(NOT last_out MATCHES "cornell-box.gltf +32 " OR NOT last_out MATCHES "peak MB")
  message(FATAL_ERROR "bench line: ${last_out}")
endif()
run(3 "${PRISM}" bench "${box}" "${WORK_DIR}/absent.gltf" --res 16x16 --spp 1)
if(NOT last_out MATCHES "absent.gltf +failed" OR NOT last_err MATCHES "absent.gltf")
  message(FATAL_ERROR "bench failure report: ${last_out} ${last_err}")
endif()

# Compositing layers: AOVs, compressions, parts, crops and sample slices; usage errors named.
run(0 "${PRISM}" render "${box}" --spp 2 --res 24x16 --aovs all -o "${WORK_DIR}/aovs.exr")
run(0 "${PRISM}" render "${box}" --spp 2 --res 24x16 --aovs albedo,normal,depth,crypto_object --multipart
    --compression piz -o "${WORK_DIR}/aovs_multipart.exr")
run(0 "${PRISM}" render "${box}" --spp 2 --res 24x16 --compression dwaa --crop 4 2 20 11 -o "${WORK_DIR}/crop.exr")
run(0 "${PRISM}" render "${box}" --res 24x16 --sample-range 2 2 -o "${WORK_DIR}/slice.exr")
file(WRITE "${WORK_DIR}/layers.json" "{\"scene\": \"${box}\", \"spp\": 1, \"resolution\": [12, 8], \"aovs\": [\"depth\", \"spp\"],
  \"compression\": \"none\", \"multipart\": true, \"crop\": [1, 1, 5, 7], \"output\": \"layers_job.exr\"}")
run(0 "${PRISM}" render "${WORK_DIR}/layers.json")
run(2 "${PRISM}" render "${box}" --aovs albedo,shadows -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "unknown AOV 'shadows'; known: albedo" "unclear --aovs message")
run(2 "${PRISM}" render "${box}" --res 24x16 --crop 4 2 30 11 -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "x1 <= 24" "unclear --crop message")
run(2 "${PRISM}" render "${box}" --sample-range 0 4 --spp 4 -o "${WORK_DIR}/x.exr")
run(2 "${PRISM}" render "${box}" --sample-range 0 4 --time 1s -o "${WORK_DIR}/x.exr")
run(2 "${PRISM}" render "${box}" --compression lzma -o "${WORK_DIR}/x.exr")
file(WRITE "${WORK_DIR}/bad_crop.json" "{\"scene\": \"${box}\", \"crop\": [5, 1, 2, 7]}")
run(3 "${PRISM}" render "${WORK_DIR}/bad_crop.json" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "crop.*x0 < x1" "unclear crop message (job)")

# OpenEXR's own exrheader reads every file written above (when the openexr tools are installed),
# and sees the layers, the data window and the camera.
find_program(EXRHEADER exrheader)
if(EXRHEADER)
  file(GLOB written "${WORK_DIR}/*.exr")
  foreach(f ${written})
    run(0 "${EXRHEADER}" "${f}")
  endforeach()
  run(0 "${EXRHEADER}" "${WORK_DIR}/aovs.exr")
  foreach(name "N.X" "P.Z" "Z," "albedo.R" "CryptoObject00.A" "CryptoMaterial00.R" "variance.B" "worldToNDC" "worldToCamera"
               "cryptomatte/[0-9a-f]+/manifest")
    expect_match("${last_out}" "${name}" "exrheader does not list ${name}")
  endforeach()
  run(0 "${EXRHEADER}" "${WORK_DIR}/crop.exr")
  expect_match("${last_out}" "dataWindow \\(type box2i\\): \\(4 2\\) - \\(19 10\\)" "crop data window")
  expect_match("${last_out}" "displayWindow \\(type box2i\\): \\(0 0\\) - \\(23 15\\)" "crop display window")
  expect_match("${last_out}" "compression \\(type compression\\): dwa" "crop compression")
  run(0 "${EXRHEADER}" "${WORK_DIR}/aovs_multipart.exr")
  expect_match("${last_out}" "part 3:" "multipart layers")
else()
  message(STATUS "exrheader not installed (Debian package openexr): skipping its checks")
endif()

# merge: four sample slices equal one render of all their samples, in every layer; three crops
# stitch into the whole image; parts that do not belong together are refused, naming the file.
run(0 "${PRISM}" render "${box}" --res 24x16 --spp 8 --aovs all -o "${WORK_DIR}/whole.exr")
set(slices "")
foreach(start 0 2 4 6)
  run(0 "${PRISM}" render "${box}" --res 24x16 --sample-range ${start} 2 --aovs all -o "${WORK_DIR}/slice${start}.exr")
  list(APPEND slices "${WORK_DIR}/slice${start}.exr")
endforeach()
run(0 "${PRISM}" merge ${slices} -o "${WORK_DIR}/merged.exr")
expect_match("${last_out}" "merged 4 parts \\(1 windows\\).*8-8 spp" "merge summary")
run(0 "${PRISM}" render "${box}" --res 24x16 --spp 8 -o "${WORK_DIR}/whole_plain.exr")
run(0 "${PRISM}" render "${box}" --res 24x16 --spp 8 --crop 0 0 10 7 -o "${WORK_DIR}/crop_a.exr")
run(0 "${PRISM}" render "${box}" --res 24x16 --spp 8 --crop 10 0 24 7 -o "${WORK_DIR}/crop_b.exr")
run(0 "${PRISM}" render "${box}" --res 24x16 --spp 8 --crop 0 7 24 16 -o "${WORK_DIR}/crop_c.exr")
run(0 "${PRISM}" merge "${WORK_DIR}/crop_a.exr" "${WORK_DIR}/crop_b.exr" "${WORK_DIR}/crop_c.exr" -o "${WORK_DIR}/stitched.exr")
run(0 "${PRISM}" compare "${WORK_DIR}/stitched.exr" "${WORK_DIR}/whole_plain.exr" --metric maxabs --threshold 0)
run(0 "${PRISM}" compare "${WORK_DIR}/merged.exr" "${WORK_DIR}/whole.exr" --metric maxabs --threshold 0)
find_program(IDIFF idiff)
if(IDIFF)  # every channel, AOVs and Cryptomatte included
  run(0 "${IDIFF}" -fail 0 -warn 0 "${WORK_DIR}/merged.exr" "${WORK_DIR}/whole.exr")
  run(0 "${IDIFF}" -fail 0 -warn 0 "${WORK_DIR}/stitched.exr" "${WORK_DIR}/whole_plain.exr")
else()
  message(STATUS "idiff not installed (Debian package openimageio-tools): merged AOVs not compared")
endif()
run(3 "${PRISM}" merge "${WORK_DIR}/slice0.exr" "${WORK_DIR}/slice0.exr" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "slice0.exr: prism/firstSample: samples 0..1 overlap" "unclear overlapping-slices message")
run(0 "${PRISM}" render "${box}" --res 24x16 --sample-range 2 2 --aovs all --seed 9 -o "${WORK_DIR}/seed9.exr")
run(3 "${PRISM}" merge "${WORK_DIR}/slice0.exr" "${WORK_DIR}/seed9.exr" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "seed9.exr: prism/seed: '9' differs" "unclear seed mismatch message")
run(3 "${PRISM}" merge "${WORK_DIR}/crop_a.exr" "${WORK_DIR}/crop_c.exr" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "uncovered" "unclear gap message")
run(3 "${PRISM}" merge "${WORK_DIR}/crop_a.exr" "${WORK_DIR}/crop.exr" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "overlaps" "unclear overlap message")
if(EXISTS "${WORK_DIR}/x.exr")
  message(FATAL_ERROR "a failed merge wrote its output")
endif()

# batch: a broken job does not stop the others; the summary reports it; the exit code is its class.
file(WRITE "${WORK_DIR}/batch.json" "{\"defaults\": {\"scene\": \"${box}\", \"spp\": 2, \"resolution\": [16, 16]},
  \"jobs\": [{\"output\": \"batch_a.exr\"}, {\"output\": \"batch_b.exr\", \"scene\": \"absent.gltf\"},
            {\"output\": \"batch_c.exr\", \"seed\": 4, \"aovs\": [\"depth\"]}, {\"output\": \"batch_d.exr\", \"spp\": \"many\"}]}")
run(3 "${PRISM}" batch "${WORK_DIR}/batch.json" --progress plain)
foreach(f batch_a.exr batch_c.exr)
  if(NOT EXISTS "${WORK_DIR}/${f}")
    message(FATAL_ERROR "batch did not render ${f}: ${last_out}")
  endif()
endforeach()
expect_match("${last_out}" "job 1/4 \\(\\$\\.jobs\\[0\\]\\)" "batch job header line")
expect_match("${last_out}" "progress 100\\.0% job 3/4 batch 75\\.0%" "batch plain progress")
expect_match("${last_out}" "2 +input error .*batch_b.exr" "broken job not in the summary")
expect_match("${last_out}" "absent.gltf: no such file" "broken job's reason not in the summary")
expect_match("${last_out}" "batch.json: \\$\\.jobs\\[3\\]: \\$\\.spp: expected an integer" "bad job key not named")
expect_match("${last_out}" "4 jobs: 2 rendered, 0 skipped, 2 failed" "batch totals")
run(3 "${PRISM}" batch "${WORK_DIR}/batch.json" --skip-existing -q)
expect_match("${last_out}" "4 jobs: 0 rendered, 2 skipped, 2 failed" "--skip-existing did not skip complete outputs")
file(WRITE "${WORK_DIR}/batch_ok.json" "[{\"scene\": \"${box}\", \"spp\": 1, \"resolution\": [8, 8], \"output\": \"batch_ok.exr\"}]")
run(0 "${PRISM}" batch "${WORK_DIR}/batch_ok.json" -q)
if(NOT last_out STREQUAL "")
  message(FATAL_ERROR "a quiet batch that succeeded printed: ${last_out}")
endif()
run(3 "${PRISM}" batch "${WORK_DIR}/absent.json")
file(WRITE "${WORK_DIR}/batch_bad.json" "{\"jobs\": 3}")
run(3 "${PRISM}" batch "${WORK_DIR}/batch_bad.json")
expect_match("${last_err}" "batch_bad.json: \\$\\.jobs: expected a list of jobs" "unclear batch file message")
