// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/input_policy.h"

#include "contourmesh/smooth/adjacency.h"
#include "contourmesh/smooth/contour_structure.h"
#include "contourmesh/smooth/errors.h"

#include "detail/edge_uses.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <utility>

namespace contourmesh {

std::string_view to_string(IdSource source) {
  switch (source) {
    case IdSource::None: return "none";
    case IdSource::File: return "file";
    case IdSource::FileRepaired: return "file-repaired";
    case IdSource::SlicePlanes: return "slice-planes";
  }
  return "none";
}

namespace {

// ----- Orientation ------------------------------------------------------------------------------------

using detail::EdgeUse;
using detail::for_each_edge;
using detail::sorted_edge_uses;

double signed_volume_term(const Mesh& mesh, const Triangle& t) {
  return mesh.positions.col(t[0]).dot(mesh.positions.col(t[1]).cross(mesh.positions.col(t[2]))) / 6.0;
}

// ----- Contour ids ------------------------------------------------------------------------------------

std::string axis_name(const Eigen::Vector3d& axis) {
  for (int k = 0; k < 3; ++k) {
    if (axis.normalized().cwiseAbs()[k] > 1.0 - 1e-12) return std::string(1, "xyz"[k]);
  }
  std::ostringstream s;
  s << "(" << axis.x() << ", " << axis.y() << ", " << axis.z() << ")";
  return s.str();
}

// The coordinate axis within about 2 degrees of `axis`, if any (CT slices are nearly always axial).
std::optional<Eigen::Vector3d> nearest_coordinate_axis(const Eigen::Vector3d& axis) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(axis[k]) > std::cos(2.0 * 3.14159265358979 / 180.0)) return Eigen::Vector3d::Unit(k);
  }
  return std::nullopt;
}

double bounding_diagonal(const Eigen::Matrix3Xd& p) {
  return p.cols() == 0 ? 0.0 : (p.rowwise().maxCoeff() - p.rowwise().minCoeff()).norm();
}

// When every vertex with a slice id has the same one: how far those vertices stray from their best-fit
// plane (0 for a flat contour). -1 when the ids name more than one slice.
double single_slice_thickness(const Mesh& mesh, std::int32_t& id) {
  id = kNoId;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Index count = 0;
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    const std::int32_t s = mesh.slice_ids[i];
    if (s == kNoId) continue;
    if (id != kNoId && s != id) return -1.0;
    id = s;
    sum += mesh.positions.col(i);
    ++count;
  }
  if (count < 4) return 0.0;
  const Eigen::Vector3d centre = sum / static_cast<double>(count);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] == kNoId) continue;
    const Eigen::Vector3d d = mesh.positions.col(i) - centre;
    scatter += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const Eigen::Vector3d normal = eig.eigenvectors().col(0);
  double thickness = 0.0;
  for (Index i = 0; i < mesh.num_vertices(); ++i) {
    if (mesh.slice_ids[i] != kNoId)
      thickness = std::max(thickness, std::abs((mesh.positions.col(i) - centre).dot(normal)));
  }
  return 2.0 * thickness;
}

class IdPreparation {
 public:
  IdPreparation(PreparedMesh& out, const InputPolicyOptions& options) : out_(out), options_(options) {}

  void run() {
    Mesh& mesh = out_.mesh;
    if (options_.ids == ContourIdUse::PassThrough) {
      out_.id_source = mesh.has_contour_ids() ? IdSource::File : IdSource::None;
      return;
    }
    if (mesh.has_contour_ids() &&
        std::all_of(mesh.slice_ids.begin(), mesh.slice_ids.end(), [](std::int32_t s) { return s == kNoId; })) {
      out_.warnings.push_back("every slice id is -1 (no vertex on a slice): treated as a mesh without contour ids");
      mesh.slice_ids.clear();
      mesh.contour_ids.clear();
    }
    const MeshAdjacency adjacency = build_adjacency(mesh);
    if (mesh.has_contour_ids()) {
      from_file(adjacency);
    } else {
      without_ids(adjacency, "the mesh has no contour ids");
    }
  }

