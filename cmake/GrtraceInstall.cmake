# Install rules and the relocatable CMake package config (included at the end of the top-level CMakeLists.txt).
#
#   <prefix>/include/grtrace/...                               the headers
#   <prefix>/<libdir>/cmake/grtrace/grtraceConfig.cmake        find_package(grtrace CONFIG)
#   <prefix>/<libdir>/cmake/grtrace/grtraceConfigVersion.cmake SameMajorVersion
#   <prefix>/<libdir>/cmake/grtrace/grtraceTargets.cmake       grtrace::grtrace (Eigen3 + GLM only)
#   <prefix>/<libdir>/cmake/grtrace/grtraceRenderTargets.cmake grtrace::render  (+ OpenMP, OpenEXR, libpng, libdeflate), if built
#   <prefix>/<libdir>/cmake/grtrace/grtraceVizTargets.cmake    grtrace::viz     (compiled, VTK), if built
#   <prefix>/<libdir>/cmake/grtrace/grtraceAppTargets.cmake    grtrace::app     (the compiled application library:
#                                                              the tools' front door; + grtrace::render), if built
#   <prefix>/<libdir>/cmake/grtrace/grtraceTestingTargets.cmake grtrace::testing (+ GTest), if GTest was found
#
# Each optional target lives in its own export set, so the package config loads it (and looks for its
# dependencies) separately: a consumer of grtrace::grtrace never needs OpenEXR or VTK installed.
include(CMakePackageConfigHelpers)

set(GRTRACE_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/grtrace" CACHE STRING
    "Where the grtrace CMake package config is installed (relative to the prefix)")
mark_as_advanced(GRTRACE_INSTALL_CMAKEDIR)

# ---- headers and the core target --------------------------------------------------------------------
install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/grtrace"
        DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}"
        FILES_MATCHING PATTERN "*.hpp" PATTERN "*.cuh" PATTERN "*.h" PATTERN "*.inl")
install(FILES "${PROJECT_BINARY_DIR}/include/grtrace/version.hpp"    # generated from cmake/version.hpp.in
        DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/grtrace")

install(TARGETS grtrace EXPORT grtraceTargets)
install(EXPORT grtraceTargets
        NAMESPACE grtrace::
        DESTINATION "${GRTRACE_INSTALL_CMAKEDIR}")

# ---- grtrace::render (header-only usage target: OpenMP + OpenEXR + libpng) ----------------------------
set(GRTRACE_EXPORTED_RENDER OFF)
if(TARGET grtrace_render)
  set_target_properties(grtrace_render PROPERTIES EXPORT_NAME render)
  install(TARGETS grtrace_render EXPORT grtraceRenderTargets)
  install(EXPORT grtraceRenderTargets
          NAMESPACE grtrace::
          DESTINATION "${GRTRACE_INSTALL_CMAKEDIR}")
  set(GRTRACE_EXPORTED_RENDER ON)
endif()

# ---- grtrace::testing (header-only usage target: grtrace/testing.hpp + GTest::gtest) -------------------
set(GRTRACE_EXPORTED_TESTING OFF)
if(TARGET grtrace_testing)
  install(TARGETS grtrace_testing EXPORT grtraceTestingTargets)
  install(EXPORT grtraceTestingTargets
          NAMESPACE grtrace::
          DESTINATION "${GRTRACE_INSTALL_CMAKEDIR}")
  set(GRTRACE_EXPORTED_TESTING ON)
endif()

# ---- grtrace::viz (compiled VTK frontend) --------------------------------------------------------------
# Its include directories must be wrapped in $<BUILD_INTERFACE:...>/$<INSTALL_INTERFACE:...> for the export.
set(GRTRACE_EXPORTED_VIZ OFF)
set(GRTRACE_VIZ_VTK_COMPONENTS "")
if(TARGET grtrace_viz)
  set_target_properties(grtrace_viz PROPERTIES EXPORT_NAME viz)
  install(TARGETS grtrace_viz EXPORT grtraceVizTargets
          RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}"
          LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
          ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
          INCLUDES DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
  if(IS_DIRECTORY "${PROJECT_SOURCE_DIR}/viz/include")
    install(DIRECTORY "${PROJECT_SOURCE_DIR}/viz/include/"
            DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}"
            FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
  endif()
  install(EXPORT grtraceVizTargets
          NAMESPACE grtrace::
          DESTINATION "${GRTRACE_INSTALL_CMAKEDIR}")
  # The VTK components the build found (VTK::CommonCore -> CommonCore), so the consumer asks for the same set.
  foreach(_lib IN LISTS VTK_LIBRARIES)
    if(_lib MATCHES "^VTK::(.+)$")
      list(APPEND GRTRACE_VIZ_VTK_COMPONENTS "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  list(JOIN GRTRACE_VIZ_VTK_COMPONENTS " " GRTRACE_VIZ_VTK_COMPONENTS)
  set(GRTRACE_EXPORTED_VIZ ON)
endif()

# ---- grtrace::app (the compiled application library: grtrace/app/front_door.hpp) ------------------------------
# Its headers are installed by app/CMakeLists.txt (component app); its two static libraries and the target that
# links both here. A build with the CUDA backend links CUDA's static runtime: the consumer then needs the toolkit's
# CMake package too (CUDA::cudart_static).
set(GRTRACE_EXPORTED_APP OFF)
if(TARGET grtrace_app)
  install(TARGETS grtrace_app_frames grtrace_app_rays grtrace_app EXPORT grtraceAppTargets
          ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT app
          INCLUDES DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
  install(EXPORT grtraceAppTargets
          NAMESPACE grtrace::
          DESTINATION "${GRTRACE_INSTALL_CMAKEDIR}"
          COMPONENT app)
  set(GRTRACE_EXPORTED_APP ON)
endif()
set(GRTRACE_APP_NEEDS_CUDA ${GRTRACE_HAVE_CUDA})

# ---- package config + version --------------------------------------------------------------------------
configure_package_config_file(
  "${PROJECT_SOURCE_DIR}/cmake/grtraceConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/grtraceConfig.cmake"
  INSTALL_DESTINATION "${GRTRACE_INSTALL_CMAKEDIR}"
  PATH_VARS CMAKE_INSTALL_INCLUDEDIR)

# Header-only unless a compiled library (viz, app) is part of the package.
if(GRTRACE_EXPORTED_VIZ OR GRTRACE_EXPORTED_APP)
  set(_grtrace_arch_independent "")
else()
  set(_grtrace_arch_independent ARCH_INDEPENDENT)
endif()
write_basic_package_version_file(
  "${PROJECT_BINARY_DIR}/grtraceConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}"
  COMPATIBILITY SameMajorVersion
  ${_grtrace_arch_independent})

install(FILES
          "${PROJECT_BINARY_DIR}/grtraceConfig.cmake"
          "${PROJECT_BINARY_DIR}/grtraceConfigVersion.cmake"
        DESTINATION "${GRTRACE_INSTALL_CMAKEDIR}")
