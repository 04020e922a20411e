// The viewer's state and its changes (see viewer_state.h).
#include "apps/viewer/viewer_state.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <utility>

#include "core/error.h"
#include "core/number_text.h"
#include "cuda/buffer.h"
#include "engine/raster/raster_projection.h"
#include "engine/scene/scene_view.h"
#include "render/frame/raster_render.h"
#include "render/io/display_encoding.h"
#include "render/io/dsm_export.h"
#include "render/io/layer_heatmap.h"
#include "render/load/gltf_import.h"
#include "render/load/scene_loader.h"
#include "strategies/shadow/shadow_method.h"
#include "strategies/storage/deep_shadow_maps.h"
#include "strategies/storage/dsm_storage.h"
#include "strategies/voxelizer/voxelizer.h"

namespace dv::viewer {

namespace {

// The registry name after `current` (case-insensitive), wrapping; the first when absent.
std::string next_name(const std::vector<std::string>& names, const std::string& current) {
  for (size_t i = 0; i < names.size(); ++i)
    if (lowercase(names[i]) == lowercase(current)) return names[(i + 1) % names.size()];
  return names.empty() ? current : names.front();
}

// A JSON value for the panel: numbers with 4 significant digits, strings unquoted.
std::string short_text(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (!value.is_number_float()) return value.dump();
  return significant_text(value.get<double>(), 4);
}

}  // namespace

ViewerState::ViewerState(const ViewerSetup& setup)
    : setup_(setup),
      move_(setup.start),
      backend_(setup.backend.empty() ? default_backend() : parse_backend(setup.backend)),
      transform_{setup.exposure.value_or(0.0), parse_tone_curve(setup.tonemap)},
      shadows_(setup.shadows) {
  require_backend(backend_);
  method_ = cli::make_shadow_method(shadows_);
  scene_ = load_scene(setup.scene_path, setup.staging);
  transform_.exposure_ev = setup.exposure.value_or(default_exposure_ev(scene_));
  camera_ = scene_.camera;
  if (setup.width) camera_.width = setup.width;
  if (setup.height) camera_.height = setup.height;
  data_ = std::make_unique<SceneData>(scene_, memory_of(backend_));
}

ViewerState::~ViewerState() = default;

bool ViewerState::try_shadows(const cli::ShadowOptions& options) {
  try {
    method_ = cli::make_shadow_method(options);
    shadows_ = options;
    dirty_ = heat_stale_ = grid_stale_ = true;
    return true;
  } catch (const InputError& e) {
    message_ = e.what();
    return false;
  }
}

void ViewerState::set_backend(Backend backend) {
  try {
    require_backend(backend);
  } catch (const Error& e) {  // not built, or no device: the previous backend stays
    message_ = e.what();
    return;
  }
  data_ = std::make_unique<SceneData>(scene_, memory_of(backend));
  backend_ = backend;
  method_ = cli::make_shadow_method(shadows_);  // fresh maps for the new backend's memory
  dirty_ = heat_stale_ = grid_stale_ = true;
}

KeyAction ViewerState::key(const std::string& name) {
  message_.clear();
  const nlohmann::json params = method_->params();
  cli::ShadowOptions next = shadows_;
  if (name == "M") {
    // Keep the knobs the new method accepts; a method that takes none of them starts plain.
    next.name = next_name(shadow_registry().names(), shadows_.name);
    if (!try_shadows(next)) {
      const std::string dropped = message_;
      cli::ShadowOptions plain;
      plain.name = next.name;
      if (try_shadows(plain))
        message_ = "settings not taken by " + next.name + " were dropped (" + dropped + ")";
    }
  } else if (name == "T") {
    next.storage = next_name(storage_registry().names(), params.value("storage", shadows_.storage));
    try_shadows(next);
  } else if (name == "[" || name == "]") {
    if (!params.contains("eps") || !params["eps"].is_number()) {
      message_ = method_->name() + " has no eps parameter";
    } else {
      const double eps = std::stod(exact_text(params["eps"].get<float>()));
      next.eps = std::clamp(name == "[" ? eps * 0.5 : eps * 2.0, 0.0, 4.0);
      try_shadows(next);
    }
  } else if (name == "-" || name == "=") {
    if (!params.contains("res") || !params["res"].is_number_integer()) {
      message_ = method_->name() + " has no res parameter";
    } else {
      const int res = params["res"].get<int>();
      next.dsm_res = std::clamp(name == "-" ? res / 2 : res * 2, 8, 16384);
      try_shadows(next);
    }
  } else if (name == "F") {
    next.filter = params.value("filter", std::string("none")) == "bilinear" ? "none" : "bilinear";
    try_shadows(next);
  } else if (name == "C") {
    if (!params.contains("clusters")) {
      message_ = method_->name() + " has no clusters parameter";
    } else {
      const int clusters = params["clusters"].is_number() ? params["clusters"].get<int>() : 1;
      std::erase_if(next.params, [](const std::string& p) { return p.starts_with("clusters="); });
      next.params.push_back("clusters=" + std::to_string(clusters >= 8 ? 1 : clusters * 2));
      try_shadows(next);
    }
  } else if (name == "V") {
    next.voxelizer =
        next_name(voxelizer_registry().names(), params.value("voxelizer", shadows_.voxelizer));
    try_shadows(next);
  } else if (name == "B") {
    set_backend(backend_ == Backend::cpu ? Backend::cuda : Backend::cpu);
  } else if (name == "H") {
    heatmap_on_ = !heatmap_on_;
  } else if (name == "E") {
    error_view_ = !error_view_;
    dirty_ = true;
  } else if (name == "G") {
    grid_on_ = !grid_on_;
    grid_stale_ = true;
  } else if (name == "P") {
    panel_ = !panel_;
  } else if (name == "F1") {
    help_ = !help_;
  } else if (name == "R") {
    move_ = CameraMove{};
    dirty_ = true;
  } else if (name == "S") {
    return KeyAction::save;
  } else if (name == "Q") {
    return KeyAction::quit;
  }
  return KeyAction::none;
}

void ViewerState::drag(double dx, double dy, MouseButton button) {
  if (button == MouseButton::left) {
    move_.yaw_deg -= 0.25 * dx;
    move_.pitch_deg = std::clamp(move_.pitch_deg + 0.25 * dy, -179.0, 179.0);
  } else if (button == MouseButton::right) {
    move_.dolly = std::clamp(move_.dolly * std::pow(1.005, dy), 1e-3, 1e3);
  } else {
    const double scale = 2.0 * move_.dolly / double(camera_.height);
    move_.pan_x -= dx * scale;
    move_.pan_y += dy * scale;
  }
  dirty_ = true;
}

void ViewerState::scroll(double steps) {
  move_.dolly = std::clamp(move_.dolly * std::pow(0.9, steps), 1e-3, 1e3);
  dirty_ = true;
}

bool ViewerState::update(bool coarse) {
  if (heatmap_on_ && heat_stale_) {
    heat_stale_ = false;
    build_heatmap();
  }
  if (grid_on_ && grid_stale_ && !dirty_) build_voxel_points();  // grids of the frame shown
  if (!dirty_ && !(coarse_shown_ && !coarse)) return false;
  dirty_ = false;
  coarse_shown_ = coarse;
  Camera cam = moved_camera(camera_, move_);
  const int step = coarse ? 4 : 1;
  cam.width = std::max(1, camera_.width / step);
  cam.height = std::max(1, camera_.height / step);
  RasterRenderResult rr = render_raster(backend_, *data_, cam, *method_, scene_.background);
  stats_ = rr.stats();
  stats_["shadows"] = {
      {"name", method_->name()}, {"params", method_->params()}, {"stats", method_->stats()}};
  stats_["backend"] = to_string(backend_);
  if (coarse) {
    stats_["coarse"] = step;
    image_ = Image(camera_.width, camera_.height);  // nearest-neighbour scale-up
    for (int y = 0; y < camera_.height; ++y)
      for (int x = 0; x < camera_.width; ++x)
        for (int c = 0; c < 3; ++c)
          image_.rgb[(size_t(y) * camera_.width + x) * 3 + c] =
              rr.render.image.rgb[(size_t(std::min(y / step, cam.height - 1)) * cam.width +
                                   std::min(x / step, cam.width - 1)) *
                                      3 +
                                  c];
    device_image_ = Buffer<float>();
  } else {
    slow_ = rr.render.milliseconds > 100.0;
    image_ = std::move(rr.render.image);
    device_image_ = std::move(rr.device_rgb);
  }
  display_ = apply_display_transform(image_, transform_);
  error_ = TransmittanceError();
  if (error_view_ && !coarse) render_error_view(cam);
  bytes_ = srgb_bytes(display_, DisplayTransform{});
  ++renders_;
  heat_stale_ = grid_stale_ = true;  // the method may have built its maps and grids just now
  if (heatmap_on_) {
    heat_stale_ = false;
    build_heatmap();
  }
  if (grid_on_) build_voxel_points();
  return true;
}

// |T' - T| at each pixel's visible surface point (viewer_error_view.h) as a colour map from
// 0 to the frame's maximum, in place of the image.
void ViewerState::render_error_view(const Camera& cam) {
  const auto start = std::chrono::steady_clock::now();
  error_ = transmittance_error(backend_, *data_, cam, *method_);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  display_ = error_image(error_);
  if (legend_.width == 0) legend_ = error_legend_bar(128, 10);
  stats_["error_view"] = {{"kind", "mean over lights of |T - T_oracle| at the visible surface"},
                          {"max", error_.max},
                          {"mean", error_.mean},
                          {"pixels", error_.pixels},
                          {"lights", error_.lights},
                          {"oracle_flags", error_.oracle_flags},
                          {"milliseconds", ms}};
}

// The layers per texel of the maps the method itself generated for the frame shown (built
// again after each render while the overlay is on; none before the method's first frame).
void ViewerState::build_heatmap() {
  const DeepShadowMaps* maps = method_->deep_shadow_maps();
  if (!maps) {
    heatmap_ = Image();
    if (method_->name() != "dsm") message_ = "heat map: only the dsm method has layers per texel";
    return;
  }
  try {
    heatmap_ = layer_heatmap(stored_layers(*maps), int(maps->layout().faces.size()),
                             maps->resolution(), face_labels(maps->layout()));
  } catch (const Error& e) {  // maps generated in sets of faces keep no per-texel records
    heatmap_ = Image();
    message_ = std::string("heat map: ") + e.what();
  }
}

const Image* ViewerState::heatmap() const {
  return heatmap_on_ && heatmap_.width > 0 ? &heatmap_ : nullptr;
}

// The set voxels of the grids the method built for the frame shown (none before its first
// frame); the stats say how many.
void ViewerState::build_voxel_points() {
  grid_stale_ = false;
  voxels_ = VoxelPoints();
  ++voxel_version_;
  const std::vector<VoxelGrid>* grids = method_->voxel_grids();
  if (!grids) {
    message_ = "voxel grid: " + method_->name() + " has no voxel grids";
    return;
  }
  if (grids->empty()) message_ = "voxel grid: no translucent casters, the grids are empty";
  for (const VoxelGrid& grid : *grids) add_set_voxels(grid, voxels_);
}

const VoxelPoints* ViewerState::voxel_points() const {
  return grid_on_ && voxels_.grids > 0 ? &voxels_ : nullptr;
}

const TransmittanceError* ViewerState::error_view() const {
  return error_view_ && error_.width > 0 ? &error_ : nullptr;
}

dmat4 ViewerState::world_to_clip() const {
  return make_camera_projection(moved_camera(camera_, move_), data_->view().bounds).world_to_clip;
}

const float* ViewerState::device_display() const {
  return device_image_.size() > 0 && !error_view() ? device_image_.data() : nullptr;
}

std::string ViewerState::panel_text() const {
  std::string text = method_->name() + " on " + to_string(backend_) + "  " +
                     std::to_string(camera_.width) + "x" + std::to_string(camera_.height);
  const nlohmann::json params = method_->params();
  for (const char* key : {"storage", "res", "eps", "filter", "voxelizer", "clusters"})
    if (params.contains(key)) text += std::string("  ") + key + "=" + short_text(params[key]);
  if (stats_.is_object()) {
    text += "\n";
    for (const char* key : {"milliseconds", "raster_ms", "fragment_ms"})
      if (stats_.contains(key)) text += std::string(key) + " " + short_text(stats_[key]) + "  ";
    // The method's figures and those of its parts one level down (storage bytes, layers).
    const nlohmann::json& s = stats_["shadows"]["stats"];
    std::string line;
    const auto add = [&](const std::string& item) {
      if (!line.empty() && line.size() + item.size() > 64) text += "\n" + std::exchange(line, "");
      line += item + "  ";
    };
    for (auto it = s.begin(); it != s.end(); ++it) {
      if (it.value().is_number()) add(it.key() + " " + short_text(it.value()));
      if (it.value().is_object())
        for (auto in = it.value().begin(); in != it.value().end(); ++in)
          if (in.value().is_number()) add(it.key() + "." + in.key() + " " + short_text(in.value()));
    }
    if (!line.empty()) text += "\n" + line;
    if (const TransmittanceError* e = error_view())
      text += "\nerror view: mean over lights |T - T_oracle|  max " + short_text(e->max) +
              "  mean " + short_text(e->mean) + "  (" + std::to_string(e->pixels) + " px)";
    if (const VoxelPoints* v = voxel_points())
      text += "\nvoxel grid: " + std::to_string(v->count()) + " set voxels in " +
              std::to_string(v->grids) + " light grids";
  }
  if (!message_.empty()) text += "\n" + message_;
  return text;
}

std::string ViewerState::render_command(const std::string& out) const {
  std::string cmd = "deepvox render " + setup_.scene_path + " --out " + out + " --backend " +
                    to_string(backend_) + " --shadows " + shadows_.name;
  for (const std::string& p : shadows_.params) cmd += " --param " + p;
  if (!shadows_.storage.empty()) cmd += " --storage " + shadows_.storage;
  if (shadows_.dsm_res) cmd += " --dsm-res " + std::to_string(*shadows_.dsm_res);
  if (shadows_.eps) cmd += " --eps " + exact_text(float(*shadows_.eps));
  if (!shadows_.filter.empty()) cmd += " --filter " + shadows_.filter;
  if (!shadows_.voxelizer.empty()) cmd += " --voxelizer " + shadows_.voxelizer;
  cmd +=
      " --width " + std::to_string(camera_.width) + " --height " + std::to_string(camera_.height);
  if (setup_.exposure) cmd += " --exposure " + exact_text(*setup_.exposure);
  if (setup_.tonemap != ViewerSetup{}.tonemap) cmd += " --tonemap " + setup_.tonemap;
  cmd += cli::staging_flag(setup_.staging);
  const CameraMove& m = move_;
  if (m.yaw_deg != 0.0 || m.pitch_deg != 0.0 || m.dolly != 1.0 || m.pan_x != 0.0 || m.pan_y != 0.0)
    cmd += " --view " + exact_text(m.yaw_deg) + "," + exact_text(m.pitch_deg) + "," +
           exact_text(m.dolly) + "," + exact_text(m.pan_x) + "," + exact_text(m.pan_y);
  return cmd;
}

void ViewerState::write_screenshot(const std::string& path) const {
  write_image(path, image_, transform_);
}

void ViewerState::save(const std::string& prefix) const {
  write_screenshot(prefix + ".png");
  std::ofstream stats(prefix + ".json");
  if (!stats) throw InputError(prefix + ".json", "cannot write stats file");
  stats << stats_.dump(2) << "\n";
  std::ofstream command(prefix + ".txt");
  if (!command) throw InputError(prefix + ".txt", "cannot write the command line");
  command << render_command(prefix + ".png") << "\n";
}

}  // namespace dv::viewer
