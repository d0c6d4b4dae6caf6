# Outputs as a user names them: folders that do not exist yet are made when the file is written (render's -o and
# --json, animate's frame pattern, --stats), and --progress-lines prints "Progress: NN%" lines on stdout that never go
# back and end at 100%, as render-farm managers read them.
# Usage: cmake -DRCSPLAT=build/rcsplat -DWORK=dir -P cli_outputs.cmake
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

function(run_ok name)
  execute_process(COMMAND "${RCSPLAT}" ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY "${WORK}" TIMEOUT 300)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: exited ${rc}\n${out}${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

function(expect_files name)
  foreach(f ${ARGN})
    if(NOT EXISTS "${WORK}/${f}")
      message(SEND_ERROR "${name}: ${f} was not written")
    endif()
  endforeach()
endfunction()

# The Progress lines in order: each at least the one before, the last 100%.
function(expect_progress name text)
  string(REGEX MATCHALL "Progress: [0-9]+%" lines "${text}")
  list(LENGTH lines count)
  if(count EQUAL 0)
    message(SEND_ERROR "${name}: no Progress lines in\n${text}")
    return()
  endif()
  set(previous -1)
  foreach(line ${lines})
    string(REGEX REPLACE "Progress: ([0-9]+)%" "\\1" percent "${line}")
    if(percent LESS previous)
      message(SEND_ERROR "${name}: progress went back from ${previous}% to ${percent}%")
    endif()
    set(previous ${percent})
  endforeach()
  if(NOT previous EQUAL 100)
    message(SEND_ERROR "${name}: the last Progress line is ${previous}%, not 100%")
  endif()
  message(STATUS "${name}: ${count} Progress lines, up to 100%")
endfunction()

run_ok("render into new folders" render --width 32 --height 24 -o made/deeper/out.exr --json made/summary/s.json
       --progress-lines -q)
expect_files("render into new folders" made/deeper/out.exr made/summary/s.json)
expect_progress("render --progress-lines" "${last_output}")

run_ok("animate into new folders" animate --width 16 --height 12 --gi none --orbit 1 --fps 2
       -o frames/%04d.exr --stats stats/frames.csv --progress-lines -q)
expect_files("animate into new folders" frames/0000.exr frames/0001.exr frames/0002.exr stats/frames.csv)
expect_progress("animate --progress-lines" "${last_output}")

run_ok("render without --progress-lines" render --width 16 --height 12 --gi none -o plain.exr -q)
if(last_output MATCHES "Progress:")
  message(SEND_ERROR "Progress lines printed without --progress-lines:\n${last_output}")
endif()
