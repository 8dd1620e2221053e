// SPDX-License-Identifier: BSD-3-Clause
#include "detail/captured_output.h"

#include <gdcmTrace.h>
#include <itkObjectFactory.h>
#include <itkOutputWindow.h>

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace contourmesh::detail {

namespace {

class StringItkWindow : public itk::OutputWindow {
 public:
  ITK_DISALLOW_COPY_AND_MOVE(StringItkWindow);
  using Self = StringItkWindow;
  using Pointer = itk::SmartPointer<Self>;
  itkNewMacro(Self)
  void DisplayText(const char* text) override {
    if (text != nullptr) captured += text;
  }
  std::string captured;

 protected:
  StringItkWindow() = default;
  ~StringItkWindow() override = default;
};

}  // namespace

struct CapturedOutput::State {
  itk::OutputWindow::Pointer previous_window;
  StringItkWindow::Pointer window;
  std::ostringstream gdcm;
  std::ostream* previous_debug = nullptr;
  std::ostream* previous_warning = nullptr;
  std::ostream* previous_error = nullptr;
  int saved_fd = -1;
  std::FILE* sink = nullptr;
};

CapturedOutput::CapturedOutput(bool active) {
  if (!active) return;
  state_ = new State;
  state_->previous_window = itk::OutputWindow::GetInstance();
  state_->window = StringItkWindow::New();
  itk::OutputWindow::SetInstance(state_->window);
  state_->previous_debug = &gdcm::Trace::GetDebugStream();
  state_->previous_warning = &gdcm::Trace::GetWarningStream();
  state_->previous_error = &gdcm::Trace::GetErrorStream();
  gdcm::Trace::SetDebugStream(state_->gdcm);
  gdcm::Trace::SetWarningStream(state_->gdcm);
  gdcm::Trace::SetErrorStream(state_->gdcm);
  // MetaIO writes to std::cerr and the NIfTI library to stderr: both end on file descriptor 2.
  std::cerr.flush();
  std::fflush(stderr);
  state_->sink = std::tmpfile();
  if (state_->sink != nullptr) {
    state_->saved_fd = ::dup(2);
    if (state_->saved_fd < 0 || ::dup2(::fileno(state_->sink), 2) < 0) {
      if (state_->saved_fd >= 0) ::close(state_->saved_fd);
      state_->saved_fd = -1;
    }
  }
}

CapturedOutput::~CapturedOutput() {
  if (state_ == nullptr) return;
  std::cerr.flush();
  std::fflush(stderr);
  if (state_->saved_fd >= 0) {
    ::dup2(state_->saved_fd, 2);
    ::close(state_->saved_fd);
  }
  if (state_->sink != nullptr) std::fclose(state_->sink);
  gdcm::Trace::SetDebugStream(*state_->previous_debug);
  gdcm::Trace::SetWarningStream(*state_->previous_warning);
  gdcm::Trace::SetErrorStream(*state_->previous_error);
  itk::OutputWindow::SetInstance(state_->previous_window);
  delete state_;
}

std::string CapturedOutput::text() {
  if (state_ == nullptr) return {};
  std::string out = state_->window->captured + state_->gdcm.str();
  std::cerr.flush();
  std::fflush(stderr);
  if (state_->sink != nullptr && state_->saved_fd >= 0) {
    // The descriptor is shared with fd 2: read by position, leaving its offset where the writers are.
    const int fd = ::fileno(state_->sink);
    const off_t end = ::lseek(fd, 0, SEEK_END);
    std::string bytes(static_cast<std::size_t>(end > 0 ? end : 0), '\0');
    std::size_t got = 0;
    while (got < bytes.size()) {
      const ssize_t n = ::pread(fd, bytes.data() + got, bytes.size() - got, static_cast<off_t>(got));
      if (n <= 0) break;
      got += static_cast<std::size_t>(n);
    }
    bytes.resize(got);
    out += bytes;
  }
  return out;
}

std::string first_line(const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    std::size_t start = 0;
    while (start < line.size() && std::isspace(static_cast<unsigned char>(line[start]))) ++start;
    line = line.substr(start);
    if (line.empty()) continue;
    bool preamble = false;
    for (const char* p : {"WARNING: In ", "ERROR: In ", "Warning: In ", "Error: In ", "Debug: In "}) {
      preamble = preamble || line.rfind(p, 0) == 0;
    }
    if (preamble) continue;
    const auto open = line.find(" (0x");
    const auto close = line.find("): ");
    if (open != std::string::npos && close != std::string::npos && open < close && close < 80)
      line = line.substr(close + 3);
    std::string printable;
    for (char c : line.substr(0, 200)) printable += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    return line.size() > 200 ? printable + "..." : printable;
  }
  return {};
}

}  // namespace contourmesh::detail
