#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes the seed corpus of the fuzz targets (tests/fuzz/corpus/<target>/seed_*): small valid files of
every mesh format and variant the readers accept, and byte strings that decode to typical contour
stacks and meshes for the tiling and feature targets. Run again after changing it; the fuzz runs add
their own files next to the seeds only in their scratch copy (scripts/run_fuzzers.sh)."""

import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

# A tetrahedron, outward oriented; slice ids 0 for the base, 1 for the apex.
POINTS = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
TRIS = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
SLICE = [0, 0, 0, 1]
CONTOUR = [0, 0, 0, 0]


def write(target, name, data):
    d = os.path.join(HERE, "corpus", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "seed_" + name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def stl_binary(header=b"binary STL written by make_seeds.py", count=None):
    out = header.ljust(80, b" ")[:80]
    out += struct.pack("<I", len(TRIS) if count is None else count)
    for t in TRIS:
        out += struct.pack("<3f", 0, 0, 0)
        for v in t:
            out += struct.pack("<3f", *POINTS[v])
        out += struct.pack("<H", 0)
    return out


def stl_ascii():
    lines = ["solid tetra"]
    for t in TRIS:
        lines += ["  facet normal 0 0 0", "    outer loop"]
        lines += ["      vertex %g %g %g" % POINTS[v] for v in t]
        lines += ["    endloop", "  endfacet"]
    lines.append("endsolid tetra")
    return "\n".join(lines) + "\n"


def ply_ascii():
    head = ["ply", "format ascii 1.0", "comment seed", "element vertex 4",
            "property float x", "property float y", "property float z",
            "property int ContourId", "property int ContourIndex",
            "element face 4", "property list uchar int vertex_indices", "end_header"]
    body = ["%g %g %g %d %d" % (*POINTS[i], SLICE[i], CONTOUR[i]) for i in range(4)]
    body += ["3 %d %d %d" % t for t in TRIS]
    return "\n".join(head + body) + "\n"


def ply_binary(endian):
    fmt = "binary_little_endian" if endian == "<" else "binary_big_endian"
    head = ["ply", "format %s 1.0" % fmt, "element vertex 4",
            "property double x", "property double y", "property double z",
            "property int ContourId", "property int ContourIndex",
            "element face 3", "property list uchar int vertex_indices",
            "element edge 1", "property int vertex1", "property int vertex2", "end_header"]
    out = ("\n".join(head) + "\n").encode()
    for i in range(4):
        out += struct.pack(endian + "3d2i", *POINTS[i], SLICE[i], CONTOUR[i])
    # two triangles and one quad (fan-triangulated by the reader)
    out += struct.pack(endian + "B3i", 3, *TRIS[0])
    out += struct.pack(endian + "B3i", 3, *TRIS[1])
    out += struct.pack(endian + "B4i", 4, 0, 3, 2, 1)
    out += struct.pack(endian + "2i", 0, 1)
    return out


def obj():
    return "\n".join([
        "# seed", "mtllib none.mtl", "o tetra",
        *["v %g %g %g" % p for p in POINTS],
        "vt 0 0", "vn 0 0 1",
        "f 1 3 2", "f 1/1 2/1 4/1", "f -4//1 -1//1 -2//1", "f 2/1/1 3/1/1 4/1/1",
        "l 1 2", "s off", ""])


def vtp_ascii():
    pts = " ".join("%g %g %g" % p for p in POINTS)
    conn = " ".join("%d %d %d" % t for t in TRIS)
    return f"""<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <PolyData>
    <Piece NumberOfPoints="4" NumberOfVerts="0" NumberOfLines="0" NumberOfStrips="0" NumberOfPolys="4">
      <PointData>
        <DataArray type="Int32" Name="ContourId" format="ascii">{" ".join(map(str, SLICE))}</DataArray>
        <DataArray type="Int32" Name="ContourIndex" format="ascii">{" ".join(map(str, CONTOUR))}</DataArray>
      </PointData>
      <Points>
        <DataArray type="Float64" Name="Points" NumberOfComponents="3" format="ascii">{pts}</DataArray>
      </Points>
      <Polys>
        <DataArray type="Int64" Name="connectivity" format="ascii">{conn}</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">3 6 9 12</DataArray>
      </Polys>
    </Piece>
  </PolyData>
