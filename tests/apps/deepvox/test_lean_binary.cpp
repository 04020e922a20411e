// The lean GPU-node binary starts with only glibc, libstdc++ (and libgcc) plus the NVIDIA
// driver (which the CUDA runtime loads at run time, so ldd does not list it): no OpenImageIO,
// tinygltf, GMP, OpenVDB or CUDA runtime library may appear among its dependencies. What needs
// OpenImageIO or OpenVDB fails there with a clear error, and the rest still works.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include "experiments/source_paths.h"

namespace {

// Runs `cmd` (stderr into stdout): exit status and output.
std::pair<int, std::string> shell(const std::string& cmd) {
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  std::string out;
  char buf[1024];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), out};
}

TEST(LeanBinary, DependsOnlyOnGlibcAndLibstdcxx) {
  const auto [status, out] = shell(std::string("ldd ") + DEEPVOX_LEAN_BINARY);
  ASSERT_EQ(status, 0) << out;
  // A sanitizer build (preset asan, which compiles this test the same way) adds its runtimes.
#if defined(__SANITIZE_ADDRESS__)
  const std::string runtimes = "|libasan|libubsan";
#else
  const std::string runtimes;
#endif
  const std::regex allowed(
      R"(^\s*(linux-vdso\.so\.1|/lib64/ld-linux-x86-64\.so\.2|(libc|libm|libdl|libpthread|librt|libstdc\+\+|libgcc_s)" +
      runtimes + R"()\.so\.[0-9]+)(\s|$))");
  std::istringstream lines(out);
  std::string line;
  int count = 0;
  while (std::getline(lines, line)) {
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    EXPECT_TRUE(std::regex_search(line, allowed)) << "unexpected dependency: " << line;
    ++count;
  }
  EXPECT_GE(count, 2) << out;
  EXPECT_EQ(out.find("not found"), std::string::npos) << out;
}

TEST(LeanBinary, DsmExrNeedsTheFullBuildButTheHeatmapWorks) {
  const std::filesystem::path dir = std::filesystem::path(dv::test::binary_dir()) / "test_lean_tmp";
  std::filesystem::create_directories(dir);
  const std::string dsm = std::string(DEEPVOX_LEAN_BINARY) + " dsm " + dv::test::source_dir() +
                          "/experiments/scenes/translucent-boxes.json --dsm-res 8 --backend cpu";
  const std::string exr = (dir / "maps.exr").string();
  const auto [exr_status, exr_out] = shell(dsm + " --out " + exr);
  EXPECT_EQ(exr_status, 2) << exr_out;
  EXPECT_NE(exr_out.find(exr), std::string::npos) << exr_out;
  EXPECT_NE(exr_out.find("full build"), std::string::npos) << exr_out;
  const std::string png = (dir / "layers.png").string();
  std::filesystem::remove(png);
  const auto [png_status, png_out] = shell(dsm + " --heatmap " + png);
  EXPECT_EQ(png_status, 0) << png_out;
  EXPECT_TRUE(std::filesystem::exists(png));
}

TEST(LeanBinary, VdbNeedsTheFullBuildAndFailsBeforeAnyWork) {
  const std::filesystem::path dir = std::filesystem::path(dv::test::binary_dir()) / "test_lean_tmp";
  std::filesystem::create_directories(dir);
  const std::string vdb = (dir / "grid.vdb").string();
  std::filesystem::remove(vdb);
  const auto [status, out] =
      shell(std::string(DEEPVOX_LEAN_BINARY) + " voxelize " + dv::test::source_dir() +
            "/experiments/assets/meshes/stanford-bunny-lowres.obj --backend cpu --res 32x32x32 "
            "--out " +
            vdb);
  EXPECT_EQ(status, 2) << out;
  EXPECT_NE(out.find(vdb + ": this deepvox is built without OpenVDB"), std::string::npos) << out;
  EXPECT_EQ(out.find("voxels set"), std::string::npos) << out;  // no voxelizing first
  EXPECT_FALSE(std::filesystem::exists(vdb));
}

}  // namespace
