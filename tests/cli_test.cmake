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

# Fails with "<what> did not write <file>: <last output>" unless every file exists in WORK_DIR.
function(expect_written what)
  foreach(f ${ARGN})
    if(NOT EXISTS "${WORK_DIR}/${f}")
      message(FATAL_ERROR "${what} did not write ${f}: ${last_out}")
    endif()
  endforeach()
endfunction()

set(box "${SOURCE_DIR}/scenes/cornell-box/cornell-box.gltf")

# A small render writes the EXR and the preview, and prints the summary line.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/box.exr" --preview "${WORK_DIR}/box.png" --spp 2 --res 32x24 --threads 2)
expect_written(render box.exr box.png)
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
# Samples shared by error: the mean is --spp, the header says so, and the counts go in a layer.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/allocated.exr" --allocation error --min-spp 4 --spp 16 --res 16x16)
expect_match("${last_out}" "\\(mean 16\\.0\\) spp" "--allocation error missed its mean spp")
file(STRINGS "${WORK_DIR}/allocated.exr" header LIMIT_INPUT 8000)
expect_match("${header}" "prism/allocation;string;error" "the header does not record the allocation")
# A noise target shared by error is the whole image's.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/allocated_noise.exr" --allocation error --noise 0.2 --min-spp 4
    --spp 64 --res 16x16)
expect_match("${last_out}" "the whole image's noise target 0.2" "no whole-image summary for --noise with --allocation error")
# Path splitting: recorded in the header (a render resumed or merged with another split is refused);
# only the path tracer splits.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/split.exr" --split 2 --spp 4 --res 16x16)
file(STRINGS "${WORK_DIR}/split.exr" header LIMIT_INPUT 8000)
expect_match("${header}" "prism/split;int" "the header does not record the split")
run(2 "${PRISM}" render "${box}" --split 2 --integrator whitted -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "split 2 is the path integrator's; the whitted integrator does not split paths"
             "unclear --split message for whitted")
run(2 "${PRISM}" render "${box}" --split 0 -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "--split" "unclear --split 0 message")
# Texture filtering: MIP levels on request, recorded in the header; an unknown filter is refused.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/trilinear.exr" --texture-filter trilinear --spp 4 --res 16x16)
file(STRINGS "${WORK_DIR}/trilinear.exr" header LIMIT_INPUT 8000)
expect_match("${header}" "prism/textureFilter;string;[^a-z]*trilinear" "the header does not record the texture filter")
run(2 "${PRISM}" render "${box}" --texture-filter anisotropic -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "--texture-filter: unknown filter 'anisotropic' \\(expected trilinear or bilinear\\)"
             "unclear --texture-filter message")
run(2 "${PRISM}" render "${box}" --allocation greedy -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "--allocation: expected uniform or error, got 'greedy'" "unclear --allocation message")
run(2 "${PRISM}" render "${box}" --allocation error --sample-range 0 4 -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "--allocation error" "unclear --allocation with --sample-range message")
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
# The measure --noise bounds, as a threshold: two renders of one scene differ by it, an image from itself not.
run(0 "${PRISM}" compare "${WORK_DIR}/timed.exr" "${WORK_DIR}/timed.exr" --metric relerr --threshold 0)
run(5 "${PRISM}" compare "${WORK_DIR}/timed.exr" "${WORK_DIR}/adaptive.exr" --metric relerr --threshold 1e-9)
expect_match("${last_out}" "relative error of the luminance per pixel \\(what --noise bounds\\): RMS [0-9]"
             "compare's relative error line")
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
# Russian roulette's start as a compared setting: one series per depth, named after it.
run(0 "${PRISM}" converge "${box}" --reference "${WORK_DIR}/converge/reference.exr" --spp 2 --samplers sobol
    --rr-start-depths 5,2 -o "${WORK_DIR}/converge" -q)
file(STRINGS "${WORK_DIR}/converge/convergence.csv" rows)
if(NOT rows MATCHES "path/sobol/rr2,2,.*path/sobol/rr5,2,")
  message(FATAL_ERROR "converge --rr-start-depths rows: ${rows}")
