# SPDX-License-Identifier: BSD-3-Clause
"""The contourmesh Python module against the command line and the analytic phantoms."""
import json
import threading

import numpy as np
import pytest

import contourmesh as cm

SPACING = (1.0, 1.0, 2.0)


def enclosed_volume(points, triangles):
    a, b, c = (points[triangles[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


@pytest.fixture(scope="module")
def box():
    return cm.phantom("ridge-box", SPACING)


@pytest.fixture(scope="module")
def box_mesh(box):
    return cm.reconstruct(box.volume, box.spacing, box.origin, threshold=520)


def test_phantom_volume_is_the_clis(box, cli, tmp_path):
    cli("phantom", "--shape", "ridge-box", "--spacing", "1,1,2", "-o", tmp_path / "box.nrrd", "-q")
    read = cm.read_volume(tmp_path / "box.nrrd")
    assert read.volume.shape == box.volume.shape
    np.testing.assert_array_equal(read.volume, box.volume)
    np.testing.assert_allclose(read.spacing, box.spacing)
    np.testing.assert_allclose(read.origin, box.origin)


def test_reconstruct_and_smooth_match_the_cli(box, box_mesh, cli, tmp_path):
    """Python from numpy and `contourmesh run` on the same phantom give the same mesh, to the bit."""
    smoothed = cm.smooth(*box_mesh[:4])
    out = tmp_path / "box.vtp"  # double coordinates
    run = json.loads(cli("run", "--shape", "ridge-box", "--spacing", "1,1,2", "-o", out, "--json", "-q").stdout)
    assert run["method"] == cm.DEFAULT_METHOD
    assert smoothed.report["method"] == cm.DEFAULT_METHOD
    vtk = pytest.importorskip("vtkmodules.vtkIOXML")
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(str(out))
    reader.Update()
    from vtkmodules.util.numpy_support import vtk_to_numpy
    cli_points = vtk_to_numpy(reader.GetOutput().GetPoints().GetData())
    assert cli_points.shape == smoothed.points.shape
    np.testing.assert_allclose(cli_points, smoothed.points, rtol=0, atol=1e-9)
    assert run["vertices"] == len(smoothed.points)
    assert run["volume_after"] == pytest.approx(enclosed_volume(smoothed.points, smoothed.triangles), rel=1e-9)


def test_reconstruction_is_closed_and_near_the_truth(box_mesh):
    points, triangles, slice_ids, contour_ids, report = box_mesh
    assert points.dtype == np.float64 and points.shape[1] == 3
    assert triangles.dtype == np.int32 and triangles.shape[1] == 3
    assert slice_ids.shape == contour_ids.shape == (len(points),)
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert (counts == 2).all()  # closed: every edge in two triangles
    truth = cm.Phantom("ridge-box")
    assert enclosed_volume(points, triangles) == pytest.approx(truth.volume, rel=0.03)
    assert np.sqrt(np.mean(truth.sdf(points) ** 2)) < 0.3
    assert report["contours"] > 10 and report["threshold"] == 520


def test_phantom_sdf_and_normals_are_callable_on_arrays():
    p = cm.Phantom("cavity")
    assert p.name == "cavity"
    centre = np.zeros((1, 3))
    assert p.sdf(centre)[0] > 0  # the centre is in the cavity: outside the solid
    assert p(centre)[0] == p.sdf(centre)[0]
    normals = p.normal(np.array([[40.0, 0, 0], [0, 0, 40.0]]))
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0)
    assert set(cm.phantom_shapes()) >= {"ridge-box", "femur", "cavity"}


def test_every_method_and_the_labels(box_mesh):
    for method in ("paper", "cross-slice"):
        s = cm.smooth(*box_mesh[:4], method=method)
        assert s.labels.shape == (len(s.points),) and s.labels.max() <= 3
        assert (s.labels == 1).any()  # the roof ridge is found
    s = cm.smooth(*box_mesh[:4], method="taubin", iterations=5, lambda_=0.5, mu=-0.55)
    assert s.labels is None and s.report["iterations"] == 5 and s.report["lambda"] == 0.5
    d = cm.detect(*box_mesh[:4])
    assert d["labels"].shape == (len(box_mesh.points),) and d["edges"] > 0


def test_default_method_and_presets_are_the_librarys(box_mesh):
    """smooth() goes through the library's one entry point: the default preset is cross-slice smoothing,
    preset="xu2006" the paper's method as the paper configures it, and a method excludes a preset."""
    assert cm.DEFAULT_METHOD == "cross-slice"
    default = cm.smooth(*box_mesh[:4])
    explicit = cm.smooth(*box_mesh[:4], method="cross-slice")
    np.testing.assert_array_equal(default.points, explicit.points)
    assert default.report["profiles"] > 0 and "iterations" not in default.report
    xu = cm.smooth(*box_mesh[:4], preset="xu2006")
    assert xu.report["method"] == "paper" and xu.report["iterations"] == 40
    assert not np.array_equal(xu.points, cm.smooth(*box_mesh[:4], method="paper").points)  # corner spread off
    with pytest.raises(cm.InvalidInputError, match="not both"):
        cm.smooth(*box_mesh[:4], method="paper", preset="xu2006")
    with pytest.raises(cm.InvalidInputError, match="unknown preset"):
        cm.smooth(*box_mesh[:4], preset="fast")
    with pytest.raises(cm.InvalidInputError, match="not known to method 'cross-slice'"):
        cm.smooth(*box_mesh[:4], iterations=3)


def test_cross_slice_off_slice_filter_options(box_mesh):
    """The normal filter of the vertices between the slices is an option of cross-slice smoothing."""
    default = cm.smooth(*box_mesh[:4])
    off = cm.smooth(*box_mesh[:4], method="cross-slice", off_slice_filter="none")
    assert not np.array_equal(default.points, off.points)
    axis = cm.smooth(*box_mesh[:4], method="cross-slice", off_slice_motion="axis", normal_iterations=5,
                     normal_sigma=15.0, vertex_iterations=10, vertex_step=1.0, max_move=0.2, contour_max_move=0.0)
    assert axis.points.shape == default.points.shape
    with pytest.raises(cm.InvalidInputError, match="vertex step"):
        cm.smooth(*box_mesh[:4], method="cross-slice", vertex_step=3.0)
    with pytest.raises(cm.InvalidInputError, match="off_slice_filter must be"):
        cm.smooth(*box_mesh[:4], method="cross-slice", off_slice_filter="guided")
    faces = cm.smooth(*box_mesh[:4], method="cross-slice", off_slice_range="faces")
    assert faces.points.shape == default.points.shape
    with pytest.raises(cm.InvalidInputError, match="off_slice_range must be"):
        cm.smooth(*box_mesh[:4], method="cross-slice", off_slice_range="guided")
    with pytest.raises(cm.InvalidInputError, match="angle"):
        cm.smooth(*box_mesh[:4], method="cross-slice", normal_sigma=0.0)
    kept = cm.smooth(*box_mesh[:4], method="cross-slice", off_slice_volume="preserve")
    assert kept.points.shape == default.points.shape
    with pytest.raises(cm.InvalidInputError, match="off_slice_volume must be"):
        cm.smooth(*box_mesh[:4], method="cross-slice", off_slice_volume="keep")


def test_cross_slice_profile_model(box_mesh):
    """The curve fitted across the slices is an option of cross-slice smoothing (parabola by default)."""
    default = cm.smooth(*box_mesh[:4])
    parabola = cm.smooth(*box_mesh[:4], method="cross-slice", profile_model="parabola")
    assert np.array_equal(default.points, parabola.points)
    circle = cm.smooth(*box_mesh[:4], method="cross-slice", profile_model="circle")
    assert circle.points.shape == default.points.shape and np.isfinite(circle.points).all()
    with pytest.raises(cm.InvalidInputError, match="profile_model must be"):
        cm.smooth(*box_mesh[:4], method="cross-slice", profile_model="ellipse")


def test_cross_slice_crease_restoration(box_mesh):
    """Restoring the creases refines the mesh around the roof's ridge: the input's vertices first (the
    labels cover them), more vertices after; other methods and other values refuse it."""
    default = cm.smooth(*box_mesh[:4])
    restored = cm.smooth(*box_mesh[:4], creases="restore")
    n = len(default.points)
    assert len(restored.points) > n and len(restored.slice_ids) == len(restored.points)
    assert restored.labels.shape == (n,)
    np.testing.assert_array_equal(restored.labels, default.labels)
    assert np.array_equal(cm.smooth(*box_mesh[:4], creases="none").points, default.points)
    with pytest.raises(cm.InvalidInputError, match="creases must be"):
        cm.smooth(*box_mesh[:4], creases="sharp")
    with pytest.raises(cm.InvalidInputError, match="not known to method 'taubin'"):
        cm.smooth(*box_mesh[:4], method="taubin", creases="restore")


def test_cross_slice_kinks(box_mesh):
    """Bounding the profiles at their slope breaks is an option of cross-slice smoothing (on by default)."""
    default = cm.smooth(*box_mesh[:4])
    bound = cm.smooth(*box_mesh[:4], method="cross-slice", kinks="bound", kink_rate=0.01)
    assert np.array_equal(default.points, bound.points)
    ignore = cm.smooth(*box_mesh[:4], method="cross-slice", kinks="ignore")
    assert ignore.points.shape == default.points.shape and np.isfinite(ignore.points).all()
    with pytest.raises(cm.InvalidInputError, match="kinks must be"):
        cm.smooth(*box_mesh[:4], method="cross-slice", kinks="cut")
    with pytest.raises(cm.InvalidInputError, match="kink false rate"):
        cm.smooth(*box_mesh[:4], method="cross-slice", kinks="bound", kink_rate=1.5)
    curves = cm.smooth(*box_mesh[:4], method="cross-slice", kink_sides="curves")
    assert np.array_equal(default.points, curves.points)
    lines = cm.smooth(*box_mesh[:4], method="cross-slice", kink_sides="lines")
    assert lines.points.shape == default.points.shape and np.isfinite(lines.points).all()
    with pytest.raises(cm.InvalidInputError, match="kink_sides must be"):
        cm.smooth(*box_mesh[:4], method="cross-slice", kink_sides="flat")


def test_flat_crossings_reach_the_library():
    """An end face on a slice centre (two-objects' prism): decided per flat patch by default, pixel by pixel
    on request, which tiles the half-bone slice's specks into more vertices."""
    two = cm.phantom("two-objects")
    patches = cm.reconstruct(two.volume, two.spacing, two.origin, threshold=520)
    pixels = cm.reconstruct(two.volume, two.spacing, two.origin, threshold=520, flat_crossings="per-pixel")
    assert len(pixels.points) > len(patches.points)
    with pytest.raises(cm.InvalidInputError, match="flat_crossings"):
        cm.reconstruct(two.volume, two.spacing, two.origin, threshold=520, flat_crossings="whole")


def test_single_slice_cavities_reach_the_library():
    """A cavity that one slice alone sees (a hole on slice 3 of a block) stays hollow by default and is
    filled with single_slice="drop"."""
    volume = np.zeros((8, 32, 32), dtype=np.float32)
    volume[1:7, 4:28, 4:28] = 1000.0
    k, j, i = np.mgrid[0:8, 0:32, 0:32]
    volume[(k == 3) & ((j - 16) ** 2 + (i - 16) ** 2 <= 25)] = 0.0
    kept = cm.reconstruct(volume, (1.0, 1.0, 2.0), threshold=500)
    dropped = cm.reconstruct(volume, (1.0, 1.0, 2.0), threshold=500, single_slice="drop")
    assert kept.report["single_slice_cavities"] == 1
    assert dropped.report["single_slice_cavities"] == 0
    assert dropped.report["single_slice_filled"] == 1
    assert kept.report["single_slice_thinned"] + kept.report["single_slice_left_out"] == 0
    assert len(kept.points) > len(dropped.points)
    with pytest.raises(cm.InvalidInputError, match="single_slice"):
        cm.reconstruct(volume, (1.0, 1.0, 2.0), threshold=500, single_slice="keep")


def test_errors_are_typed():
    with pytest.raises(cm.InvalidInputError) as e:
        cm.smooth(np.zeros((3, 3)), [[0, 1, 5]])
    assert isinstance(e.value, ValueError) and "references point 5" in str(e.value)
    with pytest.raises(cm.InvalidInputError, match="not known to method 'laplacian'"):
        cm.smooth(np.eye(3), [[0, 1, 2]], method="laplacian", beta=0.1)
    with pytest.raises(cm.InvalidInputError, match="contour ids"):
        cm.smooth(np.eye(3), [[0, 1, 2]], method="paper")
    with pytest.raises(cm.LimitError) as e:
        cm.smooth(np.eye(3), [[0, 1, 2]], method="none", max_vertices=2)
    assert isinstance(e.value, cm.InvalidInputError)
    with pytest.raises(cm.InvalidInputError, match="no region at or above the threshold"):
        cm.reconstruct(np.zeros((4, 8, 8), np.float32), threshold=300)
    with pytest.raises(cm.InvalidInputError, match="no such file"):
        cm.read_volume("/nonexistent.nrrd")
    assert issubclass(cm.TopologyError, cm.InvalidInputError)
    assert issubclass(cm.CancelledError, RuntimeError)


def test_progress_reports_cancels_and_propagates(box, box_mesh):
    stages = []
    cm.reconstruct(box.volume, box.spacing, box.origin, threshold=520, progress=lambda s, f: stages.append(s))
    assert "segment" in stages and "tile" in stages
    with pytest.raises(cm.CancelledError):
        cm.smooth(*box_mesh[:4], progress=lambda s, f: False)

    def boom(stage, fraction):
        raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        cm.reconstruct(box.volume, box.spacing, box.origin, threshold=520, progress=boom)


def test_long_calls_release_the_gil(box):
    """Another Python thread runs while reconstruct works (it would be blocked if the GIL were held)."""
    ticks = []
    stop = threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(1)
            stop.wait(0.001)

    seen = []

    def progress(stage, fraction):
        seen.append(len(ticks))

    t = threading.Thread(target=ticker)
    t.start()
    try:
        big = cm.phantom("femur", (0.7, 0.7, 2.0))
        cm.reconstruct(big.volume, big.spacing, big.origin, threshold=520, progress=progress)
    finally:
        stop.set()
        t.join()
    assert seen[-1] > seen[0]


def test_label_map_from_numpy_is_its_voxel_volume():
    labels = np.zeros((20, 30, 30), np.uint8)
    labels[4:16, 5:15, 5:20] = 2
    labels[2:18, 18:26, 8:22] = 1
    r = cm.reconstruct(labels, (1.0, 1.0, 2.0), label=2)
    assert enclosed_volume(r.points, r.triangles) == pytest.approx(12 * 10 * 15 * 2.0, rel=0.03)


def test_to_polydata(box_mesh):
    pytest.importorskip("vtkmodules")
    poly = cm.to_polydata(box_mesh)
    assert poly.GetNumberOfPoints() == len(box_mesh.points)
    assert poly.GetNumberOfCells() == len(box_mesh.triangles)
    assert poly.GetPointData().GetArray("ContourId").GetValue(0) == box_mesh.slice_ids[0]
    s = cm.smooth(*box_mesh[:4])
    labelled = cm.to_polydata(s)
    assert labelled.GetPointData().GetArray("FeatureLabel") is not None
