# `cmake --install`: the library, its public headers, the CLI and the viewer, and a CMake
# package (CutawayConfig.cmake + version file) exporting Cutaway::cutaway, so that another
# project does `find_package(Cutaway REQUIRED)` (examples/consumer/).
include(CMakePackageConfigHelpers)

set(CUTAWAY_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/Cutaway")
install(TARGETS cutaway EXPORT CutawayTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# window_context.hpp belongs to the viewer's GLFW library, which is not installed.
install(DIRECTORY include/cutaway DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        PATTERN window_context.hpp EXCLUDE)
install(TARGETS cutaway-cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET cutaway-view)
  install(TARGETS cutaway-view RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(EXPORT CutawayTargets NAMESPACE Cutaway:: DESTINATION ${CUTAWAY_CMAKE_DIR})
# The build tree is a package too (Cutaway_DIR=build/release): its config beside these targets.
export(EXPORT CutawayTargets NAMESPACE Cutaway:: FILE "${PROJECT_BINARY_DIR}/CutawayTargets.cmake")

configure_package_config_file(cmake/CutawayConfig.cmake.in
                              "${PROJECT_BINARY_DIR}/CutawayConfig.cmake"
                              INSTALL_DESTINATION ${CUTAWAY_CMAKE_DIR})
# 0.x: a minor version may change the API.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/CutawayConfigVersion.cmake"
                                 COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/CutawayConfig.cmake"
              "${PROJECT_BINARY_DIR}/CutawayConfigVersion.cmake"
        DESTINATION ${CUTAWAY_CMAKE_DIR})
