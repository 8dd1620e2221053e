// SPDX-License-Identifier: BSD-3-Clause
#include <contourmesh/smooth/errors.h>
#include <contourmesh/smooth/limits.h>

#include <gtest/gtest.h>

#include <string>

namespace contourmesh {
namespace {

std::string message_of(double vertices, double bytes, const ResourceLimits& limits) {
  try {
    check_allocation("step", vertices, bytes, limits);
  } catch (const LimitError& e) {
    return e.what();
  }
  return {};
}

TEST(Limits, VertexCapAndMemoryBudgetGiveMessagesWithTheNumbers) {
  ResourceLimits limits;
  limits.max_vertices = 1000;
  limits.max_memory_bytes = 2'000'000;
  EXPECT_EQ(message_of(1000, 100, limits), "") << "the limit itself is allowed";
  EXPECT_EQ(message_of(1001, 100, limits), "step: 1001 vertices exceed the limit of 1000 vertices");
  EXPECT_EQ(message_of(10, 3.5e9, limits), "step: needs about 3.5 GB of memory, more than the 2 MB allowed");
  limits.max_vertices = 0;
  EXPECT_THROW(check_allocation("step", 1, 1, limits), InvalidInputError);
}

TEST(Limits, TheDefaultBudgetIsTheAvailableMemory) {
  const std::size_t available = available_memory_bytes();
  ASSERT_GT(available, 0u) << "Linux reports MemAvailable";
  const ResourceLimits limits;  // max_memory_bytes 0
  EXPECT_NO_THROW(check_allocation("step", 10, 0.5 * static_cast<double>(available), limits));
  const std::string m = message_of(10, 4.0 * static_cast<double>(available), limits);
  EXPECT_NE(m.find("available"), std::string::npos) << m;
  EXPECT_EQ(format_bytes(850e6), "850 MB");
  EXPECT_EQ(format_bytes(12.34e9), "12.3 GB");
}

}  // namespace
}  // namespace contourmesh
