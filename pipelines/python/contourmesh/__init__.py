# SPDX-License-Identifier: BSD-3-Clause
"""ContourMesh from Python: CT volumes and label maps to closed meshes with contour ids, and their
feature-preserving smoothing, on numpy arrays.

Volumes are numpy arrays indexed ``[k, j, i]`` (slice, row, column: the layout of SimpleITK's
``GetArrayFromImage``), with ``spacing`` and ``origin`` in x, y, z order (millimetres) and an optional
3 x 3 ``direction`` whose columns are the i, j, k axes in physical (LPS) space. Meshes are ``points``
(n, 3) float64, ``triangles`` (m, 3) int32 (counter-clockwise seen from outside), and per point the
``slice_ids`` and ``contour_ids`` (int32, -1 for points on no slice) that the paper's method and
cross-slice smoothing need.

Long calls release the GIL and take ``progress=callable(stage, fraction)``: return False to cancel
(``CancelledError``); an exception it raises, or Ctrl-C, stops the work and propagates. Errors are
``InvalidInputError`` (a ``ValueError``), its subclasses ``TopologyError`` and ``LimitError``, and
``CancelledError`` (a ``RuntimeError``). See docs/python.md.
"""

from collections import namedtuple as _namedtuple

from ._contourmesh import (  # noqa: F401
    DEFAULT_METHOD,
    CancelledError,
    InvalidInputError,
    LimitError,
    Phantom,
    TopologyError,
    phantom_shapes,
)
from . import _contourmesh as _core

__all__ = [
    "Reconstruction", "Smoothed", "Volume", "LabelMap", "Phantom",
    "reconstruct", "smooth", "detect", "phantom", "phantom_shapes",
    "read_volume", "read_label_map", "list_series", "to_polydata",
    "DEFAULT_METHOD", "InvalidInputError", "TopologyError", "LimitError", "CancelledError",
]

#: reconstruct()'s result: the mesh arrays and a dict of what segmentation and tiling did.
Reconstruction = _namedtuple("Reconstruction", "points triangles slice_ids contour_ids report")
#: smooth()'s result: the smoothed mesh arrays, per-vertex labels (0 smooth, 1 edge, 2 corner, 3 noise;
#: None for methods that do not label) and a dict of what the method did.
Smoothed = _namedtuple("Smoothed", "points triangles slice_ids contour_ids labels report")
#: A volume: array [k, j, i], spacing and origin (x, y, z, mm), direction (3 x 3).
Volume = _namedtuple("Volume", "volume spacing origin direction")
#: A label map: one array [k, j, i] per layer, the geometry, and the labels (dicts: value, layer, name,
#: id, voxels).
LabelMap = _namedtuple("LabelMap", "layers spacing origin direction labels")

_MAX_VERTICES = 50_000_000


def reconstruct(volume, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0), direction=None, *, threshold=300.0,
                otsu=False, label=None, sampling=0.0, smoothing="none", keep="all", min_area=2.0, fill_holes=False,
                end_caps="half-spacing", flat_crossings="patches", single_slice="slab", max_vertices=_MAX_VERTICES,
                threads=0, progress=None):
    """Segments a volume and tiles its contours into a closed mesh with contour ids.

    ``threshold`` (HU, voxels >= it are foreground) or ``otsu=True``; or ``label=N`` (a value, or a
    segment name) to treat ``volume`` as a label map and mesh the voxels holding N. The other options are
    those of ``contourmesh reconstruct`` (docs/reconstruction.md). Returns a ``Reconstruction``.
    """
    return Reconstruction(*_core._reconstruct(
        volume, spacing, origin, direction, float(threshold), bool(otsu), label, float(sampling), smoothing, keep,
        float(min_area), bool(fill_holes), end_caps, flat_crossings, single_slice, int(max_vertices), int(threads),
        progress))


