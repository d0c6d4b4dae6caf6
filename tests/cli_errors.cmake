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
file(WRITE "${WORK}/plain_file" "not a folder")
expect_refused("output under a file" "plain_file/out.exr: plain_file is not a directory"
               render -o out.png -o plain_file/out.exr)
expect_refused("missing output folder, bad scene" "nothing.gltf" render nothing.gltf -o made/later/out.exr)
if(EXISTS "${WORK}/made")
  message(SEND_ERROR "a refused render made the output folder ${WORK}/made")
endif()
expect_refused("read-only output directory" "/proc/out.exr: cannot create files in /proc" render -o out.exr -o /proc/out.exr)
expect_refused("summary under a file" "plain_file/s.json: plain_file is not a directory" render -o out.exr --json plain_file/s.json)
expect_refused("folder under /proc" "/proc/rcsplat_no/out.exr: cannot create files in /proc" render -o /proc/rcsplat_no/out.exr)
expect_refused("unknown output format" "out.tiff: unknown output format" render -o out.tiff)
expect_refused("invalid JSON" "broken.gltf: is not valid JSON" render broken.gltf -o out.exr)
expect_refused("missing scene" "nothing.gltf" render nothing.gltf -o out.exr)
expect_refused("accuracy out of range" "--accuracy" render -o out.exr --accuracy 0)
expect_refused("negative adaptive rays" "--adaptive-rays must be 0" render -o out.exr --adaptive-rays -1)
expect_refused("info on invalid JSON" "broken.gltf: is not valid JSON" info broken.gltf --json out.json)
expect_refused("bounces 17" "--bounces must be between 1 and 16" render -o out.exr --bounces 17)
expect_refused("unknown bounce method" "--bounce-method photon: unknown method" render -o out.exr --bounce-method photon)
expect_refused("photons under a sky" "--bounce-method photons: the photons come from the lights"
               render -o out.exr --bounces 2 --bounce-method photons --sky 1,1,1)
expect_refused("too many photons" "--photons must be between 1 and 67108864" render -o out.exr --bounce-method photons --photons 100000000)
file(WRITE "${WORK}/garbage.hdr" "#?RADIANCE\nnot a picture")
expect_refused("missing environment map" "nosky.hdr: cannot be read" render -o out.exr --environment nosky.hdr)
expect_refused("unreadable environment map" "garbage.hdr: cannot be read" render -o out.exr --environment garbage.hdr)
expect_refused("sky and map" "--sky and --environment: give one or the other"
               render -o out.exr --sky 1,1,1 --environment garbage.hdr)
expect_refused("negative sky" "--sky \\(1, -1, 1\\): must be finite and non-negative" render -o out.exr --sky 1,-1,1)
expect_refused("sky with two numbers" "--sky" render -o out.exr --sky 1,1)
expect_refused("info with a missing map" "nosky.hdr: cannot be read" info --environment nosky.hdr)
expect_refused("pixel samples not square" "--pixel-samples 3: must be a square number" render -o out.exr --pixel-samples 3)
expect_refused("spp not a multiple of the pixel samples" "--spp 6 must be a multiple of --pixel-samples 4"
               render -o out.exr --gi path --spp 6 --pixel-samples 4)
expect_refused("device memory budget" "needs [0-9.]+ MiB; [0-9.]+ MiB are held already, and the budget is 1.0 MiB \\(--max-device-memory\\)"
               render -o out.exr --max-device-memory 0.0009765625)
expect_refused("asset root that is no folder" "--asset-root: Directory does not exist" render -o out.exr --asset-root nowhere)
expect_refused("a lag as long as the window" "--max-lag must be 0 to --temporal-window - 1 \\(3\\) frames"
               animate --orbit 1 --temporal-window 4 --max-lag 4 -o "f%d.exr")
expect_refused("a window of no frames" "--temporal-window: Value 0" animate --orbit 1 --temporal-window 0 -o "f%d.exr")
expect_refused("animate without a frame number" "-o frames.exr: a frame sequence's name holds one frame number"
               animate --orbit 1 -o frames.exr)
expect_refused("animate the Cornell box without a path" "the built-in Cornell box has no animation"
               animate -o "f%d.exr")
expect_refused("animate to an MP4 without PNG frames" "--mp4: the preview is made from PNG frames"
               animate --orbit 1 -o "f%d.exr" --mp4 out.mp4)
file(WRITE "${WORK}/walk.txt" "0 0 1 5 0 1 0 0 1 0 40\n0.5 0 1 5 0 1 5 0 1 0 40\n")
expect_refused("a keyframe that looks nowhere" "walk.txt: line 2: the eye, target and up do not define a view"
               animate --keyframes walk.txt -o "f%d.exr")
