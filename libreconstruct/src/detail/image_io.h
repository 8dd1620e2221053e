// SPDX-License-Identifier: BSD-3-Clause
// Private: ITK image IO set-up shared by the volume and label-map readers.
#pragma once

namespace contourmesh::detail {

/// Registers the MetaImage, NRRD, NIfTI and GDCM image IO factories, once per process, so that reading
/// does not depend on UseITK.cmake's generated registration code. Thread-safe.
void register_image_io_factories();

}  // namespace contourmesh::detail
