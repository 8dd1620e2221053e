// SPDX-License-Identifier: BSD-3-Clause
// Tests of the huge-page advice for the libraries' large buffers (libsmooth/internal/contourmesh/internal/
// huge_pages.h): the helpers keep the std::vector and Eigen contracts, and where Linux offers
// transparent huge pages on advice, an advised buffer is written with far fewer page faults.
#include "contourmesh/internal/huge_pages.h"
#include "detail/parallel.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#if defined(__linux__)
#include <sys/resource.h>
#endif

namespace contourmesh::detail {
namespace {

constexpr std::size_t kLarge = std::size_t{8} << 20;  // elements: 32 MiB of ints, well above the advice's floor

TEST(HugePages, ResizeValueInitialisesSmallAndLargeVectors) {
  for (const std::size_t n : {std::size_t{10}, kLarge}) {
    std::vector<int> v;
    resize_huge(v, n);
    ASSERT_EQ(v.size(), n);
    EXPECT_EQ(v.front(), 0);
    EXPECT_EQ(v[n / 2], 0);
    EXPECT_EQ(v.back(), 0);
  }
}

TEST(HugePages, AssignFillsWithTheValueAndReplacesOldContents) {
  std::vector<std::int32_t> v{1, 2, 3};
  assign_huge(v, kLarge, -1);
  ASSERT_EQ(v.size(), kLarge);
  EXPECT_EQ(v.front(), -1);
  EXPECT_EQ(v.back(), -1);
  assign_huge(v, 2, 7);  // shrinking keeps the storage, and the contents are the new ones
  EXPECT_EQ(v, (std::vector<std::int32_t>{7, 7}));
}

TEST(HugePages, ReserveKeepsTheElementsAlreadyThere) {
  std::vector<double> v{1.5, 2.5};
  reserve_huge(v, kLarge);
  EXPECT_GE(v.capacity(), kLarge);
  EXPECT_EQ(v, (std::vector<double>{1.5, 2.5}));
}

TEST(HugePages, MatricesHaveTheShapeAskedFor) {
  const auto m = huge_matrix<Eigen::Matrix3Xd>(3, 5);
  EXPECT_EQ(m.rows(), 3);
  EXPECT_EQ(m.cols(), 5);
  const auto z = huge_zero<Eigen::VectorXd>(static_cast<Eigen::Index>(kLarge / 2), 1);
  ASSERT_EQ(z.size(), static_cast<Eigen::Index>(kLarge / 2));
  EXPECT_EQ(z.cwiseAbs().maxCoeff(), 0.0);
}

TEST(HugePages, AdviceOnNullOrSmallBuffersIsHarmless) {
  advise_huge_pages(nullptr, kLarge);
  std::vector<char> small(4096, 'x');
  advise_huge_pages(small.data(), small.size());
  EXPECT_EQ(small[100], 'x');
}

#if defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
// The kernel's THP mode ("always [madvise] never") and its count of huge-page faults that fell back
// to small pages.
std::string thp_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  return line;
}

long vmstat(const std::string& key) {
  std::ifstream in("/proc/vmstat");
  std::string name;
  long value = 0;
  while (in >> name >> value) {
    if (name == key) return value;
  }
  return -1;
}

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

TEST(HugePages, AnAdvisedBufferIsWrittenWithFarFewerPageFaults) {
  const std::string mode = thp_mode();
  if (mode.find("[always]") == std::string::npos && mode.find("[madvise]") == std::string::npos) {
    GTEST_SKIP() << "this kernel offers no transparent huge pages on advice: " << mode;
  }
  const long fallbacks = vmstat("thp_fault_fallback");
  const long before = minor_faults();
  // Storage left untouched by the resize and advised, then one write per 4 KiB page.
  FillVector<int> v;
  resize_huge(v, kLarge);
  for (std::size_t i = 0; i < v.size(); i += 1024) v[i] = 1;
  const long faults = minor_faults() - before;
  if (vmstat("thp_fault_fallback") != fallbacks) GTEST_SKIP() << "the kernel had no free huge page";
  // 8192 small pages; at most two partial huge pages at the ends stay small (1024 faults).
  EXPECT_LT(faults, 1500) << "32 MiB written with " << faults << " page faults";
}
#endif

}  // namespace
}  // namespace contourmesh::detail
