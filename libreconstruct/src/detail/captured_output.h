// SPDX-License-Identifier: BSD-3-Clause
// Private: the text ITK, GDCM, MetaIO and the NIfTI library print on their own while libreconstruct
// reads or writes a volume. They print multi-line messages to std::cerr, stderr (C stdio) and ITK's
// output window; libreconstruct reports what went wrong in its own words (one line naming the file),
// so that text is captured for the duration of the call instead of reaching the terminal.
#pragma once

#include <string>

namespace contourmesh::detail {

/// While alive (and `active`): ITK's output window, GDCM's trace streams and file descriptor 2 are
/// redirected to buffers; the destructor restores them. Not reentrant; one at a time per process.
class CapturedOutput {
 public:
  explicit CapturedOutput(bool active);
  ~CapturedOutput();
  CapturedOutput(const CapturedOutput&) = delete;
  CapturedOutput& operator=(const CapturedOutput&) = delete;

  /// Everything captured so far (flushes first); empty when not active.
  [[nodiscard]] std::string text();

 private:
  struct State;
  State* state_ = nullptr;
};

/// The first meaningful line of a library's message: without "WARNING: In file, line N" preambles,
/// "Class (0x...): " prefixes and blank lines; printable, at most 200 characters. Empty if none.
[[nodiscard]] std::string first_line(const std::string& text);

}  // namespace contourmesh::detail
