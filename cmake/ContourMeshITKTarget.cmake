# SPDX-License-Identifier: BSD-3-Clause
# Defines ContourMesh::itk, an imported interface target holding the usage requirements of the ITK
# modules libreconstruct uses, from ITK_INCLUDE_DIRS and ITK_LIBRARIES as set by the last
# find_package(ITK COMPONENTS ...).
#
# Why a wrapper: ITK 5.2's imported targets (ITKCommon, ITKIOImageBase, ...) carry no include
# directories; ITK expects consumers to use the ITK_INCLUDE_DIRS variable (or include(${ITK_USE_FILE})).
# Linking this target instead keeps the exported interface of ContourMesh::reconstruct free of paths
# from the build machine: the installed ContourMeshConfig.cmake includes this same file after its own
# find_dependency(ITK ...), so the consumer's ITK fills it in. Being imported, its include directories
# are system include directories for every consumer (ITK headers are not held to our warnings).
#
# UseITK.cmake is not needed: ITK_REQUIRED_*_FLAGS are empty on Debian's ITK 5.2, ITK_LIBRARY_DIRS
# only adds the standard library directory, and libreconstruct registers the image IO factories it
# needs itself (volume.cpp) instead of relying on UseITK's generated registration headers.
if(NOT TARGET ContourMesh::itk)
  add_library(ContourMesh::itk INTERFACE IMPORTED)
  set_target_properties(ContourMesh::itk PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${ITK_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES "${ITK_LIBRARIES}")
endif()