 private:
  void from_file(const MeshAdjacency& adjacency) {
    Mesh& mesh = out_.mesh;
    if (const std::size_t gaps = compact_slice_ids(mesh)) {
      out_.warnings.push_back("the slice ids skip " + std::to_string(gaps) + " unused value" + (gaps == 1 ? "" : "s") +
                              ": renumbered them consecutively");
    }
    std::int32_t id = kNoId;
    const double thickness = single_slice_thickness(mesh, id);
    if (thickness > 1e-4 * bounding_diagonal(mesh.positions)) {
      std::ostringstream what;
      what << "every vertex has slice id " << id << ", but the vertices do not lie in one plane (they span "
           << thickness << " across their best-fit plane)";
      if (!options_.slice_axis) {
        throw InvalidInputError(what.str() +
                                ": the ids cannot describe slices; give the slice axis to recover them by binning "
                                "the vertices into slice planes");
      }
      recover_along_axis(adjacency, what.str());
      return;
    }
    const std::string problem = find_contour_id_problem(mesh, adjacency);
    if (problem.empty()) {
      out_.id_source = IdSource::File;
      return;
    }
    // Inconsistent ids: correct them from the geometry where it allows, else recover, else fall back.
    std::vector<Eigen::Vector3d> axes;
    if (options_.slice_axis) {
      axes.push_back(*options_.slice_axis);
    } else {
      try {
        const Eigen::Vector3d estimate = estimate_slice_axis(mesh);
        axes.push_back(estimate);
        if (const auto snapped = nearest_coordinate_axis(estimate)) axes.push_back(*snapped);
      } catch (const InvalidInputError&) {
      }
    }
    for (const Eigen::Vector3d& a : axes) {
      if (repair_contour_ids(mesh, adjacency, a)) {
        out_.warnings.push_back("inconsistent contour ids (" + problem + "): corrected them from the slice planes");
        out_.id_source = IdSource::FileRepaired;
        return;
      }
    }
    Mesh recovered = mesh;
    for (const Eigen::Vector3d& a : axes) {
      if (assign_ids_by_slice_planes(recovered, adjacency, a, options_.slice_tolerance)) {
        out_.warnings.push_back("inconsistent contour ids (" + problem + "): recovered them from the slice planes");
        mesh = std::move(recovered);
        out_.id_source = IdSource::SlicePlanes;
        return;
      }
    }
    no_usable_ids("inconsistent contour ids (" + problem + ") and no slice planes to recover them from");
  }

  void without_ids(const MeshAdjacency& adjacency, const std::string& what) {
    if (options_.slice_axis) {
      recover_along_axis(adjacency, "");
      return;
    }
    no_usable_ids(what);
  }

  void recover_along_axis(const MeshAdjacency& adjacency, const std::string& why) {
    Mesh& mesh = out_.mesh;
    if (!assign_ids_by_slice_planes(mesh, adjacency, *options_.slice_axis, options_.slice_tolerance)) {
      throw InvalidInputError((why.empty() ? std::string() : why + ", and ") +
                              "the vertices do not lie on planes normal to the slice axis " +
                              axis_name(*options_.slice_axis) +
                              ", so contour ids cannot be recovered (not a contour-based mesh?)");
    }
    if (!why.empty()) {
      out_.warnings.push_back(why + ": recovered the ids from the slice planes along " +
                              axis_name(*options_.slice_axis));
    }
    out_.id_source = IdSource::SlicePlanes;
  }

  void no_usable_ids(const std::string& what) {
    if (options_.missing_ids == MissingIds::Refuse) {
      throw InvalidInputError(what + ": give the slice axis to recover the ids of a contour-stack mesh, or choose a "
                                     "method or detection mode that does without them");
    }
    out_.warnings.push_back(what + ": using curvature-only feature detection (give the slice axis to recover the "
                                   "ids of a contour-stack mesh)");
    out_.mesh.slice_ids.clear();
    out_.mesh.contour_ids.clear();
    out_.id_source = IdSource::None;
    out_.detection_mode = DetectionMode::CurvatureOnly;
  }

  PreparedMesh& out_;
  const InputPolicyOptions& options_;
};

