// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: read_mesh on a .vtp file (see read_mesh_fuzzer.h).
#include "read_mesh_fuzzer.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return contourmesh::fuzz::fuzz_read_mesh(data, size, ".vtp");
}
