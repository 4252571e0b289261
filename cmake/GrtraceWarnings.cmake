# grtrace_target_warnings(<target>): the project's strict warning set for a compiled target.
# Third-party headers (Eigen, GLM, VTK, OpenEXR, GoogleTest) come in through imported targets, which CMake
# marks SYSTEM, so only our own code is held to these.
option(GRTRACE_WARNINGS_AS_ERRORS "Treat compiler warnings as errors (on in the ci preset)" OFF)

function(grtrace_target_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    # C++ sources only: nvcc has its own diagnostics (grtrace_cuda_options in the top CMakeLists.txt).
    target_compile_options(${target} PRIVATE "$<$<COMPILE_LANGUAGE:CXX>:\
-Wall;-Wextra;-Wpedantic;-Wshadow;-Wconversion;-Wsign-conversion;-Wold-style-cast;\
-Wnon-virtual-dtor;-Woverloaded-virtual;-Wcast-align;-Wnull-dereference;-Wdouble-promotion;\
-Wformat=2;-Wimplicit-fallthrough;-Wmisleading-indentation>")
    # GCC 12's -Wrestrict fires inside libstdc++'s own std::string code at -O2 (GCC bug 105329, fixed in 13):
    # a false positive about the library, not our code, so it is switched off for that compiler only.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
      target_compile_options(${target} PRIVATE "$<$<COMPILE_LANGUAGE:CXX>:-Wno-restrict>")
    endif()
    if(GRTRACE_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE "$<$<COMPILE_LANGUAGE:CXX>:-Werror>")
    endif()
  endif()
endfunction()