// Step 1: what cannot be used as it is and cannot be fixed without guessing.
void refuse_unusable(const Mesh& mesh) {
  const Index n = mesh.num_vertices();
  if (n == 0) throw InvalidInputError("the mesh has no vertices");
  if (mesh.num_faces() == 0) throw InvalidInputError("the mesh has no triangles (" + std::to_string(n) + " points)");
  for (Index i = 0; i < n; ++i) {
    const auto p = mesh.positions.col(i);
    if (p.allFinite() && p.cwiseAbs().maxCoeff() <= kMaxAbsCoordinate) continue;
    std::ostringstream msg;
    msg << "vertex " << i << " has " << (p.allFinite() ? "a coordinate beyond +-1e30" : "a non-finite coordinate")
        << " (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
    if (p.allFinite()) msg << ": squares and cubes of it overflow; scale the mesh to sensible units";
    throw InvalidInputError(msg.str());
  }
  if ((!mesh.slice_ids.empty() || !mesh.contour_ids.empty()) && !mesh.has_contour_ids()) {
    throw InvalidInputError("the contour-id arrays hold " + std::to_string(mesh.slice_ids.size()) + " and " +
                            std::to_string(mesh.contour_ids.size()) + " entries for " + std::to_string(n) +
                            " vertices");
  }
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (Index v : mesh.triangles[f]) {
      if (v < 0 || v >= n) {
        throw InvalidInputError("triangle " + std::to_string(f) + " references vertex " + std::to_string(v) +
                                " but the mesh has " + std::to_string(n) + " vertices");
      }
    }
  }
  if (mesh.has_contour_ids()) {
    for (Index i = 0; i < n; ++i) {
      if (mesh.slice_ids[i] < kNoId || mesh.contour_ids[i] < kNoId) {
        throw InvalidInputError("vertex " + std::to_string(i) + " has slice id " + std::to_string(mesh.slice_ids[i]) +
                                " and contour id " + std::to_string(mesh.contour_ids[i]) +
                                ": ids are >= 0, or -1 for a vertex on no slice");
      }
    }
  }
}

}  // namespace

std::optional<std::pair<Index, Index>> find_orientation_conflict(const Mesh& mesh) {
  const std::vector<EdgeUse> uses = sorted_edge_uses(mesh.triangles);
  std::optional<std::pair<Index, Index>> conflict;
  for_each_edge(uses, [&](std::size_t k, std::size_t count) {
    if (!conflict && count == 2 && uses[k].forward == uses[k + 1].forward) {
      conflict = std::make_pair(uses[k].face, uses[k + 1].face);
    }
  });
  return conflict;
}

namespace {

// The triangles linked across each edge of exactly two triangles (CSR), with the parity "these two must
// differ in flip state" (they traverse the edge in the same direction); `open` marks triangles with a
// boundary edge.
struct TriangleLinks {
  struct Link {
    Index other;
    bool same_direction;
  };
  std::vector<Index> offsets;
  std::vector<Link> links;
  std::vector<std::uint8_t> open;
};

TriangleLinks link_triangles(const Mesh& mesh) {
  const Index nf = mesh.num_faces();
  const std::vector<EdgeUse> uses = sorted_edge_uses(mesh.triangles);
  TriangleLinks t;
  t.offsets.assign(static_cast<std::size_t>(nf) + 1, 0);
  t.open.assign(static_cast<std::size_t>(nf), 0);
  for_each_edge(uses, [&](std::size_t k, std::size_t count) {
    if (count == 2) {
      ++t.offsets[uses[k].face + 1];
      ++t.offsets[uses[k + 1].face + 1];
    } else if (count == 1) {
      t.open[uses[k].face] = 1;
    }
  });
  std::partial_sum(t.offsets.begin(), t.offsets.end(), t.offsets.begin());
  t.links.resize(static_cast<std::size_t>(t.offsets.back()));
  std::vector<Index> fill(t.offsets.begin(), t.offsets.end() - 1);
  for_each_edge(uses, [&](std::size_t k, std::size_t count) {
    if (count != 2) return;
    const bool same = uses[k].forward == uses[k + 1].forward;
    t.links[fill[uses[k].face]++] = {uses[k + 1].face, same};
    t.links[fill[uses[k + 1].face]++] = {uses[k].face, same};
  });
  return t;
}

// A closed piece, once consistent: its triangles, enclosed volume and bounding box.
struct ClosedPiece {
  std::vector<Index> faces;
  double volume = 0.0;
  Eigen::AlignedBox3d box;
};

// A closed piece enclosing a negative volume is inside out, unless it lies within a positive piece (a
// cavity's surface faces into the cavity). Containment is judged by bounding boxes: a piece inside
// another's box is left as it is.
void turn_inside_out_pieces(Mesh& mesh, const std::vector<ClosedPiece>& pieces, OrientationRepair& report) {
  for (const ClosedPiece& c : pieces) {
    if (!(c.volume < 0.0)) continue;
    const bool nested = std::any_of(pieces.begin(), pieces.end(), [&](const ClosedPiece& outer) {
      return outer.volume > 0.0 && outer.box.contains(c.box);
    });
    if (nested) continue;
    for (Index f : c.faces) std::swap(mesh.triangles[f][1], mesh.triangles[f][2]);
    ++report.inside_out_pieces;
    report.inside_out_triangles += static_cast<Index>(c.faces.size());
  }
}

}  // namespace

