// Options and helpers shared by `smooth`, `run` and `detect` for the methods that detect features.
#pragma once

#include <pipelines/mesh_io.h>
#include <smooth/adjacency.h>
#include <smooth/feature_detection.h>
#include <smooth/mesh.h>

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace contourmesh::cli {

/// Detection options as given on the command line; unset ones keep the method's (or preset's) value.
struct FeatureArgs {
  std::optional<double> gamma;
  std::optional<double> delta;
  std::optional<std::string> measure;
  std::optional<std::string> in_slice;
  std::optional<int> prefilter;
  std::optional<int> window;
  std::optional<double> corner_spread;
  std::string slice_axis;  ///< "", "x", "y" or "z"
};

/// Registers --gamma, --delta, --measure, --in-slice, --prefilter, --window, --corner-spread.
void add_detection_options(CLI::App* cmd, FeatureArgs& args);
/// The detection options and --slice-axis.
void add_feature_options(CLI::App* command, FeatureArgs& args);

/// Sets the detection options that were given on the command line, leaving the others as they are
/// (throws InvalidInputError for a bad --measure or --in-slice).
void apply_detection_args(const FeatureArgs& args, DetectionOptions& options);

/// Makes sure detection can run on `mesh`: keeps the ids it was read with ("file"; a gap in the slice
/// ids is closed with a warning), corrects ids inconsistent with the mesh from its slice planes
/// ("file-repaired", see repair_contour_ids; with a warning naming the inconsistency), recovers them
/// from the slice planes ("slice-planes": along --slice-axis for a mesh without ids, or when the
/// correction fails), or switches `detection` to the curvature-only fallback
/// ("none", with a warning on stderr). Throws InvalidInputError naming the file when --slice-axis was
/// given but the vertices do not lie on planes normal to it.
[[nodiscard]] std::string prepare_contour_ids(Mesh& mesh, const MeshAdjacency& adjacency, const FeatureArgs& args,
                                              const std::string& path, const std::string& command,
                                              DetectionOptions& detection);

/// The per-vertex arrays of a detection, for --labels-out: FeatureLabel (0 smooth, 1 edge, 2 corner,
/// 3 noise), Umbrella, KappaMin, KappaMax, KBelow, K0, KAbove, Psi.
[[nodiscard]] std::vector<PointScalars> detection_arrays(const FeatureDetection& detection);

/// Prepares a mesh read from `path`: non-finite coordinates, bad indices and id mismatches throw
/// InvalidInputError naming `path`; coincident vertices are merged and triangles with a repeated vertex
/// and duplicate triangles dropped (repair_mesh), with one warning line; topology problems that
/// smoothing tolerates (zero-area triangles, non-manifold edges and vertices) are one warning line.
void check_mesh(Mesh& mesh, const std::string& path, const std::string& command);

}  // namespace contourmesh::cli
