# SPDX-License-Identifier: BSD-3-Clause
# Packaging test (cmake -P): install the build tree into a scratch prefix, check the installed CLI runs,
# then configure, build and run pipelines/examples/downstream against the installation with
# find_package(ContourMesh), with the same generator, compilers and build type as the build tree.
#
# Inputs (-D): BUILD_DIR, SOURCE_DIR, WORK_DIR, GENERATOR, MAKE_PROGRAM, C_COMPILER, CXX_COMPILER, CONFIG,
# and the build tree's BINDIR, LIBDIR, INCLUDEDIR (GNUInstallDirs, relative to the prefix).
# WORK_DIR is wiped first. Sanitizer builds (asan preset) need nothing extra here: the installed package
# config puts -fsanitize=<list> in the compile and link interface of its targets, so the downstream
# program is instrumented like the libraries it links (cmake/ContourMeshConfig.cmake.in says why that
# is required), and it runs under the ASAN_OPTIONS / UBSAN_OPTIONS of the test environment.
cmake_minimum_required(VERSION 3.25)

foreach(var IN ITEMS BUILD_DIR SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER C_COMPILER BINDIR LIBDIR INCLUDEDIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "downstream_test.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT CONFIG)
  set(CONFIG Release)
endif()

set(prefix "${WORK_DIR}/prefix")
set(downstream_build "${WORK_DIR}/downstream-build")
set(output "${WORK_DIR}/out/ridge-box.stl")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/out")

# step(NAME COMMAND...): run a command, print its output, stop the test when it fails.
function(step name)
  message(STATUS "[${name}] ${ARGN}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "[${name}] failed (${rc}):\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

step(install "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}" --config "${CONFIG}")

foreach(path IN ITEMS
    ${INCLUDEDIR}/contourmesh/smooth/feature_smoothing.h ${INCLUDEDIR}/contourmesh/reconstruct/reconstruction.h
    ${INCLUDEDIR}/contourmesh/vtk/mesh_io.h
    ${LIBDIR}/cmake/ContourMesh/ContourMeshConfig.cmake ${LIBDIR}/cmake/ContourMesh/ContourMeshConfigVersion.cmake
    ${LIBDIR}/cmake/ContourMesh/ContourMeshTargets.cmake ${BINDIR}/contourmesh)
  if(NOT EXISTS "${prefix}/${path}")
    message(FATAL_ERROR "the installation lacks ${path} (prefix ${prefix})")
  endif()
endforeach()

step(cli "${prefix}/${BINDIR}/contourmesh" --help)
if(NOT step_output MATCHES "reconstruct")
  message(FATAL_ERROR "installed contourmesh --help does not list its commands:\n${step_output}")
endif()

set(configure_args -S "${SOURCE_DIR}/pipelines/examples/downstream" -B "${downstream_build}"
    -G "${GENERATOR}" "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_C_COMPILER=${C_COMPILER}"
    "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_BUILD_TYPE=${CONFIG}")
if(MAKE_PROGRAM)
  list(APPEND configure_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
endif()
step(configure "${CMAKE_COMMAND}" ${configure_args})
step(build "${CMAKE_COMMAND}" --build "${downstream_build}" --config "${CONFIG}")

set(program "${downstream_build}/contourmesh_downstream")
if(NOT EXISTS "${program}")  # multi-config generators put it in a per-configuration directory
  set(program "${downstream_build}/${CONFIG}/contourmesh_downstream")
endif()
if(NOT EXISTS "${program}")
  message(FATAL_ERROR "the downstream build produced no contourmesh_downstream in ${downstream_build}")
endif()
step(run "${program}" "${output}")
message(STATUS "${step_output}")

if(NOT EXISTS "${output}")
  message(FATAL_ERROR "the downstream program exited 0 but wrote no ${output}")
endif()
file(SIZE "${output}" size)
if(size LESS 1000)  # binary STL: 84-byte header + 50 bytes per triangle
  message(FATAL_ERROR "${output} is only ${size} bytes")
endif()
message(STATUS "packaging test passed: installed to ${prefix}, downstream wrote ${output} (${size} bytes)")
