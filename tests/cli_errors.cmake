# Bad command-line input, run as a user would: each case must exit non-zero, print a message naming the option or file
# and the problem, and leave no output file behind.
# Usage: cmake -DRCSPLAT=build/rcsplat -DWORK=dir -P cli_errors.cmake
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
file(WRITE "${WORK}/broken.gltf" "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [")

function(expect_refused name expected)
  execute_process(COMMAND "${RCSPLAT}" ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY "${WORK}" TIMEOUT 120)
  set(text "${out}${err}")
  file(GLOB left "${WORK}/*.exr" "${WORK}/*.png" "${WORK}/*.json")
  if(rc EQUAL 0)
    message(SEND_ERROR "${name}: exited 0\n${text}")
  elseif(NOT text MATCHES "${expected}")
    message(SEND_ERROR "${name}: the message does not say '${expected}':\n${text}")
  elseif(left)
    message(SEND_ERROR "${name}: left ${left}")
  else()
    string(STRIP "${err}" err)
    message(STATUS "${name}: exit ${rc}: ${err}")
  endif()
  if(left)
    file(REMOVE ${left})
  endif()
endfunction()

expect_refused("width 0" "--width: Value 0" render -o out.exr --width 0)
expect_refused("a billion pixels wide" "--width: Value 1000000000" render -o out.exr --width 1000000000)
expect_refused("negative height" "--height: Value -4" render -o out.exr --height -4)
expect_refused("unknown device" "--device no-such-device: no OpenCL device" render -o out.exr --device no-such-device)
expect_refused("missing output directory" "missing/out.exr: the directory missing does not exist"
               render -o out.png -o missing/out.exr)
expect_refused("read-only output directory" "/proc/out.exr: cannot create files in /proc" render -o out.exr -o /proc/out.exr)
expect_refused("summary in a missing directory" "missing/s.json: the directory" render -o out.exr --json missing/s.json)
expect_refused("unknown output format" "out.tiff: unknown output format" render -o out.tiff)
expect_refused("invalid JSON" "broken.gltf: cannot be loaded" render broken.gltf -o out.exr)
expect_refused("missing scene" "nothing.gltf" render nothing.gltf -o out.exr)
expect_refused("accuracy out of range" "--accuracy" render -o out.exr --accuracy 0)
