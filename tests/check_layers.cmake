# Layers: nothing under host/cache, host/scene or host/image (nor the frame's results and settings) may include the
# OpenCL headers, directly or through another header. Run by CTest with -DCXX=... -DSOURCE_DIR=... -DINCLUDES=...
file(GLOB headers ${SOURCE_DIR}/host/cache/*.h ${SOURCE_DIR}/host/scene/*.h ${SOURCE_DIR}/host/image/*.h
     ${SOURCE_DIR}/host/render/frame.h ${SOURCE_DIR}/host/render/settings.h)
separate_arguments(include_flags UNIX_COMMAND "${INCLUDES}")
set(failed "")
foreach(header ${headers})
  execute_process(COMMAND ${CXX} -std=c++20 -M -x c++ ${header} -I${SOURCE_DIR}/host -I${SOURCE_DIR} ${include_flags}
                  OUTPUT_VARIABLE deps ERROR_VARIABLE errors RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    list(APPEND failed "${header} (does not compile on its own: ${errors})")
  elseif(deps MATCHES "/CL/")
    list(APPEND failed "${header} (includes OpenCL)")
  endif()
endforeach()
list(LENGTH headers count)
if(failed)
  message(FATAL_ERROR "layer violations:\n${failed}")
endif()
message(STATUS "${count} headers of host/cache, host/scene, host/image and the frame's results: no OpenCL")
