// SPDX-License-Identifier: BSD-3-Clause
// The `xu2006` preset pinned on a fixed mesh: labels and positions equal to what the paper's
// configuration gave before the preset existed (tests/data/xu2006/README.md).
#include "contourmesh/smooth/smooth.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace contourmesh {
namespace {

const std::string kData = CONTOURMESH_TEST_DATA "/xu2006/";

// The fixture's ASCII PLY: x y z ContourId ContourIndex per vertex, then "3 a b c" per face.
Mesh read_fixture() {
  std::ifstream in(kData + "input.ply");
  EXPECT_TRUE(in) << kData << "input.ply";
  std::string line;
  Index vertices = 0;
  std::size_t faces = 0;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream s(line);
    std::string word, element;
    s >> word >> element;
    if (word == "element" && element == "vertex") s >> vertices;
    if (word == "element" && element == "face") s >> faces;
  }
  Mesh m;
  m.positions.resize(3, vertices);
  m.slice_ids.resize(static_cast<std::size_t>(vertices));
  m.contour_ids.resize(static_cast<std::size_t>(vertices));
  for (Index i = 0; i < vertices; ++i) {
    in >> m.positions(0, i) >> m.positions(1, i) >> m.positions(2, i) >> m.slice_ids[i] >> m.contour_ids[i];
  }
  m.triangles.resize(faces);
  for (Triangle& t : m.triangles) {
    int count = 0;
    in >> count >> t[0] >> t[1] >> t[2];
  }
  EXPECT_TRUE(in) << "truncated fixture";
  return m;
}

struct Golden {
  std::vector<int> labels;
  Eigen::Matrix3Xd positions;
};

Golden read_golden() {
  std::ifstream in(kData + "expected.txt");
  EXPECT_TRUE(in) << kData << "expected.txt";
  std::string line;
  std::getline(in, line);  // header
  Golden g;
  std::vector<double> xyz;
  int label = 0;
  double x = 0, y = 0, z = 0;
  while (in >> label >> x >> y >> z) {
    g.labels.push_back(label);
    xyz.insert(xyz.end(), {x, y, z});
  }
  g.positions = Eigen::Map<const Eigen::Matrix3Xd>(xyz.data(), 3, static_cast<Index>(g.labels.size()));
  return g;
}

// Labels that differ and the largest position difference from the golden (mm).
struct Difference {
  std::size_t labels = 0;
  double position = 0.0;
};

Difference compare(const SmoothResult& r, const Golden& g) {
  Difference d;
  EXPECT_EQ(r.labels.size(), g.labels.size());
  EXPECT_EQ(r.mesh.num_vertices(), g.positions.cols());
  if (r.labels.size() != g.labels.size() || r.mesh.num_vertices() != g.positions.cols()) {
    return {g.labels.size(), 1e9};
  }
  for (std::size_t i = 0; i < g.labels.size(); ++i) d.labels += static_cast<int>(r.labels[i]) != g.labels[i];
  d.position = (r.mesh.positions - g.positions).cwiseAbs().maxCoeff();
  return d;
}

constexpr double kTolerance = 1e-9;  // mm: rounding of the golden's 17 digits and of the compiler

TEST(Xu2006Preset, ReproducesTheGoldenLabelsAndPositions) {
  const Mesh mesh = read_fixture();
  const Golden golden = read_golden();
  ASSERT_EQ(mesh.num_vertices(), 672);
  const MethodConfig config = preset(Preset::Xu2006);
  EXPECT_EQ(config.method, SmoothingMethod::FeaturePreserving);
  const SmoothResult r = smooth(mesh, config.method, config.options);
  const Difference d = compare(r, golden);
  EXPECT_EQ(d.labels, 0u);
  EXPECT_LE(d.position, kTolerance);
  EXPECT_EQ(r.iterations, 40);
  ASSERT_TRUE(r.detection.has_value());
  EXPECT_EQ(r.detection->edges, 26u);
  EXPECT_EQ(r.detection->noise, 103u);
  EXPECT_EQ(r.mesh.triangles, mesh.triangles);
}

// The golden comparison is sharp enough to see a change of any single option of the configuration.
TEST(Xu2006Preset, TheGoldenSeesAChangeOfAnyOption) {
  const Mesh mesh = read_fixture();
  const Golden golden = read_golden();
  const MethodConfig config = preset(Preset::Xu2006);
  const auto differs = [&](const std::function<void(SmoothOptions&)>& change) {
    SmoothOptions o = config.options;
    change(o);
    const Difference d = compare(smooth(mesh, config.method, o), golden);
    return d.labels > 0 || d.position > kTolerance;
  };
  EXPECT_TRUE(differs([](SmoothOptions& o) { o.paper.iterations = 39; }));
  EXPECT_TRUE(differs([](SmoothOptions& o) { o.iterations = 20; }));
  EXPECT_TRUE(differs([](SmoothOptions& o) { o.paper.detection.measure = UmbrellaMeasure::NormalComponent; }));
  EXPECT_TRUE(differs([](SmoothOptions& o) { o.paper.detection.corner_spread = 0.1; }));
  EXPECT_TRUE(differs([](SmoothOptions& o) { o.paper.detection.in_slice = InSliceFeatures::AlongFeatureLine; }));
  EXPECT_TRUE(differs([](SmoothOptions& o) { o.paper.detection.gamma_factor = 2.1; }));
  EXPECT_TRUE(differs([](SmoothOptions& o) { o.paper.detection.window = 9; }));
  EXPECT_TRUE(differs([](SmoothOptions& o) { o.paper.mu = -0.67; }));
  EXPECT_TRUE(differs([](SmoothOptions& o) { o.paper.lambda = 0.6; }));
}

TEST(Xu2006Preset, StatesThePapersSettingsExplicitly) {
  const MethodConfig c = preset(Preset::Xu2006);
  const FeatureSmoothingOptions& p = c.options.paper;
  EXPECT_EQ(p.diffusion, SmoothingMethod::Taubin);
  EXPECT_EQ(p.iterations, 40);
  ASSERT_TRUE(p.lambda.has_value());
  EXPECT_EQ(*p.lambda, 0.6307);
  EXPECT_EQ(p.mu, -0.6732);
  EXPECT_EQ(p.max_levels, 3);
  EXPECT_EQ(p.detection.measure, UmbrellaMeasure::Length);
  EXPECT_EQ(p.detection.in_slice, InSliceFeatures::Noise);
  EXPECT_GT(p.detection.corner_spread, 1.0 / 3.0) << "the corner-spread extension is off";
  EXPECT_FALSE(p.detection.gamma.has_value());
  EXPECT_EQ(p.detection.gamma_factor, 2.0);
  EXPECT_EQ(p.detection.window, 7);
  EXPECT_EQ(p.detection.prefilter_iterations, 0);
  EXPECT_FALSE(c.options.iterations.has_value()) << "the preset keeps its own 40, not a shared count";
}

}  // namespace
}  // namespace contourmesh
