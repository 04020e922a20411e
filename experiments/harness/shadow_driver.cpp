// Experiment kind `shadow`: a shadow method (any registered name, its parameters including the
// dsm storage) on a scene. Per item: generation (prepare) timed by PassTimer and per pass from
// the method's stats, one warm-up and `repeat` timed repetitions with a fresh method each; the
// render (raster renderer at the setting's size) timed the same way; bytes; the transmittance
// at the run's probe points against the exact oracle (|T' - T| max, mean, p50/p90/p95/p99,
// split into world-uniform surface and medium points, and the camera-visible points that
// weight the error as the image does; every probe's signed error goes to the item's samples,
// per class by name); image error against the reference render, over the image and per
// view-depth bin (nearest quarter of the surface pixels first), and PNGs (the
// render and its difference) for the report's image strip; with `strata_points`, the stratified
// error advise judges (strata_error: per stratum and the worst judged); the lights the frame's
// pixels evaluated after light culling (lights_per_pixel mean and max); on CUDA the item's peak
// device memory (device_memory: the pool's peak from the item's start). `frame_ms` (median
// generation plus median render) is the one time a Pareto front of error against time takes. The
// timed generation and frame are shadow_measure.h's, which bench_dsm and bench_renderer call too.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "cuda/pool_peak.h"
#include "experiments/harness/driver.h"
#include "experiments/harness/durable_file.h"
#include "experiments/harness/error_summary.h"
#include "experiments/harness/image_metrics.h"
#include "experiments/harness/probe_strata.h"
#include "experiments/harness/rows.h"
#include "experiments/harness/scene_cache.h"
#include "experiments/harness/shadow_measure.h"
#include "experiments/harness/timing.h"
#include "render/frame/raster_render.h"
#include "render/io/image.h"
#include "strategies/shadow/probe.h"

