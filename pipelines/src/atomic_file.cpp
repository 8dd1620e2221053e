#include "pipelines/atomic_file.h"

#include <smooth/errors.h>

#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <random>
#include <system_error>

namespace contourmesh {

namespace fs = std::filesystem;

namespace {

fs::path temporary_sibling(const fs::path& path) {
  std::random_device rd;
  const auto tag = std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000u);
  fs::path name = "." + path.stem().string() + ".tmp-" + tag + path.extension().string();
  return path.parent_path() / name;
}

}  // namespace

void check_output_path(const fs::path& path) {
  if (path.empty() || path.filename().empty() || path.filename() == "." || path.filename() == "..") {
    throw InvalidInputError("output path '" + path.string() + "' names no file");
  }
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (!fs::exists(status)) {
    throw InvalidInputError(path.string() + ": cannot write: directory '" + dir.string() + "' does not exist");
  }
  if (!fs::is_directory(status)) {
    throw InvalidInputError(path.string() + ": cannot write: '" + dir.string() + "' is not a directory");
  }
  if (fs::is_directory(path, ec)) throw InvalidInputError(path.string() + ": cannot write: it is a directory");
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    const int error = errno;
    throw InvalidInputError(path.string() + ": cannot write in '" + dir.string() +
                            "': " + std::generic_category().message(error));
  }
}

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  check_output_path(path);
  std::error_code ec;
  const fs::path tmp = temporary_sibling(path);
  try {
    write(tmp);
    if (!fs::exists(tmp, ec)) throw InvalidInputError(path.string() + ": cannot write: no output was produced");
    fs::rename(tmp, path, ec);
    if (ec) throw InvalidInputError(path.string() + ": cannot write: " + ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

void write_text_atomically(const fs::path& path, const std::string& text) {
  write_atomically(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw InvalidInputError(path.string() + ": cannot write: " + std::generic_category().message(errno));
    out << text;
    out.flush();
    if (!out) throw InvalidInputError(path.string() + ": write failed (disk full?)");
  });
}

}  // namespace contourmesh
