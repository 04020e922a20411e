// JSON scene files and the dispatch of SCENE arguments by file type (see scene_loader.h).
#include "render/load/scene_loader.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/text.h"
#include "engine/scene/default_staging.h"
#include "render/io/mesh_io.h"
#include "render/load/gltf_import.h"
#include "render/load/mesh_generators.h"
#include "render/load/volume_generators.h"

namespace dv {

namespace fs = std::filesystem;

std::string find_assets_dir() {
  if (const char* env = std::getenv("DEEPVOX_ASSETS")) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  std::vector<fs::path> candidates;
  if (!ec) {
    candidates.push_back(exe.parent_path().parent_path() / "share/deepvox/experiments/assets");
    candidates.push_back(exe.parent_path() / "share/deepvox/experiments/assets");
  }
#ifdef DEEPVOX_SOURCE_ASSETS
  candidates.push_back(DEEPVOX_SOURCE_ASSETS);
#endif
  for (const fs::path& c : candidates)
    if (fs::is_directory(c, ec)) return c.string();
  return candidates.empty() ? "assets" : candidates.back().string();
}

namespace {

constexpr double kPi = 3.14159265358979323846;

dmat4 read_transform(JsonReader& t) {
  if (t.has("matrix")) {
    const Json& m = t.raw("matrix");
    if (!m.is_array() || m.size() != 16) t.fail("matrix", "expected 16 numbers (row-major)");
    dmat4 out;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) {
        if (!m[r * 4 + c].is_number()) t.fail("matrix", "expected 16 numbers (row-major)");
        out[c][r] = m[r * 4 + c].get<double>();
      }
    t.finish();
    return out;
  }
  dmat4 out(1.0);
  const dvec3 translate = t.vec3("translate", dvec3(0.0));
  dvec3 scale(1.0);
  if (t.has("scale")) {
    const Json& s = t.raw("scale");
    if (s.is_number())
      scale = dvec3(s.get<double>());
    else
      scale = t.vec3("scale");
  }
  // rotate: [x_deg, y_deg, z_deg], applied in the order x, then y, then z.
  const dvec3 rotate = t.vec3("rotate", dvec3(0.0));
  t.finish();
  dmat4 r(1.0);
  for (int a = 0; a < 3; ++a) {
    if (rotate[a] == 0.0) continue;
    dvec3 axis(0.0);
    axis[a] = 1.0;
    const double ang = rotate[a] * kPi / 180.0, c = std::cos(ang), s = std::sin(ang);
    dmat4 m(1.0);
    const int i = (a + 1) % 3, j = (a + 2) % 3;
    m[i][i] = c, m[j][i] = -s, m[i][j] = s, m[j][j] = c;
    r = m * r;
  }
  dmat4 sc(1.0);
  for (int a = 0; a < 3; ++a) sc[a][a] = scale[a];
  out[3] = dvec4(translate, 1.0);
  return out * r * sc;
}

Material read_material(JsonReader& m) {
  Material mat;
  mat.color = m.vec3("color", mat.color);
  mat.ambient = m.number("ambient", mat.ambient);
  mat.diffuse = m.number("diffuse", mat.diffuse);
  mat.specular = m.number("specular", mat.specular);
  mat.shininess = m.number("shininess", mat.shininess);
  mat.alpha = m.number("alpha", mat.alpha);
  mat.transmission = m.number("transmission", mat.transmission);
  mat.ior = m.number("ior", mat.ior);
  m.finish();
  return mat;
}

TransferFunction read_transfer(JsonReader& in) {
  TransferFunction tf;
  const Json& pts = in.raw("transfer");
  if (!pts.is_array() || pts.empty())
    in.fail("transfer", "expected a non-empty array of {\"density\", \"color\", \"sigma\"} points");
  for (size_t i = 0; i < pts.size(); ++i) {
    JsonReader p(pts[i], in.file(), in.path() + "/transfer/" + std::to_string(i));
    TransferPoint tp;
    tp.density = p.number("density");
    tp.color = p.vec3("color", tp.color);
    tp.sigma = p.number("sigma");
    p.finish();
    tf.points.push_back(tp);
  }
  return tf;
}

struct Loader {
  Scene& scene;
  fs::path dir;
  std::string assets;
  StagingOptions staging;
  std::map<std::string, int> mesh_files;  // path -> mesh index (loaded once)
  std::map<std::string, int> volume_names;
  double imported_exposure_ev = 0.0;  // the imported glTF's (its ambient and emission's scale)
  size_t imported_objects = 0;        // the scene's first objects are the imported ones

