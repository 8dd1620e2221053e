// SPDX-License-Identifier: BSD-3-Clause
// The bad-input catalogue of docs/robustness.md, one test per entry: the contourmesh command run as a
// user runs it, on files written here. A rejected input exits 2 with one line on stderr naming the file
// and what is wrong, and leaves no output behind (an existing output untouched); a repaired input exits
// 0 with a warning.
// This part: meshes that are repaired or smoothed as they are, and missing or inconsistent contour ids.
// The support header first: it includes ITK, whose bundled Eigen must not follow the system one.
#include "bad_input_support.h"

#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/smooth/adjacency.h>
#include <contourmesh/smooth/shapes.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

namespace contourmesh {
namespace {

using namespace bad_input_test;

// ----- Meshes that are repaired or smoothed as they are --------------------------------------------------

TEST_F(BadInput, ZeroAreaAndDuplicateTrianglesAreRepairedWithAWarning) {
  Mesh m = stack_;
  const Index n = m.num_vertices();
  const Triangle t = m.triangles[20];
  m.triangles.push_back(m.triangles[3]);        // duplicate
  m.triangles.push_back({t[2], t[1], t[0]});    // duplicate, reversed
  m.triangles.push_back({t[0], t[0], t[1]});    // a repeated vertex: zero area by construction
  m.positions.conservativeResize(3, n + 1);     // a sliver: three distinct vertices on one line
  m.positions.col(n) = 0.5 * (m.positions.col(t[0]) + m.positions.col(t[1]));
  m.slice_ids.push_back(kNoId);
  m.contour_ids.push_back(kNoId);
  m.triangles.push_back({t[0], n, t[1]});
  write_mesh(m, dir_ / "dirty.ply");
  for (const std::string method : {"taubin", "paper"}) {
    const fs::path out = dir_ / ("clean_" + method + ".ply");
    const CliRun r = run("smooth " + (dir_ / "dirty.ply").string() + " -o " + out.string() + " --method " + method +
                         " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("repaired: dropped 1 triangle with a repeated vertex and 2 duplicate triangles"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("degenerate triangle " + std::to_string(stack_.num_faces()) + " (zero area)"),
              std::string::npos)
        << "the sliver is kept, and reported: " << r.err;
    EXPECT_EQ(json_of(r)["faces"], stack_.num_faces() + 1);
    const Mesh result = read_mesh(out);
    EXPECT_EQ(result.num_faces(), stack_.num_faces() + 1);
    EXPECT_TRUE(result.positions.allFinite()) << method;
  }
}

TEST_F(BadInput, CoincidentVerticesOfATriangleSoupAreMerged) {
  // Each triangle with its own three vertices: without merging, smoothing would shrink every one alone.
  const Mesh sphere = make_icosphere(2);
  Mesh soup;
  soup.positions.resize(3, 3 * sphere.num_faces());
  for (Index f = 0; f < sphere.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) soup.positions.col(3 * f + k) = sphere.positions.col(sphere.triangles[f][k]);
    soup.triangles.push_back({3 * f, 3 * f + 1, 3 * f + 2});
  }
  write_mesh(soup, dir_ / "soup.ply");
  const CliRun r = run("smooth " + (dir_ / "soup.ply").string() + " -o " + (dir_ / "out.ply").string() +
                       " --method taubin --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(
      r.err.find("merged " + std::to_string(soup.num_vertices() - sphere.num_vertices()) + " coincident vertices"),
      std::string::npos)
      << r.err;
  const auto j = json_of(r);
  EXPECT_EQ(j["vertices"], sphere.num_vertices());
  EXPECT_TRUE(j["is_closed"].get<bool>());
}

TEST_F(BadInput, NonManifoldEdgesAndVerticesAreSmoothedWithAWarning) {
  Mesh m = stack_;
  const Index n = m.num_vertices();
  const Triangle t = m.triangles[30];
  m.positions.conservativeResize(3, n + 3);
  m.positions.col(n) = m.positions.col(t[0]) + Eigen::Vector3d(4, 4, 0.3);   // a fin on edge (t0, t1)
  m.positions.col(n + 1) = m.positions.col(t[2]) + Eigen::Vector3d(5, 0, 0.2);  // a flap at vertex t2
  m.positions.col(n + 2) = m.positions.col(t[2]) + Eigen::Vector3d(5, 1, -0.2);
  m.triangles.push_back({t[0], t[1], n});
  m.triangles.push_back({t[2], n + 1, n + 2});
  for (int k = 0; k < 3; ++k) {
    m.slice_ids.push_back(kNoId);
    m.contour_ids.push_back(kNoId);
  }
  write_mesh(m, dir_ / "nonmanifold.vtp");
  for (const std::string method : {"paper", "taubin", "laplacian", "mcf", "mindist"}) {
    const fs::path out = dir_ / ("out_" + method + ".vtp");
    const CliRun r =
        run("smooth " + (dir_ / "nonmanifold.vtp").string() + " -o " + out.string() + " --method " + method);
    ASSERT_EQ(r.code, 0) << method << ": " << r.err;
    EXPECT_NE(r.err.find("topology problems left as they are, first: non-manifold edge between vertices"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(read_mesh(out).positions.allFinite()) << method;
  }
  const CliRun d = run("detect " + (dir_ / "nonmanifold.vtp").string() + " -o " + (dir_ / "labels.vtp").string());
  EXPECT_EQ(d.code, 0) << d.err;
}

TEST_F(BadInput, OpenMeshesAreSmoothedWithTheirBoundaryFixed) {
  // The stack without its caps: an open tube.
  Mesh tube = stack_;
  std::erase_if(tube.triangles, [&](const Triangle& t) {
    return tube.slice_ids[t[0]] == kNoId || tube.slice_ids[t[1]] == kNoId || tube.slice_ids[t[2]] == kNoId;
  });
  write_mesh(tube, dir_ / "tube.ply");
  const MeshAdjacency adjacency = build_adjacency(tube);
  ASSERT_FALSE(adjacency.is_closed());
  for (const std::string method : {"paper", "taubin"}) {
    const fs::path out = dir_ / ("tube_" + method + ".ply");
    const CliRun r = run("smooth " + (dir_ / "tube.ply").string() + " -o " + out.string() + " --method " + method +
                         " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_FALSE(json_of(r)["is_closed"].get<bool>());
    const Mesh result = read_mesh(out);
    ASSERT_EQ(result.num_vertices(), tube.num_vertices());
    double boundary_moved = 0.0, interior_moved = 0.0;
    for (Index i = 0; i < tube.num_vertices(); ++i) {
      const double d = (result.positions.col(i) - tube.positions.col(i)).norm();
      double& worst = adjacency.is_boundary[i] ? boundary_moved : interior_moved;
      worst = std::max(worst, d);
    }
    EXPECT_EQ(boundary_moved, 0.0) << method << ": --boundary fixed is the default";
    EXPECT_GT(interior_moved, 0.0) << method;
  }
}

// (The paper's detection: it has a fallback without ids; cross-slice smoothing, the default, needs them.)
TEST_F(BadInput, MissingContourIdsFallBackWithAWarning) {
  write_mesh(stack_, dir_ / "plain.stl");
  CliRun r =
      run("detect " + (dir_ / "plain.stl").string() + " -o " + (dir_ / "l.vtp").string() + " --method paper --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json_of(r)["mode"], "curvature-only");
  EXPECT_NE(r.err.find("has no contour ids"), std::string::npos) << r.err;
  r = run("detect " + (dir_ / "plain.stl").string() + " -o " + (dir_ / "l.vtp").string() + " --slice-axis z --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json_of(r)["id_source"], "slice-planes");
  r = run("detect " + (dir_ / "plain.stl").string() + " -o " + (dir_ / "l.vtp").string() + " --slice-axis x");
  expect_rejected(r, {"plain.stl", "do not lie on planes normal to the slice axis x"});
  // The default, cross-slice smoothing, refuses a mesh without ids, naming the way out.
  r = run("smooth " + (dir_ / "plain.stl").string() + " -o " + (dir_ / "o.stl").string());
  expect_rejected(r, {"plain.stl", "cross-slice smoothing needs contour ids", "--slice-axis"});
  r = run("smooth " + (dir_ / "plain.stl").string() + " -o " + (dir_ / "o.stl").string() + " --slice-axis z");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST_F(BadInput, InconsistentContourIdsAreCorrected) {
  auto detect = [&](const Mesh& m, const std::string& name) {
    write_mesh(m, dir_ / name);
    return run("detect " + (dir_ / name).string() + " -o " + (dir_ / "labels.ply").string() + " --method paper --json");
  };
  const CliRun clean = detect(stack_, "clean.ply");
  ASSERT_EQ(clean.code, 0) << clean.err;
  const auto truth = json_of(clean);
  EXPECT_EQ(truth["id_source"], "file");
  auto expect_same_labels = [&](const CliRun& r, const std::string& source, const std::string& warning) {
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = json_of(r);
    EXPECT_EQ(j["id_source"], source);
    EXPECT_EQ(j["edge_vertices"], truth["edge_vertices"]);
    EXPECT_EQ(j["noise_vertices"], truth["noise_vertices"]);
    EXPECT_NE(r.err.find(warning), std::string::npos) << r.err;
  };
  // Ids that jump by 2: slice 4 onwards numbered from 5.
  Mesh gap = stack_;
  for (auto& s : gap.slice_ids) s += s >= 4 ? 1 : 0;
  expect_same_labels(detect(gap, "gap.ply"), "file", "the slice ids skip 1 unused value: renumbered them");
  // A vertex of slice 4 labelled slice 5: a same-slice edge between two slice planes.
  Index v = 0;
  while (stack_.slice_ids[v] != 4) ++v;
  Mesh wrong = stack_;
  wrong.slice_ids[v] = 5;
  expect_same_labels(detect(wrong, "wrong.ply"), "file-repaired", "inconsistent contour ids (");
  // Nonsense ids: negative (refused: -1 is the only legal negative id), and far beyond the others.
  Mesh negative = stack_;
  negative.slice_ids[v] = -7;
  expect_rejected(detect(negative, "negative.ply"),
                  {"negative.ply: vertex " + std::to_string(v) + " has slice id -7", "ids are >= 0, or -1"});
  Mesh huge = stack_;
  huge.slice_ids[v] = 1'000'000;
  expect_same_labels(detect(huge, "huge.ply"), "file-repaired", "corrected them from the slice planes");
  // Off the planes (noise across the slices too): nothing to recover from, curvature-only detection.
  Mesh off_planes = stack_;
  add_noise(off_planes, {0.05, 3, NoiseDirection::Isotropic});
  off_planes.slice_ids[v] = 6;
  const CliRun r = detect(off_planes, "off_planes.ply");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json_of(r)["mode"], "curvature-only");
  EXPECT_NE(r.err.find("no slice planes to recover them from"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace contourmesh
