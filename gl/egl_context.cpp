// EGL headless context creation (see egl_context.h): tries the device platform (NVIDIA), then
// Mesa's surfaceless platform, then the default display.
#include "gl/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>

#include <cstring>
#include <vector>

#include "core/error.h"

namespace dv::gl {

namespace {

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)); p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// Candidate displays in order of preference, with the platform's name.
std::vector<std::pair<EGLDisplay, std::string>> candidate_displays() {
  std::vector<std::pair<EGLDisplay, std::string>> out;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_platform_display && has_extension(client, "EGL_EXT_platform_device")) {
    auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (query_devices && query_devices(8, devices, &count))
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY) out.emplace_back(d, "device " + std::to_string(i));
      }
  }
  if (get_platform_display && has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d =
        get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) out.emplace_back(d, "surfaceless");
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (d != EGL_NO_DISPLAY) out.emplace_back(d, "default");
  return out;
}

}  // namespace

std::unique_ptr<EglContext> EglContext::create_headless(std::string* why_not) {
  std::string reasons;
  for (auto [display, name] : candidate_displays()) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
      reasons += name + ": eglInitialize failed; ";
      continue;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
      reasons += name + ": no desktop OpenGL API; ";
      continue;
    }
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config;
    EGLint configs = 0;
    eglChooseConfig(display, config_attribs, &config, 1, &configs);
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      4,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    EGLContext context = eglCreateContext(display, configs > 0 ? config : EGL_NO_CONFIG_KHR,
                                          EGL_NO_CONTEXT, context_attribs);
    if (context == EGL_NO_CONTEXT) {
      reasons += name + ": no OpenGL 4.5 core context; ";
      continue;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
      eglDestroyContext(display, context);
      reasons += name + ": cannot make a surfaceless context current; ";
      continue;
    }
    std::unique_ptr<EglContext> out(new EglContext());
    out->display_ = display;
    out->context_ = context;
    out->platform_ = name;
    return out;
  }
  if (why_not) *why_not = reasons.empty() ? "no EGL display" : reasons;
  return nullptr;
}

EglContext::~EglContext() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, static_cast<EGLContext>(context_));
}

void EglContext::make_current() const {
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, static_cast<EGLContext>(context_)))
    throw Error("EGL: cannot make the " + platform_ + " context current");
}

std::string EglContext::renderer() const {
  const auto* s = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return s ? s : "";
}

std::string EglContext::version() const {
  const auto* s = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return s ? s : "";
}

}  // namespace dv::gl