  std::string resolve(const std::string& p) const {
    fs::path path(p);
    return path.is_absolute() ? p : (dir / path).lexically_normal().string();
  }

  int load_mesh(JsonReader& obj, const Object& o) {
    const Json& m = obj.raw("mesh");
    if (m.is_string()) {
      const std::string name = m.get<std::string>();
      if (name == "volume_bounds") {
        if (o.interior.kind != InteriorKind::volume)
          obj.fail("mesh", "\"volume_bounds\" needs a volume interior");
        const Aabb b = scene.volumes[o.interior.volume].bounds();
        scene.meshes.push_back(make_box(b.lo, b.hi));
        scene.meshes.back().name = "volume_bounds";
        return int(scene.meshes.size()) - 1;
      }
      const std::string path = resolve(name);
      auto it = mesh_files.find(path);
      if (it != mesh_files.end()) return it->second;
      scene.meshes.push_back(load_mesh_file(path));
      return mesh_files[path] = int(scene.meshes.size()) - 1;
    }
    JsonReader spec = obj.child("mesh");
    scene.meshes.push_back(generate_mesh(spec, assets));
    return int(scene.meshes.size()) - 1;
  }

  Interior read_interior(JsonReader& in) {
    Interior it;
    const std::string type = in.string("type", "none");
    if (type == "none") {
    } else if (type == "constant") {
      it.kind = InteriorKind::constant;
      if (in.has("sigma") && in.raw("sigma").is_array()) {  // tinted: per-channel extinction
        const dvec3 sigma = in.vec3("sigma");
        const bool grey = sigma.x == sigma.y && sigma.y == sigma.z;  // tint exactly 1
        it.sigma = grey ? sigma.x : (sigma.x + sigma.y + sigma.z) / 3.0;
        if (it.sigma > 0.0 && !grey) it.sigma_tint = sigma / it.sigma;
      } else {
        it.sigma = in.number("sigma");
      }
    } else if (type == "volume") {
      it.kind = InteriorKind::volume;
      const std::string v = in.string("volume");
      auto f = volume_names.find(v);
      if (f == volume_names.end()) in.fail("volume", "no volume named '" + v + "' in \"volumes\"");
      it.volume = f->second;
      it.transfer = read_transfer(in);
      it.step = in.number("step", 0.0);
    } else {
      in.fail("type", "unknown interior type '" + type + "' (known: none, constant, volume)");
    }
    in.finish();
    return it;
  }

  void read_object(JsonReader& obj, int index) {
    Object o;
    o.name = obj.string("name", "object" + std::to_string(index));
    if (obj.has("transform")) {
      JsonReader t = obj.child("transform");
      o.transform = read_transform(t);
    }
    if (obj.has("material")) {
      JsonReader m = obj.child("material");
      o.material = read_material(m);
    }
    if (obj.has("interior")) {
      JsonReader in = obj.child("interior");
      o.interior = read_interior(in);
    }
    o.mesh = load_mesh(obj, o);
    obj.finish();
    scene.objects.push_back(std::move(o));
  }

  void read_light(JsonReader& l) {
    Light light;
    const std::string type = l.string("type");
    if (type == "spot") {
      light.type = LightType::spot;
      light.position = l.vec3("position");
      light.direction = l.vec3("direction");
      light.cutoff_deg = l.number("cutoff", light.cutoff_deg);
      light.penumbra_deg = l.number("penumbra", 0.0);
    } else if (type == "omni") {
      light.type = LightType::omni;
      light.position = l.vec3("position");
    } else if (type == "directional") {
      light.type = LightType::directional;
      light.direction = l.vec3("direction");
    } else {
      l.fail("type", "unknown light type '" + type + "' (known: spot, omni, directional)");
    }
    light.color = l.vec3("color", light.color);
    light.intensity = l.number("intensity", light.intensity);
    l.finish();
    scene.lights.push_back(light);
  }

  void read_camera(JsonReader& c) {
    Camera& cam = scene.camera;
    cam.position = c.vec3("position", cam.position);
    cam.target = c.vec3("target", cam.target);
    cam.up = c.vec3("up", cam.up);
    cam.fov_deg = c.number("fov", cam.fov_deg);
    cam.width = c.integer("width", cam.width);
    cam.height = c.integer("height", cam.height);
    cam.near_plane = c.number("near", cam.near_plane);
    c.finish();
  }

