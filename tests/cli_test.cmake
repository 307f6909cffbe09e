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

set(box "${SOURCE_DIR}/scenes/cornell-box/cornell-box.gltf")

# A small render writes the EXR and the preview, and prints the summary line.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/box.exr" --preview "${WORK_DIR}/box.png" --spp 2 --res 32x24 --threads 2)
foreach(f box.exr box.png)
  if(NOT EXISTS "${WORK_DIR}/${f}")
    message(FATAL_ERROR "render did not write ${f}")
  endif()
endforeach()
if(NOT last_out MATCHES "32x24, 2 spp, .* s, .* Mpaths/s, .* Mrays/s")
  message(FATAL_ERROR "missing summary line: ${last_out}")
endif()

# A job file supplies settings; command-line flags override them.
file(WRITE "${WORK_DIR}/job.json" "{\"scene\": \"${box}\", \"spp\": 1, \"resolution\": [16, 8], \"output\": \"job.exr\",
  \"spheres\": [{\"center\": [0.3, 0.1, 0.3], \"radius\": 0.05, \"material\": {\"emissive\": [1, 1, 1]}}]}")
run(0 "${PRISM}" render "${WORK_DIR}/job.json" --res 8x4)
if(NOT EXISTS "${WORK_DIR}/job.exr" OR NOT last_out MATCHES "8x4, 1 spp")
  message(FATAL_ERROR "job file render failed: ${last_out}")
endif()

# --quiet prints nothing.
run(0 "${PRISM}" render "${box}" -o "${WORK_DIR}/quiet.exr" --spp 1 --res 8x8 --quiet)
if(NOT last_out STREQUAL "" OR NOT last_err STREQUAL "")
  message(FATAL_ERROR "--quiet printed: ${last_out}${last_err}")
endif()

# Each class of failure has its exit code and a message naming the culprit.
run(2 "${PRISM}" render "${box}" --spp 0)
run(2 "${PRISM}" render "${box}" --res 12by4 -o "${WORK_DIR}/x.exr")
run(2 "${PRISM}" render "${box}" --integrator magic -o "${WORK_DIR}/x.exr")
run(2 "${PRISM}" frobnicate)
run(3 "${PRISM}" render "${WORK_DIR}/absent.gltf" -o "${WORK_DIR}/x.exr")
if(NOT last_err MATCHES "absent.gltf: no such file")
  message(FATAL_ERROR "unclear missing-file message: ${last_err}")
endif()
run(3 "${PRISM}" render "${box}" --camera nope -o "${WORK_DIR}/x.exr")
if(NOT last_err MATCHES "no camera named or numbered 'nope'")
  message(FATAL_ERROR "unclear camera message: ${last_err}")
endif()
run(4 "${PRISM}" render "${box}" -o "${WORK_DIR}/no/such/dir/x.exr" --spp 1 --res 8x8)
if(NOT last_err MATCHES "does not exist")
  message(FATAL_ERROR "unclear output message: ${last_err}")
endif()
file(GLOB leftovers "${WORK_DIR}/.*tmp*")
if(leftovers)
  message(FATAL_ERROR "temporary files left behind: ${leftovers}")
endif()

# A job with no glTF scene: analytic spheres only, no emitters, so a warning says why it is black.
file(WRITE "${WORK_DIR}/spheres.json" "{\"spheres\": [{\"center\": [0, 0, 0], \"radius\": 1}], \"resolution\": [8, 8], \"spp\": 1}")
run(0 "${PRISM}" render "${WORK_DIR}/spheres.json" -o "${WORK_DIR}/spheres.exr")
if(NOT last_err MATCHES "no lights")
  message(FATAL_ERROR "no warning for a scene without lights: ${last_err}")
endif()

# An environment light from the command line: a constant sky, or a map that must exist.
run(0 "${PRISM}" render "${WORK_DIR}/spheres.json" -o "${WORK_DIR}/sky.exr" --env 0.5,0.6,0.7 --env-intensity 2)
if(last_err MATCHES "no lights")
  message(FATAL_ERROR "a constant sky should light the scene: ${last_err}")
endif()
run(3 "${PRISM}" render "${WORK_DIR}/spheres.json" -o "${WORK_DIR}/sky.exr" --env "${WORK_DIR}/missing.exr")
if(NOT last_err MATCHES "missing.exr")
  message(FATAL_ERROR "unclear missing-map message: ${last_err}")
endif()
