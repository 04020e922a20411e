// One writer per result folder on every file system: the lock file FOLDER/writer.lock, made
// whole under a private name and hard-linked into place (link() fails when the name exists, also
// over NFS and Lustre), holding the writer's host, pid, the pid's start time and its SLURM job.
// It backs the flock on progress.jsonl (durable_file.h), which misses a second writer where the
// file system has no locks (Lustre mounted noflock: flock fails; localflock: flock holds on one
// node only). The holder touches the file every 30 s. A lock file whose process is gone is stale
// and taken over: on this host when the pid no longer runs (or runs another process, told by its
// start time); on another host, where the process cannot be checked, when the file was not
// touched for 5 minutes (a failed node) or this process is the same SLURM job started again
// (SLURM_RESTART_COUNT higher). Taking over a stale file is not atomic against a second process
// taking it over at the same instant; the flock still guards that where it works.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

namespace dv {

// The lock file of `dir` as it reads now.
struct LockHolder {
  bool held = false;     // a live process holds it, or one on another host touched it lately
  bool checked = false;  // held, and the process was seen running (this host)
  std::string who;       // "pid 123 on host node7 (since 2026-12-06T04:00:00Z)"; empty: none
};
LockHolder writer_lock_holder(const std::filesystem::path& dir);

// The lock, held until release() or destruction (which remove the file). Move-only.
class WriterLock {
 public:
  WriterLock();
  // Takes DIR/writer.lock for this process, replacing a stale one; InputError naming the folder
  // and the holder when another process holds it.
  static WriterLock take(const std::filesystem::path& dir);
  WriterLock(WriterLock&& other) noexcept;
  WriterLock& operator=(WriterLock&& other) noexcept;
  WriterLock(const WriterLock&) = delete;
  WriterLock& operator=(const WriterLock&) = delete;
  ~WriterLock();

  // The folder moved (a new run folder renamed into place): the lock file moved with it.
  void set_dir(const std::filesystem::path& dir);
  void release() noexcept;

 private:
  struct Heartbeat;
  std::filesystem::path path_;
  std::unique_ptr<Heartbeat> heartbeat_;  // keeps the file's mtime fresh while held
};

}  // namespace dv