OrientationRepair make_orientation_consistent(Mesh& mesh) {
  const Index nf = mesh.num_faces();
  const TriangleLinks t = link_triangles(mesh);
  std::vector<ClosedPiece> closed_pieces;
  OrientationRepair report;
  // Flood each piece from its first triangle; flip[f] = whether f must turn over to agree with it.
  std::vector<std::int8_t> flip(static_cast<std::size_t>(nf), -1);
  std::vector<Index> stack, piece;
  for (Index seed = 0; seed < nf; ++seed) {
    if (flip[seed] >= 0) continue;
    piece.clear();
    flip[seed] = 0;
    stack.push_back(seed);
    bool closed = true;
    while (!stack.empty()) {
      const Index f = stack.back();
      stack.pop_back();
      piece.push_back(f);
      closed = closed && !t.open[f];
      for (Index k = t.offsets[f]; k < t.offsets[f + 1]; ++k) {
        const TriangleLinks::Link& l = t.links[k];
        const auto want = static_cast<std::int8_t>(flip[f] ^ (l.same_direction ? 1 : 0));
        if (flip[l.other] < 0) {
          flip[l.other] = want;
          stack.push_back(l.other);
        } else if (flip[l.other] != want) {
          throw InvalidInputError("the surface is not orientable (a Moebius strip or Klein bottle): triangles " +
                                  std::to_string(f) + " and " + std::to_string(l.other) +
                                  " cannot both face the same side");
        }
      }
    }
    // The minority turns over; on a tie, a closed piece takes the orientation that encloses a positive
    // volume.
    const auto to_flip =
        static_cast<Index>(std::count_if(piece.begin(), piece.end(), [&](Index f) { return flip[f]; }));
    bool invert = 2 * to_flip > static_cast<Index>(piece.size());
    if (closed && 2 * to_flip == static_cast<Index>(piece.size())) {
      double volume = 0.0;
      for (Index f : piece) {
        Triangle tri = mesh.triangles[f];
        if (flip[f]) std::swap(tri[1], tri[2]);
        volume += signed_volume_term(mesh, tri);
      }
      invert = volume < 0.0;
    }
    for (Index f : piece) {
      if ((flip[f] != 0) != invert) {
        std::swap(mesh.triangles[f][1], mesh.triangles[f][2]);
        ++report.against_neighbours;
      }
    }
    if (!closed) continue;
    ClosedPiece c;
    c.faces = piece;
    for (Index f : piece) {
      c.volume += signed_volume_term(mesh, mesh.triangles[f]);
      for (Index v : mesh.triangles[f]) c.box.extend(mesh.positions.col(v));
    }
    closed_pieces.push_back(std::move(c));
  }
  turn_inside_out_pieces(mesh, closed_pieces, report);
  return report;
}

PreparedMesh prepare_input_mesh(Mesh mesh, const InputPolicyOptions& options) {
  refuse_unusable(mesh);
  PreparedMesh out;
  out.mesh = std::move(mesh);
  Mesh& m = out.mesh;

  out.repair = repair_mesh(m, RepairOptions{options.merging});
  if (m.num_faces() == 0) {
    throw InvalidInputError("no triangles left after dropping the degenerate and duplicate ones");
  }
  if (out.repair.changed()) out.warnings.push_back("repaired: " + out.repair.describe());

  if (options.orientation == OrientationPolicy::Refuse) {
    if (const auto conflict = find_orientation_conflict(m)) {
      throw InvalidInputError("inconsistent orientation: triangles " + std::to_string(conflict->first) + " and " +
                              std::to_string(conflict->second) + " traverse their shared edge in the same direction");
    }
  } else {
    const OrientationRepair r = make_orientation_consistent(m);
    out.flipped_triangles = r.against_neighbours + r.inside_out_triangles;
    if (r.against_neighbours > 0) {
      out.warnings.push_back("repaired: turned over " + std::to_string(r.against_neighbours) + " of " +
                             std::to_string(m.num_faces()) +
                             " triangles that faced against their neighbours (inconsistent orientation)");
    }
    if (r.inside_out_pieces > 0) {
      out.warnings.push_back("repaired: turned over " + std::to_string(r.inside_out_pieces) + " closed piece" +
                             (r.inside_out_pieces == 1 ? "" : "s") +
                             " that enclosed a negative volume (inside out: triangles facing inwards)");
    }
  }

  const auto problems = find_mesh_problems(m);
  if (!problems.empty()) {
    std::ostringstream text;
    text << problems.size() << (problems.size() >= ValidationOptions{}.max_problems ? "+" : "") << " topology problem"
         << (problems.size() == 1 ? "" : "s") << " left as they are, first: " << describe(problems.front());
    out.warnings.push_back(text.str());
  }

  IdPreparation(out, options).run();
  return out;
}

}  // namespace contourmesh