endif()
run(2 "${PRISM}" converge "${box}" --rr-start-depths 0 -o "${WORK_DIR}/converge")
expect_match("${last_err}" "--rr-start-depths: expected a list of counts" "unclear --rr-start-depths message")
# Time budgets and noise targets: a render of its own per level, its mean spp in the CSV, a series
# per kind of budget (named after it when there are several).
run(0 "${PRISM}" converge "${box}" --reference "${WORK_DIR}/converge/reference.exr" --times 50ms,0.1s --samplers sobol
    -o "${WORK_DIR}/converge" -q)
file(STRINGS "${WORK_DIR}/converge/convergence.csv" rows)
list(LENGTH rows row_count)
if(NOT row_count EQUAL 3 OR
   NOT rows MATCHES "^setting,spp,seconds,rmse,relmse,efficiency,relerr;path/sobol,[0-9.]+,[0-9.]+,")
  message(FATAL_ERROR "converge --times rows: ${rows}")
endif()
run(0 "${PRISM}" converge "${box}" --reference "${WORK_DIR}/converge/reference.exr" --spp 16 --noise 0.5,0.2
    --samplers independent -o "${WORK_DIR}/converge" -q)
file(STRINGS "${WORK_DIR}/converge/convergence.csv" rows)
if(NOT rows MATCHES ";path/independent/spp,16,[^;]*;path/independent/noise,[0-9.]+,[^;]*;path/independent/noise,")
  message(FATAL_ERROR "converge --spp with --noise rows: ${rows}")
endif()
run(2 "${PRISM}" converge "${box}" --times 1s,soon -o "${WORK_DIR}/converge")
expect_match("${last_err}" "--times: expected a duration such as 60, 30s" "unclear --times message")
run(2 "${PRISM}" converge "${box}" --noise 0.01,2 -o "${WORK_DIR}/converge")
expect_match("${last_err}" "--noise: expected a list of relative errors" "unclear --noise message")

# bench: one line of figures per scene; a scene that fails is reported and fails the run.
run(0 "${PRISM}" bench "${box}" --res 16x16 --spp 1)
if(NOT last_out MATCHES "cornell-box.gltf +32 " OR NOT last_out MATCHES "peak MB")
  message(FATAL_ERROR "bench line: ${last_out}")
endif()
# --repeat: the medians of the runs, with the range of render seconds; --csv: a row per run.
run(0 "${PRISM}" bench "${box}" --res 16x16 --spp 1 --repeat 3 --csv "${WORK_DIR}/bench.csv")
if(NOT last_out MATCHES "medians of 3 runs" OR NOT last_out MATCHES "cornell-box.gltf +32 [^\n]* [0-9.]+\\.\\.[0-9.]+\n")
  message(FATAL_ERROR "bench --repeat line: ${last_out}")
endif()
file(STRINGS "${WORK_DIR}/bench.csv" rows)
list(LENGTH rows row_count)
if(NOT row_count EQUAL 4 OR NOT rows MATCHES "^scene,run,spp,[^;]*;cornell-box.gltf,1,1,16x16,8,sobol,[^;]*;cornell-box.gltf,2,[^;]*;cornell-box.gltf,3,")
  message(FATAL_ERROR "bench --csv rows: ${rows}")
endif()
# --references: each render's relMSE and efficiency against a converged image, rendered into the
# folder once and then reused (its name says what it depends on).
file(MAKE_DIRECTORY "${WORK_DIR}/bench-refs")
run(0 "${PRISM}" bench "${box}" --res 16x16 --spp 2 --references "${WORK_DIR}/bench-refs" --reference-spp 64
    --csv "${WORK_DIR}/bench-errors.csv")
file(GLOB refs "${WORK_DIR}/bench-refs/cornell-box-*-16x16-d8-64spp.exr")
list(LENGTH refs ref_count)
if(NOT ref_count EQUAL 1 OR NOT last_out MATCHES "rendering the reference of cornell-box.gltf: 64 spp"
   OR NOT last_out MATCHES "relMSE  efficiency\n" OR NOT last_out MATCHES "cornell-box.gltf +32 [^\n]* [0-9.e-]+ +[0-9.e+]+\n")
  message(FATAL_ERROR "bench --references: ${refs} ${last_out}")
