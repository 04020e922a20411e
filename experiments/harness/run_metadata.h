// Metadata every result file carries so a run can be reproduced: version, git commit (at build
// time, with the dirty flag, and at run time where git answers), build type, compiler, CPU
// model and threads, host name, CUDA_VISIBLE_DEVICES, CUDA runtime and driver API versions, GPU
// name and peak clocks, backend and the command line; and the machine's state a reviewer needs
// to trust a timing: the NVIDIA driver version, current and maximum SM and memory
// clocks, persistence and compute mode, whether other compute processes shared the GPU at the
// start, the OS and kernel. Each of those is "unknown" where it cannot be known (no nvidia-smi,
// a CPU-only machine). The CLI and the experiment harness share it.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cuda/execute.h"

namespace dv {

void remember_command_line(int argc, char** argv);
// The command line given to remember_command_line, arguments joined by spaces.
const std::string& command_line();
nlohmann::json run_metadata(Backend backend);
// Now, as run_metadata's "utc_time" writes it (2026-12-04T17:45:21Z).
std::string utc_time_now();

// The commit the binary was built from: 12 hex digits, "-dirty" appended when tracked files
// differed, or "unknown".
std::string build_git_sha();

// `deepvox --version`: the version, the commit built (with -dirty), build type, compiler and
// whether CUDA was built in, one item a line.
std::string version_text();
// gethostname(), or "unknown".
std::string host_name();
// The first line of /proc/cpuinfo's "model name", or "unknown".
std::string cpu_model();

// Where machine_state looks; tests point them at sample files and a fake nvidia-smi.
struct MachineSources {
  std::string nvidia_smi = "nvidia-smi";  // run by the shell with its query arguments
  std::string nvidia_proc_version = "/proc/driver/nvidia/version";
  std::string os_release = "/etc/os-release";
};

// The machine's state: {"nvidia_driver": "580.159.04", "driver_source": "nvidia-smi" |
// "/proc/driver/nvidia/version" | "none", "gpu_index", "gpu_uuid", "sm_clock_mhz",
// "sm_clock_max_mhz", "memory_clock_mhz", "memory_clock_max_mhz" (numbers),
// "persistence_mode", "compute_mode", "gpu_shared" ("no", "yes: N other compute processes" or
// "unknown"), "os" (/etc/os-release's PRETTY_NAME), "kernel" (uname: system, release, machine)};
// a value that cannot be read is the string "unknown". The GPU is the one CUDA uses first: the
// first entry of CUDA_VISIBLE_DEVICES (an index or a UUID), else nvidia-smi's index 0. Other
// processes are those nvidia-smi lists on that GPU besides this one (a container may hide
// other containers' processes from it).
nlohmann::json machine_state(const MachineSources& sources = {});

// One line of `nvidia-smi --query-gpu=index,uuid,driver_version,clocks.sm,clocks.max.sm,
// clocks.mem,clocks.max.mem,persistence_mode,compute_mode --format=csv,noheader` as the keys of
// machine_state; "[N/A]" and missing fields are "unknown".
nlohmann::json parse_nvidia_smi_gpu(const std::string& csv_line);
// The version in /proc/driver/nvidia/version's first line ("NVRM version: NVIDIA UNIX x86_64
// Kernel Module  580.159.04  ..."), or "unknown".
std::string driver_from_proc_version(const std::string& text);
// PRETTY_NAME of an os-release file's text, unquoted, or "unknown".
std::string os_pretty_name(const std::string& os_release_text);

}  // namespace dv
