# Embeds .glsl files into the library at build time: each file becomes an entry of the
# shader registry (src/gl/shader_registry.cpp generated into the build tree), keyed by its
# path relative to src/ (e.g. "styles/gooch/gooch.glsl"), so `#include` resolves by that name.
function(cutaway_embed_shaders target)
  set(out "${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp")
  set(files ${ARGN})
  add_custom_command(
    OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DROOT=${CMAKE_CURRENT_SOURCE_DIR}
            "-DFILES=${files}" -P ${PROJECT_SOURCE_DIR}/cmake/embed_shaders_script.cmake
    DEPENDS ${files} ${PROJECT_SOURCE_DIR}/cmake/embed_shaders_script.cmake
    COMMENT "Embedding ${CMAKE_CURRENT_LIST_DIR} shaders"
    VERBATIM)
  target_sources(${target} PRIVATE "${out}")
endfunction()
