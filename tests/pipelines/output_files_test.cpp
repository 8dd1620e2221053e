// SPDX-License-Identifier: BSD-3-Clause
// Output files (contourmesh/smooth/atomic_file.h, write_mesh): whatever fails, an existing file is left as it was
// and no temporary stays behind.
#include <contourmesh/vtk/mesh_io.h>
#include <contourmesh/smooth/atomic_file.h>
#include <contourmesh/smooth/errors.h>

#include "cli_runner.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

namespace contourmesh {
namespace {

namespace fs = std::filesystem;

// Lowers the file size limit for its lifetime: writes beyond it fail with EFBIG, as on a full disk.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    ::getrlimit(RLIMIT_FSIZE, &previous_);
    rlimit limit = previous_;
    limit.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &previous_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit previous_{};
  void (*previous_handler_)(int) = nullptr;
};

class OutputFiles : public ::testing::Test {
 protected:
  fs::path precious(const std::string& name) const {
    std::ofstream(dir_ / name) << "precious";
    return dir_ / name;
  }
  test::ScopedTempDir tmp_{"contourmesh_output_files"};
  const fs::path& dir_ = tmp_.path();
  const Mesh stack_ = test::noisy_ridge_stack(8, 40, 2.0, 5);
};

TEST_F(OutputFiles, TemporaryNamesFitNameMax) {
  const std::string tag = "123456-999999";
  const fs::path long_name = dir_ / (std::string(245, 'n') + ".stl");
  const fs::path tmp = temporary_name(long_name, tag, 255);
  EXPECT_LE(tmp.filename().string().size(), 255u);
  EXPECT_EQ(tmp.filename().string().front(), '.');
  EXPECT_EQ(tmp.extension(), ".stl");
  EXPECT_EQ(temporary_name(dir_ / "v.nii.gz", tag).filename().string(), ".v.tmp-" + tag + ".nii.gz");
  // Multi-byte characters are never cut in half.
  std::string accents;
  for (int k = 0; k < 126; ++k) accents += "\xc3\xa9";  // e-acute, 2 bytes
  const std::string shortened = temporary_name(dir_ / (accents + ".ply"), tag, 255).filename().string();
  EXPECT_LE(shortened.size(), 255u);
  const std::string stem = shortened.substr(1, shortened.find(".tmp-") - 1);
  EXPECT_EQ(stem.size() % 2, 0u) << "whole characters only";
}

TEST_F(OutputFiles, EveryMeshWriterFailsCleanlyAtTheFileSizeLimit) {
  for (const std::string ext : {"stl", "obj", "ply", "vtp"}) {
    const fs::path out = precious("out." + ext);
    {
      const FileSizeLimit limit(2048);
      try {
        write_mesh(stack_, out);
        ADD_FAILURE() << ext << ": written past the limit";
      } catch (const InvalidInputError& e) {
        EXPECT_NE(std::string(e.what()).find(out.string() + ": cannot write"), std::string::npos) << e.what();
      }
    }
    EXPECT_EQ(test::read_bytes(out), "precious") << ext;
  }
  test::expect_no_temporaries(dir_);
}

TEST_F(OutputFiles, CancellingBeforeTheRenameLeavesNothing) {
  const fs::path out = precious("out.ply");
  MeshWriteOptions options;
  options.progress = [](std::string_view stage, double) { return stage != "write"; };
  EXPECT_THROW(write_mesh(stack_, out, options), CancelledError);
  EXPECT_EQ(test::read_bytes(out), "precious");
  test::expect_no_temporaries(dir_);
}

TEST_F(OutputFiles, ASignalHandlerCanRemoveTheTemporariesInFlight) {
  const fs::path out = precious("out.txt");
  try {
    write_atomically(out, [](const fs::path& tmp) {
      std::ofstream(tmp) << "half";
      remove_pending_temporaries();  // what the CLI's handler does on a second Ctrl-C
    });
    ADD_FAILURE() << "the temporary was removed: nothing to rename";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("no output was produced"), std::string::npos) << e.what();
  }
  EXPECT_EQ(test::read_bytes(out), "precious");
  test::expect_no_temporaries(dir_);
}

TEST_F(OutputFiles, ReplacingAFileKeepsItsPermissions) {
  const fs::path out = precious("out.stl");
  fs::permissions(out, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  write_mesh(stack_, out);
  EXPECT_EQ(fs::status(out).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
}

}  // namespace
}  // namespace contourmesh