</VTKFile>
"""


def vtp_appended(compressed):
    arrays = [
        ("Int32", "ContourId", 1, struct.pack("<4i", *SLICE)),
        ("Int32", "ContourIndex", 1, struct.pack("<4i", *CONTOUR)),
        ("Float64", "Points", 3, b"".join(struct.pack("<3d", *p) for p in POINTS)),
        ("Int64", "connectivity", 1, b"".join(struct.pack("<3q", *t) for t in TRIS)),
        ("Int64", "offsets", 1, struct.pack("<4q", 3, 6, 9, 12)),
    ]
    blobs, offsets, offset = [], [], 0
    for _, _, _, raw in arrays:
        if compressed:
            c = zlib.compress(raw)
            blob = struct.pack("<4Q", 1, 32768, len(raw), len(c)) + c
        else:
            blob = struct.pack("<Q", len(raw)) + raw
        offsets.append(offset)
        offset += len(blob)
        blobs.append(blob)

    def da(k):
        t, name, comps, _ = arrays[k]
        nc = f' NumberOfComponents="{comps}"' if comps > 1 else ""
        return f'<DataArray type="{t}" Name="{name}"{nc} format="appended" offset="{offsets[k]}"/>'

    comp = ' compressor="vtkZLibDataCompressor"' if compressed else ""
    head = f"""<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64"{comp}>
  <PolyData>
    <Piece NumberOfPoints="4" NumberOfVerts="0" NumberOfLines="0" NumberOfStrips="0" NumberOfPolys="4">
      <PointData>{da(0)}{da(1)}</PointData>
      <Points>{da(2)}</Points>
      <Polys>{da(3)}{da(4)}</Polys>
    </Piece>
  </PolyData>
  <AppendedData encoding="raw">
   _"""
    return head.encode() + b"".join(blobs) + b"\n  </AppendedData>\n</VTKFile>\n"


# fuzz_tiling (byte layout: fuzz_tiling.cpp, decode_stack). Byte 0 = option bits, then the slices;
# layout: per slice a list of (kind, centre x byte, radius byte), kind "outer", "hole" (in outer 0) or
# "raw" (a crossing quadrilateral; needs modes & 32).
def tiling(modes, slices, contours_per_slice, kinds, layout=None):
    invalid = modes & 32
    out = bytes([modes])
    if modes & 4:
        out += bytes([0x08, 0x00])  # min_overlap_fraction
    if modes & 8:
        out += bytes([0x00, 0x20])  # full_dp_limit 33: the banded programme
    if modes & 16:
        out += bytes([0x20, 0x00])  # band_fraction
    out += bytes([slices - 1, 0x40, 0x00, 3, 0x80, 0x00])  # slices, spacing 2, scale 1, w 0
    k = 0
    for s in range(slices):
        if s > 0:
            out += bytes([0x80, 0x00]) + (bytes([0]) if invalid else b"")
        here = layout[s] if layout else [(kinds[(k + c) % len(kinds)], 0x40 + 0x80 * c, 0x40)
                                         for c in range(contours_per_slice)]
        k += len(here)
        out += bytes([len(here)])
        for kind, cx, radius in here:
            if kind == "outer":  # kind 0, centre(4), radius(2), n (9 -> 12 points), phase(2), 4 bytes a point
                out += bytes([0, cx, 0, 0x80, 0, radius, 0, 9, 0, 0])
                out += bytes([0x80, 0x00, 0x00, 0x00]) * 12 + (bytes([0]) if invalid else b"")
            elif kind == "hole":  # kind 6 (in outer 0), radius(2), offset(6), n (5 -> 8 points), phase(2), points, parent
                out += bytes([6, radius or 0x80, 0, 0x80, 0, 0x80, 0, 0x80, 0, 5, 0, 0])
                out += bytes([0x80, 0x00, 0x00, 0x00]) * 8 + bytes([1])
            else:  # kind 7 with invalid pieces allowed: 4 points, the last two crossing
                out += bytes([7, 4]) + bytes([0, 0x40, 0, 0x40, 0, 0, 0xc0, 0, 0x40, 0, 0, 0x40, 0, 0xc0, 0, 0, 0xc0, 0, 0xc0, 0])
                out += bytes([0, 0])  # not a hole, parent -1
    return out


def main():
    write("fuzz_read_stl", "binary.stl", stl_binary())
    write("fuzz_read_stl", "binary_solid_header.stl", stl_binary(b"solid but binary"))
    write("fuzz_read_stl", "binary_count0.stl", stl_binary(count=0))
    write("fuzz_read_stl", "ascii.stl", stl_ascii())
    write("fuzz_read_ply", "ascii.ply", ply_ascii())
    write("fuzz_read_ply", "binary_le.ply", ply_binary("<"))
    write("fuzz_read_ply", "binary_be.ply", ply_binary(">"))
    write("fuzz_read_obj", "tetra.obj", obj())
    write("fuzz_read_vtp", "ascii.vtp", vtp_ascii())
    write("fuzz_read_vtp", "appended_raw.vtp", vtp_appended(False))
    write("fuzz_read_vtp", "appended_zlib.vtp", vtp_appended(True))

    write("fuzz_tiling", "two_slices", tiling(0, 2, 1, ["outer"]))
    write("fuzz_tiling", "stack_end_slice_caps", tiling(1 | 2, 5, 1, ["outer"]))
    write("fuzz_tiling", "two_objects", tiling(0, 3, 2, ["outer"]))
    write("fuzz_tiling", "hole", tiling(0, 4, 2, ["outer", "hole"]))
    big, left, right = ("outer", 0x80, 0x80), ("outer", 0x70, 0x28), ("outer", 0x90, 0x28)
    write("fuzz_tiling", "one_to_two", tiling(0, 3, 0, [], [[big], [left, right], [big]]))
    write("fuzz_tiling", "banded", tiling(8 | 16, 3, 1, ["outer"]) )
    write("fuzz_tiling", "invalid_allowed", tiling(32, 3, 2, ["outer", "raw"]))

    # fuzz_features (byte layout: fuzz_features.cpp). Shape byte first: 0-3 Fourier stack, 4-5 ridge,
    # 6 icosphere, 7 cube.
    write("fuzz_features", "fourier_stack", bytes([0, 0x80, 0, 2, 0x40, 0, 0x80, 0, 0x20, 0, 0x40, 0, 8, 24, 0x40, 0, 0x80, 0, 0]))
    write("fuzz_features", "ridge_stack", bytes([4, 0x80, 0, 0x80, 0, 0x40, 0, 10, 40, 0x30, 0, 0x80, 0, 1, 1, 0x20, 0, 7]))
    write("fuzz_features", "icosphere", bytes([6, 0x80, 0, 2, 0, 0, 0, 6]))
    write("fuzz_features", "cube", bytes([7, 0x80, 0, 4, 0, 0, 0, 6, 1]))
    write("fuzz_features", "noisy_ridge_ids_damaged", bytes([5, 0x80, 0, 0x80, 0, 0x40, 0, 10, 40, 0x30, 0, 0x80, 0, 0,
                                                             3, 0x30, 0, 9, 2, 0x10, 0x20, 1, 2, 0x80, 0x80, 0x40, 0, 0, 0, 6,
                                                             0x0d, 0x40, 0, 0x40, 0, 1, 2, 3, 5, 2]))


if __name__ == "__main__":
    main()
