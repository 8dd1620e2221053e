// SPDX-License-Identifier: BSD-3-Clause
// rethrow_with_context: the one way to add context to a library error without losing its type.
#include "contourmesh/smooth/errors.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace contourmesh {
namespace {

template <typename Thrown, typename Caught = InvalidInputError>
void rethrow_under(const std::string& context, const std::string& message) {
  try {
    throw Thrown(message);
  } catch (const Caught&) {
    rethrow_with_context(context);
  }
}

TEST(RethrowWithContext, ATopologyErrorStaysATopologyError) {
  try {
    rethrow_under<TopologyError>("mesh.stl", "non-manifold edge (3, 4)");
    FAIL() << "nothing thrown";
  } catch (const TopologyError& e) {
    EXPECT_EQ(std::string(e.what()), "mesh.stl: non-manifold edge (3, 4)");
  } catch (...) {
    FAIL() << "the type was lost";
  }
}

TEST(RethrowWithContext, LimitAndDivergenceErrorsKeepTheirTypes) {
  EXPECT_THROW(rethrow_under<LimitError>("scan", "too many voxels"), LimitError);
  EXPECT_THROW(rethrow_under<DivergenceError>("label 'liver'", "NaN at vertex 7"), DivergenceError);
}

TEST(RethrowWithContext, APlainInvalidInputErrorStaysOneAndGetsTheContext) {
  try {
    rethrow_under<InvalidInputError>("a.ply", "bad header");
    FAIL() << "nothing thrown";
  } catch (const TopologyError&) {
    FAIL() << "became more specific";
  } catch (const InvalidInputError& e) {
    EXPECT_EQ(std::string(e.what()), "a.ply: bad header");
  }
}

TEST(RethrowWithContext, AMessageThatAlreadyNamesTheContextIsNotPrefixedTwice) {
  try {
    rethrow_under<TopologyError>("a.obj", "a.obj: open mesh");
  } catch (const TopologyError& e) {
    EXPECT_EQ(std::string(e.what()), "a.obj: open mesh");
  }
}

TEST(RethrowWithContext, OtherExceptionsPassUnchanged) {
  try {
    rethrow_under<std::runtime_error, std::exception>("ctx", "disk on fire");
    FAIL() << "nothing thrown";
  } catch (const InvalidInputError&) {
    FAIL() << "turned into an input error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "disk on fire");
  }
}

}  // namespace
}  // namespace contourmesh
