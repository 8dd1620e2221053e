// SPDX-License-Identifier: BSD-3-Clause
#include "contourmesh/smooth/atomic_file.h"

#include "contourmesh/smooth/errors.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <random>
#include <system_error>

namespace contourmesh {

namespace fs = std::filesystem;

namespace {

// The temporaries in flight, for remove_pending_temporaries (called from signal handlers): a slot is
// claimed, its path copied, then published; the handler reads published slots only.
struct PendingSlot {
  std::atomic<bool> claimed{false};
  std::atomic<bool> published{false};
  char path[4096] = {};
};
PendingSlot g_pending[64];

class PendingTemporary {
 public:
  explicit PendingTemporary(const fs::path& path) {
    const std::string& text = path.native();
    if (text.size() >= sizeof(PendingSlot::path)) return;
    for (PendingSlot& slot : g_pending) {
      if (slot.claimed.exchange(true)) continue;
      std::memcpy(slot.path, text.c_str(), text.size() + 1);
      slot.published.store(true, std::memory_order_release);
      slot_ = &slot;
      return;
    }
  }
  ~PendingTemporary() {
    if (slot_ == nullptr) return;
    slot_->published.store(false, std::memory_order_release);
    slot_->claimed.store(false, std::memory_order_release);
  }
  PendingTemporary(const PendingTemporary&) = delete;
  PendingTemporary& operator=(const PendingTemporary&) = delete;

 private:
  PendingSlot* slot_ = nullptr;
};

std::string error_text(int error) { return std::generic_category().message(error); }

fs::path directory_of(const fs::path& path) { return path.parent_path().empty() ? fs::path(".") : path.parent_path(); }

const char* kind_of(const fs::file_status& status) {
  switch (status.type()) {
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::fifo: return "a FIFO";
    case fs::file_type::socket: return "a socket";
    default: return "not a regular file";
  }
}

// The extension a writer recognises: ".nii.gz" counts as one (the NIfTI writer compresses on ".gz").
std::string full_extension(const fs::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".gz" || ext == ".bz2" || ext == ".xz" || ext == ".zst") {
    const std::string inner = path.stem().extension().string();
    if (!inner.empty() && inner.size() <= 8) return inner + ext;
  }
  return ext;
}

std::size_t name_max_of(const fs::path& dir) {
  errno = 0;
  const long n = ::pathconf(dir.c_str(), _PC_NAME_MAX);
  return n > 0 ? static_cast<std::size_t>(n) : 255;
}

// fsync on a path: the data of a file, or the entry list of a directory.
int sync_path(const fs::path& path, bool directory) {
  const int fd = ::open(path.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) return errno;
  int error = 0;
  if (::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  return error;
}

// Creates the temporary (exclusively: never an existing file) with the destination's permissions.
fs::path reserve_temporary(const fs::path& destination, const std::string& shown) {
  const fs::path dir = directory_of(destination);
  const std::size_t name_max = name_max_of(dir);
  std::random_device rd;
  struct stat existing {};
  const bool replace = ::stat(destination.c_str(), &existing) == 0;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string tag = std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000u);
    const fs::path tmp = temporary_name(destination, tag, name_max);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) {
      if (errno == EEXIST) continue;
      throw InvalidInputError(shown + ": cannot write: cannot create a temporary file in '" + dir.string() +
                              "': " + error_text(errno));
    }
    if (replace) (void)::fchmod(fd, existing.st_mode & 07777);
    ::close(fd);
    return tmp;
  }
  throw InvalidInputError(shown + ": cannot write: no free temporary name in '" + dir.string() + "'");
}

}  // namespace

fs::path temporary_name(const fs::path& destination, const std::string& tag, std::size_t name_max) {
  const std::string file = destination.filename().string();
  const std::string ext = full_extension(destination);
  std::string stem = file.substr(0, file.size() - ext.size());
  const std::string suffix = ".tmp-" + tag + ext;
  const std::size_t room = name_max > 1 + suffix.size() ? name_max - 1 - suffix.size() : 0;
  if (stem.size() > room) {
    std::size_t cut = room;
    while (cut > 0 && (static_cast<unsigned char>(stem[cut]) & 0xC0) == 0x80) --cut;  // inside a UTF-8 character
    stem.resize(cut);
  }
  return destination.parent_path() / ("." + stem + suffix);
}

