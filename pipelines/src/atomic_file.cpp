#include "pipelines/atomic_file.h"

#include <smooth/errors.h>

#include <unistd.h>

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

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  if (path.empty() || path.filename().empty()) throw InvalidInputError("output path '" + path.string() + "' names no file");
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw InvalidInputError(path.string() + ": cannot write: directory '" + dir.string() + "' does not exist");
  }
  if (fs::is_directory(path, ec)) throw InvalidInputError(path.string() + ": cannot write: it is a directory");
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
