// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/reconstruct/phantom.h"

#include "detail/phantom_shapes.h"

#include <contourmesh/smooth/errors.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace contourmesh {

namespace {

using detail::Box3;
using detail::ShapeBuild;
using detail::Vec3;

constexpr std::array<std::pair<PhantomShape, std::string_view>, 11> kShapeNames = {{
    {PhantomShape::RidgeBox, "ridge-box"},
    {PhantomShape::Femur, "femur"},
    {PhantomShape::Pelvis, "pelvis"},
    {PhantomShape::Skull, "skull"},
    {PhantomShape::Branch, "branch"},
    {PhantomShape::TwoObjects, "two-objects"},
    {PhantomShape::Cavity, "cavity"},
    {PhantomShape::TiltedBox, "tilted-box"},
    {PhantomShape::InSliceRidge, "in-slice-ridge"},
    {PhantomShape::EndFaceOnSlice, "end-face-on-slice"},
    {PhantomShape::SkullDiploe, "skull-diploe"},
}};


}  // namespace

std::string_view to_string(PhantomShape shape) {
  for (const auto& [s, name] : kShapeNames) {
    if (s == shape) return name;
  }
  return "unknown";
}

PhantomShape parse_phantom_shape(std::string_view name) {
  std::string valid;
  for (const auto& [s, n] : kShapeNames) {
    if (n == name) return s;
    valid += (valid.empty() ? "" : ", ") + std::string(n);
  }
  throw InvalidInputError("unknown phantom shape '" + std::string(name) + "'; valid shapes: " + valid);
}

std::vector<PhantomShape> all_phantom_shapes() {
  std::vector<PhantomShape> shapes;
  for (const auto& entry : kShapeNames) {
    if (entry.first != PhantomShape::SkullDiploe) shapes.push_back(entry.first);
  }
  return shapes;
}

std::vector<PhantomShape> extra_phantom_shapes() { return {PhantomShape::SkullDiploe}; }

Phantom make_phantom(PhantomShape shape) {
  ShapeBuild s;
  switch (shape) {
    case PhantomShape::RidgeBox:
      s = detail::build_ridge_box();
      break;
    case PhantomShape::Femur:
      s = detail::build_femur();
      break;
    case PhantomShape::Pelvis:
      s = detail::build_pelvis();
      break;
    case PhantomShape::Skull:
      s = detail::build_skull();
      break;
    case PhantomShape::Branch:
      s = detail::build_branch();
      break;
    case PhantomShape::TwoObjects:
      s = detail::build_two_objects();
      break;
    case PhantomShape::Cavity:
      s = detail::build_cavity();
      break;
    case PhantomShape::TiltedBox:
      s = detail::build_tilted_box();
      break;
    case PhantomShape::InSliceRidge:
      s = detail::build_in_slice_ridge();
      break;
    case PhantomShape::EndFaceOnSlice:
      s = detail::build_end_face_on_slice();
      break;
    case PhantomShape::SkullDiploe:
      s = detail::build_skull_diploe();
      break;
    default:
      throw InvalidInputError("make_phantom: unknown shape " + std::to_string(static_cast<int>(shape)));
  }
  Phantom p;
  p.shape = shape;
  p.sdf = s.sdf;
  p.normal = detail::normal_field(s.sdf);
  p.bounds = s.bounds;
  if (s.volume) {
    p.volume = *s.volume;
  } else {
    Box3 box = s.bounds;
    box.min().array() -= 0.5;
    box.max().array() += 0.5;
    p.volume = detail::integrate_volume(s.sdf, box, 0.5);
  }
  p.surface_components = s.surface_components;
  p.euler_characteristic = s.euler_characteristic;
  p.feature_points = detail::thin_points(s.features, 0.2);
  return p;
}

double distance_to_features(const Phantom& phantom, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& q : phantom.feature_points) best = std::min(best, (q - p).squaredNorm());
  return std::sqrt(best);
}

}  // namespace contourmesh