fs::path resolve_output_path(const fs::path& path) {
  fs::path p = path;
  for (int hops = 0;; ++hops) {
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(p, ec);
    if (ec || !fs::is_symlink(status)) return p;
    if (hops >= 40) throw InvalidInputError(path.string() + ": cannot write: too many levels of symbolic links");
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) throw InvalidInputError(path.string() + ": cannot write: cannot read the symbolic link: " + ec.message());
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
}

void check_output_path(const fs::path& path) {
  if (path.empty() || path.filename().empty() || path.filename() == "." || path.filename() == "..") {
    throw InvalidInputError("output path '" + path.string() + "' names no file");
  }
  const std::string shown = path.string();
  const fs::path real = resolve_output_path(path);
  const std::string via = real == path ? "" : " (the target of the symbolic link, '" + real.string() + "')";
  const fs::path dir = directory_of(real);
  std::error_code ec;
  const fs::file_status dir_status = fs::status(dir, ec);
  if (!fs::exists(dir_status)) {
    throw InvalidInputError(shown + ": cannot write: directory '" + dir.string() + "' does not exist" + via);
  }
  if (!fs::is_directory(dir_status)) {
    throw InvalidInputError(shown + ": cannot write: '" + dir.string() + "' is not a directory" + via);
  }
  const fs::file_status status = fs::status(real, ec);
  if (fs::exists(status)) {
    if (fs::is_directory(status)) throw InvalidInputError(shown + ": cannot write: it is a directory" + via);
    if (!fs::is_regular_file(status)) {
      throw InvalidInputError(shown + ": cannot write: it is " + kind_of(status) + via +
                              ", not a regular file; outputs replace regular files only (name a file)");
    }
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    const int error = errno;
    throw InvalidInputError(shown + ": cannot write in '" + dir.string() + "': " + error_text(error));
  }
}

void check_distinct_outputs(const std::vector<std::pair<std::string, fs::path>>& outputs) {
  std::vector<fs::path> resolved;
  for (const auto& [label, path] : outputs) {
    std::error_code ec;
    const fs::path real = path.empty() ? fs::path() : resolve_output_path(path);
    fs::path canonical = real.empty() ? real : fs::weakly_canonical(fs::absolute(real, ec), ec);
    if (ec) canonical = real;
    resolved.push_back(canonical);
  }
  for (std::size_t a = 0; a < outputs.size(); ++a) {
    for (std::size_t b = a + 1; b < outputs.size(); ++b) {
      if (resolved[a].empty() || resolved[b].empty()) continue;
      std::error_code ec;
      const bool same = resolved[a] == resolved[b] || fs::equivalent(resolved[a], resolved[b], ec);
      if (same) {
        throw InvalidInputError(outputs[b].second.string() + ": " + outputs[a].first + " and " + outputs[b].first +
                                " name the same file: the second would replace the first");
      }
    }
  }
}

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write,
                      const ProgressCallback& progress) {
  check_output_path(path);
  const std::string shown = path.string();
  const fs::path real = resolve_output_path(path);
  const fs::path tmp = reserve_temporary(real, shown);
  const PendingTemporary pending(tmp);
  std::error_code ec;
  try {
    write(tmp);
    if (!fs::exists(tmp, ec)) throw InvalidInputError(shown + ": cannot write: no output was produced");
    if (const int error = sync_path(tmp, false)) {
      throw InvalidInputError(shown + ": cannot write: " + error_text(error) + " while flushing to disk (disk full?)");
    }
    if (progress && !progress("write", 1.0)) throw CancelledError("write");
    if (::rename(tmp.c_str(), real.c_str()) != 0) {
      throw InvalidInputError(shown + ": cannot write: " + error_text(errno));
    }
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  (void)sync_path(directory_of(real), true);  // the rename itself; some file systems cannot, which is fine
}

void remove_pending_temporaries() noexcept {
  for (PendingSlot& slot : g_pending) {
    if (slot.published.load(std::memory_order_acquire)) ::unlink(slot.path);
  }
}

void write_text_atomically(const fs::path& path, const std::string& text, const ProgressCallback& progress) {
  write_atomically(
      path,
      [&](const fs::path& tmp) {
        std::FILE* out = std::fopen(tmp.c_str(), "wb");
        if (out == nullptr) throw InvalidInputError(path.string() + ": cannot write: " + error_text(errno));
        const bool written = std::fwrite(text.data(), 1, text.size(), out) == text.size();
        const int error = errno;
        if (std::fclose(out) != 0 || !written) {
          throw InvalidInputError(path.string() + ": cannot write: " + error_text(written ? errno : error) +
                                  " (disk full?)");
        }
      },
      progress);
}

}  // namespace contourmesh