namespace dv {

namespace {

// The image error's view-depth bins: quarters of the surface pixels, nearest first.
constexpr int kDepthBins = 4;

struct ShadowSettings {
  int width, height, probe_points;
  double medium_fraction;
  uint64_t seed;
  double isosurface;  // >= 0: surface probes also on the volumes' isosurface at this density
  bool images;
  int visible_points;  // camera-visible probes; default probe_points
  int strata_points;   // > 0: the stratified probes (probe_strata.h) from this camera draw
  int stratum_min;     // their samples wanted per surface stratum
};

ShadowSettings read_settings(const RunItem& item, const Scene& scene) {
  const StrategyParams p(item.settings);
  ShadowSettings s{p.integer("width", scene.camera.width),
                   p.integer("height", scene.camera.height),
                   p.integer("probe_points", 400),
                   p.number("medium_fraction", 0.5),
                   uint64_t(p.integer("seed", 1)),
                   p.number("isosurface", -1.0),
                   p.integer("images", 1) != 0,
                   0,
                   p.integer("strata_points", 0),
                   p.integer("stratum_min", 200)};
  s.visible_points = p.integer("visible_points", s.probe_points);
  p.finish("experiment '" + item.experiment_name + "' settings");
  if (s.width < 1 || s.height < 1 || s.probe_points < 0 || s.visible_points < 0 ||
      s.strata_points < 0 || s.stratum_min < 1)
    throw InputError("experiment '" + item.experiment_name + "'",
                     "width, height and stratum_min must be positive and probe_points, "
                     "visible_points, strata_points not negative");
  return s;
}

// Numeric stats leaves: "*_ms" figures and {pass, ms} arrays become pass times, the rest values.
void collect_stats(const nlohmann::json& j, const std::string& path, PassTimes* times,
                   std::vector<std::pair<std::string, double>>* values) {
  for (const auto& [key, v] : j.items()) {
    const std::string name = path.empty() ? key : path + "." + key;
    if (v.is_object()) {
      collect_stats(v, name, times, values);
    } else if (v.is_array()) {
      for (const auto& e : v)
        if (e.is_object() && e.contains("pass") && e.contains("ms") && times)
          times->add(name + "." + e["pass"].get<std::string>(), e["ms"].get<double>());
    } else if (v.is_number() && is_time_metric(key)) {
      if (times) times->add(name.substr(0, name.size() - 3), v.get<double>());
    } else if (v.is_number() && values) {
      values->push_back({name, v.get<double>()});
    }
  }
}

// The summary rows of |error| over signed errors T' - T.
void emit_errors(RowSink& rows, const std::string& metric, std::vector<double> errors) {
  for (double& e : errors) e = std::abs(e);
  const ErrorSummary e = summarize_errors(std::move(errors));
  rows.add(metric, "count", double(e.count), "count");
  if (e.count == 0) return;
  rows.add(metric, "max", e.max, "T");
  rows.add(metric, "mean", e.mean, "T");
  rows.add(metric, "mean_lo", e.mean_lo, "T");
  rows.add(metric, "mean_hi", e.mean_hi, "T");
  rows.add(metric, "p50", e.p50, "T");
  rows.add(metric, "p90", e.p90, "T");
  rows.add(metric, "p95", e.p95, "T");
  rows.add(metric, "p95_lo", e.p95_lo, "T");
  rows.add(metric, "p95_hi", e.p95_hi, "T");
  rows.add(metric, "p99", e.p99, "T");
}

// The signed error T' - T per point-light pair of `probes`, into the vector of the point's
// class; counts the pairs the method or the oracle flagged.
void class_errors(const ProbeResults& r, const ProbeSet& probes,
                  std::map<ProbeClass, std::vector<double>>& errors, size_t& flagged) {
  for (size_t i = 0; i < r.transmittance.size(); ++i) {
    errors[probes.points.classes[i / size_t(r.light_count)]].push_back(r.transmittance[i] -
                                                                       probes.exact[i]);
    flagged += r.flags[i] != 0 || probes.exact_flags[i] != 0;
  }
}

class ShadowDriver : public Driver {
 public:
  std::vector<std::string> settings() const override {
    return {"width",      "height", "probe_points",   "medium_fraction", "seed",
            "isosurface", "images", "visible_points", "strata_points",   "stratum_min"};
  }
  std::vector<std::string> default_columns() const override {
    return {
        "generate_ms:median",     "render_ms:median",     "bytes",      "probe_error_surface:max",
        "probe_error_medium:max", "probe_error_all:mean", "image_rmse", "image_over_8"};
  }

