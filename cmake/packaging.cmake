# SPDX-License-Identifier: BSD-3-Clause
# The ContourMesh CMake package: `cmake --install <build> --prefix <prefix>` puts
#   <prefix>/include/contourmesh/{smooth,reconstruct,vtk}/*.h   public headers
#   <prefix>/lib/libcontourmesh_*.a                       the libraries (static by default)
#   <prefix>/bin/contourmesh                              the CLI
#   <prefix>/lib/cmake/ContourMesh/                       ContourMeshConfig.cmake, version file, targets
# so that another project can `find_package(ContourMesh)` and link ContourMesh::smooth,
# ContourMesh::reconstruct and ContourMesh::vtk. The install(TARGETS) rules live next to each target
# (libsmooth/, libreconstruct/, pipelines/); this file writes the package files. See docs/install.md.
include(CMakePackageConfigHelpers)

set(CONTOURMESH_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/ContourMesh")

# Components = the libraries this build tree installs; the config only looks for their dependencies.
set(CONTOURMESH_INSTALLED_COMPONENTS smooth)
if(TARGET contourmesh_reconstruct)
  list(APPEND CONTOURMESH_INSTALLED_COMPONENTS reconstruct)
endif()
if(TARGET contourmesh_vtk)
  list(APPEND CONTOURMESH_INSTALLED_COMPONENTS vtk)
endif()

# Space-separated for the config file (the lists come up from libreconstruct/ and pipelines/).
list(JOIN CONTOURMESH_ITK_COMPONENTS " " CONTOURMESH_ITK_COMPONENT_ARGS)
list(JOIN CONTOURMESH_VTK_COMPONENTS " " CONTOURMESH_VTK_COMPONENT_ARGS)

install(EXPORT ContourMeshTargets
  NAMESPACE ContourMesh::
  FILE ContourMeshTargets.cmake
  DESTINATION "${CONTOURMESH_INSTALL_CMAKEDIR}")

configure_package_config_file(
  "${CMAKE_CURRENT_LIST_DIR}/ContourMeshConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/ContourMeshConfig.cmake"
  INSTALL_DESTINATION "${CONTOURMESH_INSTALL_CMAKEDIR}")

# 0.x: no API or ABI stability between minor versions (semantic versioning, item 4), so 0.1.3 may
# satisfy a request for 0.1 but 0.2 must not; SameMajorVersion would accept 0.2 for 0.1. From 1.0 on
# this becomes SameMajorVersion. The check on the pointer size (not ARCH_INDEPENDENT) stays: the
# package holds compiled libraries.
write_basic_package_version_file(
  "${PROJECT_BINARY_DIR}/ContourMeshConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)

install(FILES
  "${PROJECT_BINARY_DIR}/ContourMeshConfig.cmake"
  "${PROJECT_BINARY_DIR}/ContourMeshConfigVersion.cmake"
  DESTINATION "${CONTOURMESH_INSTALL_CMAKEDIR}")
if("reconstruct" IN_LIST CONTOURMESH_INSTALLED_COMPONENTS)
  install(FILES "${CMAKE_CURRENT_LIST_DIR}/ContourMeshITKTarget.cmake"
    DESTINATION "${CONTOURMESH_INSTALL_CMAKEDIR}")
endif()

# BSD-3-Clause asks binary redistributions to carry the notice.
install(FILES "${PROJECT_SOURCE_DIR}/LICENSE" DESTINATION "${CMAKE_INSTALL_DOCDIR}")
