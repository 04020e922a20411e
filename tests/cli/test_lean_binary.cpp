// The lean GPU-node binary starts with only glibc, libstdc++ (and libgcc) plus the NVIDIA
// driver (which the CUDA runtime loads at run time, so ldd does not list it): no OpenImageIO,
// tinygltf, GMP or CUDA runtime library may appear among its dependencies.
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <sstream>
#include <string>

namespace {

TEST(LeanBinary, DependsOnlyOnGlibcAndLibstdcxx) {
  const std::string cmd = std::string("ldd ") + DEEPVOX_LEAN_BINARY + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[1024];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  ASSERT_EQ(pclose(pipe), 0) << out;
  const std::regex allowed(
      R"(^\s*(linux-vdso\.so\.1|/lib64/ld-linux-x86-64\.so\.2|(libc|libm|libdl|libpthread|librt|libstdc\+\+|libgcc_s)\.so\.[0-9]+)(\s|$))");
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

}  // namespace