  nlohmann::json run(const RunItem& item, RunContext& ctx, RowSink& rows) override {
    SceneCache& cache = *ctx.scenes;
    const Scene& scene = cache.scene(item.scene_path);
    const SceneData& data = cache.data(item.scene_path);
    const ShadowSettings s = read_settings(item, scene);
    Camera camera = scene.camera;
    camera.width = s.width;
    camera.height = s.height;
    const StrategyParams params = StrategyParams::parse(item.param_items());
    // The item's device footprint: the pool's peak from here (the cached scene data included).
    if (ctx.backend == Backend::cuda) reset_device_pool_peak();

    // A fresh method per generation and timed frames, each after a warm-up.
    TimedRepeats timed = timed_repeats(item.strategy, params, data, ctx.backend, camera,
                                       scene.background, ctx.repeat);
    PassTimes generation;
    for (size_t k = 0; k < timed.generate_ms.size(); ++k) {
      generation.add("generate", timed.generate_ms[k]);
      collect_stats(timed.generate_stats[k], "generate", &generation, nullptr);
    }
    generation.emit(rows, "");
    ShadowMethod& method = *timed.last.method;
    const nlohmann::json& stats = timed.last.stats;
    rows.add("bytes", "value", method_bytes(stats), "bytes");
    std::vector<std::pair<std::string, double>> figures;
    collect_stats(stats, "", nullptr, &figures);
    for (const auto& [name, value] : figures) rows.add("stats." + name, "value", value, "");

    PassTimes render;
    for (size_t k = 0; k < timed.render_ms.size(); ++k) {
      render.add("render", timed.render_ms[k]);
      render.add("render.raster", timed.raster_ms[k]);
      render.add("render.fragment", timed.fragment_ms[k]);
    }
    render.emit(rows, "");
    const RasterRenderResult& last = timed.frame;
    rows.add("frame_ms", "value", timed.frame_ms(), "ms");
    std::vector<double> frame_samples;
    for (size_t k = 0; k < timed.generate_ms.size(); ++k)
      frame_samples.push_back(timed.generate_ms[k] + timed.render_ms[k]);
    rows.samples()["timings"]["frame_ms"] = frame_samples;
    rows.add("render_flagged_pixels", "value",
             double(last.render.counters.overflow_pixels + last.render.counters.oracle_flag_pixels),
             "count");
    const double pixels = double(s.width) * s.height;
    rows.add("lights_per_pixel", "mean", double(last.render.counters.listed_lights) / pixels,
             "count");
    rows.add("lights_per_pixel", "max", double(last.render.counters.max_listed_lights), "count");
    if (ctx.backend == Backend::cuda) {
      const DevicePoolPeak peak = device_pool_peak();
      rows.add("device_memory", "peak_used", double(peak.used_bytes), "bytes");
      rows.add("device_memory", "peak_reserved", double(peak.reserved_bytes), "bytes");
    }

    probe_errors(item, ctx, s, method, rows);
    strata_errors(item, ctx, s, camera, method, rows);
    image_errors(item, ctx, s, last.render.image, rows);
    return {{"strategy", method.name()}, {"params", method.params()}};
  }

 private:
  static void probe_errors(const RunItem& item, RunContext& ctx, const ShadowSettings& s,
                           ShadowMethod& method, RowSink& rows) {
    const SceneData& data = ctx.scenes->data(item.scene_path);
    std::map<ProbeClass, std::vector<double>> errors;
    size_t flagged = 0;
    if (s.probe_points > 0) {
      const ProbeSet& probes = ctx.scenes->probes(item.scene_path, s.probe_points,
                                                  s.medium_fraction, s.seed, s.isosurface);
      const ProbeResults r = probe_transmittance(ctx.backend, data, method, probes.points.points);
      rows.add("probe_ms", "value", r.milliseconds, "ms");
      class_errors(r, probes, errors, flagged);
      std::vector<double> all = errors[ProbeClass::surface];
      all.insert(all.end(), errors[ProbeClass::medium].begin(), errors[ProbeClass::medium].end());
      emit_errors(rows, "probe_error_surface", errors[ProbeClass::surface]);
      emit_errors(rows, "probe_error_medium", errors[ProbeClass::medium]);
      emit_errors(rows, "probe_error_all", std::move(all));
      rows.samples()["probe_all"] = {to_string(ProbeClass::surface), to_string(ProbeClass::medium)};
    }
    if (s.visible_points > 0) {
      const ProbeSet& probes =
          ctx.scenes->visible_probes(item.scene_path, s.width, s.height, s.visible_points, s.seed);
      const ProbeResults r = probe_transmittance(ctx.backend, data, method, probes.points.points);
      class_errors(r, probes, errors, flagged);
      emit_errors(rows, std::string("probe_error_") + to_string(ProbeClass::visible),
                  errors[ProbeClass::visible]);
    }
    if (s.probe_points > 0 || s.visible_points > 0)
      rows.add("probe_flagged", "value", double(flagged), "count");
    // The signed errors per class, in point order, for the findings' paired bootstrap.
    for (const auto& [c, e] : errors) rows.samples()["probe_errors"][to_string(c)] = e;
  }

