// The lock file of a result folder (writer_lock.h).
#include "experiments/harness/writer_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "core/json_reader.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/run_metadata.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

constexpr const char* kLockFile = "writer.lock";
// The writer touches its lock file this often; a lock file of another host untouched for
// kStaleAfterSeconds is stale (its writer stopped without removing it: a node that failed).
constexpr int kHeartbeatSeconds = 30;
constexpr double kStaleAfterSeconds = 300;

// Field 22 of /proc/PID/stat: when the process started, in clock ticks since boot (a pid that
// was reused by another process has another start time); -1 when no such process runs (or it
// is a zombie).
long long process_start_ticks(long long pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t name_end = stat.rfind(')');
  if (name_end == std::string::npos) return -1;
  std::istringstream fields(stat.substr(name_end + 1));
  std::string state, field;
  fields >> state;  // field 3
  for (int k = 4; k < 22 && fields >> field;) ++k;
  long long ticks = -1;
  if (!(fields >> ticks) || state == "Z") return -1;
  return ticks;
}

std::string env_or_empty(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

Json this_writer() {
  const long long pid = ::getpid();
  return {{"host", host_name()},
          {"pid", pid},
          {"start_ticks", process_start_ticks(pid)},
          {"since", utc_time_now()},
          {"slurm_job", env_or_empty("SLURM_JOB_ID")},
          {"slurm_restart", std::atoi(env_or_empty("SLURM_RESTART_COUNT").c_str())}};
}

// Whether the writer a lock file names may still run, seen from this process.
LockHolder holder_of(const Json& lock, double age_seconds) {
  LockHolder h;
  if (!lock.is_object() || !lock.contains("pid") || !lock.contains("host")) return h;  // stale
  const long long pid = lock.value("pid", 0LL);
  const std::string host = lock.value("host", "");
  h.who = "pid " + std::to_string(pid) + " on host " + host + " (since " +
          lock.value("since", "?") + ")";
  if (host == host_name()) {
    const long long started = lock.value("start_ticks", -1LL);
    h.checked = h.held = started >= 0 ? process_start_ticks(pid) == started
                                      : ::kill(pid_t(pid), 0) == 0 || errno == EPERM;
  } else {
    // SLURM starts a requeued job again only after its earlier run ended.
    const std::string job = env_or_empty("SLURM_JOB_ID");
    const bool restarted_job =
        !job.empty() && lock.value("slurm_job", "") == job &&
        std::atoi(env_or_empty("SLURM_RESTART_COUNT").c_str()) > lock.value("slurm_restart", 0);
    h.held = !restarted_job && age_seconds < kStaleAfterSeconds;
  }
  if (!h.held) h.who.clear();
  return h;
}

Json read_lock(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return Json();
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return Json::parse(text, nullptr, false);
}

// Where link() cannot be used: O_EXCL, which also fails when the name exists.
bool create_exclusively(const fs::path& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (errno == EEXIST) return false;
    throw ResultWriteError(path.string(), std::string("cannot create: ") + std::strerror(errno));
  }
  const bool written = ::write(fd, text.data(), text.size()) == ssize_t(text.size());
  const int saved = errno;
  ::close(fd);
  if (!written) {
    ::unlink(path.c_str());
    throw ResultWriteError(path.string(), std::string("cannot write: ") + std::strerror(saved));
  }
  return true;
}

}  // namespace

LockHolder writer_lock_holder(const fs::path& dir) {
  const fs::path path = dir / kLockFile;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return {};
  return holder_of(read_lock(path), double(std::time(nullptr) - st.st_mtime));
}

// Touches the lock file every kHeartbeatSeconds until stopped.
struct WriterLock::Heartbeat {
  std::mutex mutex;
  std::condition_variable wake;
  bool stop = false;
  fs::path path;  // guarded by mutex
  std::thread thread;

  explicit Heartbeat(const fs::path& lock_file) : path(lock_file) {
    thread = std::thread([this] {
      std::unique_lock<std::mutex> guard(mutex);
      while (!wake.wait_for(guard, std::chrono::seconds(kHeartbeatSeconds), [&] { return stop; }))
        ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0);  // mtime: now
    });
  }
  ~Heartbeat() {
    {
      const std::lock_guard<std::mutex> guard(mutex);
      stop = true;
    }
    wake.notify_all();
    thread.join();
  }
};

WriterLock WriterLock::take(const fs::path& dir) {
  const fs::path path = dir / kLockFile;
  const std::string text = this_writer().dump() + "\n";
  const fs::path mine = dir / (".writer.lock." + host_name() + "." + std::to_string(::getpid()));
  write_file_atomically(mine, text);
  for (int attempt = 0; attempt < 3; ++attempt) {
    bool taken = ::link(mine.c_str(), path.c_str()) == 0;
    if (!taken && errno != EEXIST) taken = create_exclusively(path, text);  // no hard links
    if (taken) {
      ::unlink(mine.c_str());
      WriterLock lock;
      lock.path_ = path;
      lock.heartbeat_ = std::make_unique<Heartbeat>(path);
      return lock;
    }
    const LockHolder holder = writer_lock_holder(dir);
    if (holder.held) {
      ::unlink(mine.c_str());
      throw InputError(
          dir.string(),
          "another deepvox process (" + holder.who + ") is writing this folder now; wait for it " +
              "to end" +
              (holder.checked
                   ? std::string()
                   : "; it runs on another host, which cannot be checked from here: "
                     "its lock " +
                         path.string() + " is taken over 5 minutes after its last heartbeat"));
    }
    ::unlink(path.c_str());  // stale: its writer is gone
  }
  ::unlink(mine.c_str());
  throw Error(path.string() + ": cannot take the folder's lock (taken and released meanwhile " +
              "three times)");
}

WriterLock::WriterLock() = default;

WriterLock::WriterLock(WriterLock&& other) noexcept
    : path_(std::move(other.path_)), heartbeat_(std::move(other.heartbeat_)) {
  other.path_.clear();
}

WriterLock& WriterLock::operator=(WriterLock&& other) noexcept {
  if (this != &other) {
    release();
    path_ = std::move(other.path_);
    heartbeat_ = std::move(other.heartbeat_);
    other.path_.clear();
  }
  return *this;
}

WriterLock::~WriterLock() {
  release();
}

void WriterLock::set_dir(const fs::path& dir) {
  path_ = dir / kLockFile;
  if (!heartbeat_) return;
  const std::lock_guard<std::mutex> guard(heartbeat_->mutex);
  heartbeat_->path = path_;
}

void WriterLock::release() noexcept {
  heartbeat_.reset();
  if (path_.empty()) return;
  ::unlink(path_.c_str());
  path_.clear();
}

}  // namespace dv
