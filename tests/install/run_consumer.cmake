# cmake -P script behind the install_consumer test (see CMakeLists.txt beside it).
#   1. cmake --install the build tree into WORK_DIR/stage
#   2. move the prefix to WORK_DIR/moved and check no installed CMake file still names the old prefix
#   3. configure + build consumer/ against it with find_package(grtrace CONFIG REQUIRED)
#   4. run the consumer (non-zero exit = a failed check)
#   5. run grtrace_consumer_kit (the testing component's GoogleTest suite) when the consumer built it
#   6. run grtrace_consumer_app (a program on the app component, the application library) when it built it
# Inputs (-D): GRTRACE_BUILD_DIR GRTRACE_CONFIG GRTRACE_VERSION WORK_DIR CONSUMER_SOURCE_DIR
#              CONSUMER_GENERATOR CONSUMER_CXX_COMPILER
cmake_minimum_required(VERSION 3.25)

foreach(_var GRTRACE_BUILD_DIR WORK_DIR CONSUMER_SOURCE_DIR CONSUMER_GENERATOR)
  if(NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
    message(FATAL_ERROR "run_consumer.cmake: -D${_var}=... is required")
  endif()
endforeach()
if(NOT GRTRACE_CONFIG)
  set(GRTRACE_CONFIG Release)
endif()

# Runs one command; on failure prints what it said and stops the test.
function(run_step what)
  string(TIMESTAMP _t0 "%s")
  execute_process(COMMAND ${ARGN}
                  RESULT_VARIABLE _rc
                  OUTPUT_VARIABLE _out
                  ERROR_VARIABLE _err)
  string(TIMESTAMP _t1 "%s")
  math(EXPR _dt "${_t1} - ${_t0}")
  if(NOT _rc EQUAL 0)
    list(JOIN ARGN " " _cmd)
    message(NOTICE "---- stdout of ${what} ----\n${_out}\n---- stderr of ${what} ----\n${_err}")
    message(FATAL_ERROR "install test: ${what} failed (exit ${_rc})\n  command: ${_cmd}")
  endif()
  message(STATUS "install test: ${what}: ok (${_dt} s)")
  set(step_output "${_out}" PARENT_SCOPE)
endfunction()

set(_stage "${WORK_DIR}/stage")
set(_prefix "${WORK_DIR}/moved")
set(_consumer_build "${WORK_DIR}/consumer-build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# 1. install
run_step("cmake --install ${GRTRACE_BUILD_DIR}"
  "${CMAKE_COMMAND}" --install "${GRTRACE_BUILD_DIR}" --prefix "${_stage}" --config "${GRTRACE_CONFIG}")

# 2. relocate
file(RENAME "${_stage}" "${_prefix}")
file(GLOB_RECURSE _configs "${_prefix}/*grtraceConfig.cmake")
list(LENGTH _configs _n)
if(NOT _n EQUAL 1)
  message(FATAL_ERROR "install test: expected one grtraceConfig.cmake under ${_prefix}, found ${_n}: ${_configs}")
endif()
if(NOT EXISTS "${_prefix}/include/grtrace/metric/schwarzschild.hpp")
  message(FATAL_ERROR "install test: headers missing under ${_prefix}/include/grtrace")
endif()
get_filename_component(_cmakedir "${_configs}" DIRECTORY)
file(GLOB _package_files "${_cmakedir}/*.cmake")
foreach(_f IN LISTS _package_files)
  file(READ "${_f}" _text)
  string(FIND "${_text}" "${_stage}" _pos)
  if(NOT _pos EQUAL -1)
    message(FATAL_ERROR "install test: ${_f} hard-codes the install prefix ${_stage}: the package is not relocatable")
  endif()
endforeach()
message(STATUS "install test: package config in ${_cmakedir} is relocatable")

# 3. configure and build the consumer
set(_configure_args
  -S "${CONSUMER_SOURCE_DIR}" -B "${_consumer_build}" -G "${CONSUMER_GENERATOR}"
  "-DCMAKE_BUILD_TYPE=${GRTRACE_CONFIG}"
  "-DCMAKE_PREFIX_PATH=${_prefix}"
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
  "-DGRTRACE_EXPECTED_PREFIX=${_prefix}")
if(CONSUMER_CXX_COMPILER)
  list(APPEND _configure_args "-DCMAKE_CXX_COMPILER=${CONSUMER_CXX_COMPILER}")
endif()
if(GRTRACE_VERSION)
  list(APPEND _configure_args "-DGRTRACE_EXPECTED_VERSION=${GRTRACE_VERSION}")
endif()
run_step("configure consumer" "${CMAKE_COMMAND}" ${_configure_args})
run_step("build consumer" "${CMAKE_COMMAND}" --build "${_consumer_build}" --config "${GRTRACE_CONFIG}")

# 4. run it
set(_exe "${_consumer_build}/grtrace_consumer")
if(NOT EXISTS "${_exe}")
  set(_exe "${_consumer_build}/${GRTRACE_CONFIG}/grtrace_consumer")  # multi-config generators
endif()
run_step("run consumer" "${_exe}")
message(STATUS "install test: consumer says:\n${step_output}")

# 5. the testing component's consumer (a GoogleTest suite using grtrace/testing.hpp), when it was built
get_filename_component(_exe_dir "${_exe}" DIRECTORY)
if(EXISTS "${_exe_dir}/grtrace_consumer_kit")
  run_step("run consumer kit suite" "${_exe_dir}/grtrace_consumer_kit" --gtest_brief=1)
  message(STATUS "install test: kit suite says:\n${step_output}")
endif()

# 6. the app component's consumer (a program on the application library's front door), when it was built
if(EXISTS "${_exe_dir}/grtrace_consumer_app")
  run_step("run consumer app" "${_exe_dir}/grtrace_consumer_app")
  message(STATUS "install test: app consumer says:\n${step_output}")
endif()
