// The viewer's window loop (see viewer.h): GLFW for the window and input, an OpenGL 4.5 core
// context, the image handed to a texture by the backend's image sink (image_sink.h: upload on
// the CPU, CUDA-GL interop on CUDA) and drawn by a full-screen triangle; on top the voxel grid
// overlay (GL points projected with the camera), the heat map in a corner, the error view's
// legend and the panel's text (stb_easy_font quads).
#include "apps/viewer/viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <stb_easy_font.h>

#include <cstdio>
#include <deque>

#include "apps/viewer/image_sink.h"
#include "apps/viewer/viewer_keys.h"
#include "core/error.h"
#include "core/log.h"
#include "core/number_text.h"
#include "gl/gl_program.h"
#include "render/io/display_encoding.h"
#include "render/io/image.h"

namespace dv::viewer {

namespace {

const char* kTriangleVertex = R"(#version 450 core
uniform vec4 rect;  // x0, y0, x1, y1 in normalized device coordinates
out vec2 uv;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  uv = p;
  gl_Position = vec4(rect.xy + (rect.zw - rect.xy) * p, 0.0, 1.0);
})";
// The triangle covers twice the rect; uv in [0, 1] over the rect itself.
const char* kImageFragment = R"(#version 450 core
uniform sampler2D image;
in vec2 uv;
out vec4 colour;
void main() {
  if (uv.x > 1.0 || uv.y > 1.0) discard;
  colour = vec4(texture(image, vec2(uv.x, 1.0 - uv.y)).rgb, 1.0);
})";
const char* kTextVertex = R"(#version 450 core
layout(location = 0) in vec2 pixel;
uniform vec2 viewport;
uniform vec2 offset;
void main() {
  vec2 p = (pixel + offset) / viewport * 2.0 - 1.0;
  gl_Position = vec4(p.x, -p.y, 0.0, 1.0);
})";
const char* kTextFragment = R"(#version 450 core
uniform vec4 ink;
out vec4 colour;
void main() { colour = ink; })";
// Voxel centres in world space, projected like the rasterizer (raster_projection.h); cyan
// nearest the light to magenta farthest.
const char* kVoxelVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in float depth;
uniform mat4 world_to_clip;
out vec3 tint;
void main() {
  tint = mix(vec3(0.0, 1.0, 1.0), vec3(1.0, 0.0, 1.0), depth);
  gl_Position = world_to_clip * vec4(position, 1.0);
})";
const char* kVoxelFragment = R"(#version 450 core
in vec3 tint;
out vec4 colour;
void main() { colour = vec4(tint, 1.0); })";

std::string glfw_key_name(int key) {
  switch (key) {
    case GLFW_KEY_LEFT_BRACKET:
      return "[";
    case GLFW_KEY_RIGHT_BRACKET:
      return "]";
    case GLFW_KEY_MINUS:
      return "-";
    case GLFW_KEY_EQUAL:
      return "=";
    case GLFW_KEY_ESCAPE:
      return "ESCAPE";
    case GLFW_KEY_F1:
      return "F1";
    case GLFW_KEY_SLASH:
      return "?";
    default:
      break;
  }
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return std::string(1, char('A' + key - GLFW_KEY_A));
  return "";
}

// Window input as script events, queued by the GLFW callbacks, applied by the loop.
struct Input {
  std::deque<ViewerEvent> events;
  bool dragging[3] = {false, false, false};
  double last_x = 0.0, last_y = 0.0;
};

Input& input_of(GLFWwindow* w) {
  return *static_cast<Input*>(glfwGetWindowUserPointer(w));
}

void on_key(GLFWwindow* w, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  const std::string name = key_from_name(glfw_key_name(key));
  if (name.empty()) return;
  ViewerEvent e;
  e.kind = EventKind::key;
  e.key = name;
  input_of(w).events.push_back(e);
}

void on_button(GLFWwindow* w, int button, int action, int) {
  if (button > 2) return;
  Input& in = input_of(w);
  in.dragging[button] = action == GLFW_PRESS;
  glfwGetCursorPos(w, &in.last_x, &in.last_y);
}

void on_cursor(GLFWwindow* w, double x, double y) {
  Input& in = input_of(w);
  const MouseButton buttons[3] = {MouseButton::left, MouseButton::right, MouseButton::middle};
  for (int b = 0; b < 3; ++b)
    if (in.dragging[b]) {
      ViewerEvent e;
      e.kind = EventKind::drag;
      e.dx = x - in.last_x;
      e.dy = y - in.last_y;
      e.button = buttons[b];
      in.events.push_back(e);
    }
  in.last_x = x;
  in.last_y = y;
}

