// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/reconstruct/phantom.h>
#include <contourmesh/reconstruct/segmentation.h>
#include <contourmesh/reconstruct/threads.h>
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/threads.h>

#include <itkMultiThreaderBase.h>

#include <gtest/gtest.h>

namespace contourmesh {
namespace {

TEST(Threads, ALimitCapsTbbAndItkAndRestoresItk) {
  const auto itk_before = itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads();
  const int before = available_threads();
  const int smooth_before = smooth_threads();
  EXPECT_GE(before, 1);
  {
    const ThreadLimit one(1);
    EXPECT_EQ(one.threads(), 1);
    EXPECT_EQ(available_threads(), 1);
    EXPECT_EQ(itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads(), 1u);
    EXPECT_EQ(smooth_threads(), 1);  // libsmooth's loops too
    {
      const ThreadLimit more(4);  // an inner limit never raises an outer one
      EXPECT_EQ(available_threads(), 1);
      EXPECT_EQ(itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads(), 1u);
    }
    EXPECT_EQ(available_threads(), 1);
  }
  EXPECT_EQ(available_threads(), before);
  EXPECT_EQ(itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads(), itk_before);
  EXPECT_EQ(smooth_threads(), smooth_before);
  {
    const ThreadLimit none(0);  // no cap
    EXPECT_EQ(available_threads(), before);
  }
  EXPECT_THROW(ThreadLimit(-1), InvalidInputError);
}

// Slices are segmented in parallel; the contours must not depend on how many threads did it.
TEST(Threads, SegmentationIsTheSameOnOneThreadAndOnAll) {
  PhantomVolumeOptions vo;
  vo.spacing = {1.2, 1.2, 2.0};
  vo.noise = 40.0;
  vo.blur = 0.5;
  const auto image = render_phantom(make_phantom(PhantomShape::Skull), vo);
  SegmentationOptions o;
  o.threshold = 520.0;
  const SegmentationResult all = segment_contours(*image, o);
  SegmentationResult one;
  {
    const ThreadLimit limit(1);
    one = segment_contours(*image, o);
  }
  ASSERT_EQ(one.stack.slices.size(), all.stack.slices.size());
  EXPECT_EQ(one.dropped_regions, all.dropped_regions);
  EXPECT_EQ(one.foreground_voxels, all.foreground_voxels);
  std::size_t contours = 0;
  for (std::size_t z = 0; z < one.stack.slices.size(); ++z) {
    const auto& a = one.stack.slices[z].contours;
    const auto& b = all.stack.slices[z].contours;
    ASSERT_EQ(a.size(), b.size()) << "slice " << z;
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].is_hole, b[k].is_hole);
      EXPECT_EQ(a[k].parent, b[k].parent);
      EXPECT_EQ(a[k].points, b[k].points) << "slice " << z << ", contour " << k;
    }
    contours += a.size();
  }
  EXPECT_GT(contours, 50u);
}

}  // namespace
}  // namespace contourmesh
