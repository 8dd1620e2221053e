// SPDX-License-Identifier: BSD-3-Clause
#include "library_messages.h"

#include <gdcmTrace.h>
#include <itkObject.h>
#include <itkObjectFactory.h>
#include <itkOutputWindow.h>
#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <cctype>
#include <iostream>
#include <sstream>

namespace contourmesh::cli {

namespace {

std::string g_command = "contourmesh";

bool is_preamble(const std::string& line) {
  for (const char* start :
       {"WARNING: In ", "ERROR: In ", "Warning: In ", "Error: In ", "Debug: In ", "Generic Warning: In "}) {
    if (line.rfind(start, 0) == 0) return true;
  }
  return false;
}

// "ImageSeriesReader (0x55d1c2a0): text" -> "text"
std::string without_object_prefix(const std::string& line) {
  const auto open = line.find(" (0x");
  const auto close = line.find("): ");
  if (open != std::string::npos && close != std::string::npos && open < close && close < 80)
    return line.substr(close + 3);
  return line;
}

void print_warning(const char* library, const std::string& text) {
  const std::string line = one_line(text);
  if (!line.empty()) std::cerr << "contourmesh " << g_command << ": warning: " << library << ": " << line << "\n";
}

class OneLineItkWindow : public itk::OutputWindow {
 public:
  ITK_DISALLOW_COPY_AND_MOVE(OneLineItkWindow);
  using Self = OneLineItkWindow;
  using Pointer = itk::SmartPointer<Self>;
  itkNewMacro(Self)
  void DisplayText(const char* text) override { print_warning("ITK", text == nullptr ? "" : text); }

 protected:
  OneLineItkWindow() = default;
  ~OneLineItkWindow() override = default;
};

class OneLineVtkWindow : public vtkOutputWindow {
 public:
  static OneLineVtkWindow* New();
  vtkTypeMacro(OneLineVtkWindow, vtkOutputWindow)
  void DisplayText(const char* text) override { print_warning("VTK", text == nullptr ? "" : text); }

 protected:
  OneLineVtkWindow() = default;
  ~OneLineVtkWindow() override = default;

 private:
  OneLineVtkWindow(const OneLineVtkWindow&) = delete;
  void operator=(const OneLineVtkWindow&) = delete;
};
vtkStandardNewMacro(OneLineVtkWindow);

}  // namespace

std::string one_line(const std::string& text) {
  std::istringstream lines(text);
  std::string out;
  for (std::string line; std::getline(lines, line);) {
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    std::size_t start = 0;
    while (start < line.size() && std::isspace(static_cast<unsigned char>(line[start]))) ++start;
    line = line.substr(start);
    if (line.empty() || is_preamble(line)) continue;
    line = without_object_prefix(line);
    out += (out.empty() ? "" : "; ") + line;
  }
  std::string printable;
  for (char c : out.substr(0, 300)) printable += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  return out.size() > 300 ? printable + "..." : printable;
}

void configure_library_messages(const std::string& command, bool verbose) {
  g_command = command;
  if (verbose) return;  // the libraries' own defaults: everything on stderr as they print it
  itk::OutputWindow::SetInstance(OneLineItkWindow::New());
  vtkOutputWindow::SetInstance(vtkSmartPointer<OneLineVtkWindow>::New());
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  // GDCM traces what ITK then reports as an exception (or what the DICOM checks name): silent.
  gdcm::Trace::WarningOff();
  gdcm::Trace::ErrorOff();
  gdcm::Trace::DebugOff();
}

}  // namespace contourmesh::cli
