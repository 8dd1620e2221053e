// SPDX-License-Identifier: BSD-3-Clause
#include "isolated_process.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <exception>
#include <iostream>

namespace contourmesh::cli {

std::string run_isolated(const std::string& what, const std::function<void()>& work) {
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = fork();
  if (pid < 0) return "cannot start the " + what + " process: " + std::strerror(errno);
  if (pid == 0) {
    int code = 0;
    try {
      work();
    } catch (const std::exception& e) {
      std::cerr << what << ": " << e.what() << "\n";
      code = 2;
    }
    std::cerr.flush();
    _exit(code);  // no destructors or atexit handlers of the parent's state in the child
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return "lost the " + what + " process: " + std::strerror(errno);
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};
  if (WIFSIGNALED(status)) {
    return what + " failed (signal " + std::to_string(WTERMSIG(status)) +
           "; VTK aborts when the X display goes away, see the message above)";
  }
  return what + " failed (exit code " + std::to_string(WEXITSTATUS(status)) + ", see the message above)";
}

}  // namespace contourmesh::cli