endif()
file(STRINGS "${WORK_DIR}/bench-errors.csv" rows)
if(NOT rows MATCHES ";cornell-box.gltf,1,2,16x16,[^;]*,[0-9.e-]+,[0-9.e+]+$")
  message(FATAL_ERROR "bench --references CSV: ${rows}")
endif()
run(0 "${PRISM}" bench "${box}" --res 16x16 --spp 2 --references "${WORK_DIR}/bench-refs" --reference-spp 64)
if(last_out MATCHES "rendering the reference")
  message(FATAL_ERROR "bench rendered a reference it had: ${last_out}")
endif()
# A foreign image under a reference's name: the scene fails, naming the file and the sizes.
string(REPLACE "-16x16-" "-8x8-" wrong_size "${refs}")
file(COPY_FILE "${refs}" "${wrong_size}")
run(3 "${PRISM}" bench "${box}" --res 8x8 --spp 1 --references "${WORK_DIR}/bench-refs" --reference-spp 64)
if(NOT last_out MATCHES "cornell-box.gltf +failed" OR NOT last_err MATCHES "-8x8-d8-64spp.exr.*the reference is 16x16, the bench renders 8x8")
  message(FATAL_ERROR "bench with a reference of another size: ${last_out} ${last_err}")
endif()
run(4 "${PRISM}" bench "${box}" --res 16x16 --spp 1 --references "${WORK_DIR}/no-such-dir")
expect_match("${last_err}" "no-such-dir" "bench --references into a missing folder: unclear message")
run(2 "${PRISM}" bench "${box}" --repeat 0)
run(4 "${PRISM}" bench "${box}" --res 16x16 --spp 1 --csv "${WORK_DIR}/no-such-dir/bench.csv")
expect_match("${last_err}" "no-such-dir" "bench --csv into a missing folder: unclear message")
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
  foreach(name "capDate" "prism/renderSeconds")
    if(last_out MATCHES "${name}")
      message(FATAL_ERROR "${name} written without --stamp: the bytes would not be reproducible")
    endif()
  endforeach()
  run(0 "${PRISM}" render "${box}" --spp 1 --res 8x8 --stamp -o "${WORK_DIR}/stamped.exr")
  run(0 "${EXRHEADER}" "${WORK_DIR}/stamped.exr")
  expect_match("${last_out}" "capDate \\(type string\\): \"[0-9]+:[0-9][0-9]:[0-9][0-9] [0-9][0-9]:[0-9][0-9]:[0-9][0-9]\"" "no capDate with --stamp")
  expect_match("${last_out}" "prism/renderSeconds" "no render time with --stamp")
  run(0 "${EXRHEADER}" "${WORK_DIR}/crop.exr")
  expect_match("${last_out}" "dataWindow \\(type box2i\\): \\(4 2\\) - \\(19 10\\)" "crop data window")
  expect_match("${last_out}" "displayWindow \\(type box2i\\): \\(0 0\\) - \\(23 15\\)" "crop display window")
  expect_match("${last_out}" "compression \\(type compression\\): dwa" "crop compression")
  run(0 "${EXRHEADER}" "${WORK_DIR}/aovs_multipart.exr")
  expect_match("${last_out}" "part 3:" "multipart layers")
else()
  message(STATUS "exrheader not installed (Debian package openexr): skipping its checks")
endif()

# merge: four sample slices equal one render of all their samples, in every layer; four crops
# stitch into the whole image, in every layer; parts that do not belong together are refused, naming the file.
run(0 "${PRISM}" render "${box}" --res 24x16 --spp 8 --aovs all -o "${WORK_DIR}/whole.exr")
set(slices "")
foreach(start 0 2 4 6)
  run(0 "${PRISM}" render "${box}" --res 24x16 --sample-range ${start} 2 --aovs all -o "${WORK_DIR}/slice${start}.exr")
  list(APPEND slices "${WORK_DIR}/slice${start}.exr")
endforeach()
run(0 "${PRISM}" merge ${slices} -o "${WORK_DIR}/merged.exr")
expect_match("${last_out}" "merged 4 parts \\(1 windows\\).*8-8 spp" "merge summary")
if(EXRHEADER)
  run(0 "${EXRHEADER}" "${WORK_DIR}/merged.exr")
  expect_match("${last_out}" "prism/status \\(type string\\): \"complete\"" "a merge of complete parts is not complete")