  // The error advise and --error-budget judge (probe_strata.h): per stratum its sample count,
  // p95, the p95's upper bound and max; strata_error's `judged` is the worst stratum's judged
  // error, what a bound E is checked against.
  static void strata_errors(const RunItem& item, RunContext& ctx, const ShadowSettings& s,
                            const Camera& camera, ShadowMethod& method, RowSink& rows) {
    if (s.strata_points == 0) return;
    const StratifiedProbes& probes = ctx.scenes->stratified_probes(
        item.scene_path, s.width, s.height, {s.strata_points, s.stratum_min, s.seed});
    if (probes.points.empty()) return;
    const std::array<StratumError, kStrata> errors =
        stratum_errors(probes, probe_transmittance(ctx.backend, ctx.scenes->data(item.scene_path),
                                                   method, probes.points, &camera)
                                   .transmittance);
    for (Stratum st : kAllStrata) {
      const StratumError& e = errors[size_t(st)];
      const std::string metric = std::string("strata_error_") + to_string(st);
      rows.add(metric, "count", double(e.count), "count");
      if (e.count == 0) continue;
      rows.add(metric, "p95", e.p95, "T");
      rows.add(metric, "p95_upper", e.p95_upper, "T");
      rows.add(metric, "max", e.max, "T");
    }
    rows.add("strata_error", "judged", worst_judged(errors), "T");
    rows.add("strata_error", "max", largest_error(errors), "T");
  }

  static void image_errors(const RunItem& item, RunContext& ctx, const ShadowSettings& s,
                           const Image& image, RowSink& rows) {
    ReferenceRender& ref = ctx.scenes->reference(item.scene_path, s.width, s.height);
    const ImageError e = image_error(image, ref.image);
    rows.add("image_rmse", "value", e.rmse, "1");
    rows.add("image_psnr", "value", e.psnr_db, "dB");
    rows.add("image_over_8", "value", e.fraction_over_8, "fraction");
    const DepthBins bins =
        depth_bins(ctx.scenes->sight(item.scene_path, s.width, s.height).depth, kDepthBins);
    const std::vector<double> binned = binned_rmse(image, ref.image, bins);
    for (int k = 0; k < kDepthBins; ++k) {
      const std::string bin = "depth" + std::to_string(k);
      rows.add("image_rmse_" + bin, "value", binned[size_t(k)], "1");
      rows.add("image_pixels_" + bin, "value", double(bins.pixels[size_t(k)]), "count");
    }
    for (int k = 0; k <= kDepthBins; ++k)
      rows.add("image_depth_edge" + std::to_string(k), "value", bins.edges[size_t(k)], "world");
    if (!s.images) return;
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(ctx.run_dir / "images", ec);
    if (ec) throw ResultWriteError((ctx.run_dir / "images").string(), ec.message());
    if (ref.png.empty()) {
      ref.png = "images/reference_" + fs::path(item.scene_path).stem().string() + "_" +
                std::to_string(s.width) + "x" + std::to_string(s.height) + ".png";
      save_png((ctx.run_dir / ref.png).string(), ref.image);
    }
    const std::string stem = "images/" + std::to_string(item.index) + "_" + item.strategy;
    save_png((ctx.run_dir / (stem + ".png")).string(), image);
    write_difference_png((ctx.run_dir / (stem + "_diff.png")).string(), image, ref.image);
    rows.add("image", "reference", 0.0, "", ref.png);
    rows.add("image", "render", 0.0, "", stem + ".png");
    rows.add("image", "difference", 0.0, "", stem + "_diff.png");
  }
};

}  // namespace

void register_shadow_driver(Registry<Driver>& registry) {
  registry.add("shadow",
               "a shadow method on a scene: generation and render time per pass, bytes, error at "
               "probe points against the exact oracle, image error against the reference render",
               {}, [](const StrategyParams&) { return std::make_unique<ShadowDriver>(); });
}

}  // namespace dv
