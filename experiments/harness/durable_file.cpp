// Crash-safe files for result folders (durable_file.h).
#include "experiments/harness/durable_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "experiments/harness/run_folder.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& path, const std::string& what) {
  throw ResultWriteError(path.string(), what + ": " + std::strerror(errno));
}

void write_all(int fd, const std::string& bytes, const fs::path& path) {
  size_t at = 0;
  while (at < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + at, bytes.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path, "cannot write");
    at += size_t(n);
  }
}

void sync_folder(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) fail(dir, "cannot open folder to sync it");
  const int rc = ::fsync(fd);
  const int saved = errno;
  ::close(fd);
  errno = saved;
  if (rc != 0 && errno != EINVAL) fail(dir, "cannot sync folder");
}

// ".new-HOST-" + PID + ".partial".
std::string filling_prefix(const std::string& host) {
  return ".new-" + host + "-";
}
constexpr const char* kFillingSuffix = ".partial";

}  // namespace

void write_file_atomically(const fs::path& path, const std::string& bytes) {
  const fs::path tmp = path.string() + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(tmp, "cannot create");
  try {
    write_all(fd, bytes, tmp);
    if (::fsync(fd) != 0) fail(tmp, "cannot sync");
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  if (::close(fd) != 0) {
    ::unlink(tmp.c_str());
    fail(tmp, "cannot close");
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    errno = saved;
    fail(path, "cannot rename " + tmp.filename().string() + " to it");
  }
  sync_folder(path.has_parent_path() ? path.parent_path() : fs::path("."));
}

std::string read_file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "cannot read");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

AppendFile::AppendFile(const fs::path& path, bool create) : path_(path) {
  fd_ =
      ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC | (create ? O_CREAT | O_EXCL : 0), 0644);
  if (fd_ < 0) fail(path, create ? "cannot create" : "cannot open for appending");
}

AppendFile::AppendFile(AppendFile&& other) noexcept
    : fd_(other.fd_), path_(std::move(other.path_)) {
  other.fd_ = -1;
}

AppendFile& AppendFile::operator=(AppendFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    path_ = std::move(other.path_);
    other.fd_ = -1;
  }
  return *this;
}

AppendFile::~AppendFile() {
  if (fd_ >= 0) ::close(fd_);
}

void AppendFile::append(const std::string& bytes) {
  write_all(fd_, bytes, path_);
  if (::fdatasync(fd_) != 0) fail(path_, "cannot sync");
}

void AppendFile::truncate(int64_t size) {
  if (::ftruncate(fd_, off_t(size)) != 0) fail(path_, "cannot truncate");
  if (::fdatasync(fd_) != 0) fail(path_, "cannot sync");
}

int64_t AppendFile::size() const {
  struct stat st {};
  if (::fstat(fd_, &st) != 0) fail(path_, "cannot stat");
  return int64_t(st.st_size);
}

bool AppendFile::try_lock(std::string* no_locks) {
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return true;
  if (errno == EWOULDBLOCK) return false;
  if (no_locks) *no_locks = std::strerror(errno);  // ENOLCK, ENOSYS, EOPNOTSUPP: no locks here
  return true;
}

bool file_is_locked(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool locked = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return locked;
}

std::string this_host() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0 || name[0] == 0) return "host";
  std::string host(name);
  for (char& c : host)
    if (c == '/' || c == '.') c = '_';
  return host;
}

std::string filling_folder_name(const std::string& host, long pid) {
  return filling_prefix(host) + std::to_string(pid) + kFillingSuffix;
}

void remove_abandoned_filling_folders(const fs::path& parent) {
  const std::string prefix = filling_prefix(this_host()), suffix = kFillingSuffix;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string digits =
        name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::atol(digits.c_str());
    if (pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove_all(entry.path(), ignored);
    }
  }
}

fs::path make_filled_run_folder(const fs::path& out, const std::string& suite,
                                const std::string& git_sha, const std::string& tag,
                                const std::function<void(const fs::path&)>& fill) {
  const fs::path parent = fs::path(out) / suite;
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw InputError(parent.string(), "cannot create folder: " + ec.message());
  remove_abandoned_filling_folders(parent);
  const fs::path tmp = parent / filling_folder_name(this_host(), long(::getpid()));
  fs::remove_all(tmp, ec);
  if (!fs::create_directory(tmp, ec))
    throw ResultWriteError(tmp.string(), "cannot create folder: " + ec.message());
  fs::path dir;
  try {
    fill(tmp);
    sync_folder(tmp);
    // Reserve the name, then rename() replaces the empty folder in one step: a kill leaves
    // the hidden folder or the whole result folder, an empty one only in between the two calls.
    dir = make_run_folder(out, suite, git_sha, tag);
    if (::rename(tmp.c_str(), dir.c_str()) != 0)
      fail(dir, "cannot rename " + tmp.string() + " to it");
    sync_folder(parent);
  } catch (...) {
    fs::remove_all(tmp, ec);
    if (!dir.empty()) fs::remove(dir, ec);
    throw;
  }
  return dir;
}

}  // namespace dv
