// What the viewer shows and how keys and the mouse change it, without any window: the scene,
// the camera move, the shadow options (every switch goes through the strategy registries, and
// a switch the registry rejects leaves a message, not a crash), the backend and display
// transform; rendering through render_raster exactly as `deepvox render` does, and the
// `deepvox render` command line that reproduces the current image.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/common/shadow_options.h"
#include "apps/common/staging_options.h"
#include "apps/viewer/viewer_error_view.h"
#include "apps/viewer/viewer_script.h"
#include "apps/viewer/viewer_voxel_overlay.h"
#include "cuda/execute.h"
#include "engine/raster/camera_rays.h"
#include "engine/scene/scene.h"
#include "render/io/image.h"
#include "render/io/tone_mapping.h"

namespace dv {
class SceneData;
}

namespace dv::viewer {

struct ViewerSetup {
  std::string scene_path;
  cli::ShadowOptions shadows;
  std::string backend;  // "" = default_backend()
  int width = 0, height = 0;
  std::optional<double> exposure;  // unset: the scene's (default_exposure_ev), as render
  std::string tonemap = to_string(kDefaultToneCurve);  // render's default
  StagingOptions staging;
  CameraMove start;  // the camera R returns to is the scene's; this is where the viewer starts
};

// What a key asks of the window beyond a changed state.
enum class KeyAction { none, save, quit };

class ViewerState {
 public:
  explicit ViewerState(const ViewerSetup& setup);  // InputError for a bad scene or method
  ~ViewerState();

  KeyAction key(const std::string& name);  // a canonical name of viewer_keys.h
  // Left: orbit (0.25 degrees a pixel); right: dolly; middle: pan (in image heights).
  void drag(double dx, double dy, MouseButton button);
  void scroll(double steps);  // dolly by 0.9 a step towards the target

  // Renders when something changed since the last call (and rebuilds a shown heat map whose
  // method changed); returns whether the image changed. `coarse` (progressive refinement while
  // the camera moves): a quarter-size image scaled up, no error view; the next update without
  // it renders the full image even when nothing else changed.
  bool update(bool coarse = false);
  // Whether the last full image took long enough (> 100 ms) to render coarse while moving.
  bool slow() const { return slow_; }
  int renders() const { return renders_; }           // how many images update() has made: a version
  const Image& image() const { return image_; }      // linear, as the renderer produced it
  const Image& display() const { return display_; }  // what the window shows (see below)
  // Display-transformed sRGB bytes of `display()`, 3 per pixel, rows from the top: the bytes a
  // PNG of `render` holds (view image), or the error view.
  const std::vector<unsigned char>& display_bytes() const { return bytes_; }
  const Image* heatmap() const;  // the dsm method's layer heat map when shown, else null
  // The error view of the last full frame when shown (viewer_error_view.h), else null; its
  // legend's colour bar (0 left, error->max right).
  const TransmittanceError* error_view() const;
  const Image& error_legend() const { return legend_; }
  // The set voxels of the method's light grids when the overlay is on and it has grids, else
  // null; `voxel_version` changes whenever they are rebuilt.
  const VoxelPoints* voxel_points() const;
  int voxel_version() const { return voxel_version_; }
  // World -> clip of the current camera, as the rasterizer projects (raster_projection.h).
  dmat4 world_to_clip() const;
  // CUDA: the displayed image in device memory (linear rgb, before the display transform) when
  // it is the last full render (not coarse, not the error view); else null.
  const float* device_display() const;
  nlohmann::json stats() const { return stats_; }
  std::string panel_text() const;
  std::string render_command(const std::string& out) const;
  const std::string& message() const { return message_; }
  bool help_shown() const { return help_; }
  bool panel_shown() const { return panel_; }
  Backend backend() const { return backend_; }
  const DisplayTransform& display_transform() const { return transform_; }
  int width() const { return camera_.width; }
  int height() const { return camera_.height; }

  // Writes the rendered image as `render` writes a PNG (same display transform).
  void write_screenshot(const std::string& path) const;
  // Writes PREFIX.png, PREFIX.json (stats) and PREFIX.txt (the render command line).
  void save(const std::string& prefix) const;

 private:
  bool try_shadows(const cli::ShadowOptions& options);
  void set_backend(Backend backend);
  void render_error_view(const Camera& cam);
  void build_heatmap();
  void build_voxel_points();

  ViewerSetup setup_;
  Scene scene_;
  Camera camera_;  // the scene's, at the viewer's size
  CameraMove move_;
  Backend backend_;
  DisplayTransform transform_;
  std::unique_ptr<SceneData> data_;
  cli::ShadowOptions shadows_;
  std::unique_ptr<ShadowMethod> method_;
  bool dirty_ = true, coarse_shown_ = false, slow_ = false, heat_stale_ = true, heatmap_on_ = false,
       error_view_ = false, help_ = false, panel_ = true, grid_on_ = false, grid_stale_ = true;
  Image image_, display_, heatmap_, legend_;
  TransmittanceError error_;
  VoxelPoints voxels_;
  int voxel_version_ = 0;
  Buffer<float> device_image_;
  std::vector<unsigned char> bytes_;
  nlohmann::json stats_;
  std::string message_;
  int renders_ = 0;
};

}  // namespace dv::viewer
