// The machine state run metadata records for a reviewer: nvidia-smi's GPU line and
// compute processes parsed from a fake nvidia-smi, the driver from /proc/driver/nvidia/version,
// the OS from os-release, and "unknown" for everything a CPU-only machine cannot say.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "experiments/harness/run_metadata.h"
#include "tests/support/scratch_dir.h"

namespace dv {
namespace {

const char* kGpuLine =
    "0, GPU-6c1f2a3b-0000-1111-2222-333344445555, 580.159.04, 1755 MHz, 1980 MHz, 3201 MHz, "
    "3201 MHz, Enabled, Default";

// CUDA_VISIBLE_DEVICES set (or unset) for one test, restored after it.
class VisibleDevices {
 public:
  explicit VisibleDevices(const char* value) {
    if (const char* old = std::getenv("CUDA_VISIBLE_DEVICES")) old_ = old;
    value ? setenv("CUDA_VISIBLE_DEVICES", value, 1) : unsetenv("CUDA_VISIBLE_DEVICES");
  }
  ~VisibleDevices() {
    old_ ? setenv("CUDA_VISIBLE_DEVICES", old_->c_str(), 1) : unsetenv("CUDA_VISIBLE_DEVICES");
  }

 private:
  std::optional<std::string> old_;
};

// A shell script answering nvidia-smi's two queries with `gpus` and `apps`.
std::string fake_nvidia_smi(const std::filesystem::path& dir, const std::string& gpus,
                            const std::string& apps) {
  const std::string path = (dir / "nvidia-smi").string();
  std::ofstream(path) << "#!/bin/sh\ncase \"$1\" in\n  --query-gpu=*) printf '%s\\n' '" << gpus
                      << "';;\n  --query-compute-apps=*) printf '%s' '" << apps
                      << "';;\n  *) exit 2;;\nesac\n";
  chmod(path.c_str(), 0755);
  return path;
}

TEST(RunMetadata, ParsesTheNvidiaSmiGpuLine) {
  const nlohmann::json g = parse_nvidia_smi_gpu(kGpuLine);
  EXPECT_EQ(g["gpu_index"], 0);
  EXPECT_EQ(g["gpu_uuid"], "GPU-6c1f2a3b-0000-1111-2222-333344445555");
  EXPECT_EQ(g["nvidia_driver"], "580.159.04");
  EXPECT_EQ(g["sm_clock_mhz"], 1755);
  EXPECT_EQ(g["sm_clock_max_mhz"], 1980);
  EXPECT_EQ(g["memory_clock_mhz"], 3201);
  EXPECT_EQ(g["memory_clock_max_mhz"], 3201);
  EXPECT_EQ(g["persistence_mode"], "Enabled");
  EXPECT_EQ(g["compute_mode"], "Default");
  const nlohmann::json na = parse_nvidia_smi_gpu("1, GPU-x, 580.1, [N/A], 1980 MHz");
  EXPECT_EQ(na["sm_clock_mhz"], "unknown");
  EXPECT_EQ(na["sm_clock_max_mhz"], 1980);
  EXPECT_EQ(na["compute_mode"], "unknown");
}

TEST(RunMetadata, DriverFromProcAndOsFromOsRelease) {
  EXPECT_EQ(driver_from_proc_version("NVRM version: NVIDIA UNIX x86_64 Kernel Module  580.159.04  "
                                     "Thu Nov 13 12:00:00 UTC 2025\nGCC version:  gcc 12\n"),
            "580.159.04");
  EXPECT_EQ(driver_from_proc_version(""), "unknown");
  EXPECT_EQ(os_pretty_name("NAME=\"Ubuntu\"\nPRETTY_NAME=\"Ubuntu 22.04.4 LTS\"\nID=ubuntu\n"),
            "Ubuntu 22.04.4 LTS");
  EXPECT_EQ(os_pretty_name("NAME=x\n"), "unknown");
}

TEST(RunMetadata, UnknownWithoutNvidiaSmiOrDriver) {
  const std::filesystem::path dir = test::scratch_dir("test_harness_tmp");
  std::ofstream(dir / "os-release") << "PRETTY_NAME=\"Debian GNU/Linux 12 (bookworm)\"\n";
  MachineSources sources;
  sources.nvidia_smi = (dir / "no-nvidia-smi").string();
  sources.nvidia_proc_version = (dir / "no-proc-version").string();
  sources.os_release = (dir / "os-release").string();
  const nlohmann::json m = machine_state(sources);
  for (const char* key :
       {"nvidia_driver", "sm_clock_mhz", "sm_clock_max_mhz", "memory_clock_mhz",
        "memory_clock_max_mhz", "persistence_mode", "compute_mode", "gpu_shared", "gpu_uuid"})
    EXPECT_EQ(m[key], "unknown") << key;
  EXPECT_EQ(m["driver_source"], "none");
  EXPECT_EQ(m["os"], "Debian GNU/Linux 12 (bookworm)");
  EXPECT_NE(m["kernel"], "unknown");

  // Without nvidia-smi the driver still comes from /proc; the rest stays unknown.
  std::ofstream(dir / "version") << "NVRM version: NVIDIA UNIX x86_64 Kernel Module  580.159.04  "
                                    "Thu Nov 13 2025\n";
  sources.nvidia_proc_version = (dir / "version").string();
  const nlohmann::json p = machine_state(sources);
  EXPECT_EQ(p["nvidia_driver"], "580.159.04");
  EXPECT_EQ(p["driver_source"], sources.nvidia_proc_version);
  EXPECT_EQ(p["gpu_shared"], "unknown");
}

TEST(RunMetadata, ReadsTheGpuCudaUsesAndItsOtherProcesses) {
  const std::filesystem::path dir = test::scratch_dir("test_harness_tmp");
  const std::string second =
      "1, GPU-99, 580.159.04, 1980 MHz, 1980 MHz, 3201 MHz, 3201 MHz, Disabled, Exclusive_Process";
  MachineSources sources;
  sources.nvidia_smi =
      fake_nvidia_smi(dir, std::string(kGpuLine) + "\n" + second,
                      "GPU-6c1f2a3b-0000-1111-2222-333344445555, 4242\nGPU-6c1f2a3b-0000-1111-2222-"
                      "333344445555, 4343\nGPU-99, 17\n");
  {
    const VisibleDevices unset(nullptr);
    const nlohmann::json m = machine_state(sources);
    EXPECT_EQ(m["driver_source"], "nvidia-smi");
    EXPECT_EQ(m["nvidia_driver"], "580.159.04");
    EXPECT_EQ(m["gpu_index"], 0);
    EXPECT_EQ(m["sm_clock_mhz"], 1755);
    EXPECT_EQ(m["persistence_mode"], "Enabled");
    EXPECT_EQ(m["gpu_shared"], "yes: 2 other compute processes");
  }
  {
    const VisibleDevices one("1,0");
    const nlohmann::json m = machine_state(sources);
    EXPECT_EQ(m["gpu_index"], 1);
    EXPECT_EQ(m["compute_mode"], "Exclusive_Process");
    EXPECT_EQ(m["gpu_shared"], "yes: 1 other compute processes");
  }
  {
    const VisibleDevices by_uuid("GPU-99");
    EXPECT_EQ(machine_state(sources)["gpu_index"], 1);
  }
  sources.nvidia_smi = fake_nvidia_smi(dir, kGpuLine, "");
  const VisibleDevices unset(nullptr);
  EXPECT_EQ(machine_state(sources)["gpu_shared"], "no");
}

}  // namespace
}  // namespace dv
