// Runs the contourmesh command as a user does, for the CLI-level tests: exit code, stdout, stderr.
#pragma once

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace contourmesh::test {

struct CliRun {
  int code = -1;    ///< exit status; 128 + N when the process was killed by signal N
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// Runs `sh -c "PREFIX CONTOURMESH ARGS"` with stderr captured in `scratch`/stderr.txt. `prefix` may be
/// shell set-up ending with ';', such as "ulimit -f 64;" (the command is then exec'ed, so that the
/// limit applies to it), or a wrapper command such as "strace -o trace.txt".
/// CONTOURMESH_TEST_CLI in the environment replaces `cli` (to run the tests against another build, e.g.
/// the parent commit's, and see them fail there).
inline CliRun run_cli(std::filesystem::path cli, const std::string& args, const std::filesystem::path& scratch,
                      const std::string& prefix = "") {
  if (const char* other = std::getenv("CONTOURMESH_TEST_CLI"); other != nullptr && *other != '\0') cli = other;
  const std::filesystem::path err_file = scratch / "stderr.txt";
  const bool setup = prefix.empty() || prefix.back() == ';';
  const std::string command = prefix + (setup ? " exec " : " ") + cli.string() + " " + args;
  const std::string cmd = "sh -c '" + command + "' 2>" + err_file.string();
  CliRun r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
  std::ifstream in(err_file);
  r.err.assign(std::istreambuf_iterator<char>(in), {});
  std::filesystem::remove(err_file);
  return r;
}

/// Lines of stderr other than the progress display's "STAGE done in X s" lines.
inline int non_progress_lines(const std::string& err) {
  std::istringstream in(err);
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.find(" done in ") == std::string::npos) ++n;
  }
  return n;
}

/// Exit code 2, exactly one line on stderr besides the progress lines, "contourmesh CMD: error: " and
/// every fragment.
inline void expect_rejected(const CliRun& r, const std::vector<std::string>& fragments) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(non_progress_lines(r.err), 1) << "one line: " << r.err;
  EXPECT_NE(r.err.find(": error: "), std::string::npos) << r.err;
  for (const std::string& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << "'" << f << "' in " << r.err;
}

/// No file in `dir` starts with a dot: no temporary was left behind.
inline void expect_no_temporaries(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    EXPECT_NE(e.path().filename().string().front(), '.') << "stray temporary " << e.path();
  }
}

inline std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace contourmesh::test
