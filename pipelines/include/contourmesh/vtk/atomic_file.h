// SPDX-License-Identifier: BSD-3-Clause
// Atomic output files for the pipelines: the implementation is libsmooth's (contourmesh/smooth/atomic_file.h), which
// every writer of ContourMesh shares; this header keeps the pipelines' include path working.
#pragma once

#include <contourmesh/smooth/atomic_file.h>
