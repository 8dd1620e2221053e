// SPDX-License-Identifier: BSD-3-Clause
// Runs the contourmesh command (or another program) as a user does, for the CLI-level tests: exit code,
// stdout, stderr.
#pragma once

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

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

/// `text` quoted for sh: between single quotes, each single quote written as '\''.
inline std::string shell_quote(const std::string& text) {
  std::string q(1, '\'');
  for (const char c : text) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q.push_back(c);
    }
  }
  q.push_back('\'');
  return q;
}

/// A prefix for run_cli that runs the command under its own X server (xvfb-run), for the renders when no
/// display is reachable: a server number derived from the process id and an authority file in `scratch`,
/// so that parallel tests and other users' servers do not collide.
inline std::string xvfb_prefix(const std::filesystem::path& scratch) {
  const int server = 200 + static_cast<int>(getpid() % 700);
  return "xvfb-run -a -n " + std::to_string(server) + " -f " + (scratch / "xauthority").string();
}

/// Runs `sh -c "PREFIX PROGRAM ARGS"` with stderr captured in `scratch`/stderr.txt (removed
/// afterwards). `args` is shell text: quote paths that may hold spaces or quotes (shell_quote). `prefix`
/// may be shell set-up ending with ';', such as "ulimit -f 64;" (the program is then exec'ed, so that
/// the limit applies to it), or a wrapper command such as "strace -o trace.txt", "env -u DISPLAY",
/// "NAME=value" or xvfb_prefix().
inline CliRun run_program(const std::filesystem::path& program, const std::string& args,
                          const std::filesystem::path& scratch, const std::string& prefix = "") {
  const std::filesystem::path err_file = scratch / "stderr.txt";
  const bool setup = prefix.empty() || prefix.back() == ';';
  const std::string command = prefix + (setup ? " exec " : " ") + program.string() + " " + args;
  const std::string cmd = "sh -c " + shell_quote(command) + " 2>" + err_file.string();
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

/// run_program for the contourmesh command `cli`. CONTOURMESH_TEST_CLI in the environment replaces `cli`
/// (to run the tests against another build, e.g. the parent commit's, and see them fail there).
inline CliRun run_cli(std::filesystem::path cli, const std::string& args, const std::filesystem::path& scratch,
                      const std::string& prefix = "") {
  if (const char* other = std::getenv("CONTOURMESH_TEST_CLI"); other != nullptr && *other != '\0') cli = other;
  return run_program(cli, args, scratch, prefix);
}

#ifdef CONTOURMESH_CLI
/// run_cli for the contourmesh command of this test target (CONTOURMESH_CLI, set by tests/CMakeLists.txt).
inline CliRun run_cli(const std::string& args, const std::filesystem::path& scratch) {
  return run_cli(CONTOURMESH_CLI, args, scratch);
}
#endif

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
