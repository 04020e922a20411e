// Crash-safe files for suite result folders (docs/suite-format.md, "Killed runs and --resume"):
// whole files are written under a temporary name, synced and renamed over the old one, so a
// reader sees the old or the new file, never half of one; journals are appended and synced
// (rows.csv, progress.jsonl); a new folder is filled under a hidden name and renamed into place,
// so a result folder never lacks its meta.json. A failing write (full disk, read-only or
// unwritable folder) is a ResultWriteError naming the file and the system's reason: the runner
// stops on it instead of recording a failed experiment.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "core/error.h"

namespace dv {

class ResultWriteError : public Error {
 public:
  ResultWriteError(const std::string& path, const std::string& problem)
      : Error(path + ": " + problem) {}
  // The whole message as given (a stopped run's: the failed write, what is kept, how to resume).
  explicit ResultWriteError(const std::string& message) : Error(message) {}
};

// Writes PATH.tmp, syncs it, renames it to PATH and syncs the folder.
void write_file_atomically(const std::filesystem::path& path, const std::string& bytes);

// The file's bytes; InputError naming it when it cannot be read.
std::string read_file_text(const std::filesystem::path& path);

// A file open for appending synced records (a journal). Move-only; closes on destruction.
class AppendFile {
 public:
  AppendFile() = default;
  // Opens (creating when `create`) for appending; ResultWriteError when it cannot.
  AppendFile(const std::filesystem::path& path, bool create);
  AppendFile(AppendFile&& other) noexcept;
  AppendFile& operator=(AppendFile&& other) noexcept;
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;
  ~AppendFile();

  // Writes every byte at the end, then fdatasync; ResultWriteError on a short write or error.
  void append(const std::string& bytes);
  // Cuts the file back to `size` bytes (a torn tail) and syncs.
  void truncate(int64_t size);
  int64_t size() const;
  // An exclusive advisory lock (flock) held until the file is closed: false when another
  // process holds it; true also where the file system has no locks, and then `no_locks` (when
  // given) receives the system's reason (e.g. "Function not implemented" on Lustre mounted
  // noflock), else it is left empty.
  bool try_lock(std::string* no_locks = nullptr);
  void set_path(const std::filesystem::path& path) { path_ = path; }

 private:
  int fd_ = -1;
  std::filesystem::path path_;
};

// Whether a process holds the lock of AppendFile::try_lock on `path` now.
bool file_is_locked(const std::filesystem::path& path);

// This machine's name for file names ('/' and '.' made '_'; "host" when it has none).
std::string this_host();
// ".new-HOST-PID.partial": the hidden folder a new result folder is filled in.
std::string filling_folder_name(const std::string& host, long pid);
// Removes the hidden filling folders under `parent` of this host's processes that are gone (a
// run killed while it filled one); another host's, and a live process's, are left alone.
void remove_abandoned_filling_folders(const std::filesystem::path& parent);

// Makes OUT/<suite>/<name> (run_folder.h) with its first files at once: `fill` writes into a
// hidden folder OUT/<suite>/.new-HOST-PID.partial, which is synced, then the name is reserved
// and the hidden folder renamed over the reserved (empty) one. Returns the folder. Abandoned
// filling folders of this host are removed first.
std::filesystem::path make_filled_run_folder(
    const std::filesystem::path& out, const std::string& suite, const std::string& git_sha,
    const std::string& tag, const std::function<void(const std::filesystem::path&)>& fill);

}  // namespace dv