def smooth(points, triangles, slice_ids=None, contour_ids=None, method=None, *, progress=None, threads=0,
           max_vertices=_MAX_VERTICES, **options):
    """Smooths a mesh with ``method``, or without one with the preset ``options["preset"]``: "default"
    (the default: cross-slice smoothing, ``DEFAULT_METHOD``) or "xu2006" (the paper's method as the
    paper configures it). The library's one entry point, as on the command line.

    Methods: "cross-slice" (needs contour ids), "paper" (Xu et al. 2006, needs contour ids), "none",
    "laplacian", "taubin", "mcf", "mindist". ``options`` are the command line's options of the method
    with ``_`` for ``-``: iterations, lambda (or lambda_), mu, beta, boundary; for "paper" also max_levels,
    diffusion, keep_adaptive, gamma, delta, measure, in_slice, prefilter, window, corner_spread,
    slice_axis; for "cross-slice" creases ("none" or "restore": the creases the image's blur rounded,
    restored on a refined mesh whose new vertices follow the input's), reach, along_reach, gamma,
    noise_across, noise_along, profile_model, kinks
    ("ignore" or "bound"), kink_rate, kink_sides ("curves" or "lines"), stages, extension_iterations,
    slice_axis (and no iterations). An option the method does not know is an
    InvalidInputError, as is a diverging run. Returns a ``Smoothed``.
    """
    return Smoothed(*_core._smooth(points, triangles, slice_ids, contour_ids, method, progress, int(threads),
                                   int(max_vertices), options))


def detect(points, triangles, slice_ids=None, contour_ids=None, *, progress=None, **options):
    """The paper's feature detection (Algorithm 2) alone.

    Options: gamma, delta, measure ("length" | "normal"), in_slice ("noise" | "along-line"), prefilter,
    window, corner_spread, slice_axis, mode ("contour-continuity" | "curvature-only"). Returns a dict of
    per-vertex arrays ``labels`` (0 smooth, 1 edge, 2 corner, 3 noise), ``umbrella``, ``kappa_min``,
    ``kappa_max``, ``k_below``, ``k0``, ``k_above``, ``psi`` (NaN where not computed) and the counts
    ``candidates``, ``edges``, ``corners``, ``noise`` and ``gamma``.
    """
    return _core._detect(points, triangles, slice_ids, contour_ids, progress, options)


def phantom(name, spacing=(0.7, 0.7, 2.0), *, noise=20.0, blur=0.5, contour_noise=0.0, seed=1, margin=6.0,
            threads=0):
    """Renders a built-in phantom as a CT volume in HU (bone 1000, tissue 40), as ``contourmesh phantom``
    does with the same options. Returns a ``Volume``; ``Phantom(name)`` is its analytic truth."""
    return Volume(*_core._render_phantom(name, spacing, float(noise), float(blur), float(contour_noise), int(seed),
                                         float(margin), int(threads)))


def read_volume(path, series=None):
    """Reads a volume file (.mha, .nrrd, .nii, .nii.gz) or a DICOM directory (``series``: the Series
    Instance UID when it holds several; see ``list_series``). Returns a ``Volume``."""
    return Volume(*_core._read_volume(str(path), series or ""))


def read_label_map(path):
    """Reads a label map (.nii, .nrrd, ...) or a 3D Slicer segmentation (.seg.nrrd, layered ones too).
    Returns a ``LabelMap``; mesh one label with ``reconstruct(layers[l], spacing, origin, direction,
    label=value)``."""
    return LabelMap(*_core._read_label_map(str(path)))


def list_series(path):
    """The DICOM series of a directory: dicts with uid, number, modality, description, files."""
    return _core._list_series(str(path))


def to_polydata(points, triangles=None, slice_ids=None, contour_ids=None, point_arrays=None):
    """A ``vtkPolyData`` of the arrays (needs VTK's Python package, Debian's python3-vtk9): points,
    triangles, the ids as int point arrays ``ContourId`` and ``ContourIndex`` (as the command line writes
    them), and any ``point_arrays`` {name: per-point array}. Also takes a Reconstruction or a Smoothed
    as its first argument."""
    from ._vtk import to_polydata as _to_polydata
    return _to_polydata(points, triangles, slice_ids, contour_ids, point_arrays)
