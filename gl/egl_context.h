// Headless OpenGL 4.5 core contexts through EGL, for the GL voxelizers (slicemap, atlas): the
// NVIDIA driver's device platform on GPU nodes, Mesa's surfaceless platform (llvmpipe) in CI.
// No window system is needed; render into framebuffer objects.
#pragma once

#include <memory>
#include <string>

namespace dv::gl {

class EglContext {
 public:
  // Creates and makes current a context on this thread; returns null and the reason when no
  // EGL display or GL 4.5 core context can be had here.
  static std::unique_ptr<EglContext> create_headless(std::string* why_not);
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // Makes this context current on the calling thread (again); throws dv::Error when EGL fails.
  void make_current() const;
  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;   // GL_VERSION
  const std::string& platform() const { return platform_; }

 private:
  EglContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string platform_;
};

}  // namespace dv::gl
