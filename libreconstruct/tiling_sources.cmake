# SPDX-License-Identifier: BSD-3-Clause
# The ITK-free sources of the tiler (contour stacks in, closed meshes with contour ids out), relative
# to libreconstruct/. One list for the library and for the fuzz build, which compiles them with clang
# without ITK (tests/fuzz/CMakeLists.txt), so a new tiler source can't be missing from either.
set(CONTOURMESH_TILING_SOURCES
  src/available_threads.cpp
  src/contours.cpp
  src/detail/band_tiling.cpp
  src/detail/branching.cpp
  src/detail/cap_refinement.cpp
  src/detail/caps.cpp
  src/detail/composite.cpp
  src/detail/correspondence.cpp
  src/detail/crossing_band.cpp
  src/detail/lifted_transition.cpp
  src/detail/shape_interpolation.cpp
  src/detail/slab_remeshing.cpp
  src/detail/slab_tiling.cpp
  src/detail/sliver_collapse.cpp
  src/detail/stack_preparation.cpp
  src/detail/tiling_types.cpp
  src/tiling.cpp)
