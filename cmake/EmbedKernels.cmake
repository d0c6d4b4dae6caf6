# Embeds the kernel sources into the binary as string literals, so that an installed rcsplat needs no kernel files.
# Each file becomes one entry of a name -> text table; a raw-string delimiter keeps the text verbatim.
function(rcsplat_embed_kernels output)
  string(REPLACE ";" "::" inputs "${ARGN}")  # a list would be split into separate command arguments
  add_custom_command(
    OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${output} -DINPUTS=${inputs} -P ${CMAKE_SOURCE_DIR}/cmake/WriteEmbeddedKernels.cmake
    DEPENDS ${ARGN} ${CMAKE_SOURCE_DIR}/cmake/WriteEmbeddedKernels.cmake
    COMMENT "Embedding OpenCL kernel sources" VERBATIM)
endfunction()