endif()
set(crops "")
foreach(crop a b c d)
  set(window_a 0 0 10 7)
  set(window_b 10 0 24 7)
  set(window_c 0 7 13 16)
  set(window_d 13 7 24 16)
  run(0 "${PRISM}" render "${box}" --res 24x16 --spp 8 --aovs all --crop ${window_${crop}} -o "${WORK_DIR}/crop_${crop}.exr")
  list(APPEND crops "${WORK_DIR}/crop_${crop}.exr")
endforeach()
run(0 "${PRISM}" merge ${crops} -o "${WORK_DIR}/stitched.exr")
expect_match("${last_out}" "merged 4 parts \\(4 windows\\)" "crop merge summary")
run(0 "${PRISM}" compare "${WORK_DIR}/stitched.exr" "${WORK_DIR}/whole.exr" --metric maxabs --threshold 0)
run(0 "${PRISM}" compare "${WORK_DIR}/merged.exr" "${WORK_DIR}/whole.exr" --metric maxabs --threshold 0)
find_program(IDIFF idiff)
if(IDIFF)  # every channel, AOVs and Cryptomatte included
  run(0 "${IDIFF}" -fail 0 -warn 0 "${WORK_DIR}/merged.exr" "${WORK_DIR}/whole.exr")
  run(0 "${IDIFF}" -fail 0 -warn 0 "${WORK_DIR}/stitched.exr" "${WORK_DIR}/whole.exr")
else()
  message(STATUS "idiff not installed (Debian package openimageio-tools): merged AOVs not compared")
endif()
run(3 "${PRISM}" merge "${WORK_DIR}/slice0.exr" "${WORK_DIR}/slice0.exr" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "slice0.exr: prism/firstSample: samples 0..1 overlap" "unclear overlapping-slices message")
run(0 "${PRISM}" render "${box}" --res 24x16 --sample-range 2 2 --aovs all --seed 9 -o "${WORK_DIR}/seed9.exr")
run(3 "${PRISM}" merge "${WORK_DIR}/slice0.exr" "${WORK_DIR}/seed9.exr" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "seed9.exr: prism/seed: '9' differs" "unclear seed mismatch message")
run(0 "${PRISM}" render "${box}" --res 24x16 --sample-range 2 2 --aovs all --split 2 -o "${WORK_DIR}/split2.exr")
run(3 "${PRISM}" merge "${WORK_DIR}/slice0.exr" "${WORK_DIR}/split2.exr" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "split2.exr: prism/split: '2' differs from [^ ]*slice0.exr's '1'" "unclear split mismatch message")
run(3 "${PRISM}" merge "${WORK_DIR}/crop_a.exr" "${WORK_DIR}/crop_c.exr" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "uncovered" "unclear gap message")
run(0 "${PRISM}" render "${box}" --res 24x16 --spp 8 --aovs all --crop 5 3 15 10 -o "${WORK_DIR}/crop_overlap.exr")
run(3 "${PRISM}" merge "${WORK_DIR}/crop_a.exr" "${WORK_DIR}/crop_overlap.exr" -o "${WORK_DIR}/x.exr")
expect_match("${last_err}" "overlaps" "unclear overlap message")
if(EXISTS "${WORK_DIR}/x.exr")
  message(FATAL_ERROR "a failed merge wrote its output")
endif()

# batch: a broken job does not stop the others; the summary reports it; the exit code is its class.
file(WRITE "${WORK_DIR}/batch.json" "{\"defaults\": {\"scene\": \"${box}\", \"spp\": 2, \"resolution\": [16, 16]},
  \"jobs\": [{\"output\": \"batch_a.exr\"}, {\"output\": \"batch_b.exr\", \"scene\": \"absent.gltf\"},
            {\"output\": \"batch_c.exr\", \"seed\": 4, \"aovs\": [\"depth\"]}, {\"output\": \"batch_d.exr\", \"spp\": \"many\"}]}")
run(3 "${PRISM}" batch "${WORK_DIR}/batch.json" --progress plain)
expect_written(batch batch_a.exr batch_c.exr)
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