  // "import": "file.glb" or {"file": ..., "lights": true|false, "light_scale": k}: the glTF's
  // meshes, objects, camera and (unless "lights" is false) its lights times k. Default
  // lights are left to read(): they are added only when the whole scene has none.
  void read_import(JsonReader& r) {
    std::string file;
    bool keep_lights = true;
    double light_scale = 1.0;
    if (r.raw("import").is_string()) {
      file = r.string("import");
    } else {
      JsonReader in = r.child("import");
      file = in.string("file");
      keep_lights = in.boolean("lights", keep_lights);
      light_scale = in.number("light_scale", light_scale);
      if (!(light_scale >= 0.0 && std::isfinite(light_scale)))
        in.fail("light_scale", "must be a finite number >= 0");
      in.finish();
    }
    Scene imported = load_gltf_scene(resolve(file), {.default_lights = false});
    scene.meshes = std::move(imported.meshes);
    scene.textures = std::move(imported.textures);
    scene.objects = std::move(imported.objects);
    imported_exposure_ev = default_exposure_ev(imported);
    imported_objects = scene.objects.size();
    if (keep_lights) scene.lights = std::move(imported.lights);
    for (Light& light : scene.lights) {
      light.intensity *= light_scale;
      light.source_intensity *= light_scale;
    }
    scene.camera = imported.camera;
  }

  void read(const Json& root, const std::string& file) {
    JsonReader r(root, file, "");
    const bool imports = r.has("import");
    if (imports) read_import(r);
    if (r.has("volumes")) {
      JsonReader vols = r.child("volumes");
      for (auto& [name, spec] : r.raw("volumes").items()) {
        vols.raw(name);
        JsonReader v(spec, file, "/volumes/" + name);
        scene.volumes.push_back(generate_volume(v, dir.string()));
        scene.volumes.back().name = name;
        volume_names[name] = int(scene.volumes.size()) - 1;
      }
    }
    if (r.has("camera")) {
      JsonReader c = r.child("camera");
      read_camera(c);
    }
    scene.background = r.vec3("background", scene.background);
    if (r.has("lights"))
      for (JsonReader& l : r.children("lights")) read_light(l);
    if (r.has("objects")) {
      int i = 0;
      for (JsonReader& o : r.children("objects")) read_object(o, i++);
    }
    // "ground": true|false decides unless the command line does (--ground, --no-ground);
    // absent: a ground when the lights are staged.
    StagingOptions staged = staging;
    if (r.has("ground")) {
      const GroundPlane file_choice =
          r.boolean("ground", false) ? GroundPlane::on : GroundPlane::off;
      if (staging.ground == GroundPlane::staged) staged.ground = file_choice;
    }
    r.finish();
    if (scene.objects.empty()) throw InputError(file, "scene has no objects");
    if (scene.lights.empty() && !imports) throw InputError(file, "scene has no lights");
    // Only an imported glTF's photometric lights alone (light_scale or not) keep its exposure;
    // the display quantities (ambient, emission, background) follow the exposure the scene
    // ends with, the imported objects' from the exposure they were imported at.
    stage_scene(scene, staged);
    const double exposure_ev = default_exposure_ev(scene);
    for (size_t i = 0; i < scene.objects.size(); ++i)
      put_on_display_scale(scene.objects[i].material,
                           (i < imported_objects ? imported_exposure_ev : 0.0) - exposure_ev);
    scene.background *= std::exp2(-exposure_ev);
  }
};

}  // namespace

Scene load_scene(const std::string& path, const StagingOptions& staging,
                 const std::string& assets_dir) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, "file not found");
  Scene scene;
  scene.source = path;
  if (is_gltf_file(path)) {
    scene = load_gltf_scene(path, {.staging = staging});
  } else if (is_mesh_file(path)) {
    TriangleMesh mesh = load_mesh_file(path);
    scene.meshes.push_back(std::move(mesh));
    Object o;
    o.name = fs::path(path).stem().string();
    o.mesh = 0;
    scene.objects.push_back(o);
    scene.camera = default_camera(world_bounds(scene));
    stage_scene(scene, staging);
  } else if (lowercase_extension(path) == ".json") {
    Loader loader{scene,
                  fs::path(path).parent_path(),
                  assets_dir.empty() ? find_assets_dir() : assets_dir,
                  staging,
                  {},
                  {}};
    loader.read(parse_json_file(path), path);
  } else {
    throw InputError(path, "unknown scene type '" + lowercase_extension(path) +
                               "' (known: .json, .gltf, .glb, .obj, .off, .ply, .stl)");
  }
  scene.source = path;
  validate_scene(scene);
  return scene;
}

}  // namespace dv