void on_scroll(GLFWwindow* w, double, double dy) {
  ViewerEvent e;
  e.kind = EventKind::scroll;
  e.dy = dy;
  input_of(w).events.push_back(e);
}

class Window {
 public:
  Window(int width, int height) {
    if (!glfwInit())
      throw Error("view: cannot open a window (no display? run under `xvfb-run -a`)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, "deepvox view", nullptr, nullptr);
    if (!window_) {
      glfwTerminate();
      throw Error("view: cannot create an OpenGL 4.5 core window");
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(0);
    glfwSetWindowUserPointer(window_, &input_);
    glfwSetKeyCallback(window_, on_key);
    glfwSetMouseButtonCallback(window_, on_button);
    glfwSetCursorPosCallback(window_, on_cursor);
    glfwSetScrollCallback(window_, on_scroll);
    image_program_ = gl::link_program(kTriangleVertex, kImageFragment);
    text_program_ = gl::link_program(kTextVertex, kTextFragment);
    voxel_program_ = gl::link_program(kVoxelVertex, kVoxelFragment);
    glCreateVertexArrays(1, &voxel_vao_);
    glCreateBuffers(2, voxel_buffers_);
    glVertexArrayVertexBuffer(voxel_vao_, 0, voxel_buffers_[0], 0, 3 * sizeof(float));
    glVertexArrayVertexBuffer(voxel_vao_, 1, voxel_buffers_[1], 0, sizeof(float));
    for (GLuint a : {0u, 1u}) {
      glEnableVertexArrayAttrib(voxel_vao_, a);
      glVertexArrayAttribFormat(voxel_vao_, a, a == 0 ? 3 : 1, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(voxel_vao_, a, a);
    }
    glCreateVertexArrays(1, &empty_vao_);
    glCreateVertexArrays(1, &text_vao_);
    glCreateBuffers(1, &text_buffer_);
    glVertexArrayVertexBuffer(text_vao_, 0, text_buffer_, 0, 16);  // stb_easy_font's vertex
    glEnableVertexArrayAttrib(text_vao_, 0);
    glVertexArrayAttribFormat(text_vao_, 0, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(text_vao_, 0, 0);
    gl::check_gl("view: GL setup");
  }
  ~Window() {
    sink_.reset();
    heat_.reset();
    legend_.reset();
    glDeleteBuffers(1, &text_buffer_);
    glDeleteBuffers(2, voxel_buffers_);
    glDeleteVertexArrays(1, &voxel_vao_);
    glDeleteProgram(voxel_program_);
    glDeleteVertexArrays(1, &empty_vao_);
    glDeleteVertexArrays(1, &text_vao_);
    glDeleteProgram(image_program_);
    glDeleteProgram(text_program_);
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  GLFWwindow* handle() const { return window_; }
  Input& input() { return input_; }

  // The image through the sink for `backend` (a new sink when the backend changed).
  void present(Backend backend, const SinkFrame& frame) {
    if (!sink_ || sink_backend_ != backend) {
      sink_ = make_image_sink(backend);
      sink_backend_ = backend;
    }
    sink_->present(frame);
  }
  const char* image_path() const { return sink_ ? sink_->last_path() : "none"; }
  unsigned image_texture() const { return sink_ ? sink_->texture() : 0; }
  // Overlay textures: the heat map and the error legend, from linear images.
  unsigned upload_heat(const Image& image) { return upload_linear(heat_, image); }
  unsigned upload_legend(const Image& image) { return upload_linear(legend_, image); }

  // The voxel points, uploaded again when their version changes.
  void draw_voxels(const VoxelPoints& points, int version, const dmat4& world_to_clip) {
    if (version != voxel_version_) {
      glNamedBufferData(voxel_buffers_[0], GLsizeiptr(points.positions.size() * sizeof(float)),
                        points.positions.data(), GL_STATIC_DRAW);
      glNamedBufferData(voxel_buffers_[1], GLsizeiptr(points.depths.size() * sizeof(float)),
                        points.depths.data(), GL_STATIC_DRAW);
      voxel_version_ = version;
    }
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    glViewport(0, 0, fw, fh);
    float m[16];
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c * 4 + r] = float(world_to_clip[c][r]);
    glUseProgram(voxel_program_);
    glUniformMatrix4fv(glGetUniformLocation(voxel_program_, "world_to_clip"), 1, GL_FALSE, m);
    glPointSize(2.0f);
    glBindVertexArray(voxel_vao_);
    glDrawArrays(GL_POINTS, 0, GLsizei(points.count()));
  }

  // `texture` over the pixel rectangle (x, y, w, h) of the window, y from the top.
  void draw_texture(unsigned texture, int x, int y, int w, int h) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    glViewport(0, 0, fw, fh);
    glUseProgram(image_program_);
    glUniform4f(glGetUniformLocation(image_program_, "rect"), 2.0f * x / fw - 1.0f,
                1.0f - 2.0f * (y + h) / fh, 2.0f * (x + w) / fw - 1.0f, 1.0f - 2.0f * y / fh);
    glBindTextureUnit(0, texture);
    glBindVertexArray(empty_vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }

  // Text with a one-pixel shadow, top-left at (x, y) window pixels.
  void draw_text(const std::string& text, int x, int y) {
    std::vector<char> quads(text.size() * 270 + 1024);
    const int count = stb_easy_font_print(0.0f, 0.0f, const_cast<char*>(text.c_str()), nullptr,
                                          quads.data(), int(quads.size()));
    std::vector<float> triangles;  // two per quad, x y pairs
    for (int q = 0; q < count; ++q) {
      const float* v = reinterpret_cast<const float*>(quads.data() + size_t(q) * 64);
      for (int corner : {0, 1, 2, 0, 2, 3}) {
        triangles.push_back(v[corner * 4]);
        triangles.push_back(v[corner * 4 + 1]);
      }
    }
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    glNamedBufferData(text_buffer_, GLsizeiptr(triangles.size() * sizeof(float)), triangles.data(),
                      GL_STREAM_DRAW);
    glVertexArrayVertexBuffer(text_vao_, 0, text_buffer_, 0, 2 * sizeof(float));
    glUseProgram(text_program_);
    glUniform2f(glGetUniformLocation(text_program_, "viewport"), float(fw), float(fh));
    glBindVertexArray(text_vao_);
    const float shadow[4] = {0.0f, 0.0f, 0.0f, 1.0f}, white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    for (int pass = 0; pass < 2; ++pass) {
      glUniform2f(glGetUniformLocation(text_program_, "offset"), float(x + 1 - pass),
                  float(y + 1 - pass));
      glUniform4fv(glGetUniformLocation(text_program_, "ink"), 1, pass ? white : shadow);
      glDrawArrays(GL_TRIANGLES, 0, GLsizei(triangles.size() / 2));
    }
  }

  void write_framebuffer(const std::string& path) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    std::vector<unsigned char> rgb(size_t(fw) * fh * 3), rows(rgb.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, fw, fh, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    for (int y = 0; y < fh; ++y)  // GL rows run from the bottom
      std::copy_n(&rgb[size_t(fh - 1 - y) * fw * 3], size_t(fw) * 3, &rows[size_t(y) * fw * 3]);
    write_png_bytes(path, fw, fh, rows);
  }

 private:
  unsigned upload_linear(std::unique_ptr<ImageTexture>& texture, const Image& image) {
    const std::vector<unsigned char> bytes = srgb_bytes(image, DisplayTransform{});
    if (!texture) texture = std::make_unique<ImageTexture>();
    upload_bytes(*texture, image.width, image.height, bytes.data());
    return texture->id();
  }

  GLFWwindow* window_ = nullptr;
  Input input_;
  GLuint image_program_ = 0, text_program_ = 0, empty_vao_ = 0, text_vao_ = 0, text_buffer_ = 0;
  GLuint voxel_program_ = 0, voxel_vao_ = 0, voxel_buffers_[2] = {0, 0};
  int voxel_version_ = -1;
  std::unique_ptr<ImageSink> sink_;
  Backend sink_backend_ = Backend::cpu;
  std::unique_ptr<ImageTexture> heat_, legend_;
};

// The error view's legend, bottom right: its colour bar over 0 .. max with three numbers.
void draw_error_legend(Window& window, const ViewerState& state, const TransmittanceError& e) {
  const Image& bar = state.error_legend();
  const int w = std::min(bar.width, state.width() - 8), h = bar.height;
  const int x = state.width() - w - 4, y = state.height() - h - 16;
  window.draw_text("|T - T_oracle|", x, y - 12);
  window.draw_texture(window.upload_legend(bar), x, y, w, h);
  const std::string mid = significant_text(0.5 * e.max, 3), max = significant_text(e.max, 3);
  window.draw_text("0", x, y + h + 2);
  window.draw_text(mid, x + w / 2 - 3 * int(mid.size()), y + h + 2);
  window.draw_text(max, x + w - 6 * int(max.size()), y + h + 2);
}

// Draws the frame into the back buffer: image, voxel points, heat map (bottom-left, at most a
// third of the window), the error legend, then the help or else the panel text.
void draw(Window& window, const ViewerState& state) {
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  window.draw_texture(window.image_texture(), 0, 0, state.width(), state.height());
  if (const VoxelPoints* points = state.voxel_points())
    window.draw_voxels(*points, state.voxel_version(), state.world_to_clip());
  if (const Image* heat = state.heatmap()) {
    const double scale =
        std::min({1.0, state.width() / 3.0 / heat->width, state.height() / 3.0 / heat->height});
    const int w = std::max(1, int(heat->width * scale)), h = std::max(1, int(heat->height * scale));
    window.draw_texture(window.upload_heat(*heat), 0, state.height() - h, w, h);
  }
  if (const TransmittanceError* e = state.error_view()) draw_error_legend(window, state, *e);
  if (state.help_shown())  // in the panel's place
    window.draw_text(keys_help(), 4, 4);
  else if (state.panel_shown())
    window.draw_text(state.panel_text() + "\nimage to GL: " + window.image_path(), 4, 4);
  gl::check_gl("view: draw");
}

}  // namespace

int run_viewer(const ViewerRun& run) {
  const std::vector<ViewerEvent> script =
      run.script.empty() ? std::vector<ViewerEvent>{} : parse_script(run.script);
  if (!run.screenshot.empty()) check_image_path(run.screenshot);
  for (const ViewerEvent& e : script)
    if (e.kind == EventKind::screenshot) check_image_path(e.path);
  ViewerState state(run.setup);
  int frames = run.frames;
  if (frames == 0 && !script.empty()) frames = script.back().frame + 1;
  Window window(state.width(), state.height());
  size_t next = 0;
  int saves = 0, shown = 0;
  const bool interactive = frames == 0 && script.empty();
  double last_input = -1.0;
  bool quit = false;
  std::vector<std::string> shots;
  for (int frame = 0; !quit && (frames == 0 || frame < frames); ++frame) {
    if (glfwWindowShouldClose(window.handle())) break;
    glfwPollEvents();
    std::deque<ViewerEvent> events;
    events.swap(window.input().events);
    shots.clear();
    for (; next < script.size() && script[next].frame == frame; ++next) {
      if (script[next].kind == EventKind::screenshot)
        shots.push_back(script[next].path);
      else
        events.push_back(script[next]);
    }
    for (const ViewerEvent& e : events) {
      if (e.kind == EventKind::drag) state.drag(e.dx, e.dy, e.button);
      if (e.kind == EventKind::scroll) state.scroll(e.dy);
      if (e.kind != EventKind::key) continue;
      const KeyAction action = state.key(e.key);
      if (action == KeyAction::quit) quit = true;
      if (action == KeyAction::save) {
        char prefix[32];
        std::snprintf(prefix, sizeof prefix, "_%03d", saves++);
        state.update();
        state.save(run.save_prefix + prefix);
        log_info("view: saved " + run.save_prefix + prefix +
                 ".png/.json/.txt: " + state.render_command(run.save_prefix + prefix + ".png"));
      }
      if (!state.message().empty()) log_info("view: " + state.message());
    }
    // Progressive refinement, interactive runs only: coarse while input keeps coming to a slow
    // method, the full image once the camera has rested 0.3 s.
    if (!events.empty()) last_input = glfwGetTime();
    state.update(interactive && state.slow() && glfwGetTime() - last_input < 0.3);
    if (state.renders() != shown) {  // also when a save rendered it earlier this frame
      shown = state.renders();
      SinkFrame frame;
      frame.width = state.width();
      frame.height = state.height();
      frame.bytes = state.display_bytes().data();
      frame.device_rgb = state.device_display();
      frame.transform = state.display_transform();
      window.present(state.backend(), frame);
      glfwSetWindowTitle(window.handle(),
                         ("deepvox view: " + state.render_command("x.png")).c_str());
    }
    draw(window, state);
    for (const std::string& path : shots) state.write_screenshot(path);
    if (frames > 0 && frame == frames - 1) {
      if (!run.screenshot.empty()) state.write_screenshot(run.screenshot);
      if (!run.screenshot_window.empty()) window.write_framebuffer(run.screenshot_window);
    }
    glfwSwapBuffers(window.handle());
    if (frames == 0 && script.size() == next) glfwWaitEventsTimeout(0.05);
  }
  return 0;
}

}  // namespace dv::viewer
