// Deep-shadow-map EXR files through OpenImageIO's deep-data API (see deep_exr.h): the full
// build's implementation.
#include <OpenImageIO/deepdata.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "render/io/deep_exr.h"

namespace dv {

namespace {

const char* const kPerspectiveDepth = "distance from the light";
const char* const kOrthographicDepth = "distance along the light direction from the near plane";
const OIIO::TypeDesc kMatrix44d(OIIO::TypeDesc::DOUBLE, OIIO::TypeDesc::MATRIX44);

OIIO::ImageSpec face_spec(const DeepMapFile& file, const DeepMapFace& f) {
  OIIO::ImageSpec spec(f.resolution, f.resolution, 3, OIIO::TypeDesc::FLOAT);
  spec.deep = true;
  spec.channelnames = {"A", "Z", "V"};
  spec.alpha_channel = 0;
  spec.z_channel = 1;
  spec.attribute("name", "light" + std::to_string(f.light) + ".face" + std::to_string(f.face));
  spec.attribute("compression", "zips");
  spec.attribute("deepvox:world_to_clip", kMatrix44d, f.world_to_clip.data());
  spec.attribute("deepvox:light", f.light);
  spec.attribute("deepvox:face", f.face);
  spec.attribute("deepvox:eps", file.eps);
  spec.attribute("deepvox:resolution", f.resolution);
  spec.attribute("deepvox:projection", f.orthographic ? "orthographic" : "perspective");
  spec.attribute("deepvox:depth", f.orthographic ? kOrthographicDepth : kPerspectiveDepth);
  spec.attribute("deepvox:channels", "Z: node depth; V: visibility after the node; A: alpha");
  if (!file.commit.empty()) spec.attribute("deepvox:commit", file.commit);
  return spec;
}

OIIO::DeepData face_samples(const OIIO::ImageSpec& spec, const DeepMapFace& f) {
  OIIO::DeepData d;
  d.init(spec);
  const int64_t texels = int64_t(f.resolution) * f.resolution;
  for (int64_t t = 0; t < texels; ++t) d.set_samples(t, int(f.offsets[t + 1] - f.offsets[t]));
  for (int64_t t = 0; t < texels; ++t) {
    float v_before = 1.0f;
    for (int64_t k = f.offsets[t]; k < f.offsets[t + 1]; ++k) {
      const int s = int(k - f.offsets[t]);
      d.set_deep_value(t, 0, s, deep_sample_alpha(v_before, f.nodes[k].v));
      d.set_deep_value(t, 1, s, f.nodes[k].z);
      d.set_deep_value(t, 2, s, f.nodes[k].v);
      v_before = f.nodes[k].v;
    }
  }
  return d;
}

void check_face(const std::string& path, const DeepMapFace& f) {
  const int64_t texels = int64_t(f.resolution) * f.resolution;
  if (f.resolution < 1 || f.offsets.size() != size_t(texels + 1) ||
      f.offsets.back() != int64_t(f.nodes.size()))
    throw InputError(path, "face " + std::to_string(f.face) + " of light " +
                               std::to_string(f.light) + ": offsets do not match its texels");
}

int channel_index(const std::string& path, int subimage, const OIIO::ImageSpec& spec,
                  const char* name) {
  for (int c = 0; c < spec.nchannels; ++c)
    if (spec.channelnames[c] == name) {
      if (spec.channelformat(c) != OIIO::TypeDesc::FLOAT)
        throw InputError(
            path, "subimage " + std::to_string(subimage) + ": channel " + name + " is not float");
      return c;
    }
  throw InputError(path, "subimage " + std::to_string(subimage) + " has no channel " + name +
                             " (a deepvox map has channels A, Z and V)");
}

DeepMapFace read_face(const std::string& path, OIIO::ImageInput& in, int s,
                      const OIIO::ImageSpec& spec) {
  const std::string where = "subimage " + std::to_string(s);
  if (!spec.deep)
    throw InputError(path, where + " is not a deep image (expected a `deepvox dsm` export)");
  if (spec.width != spec.height || spec.depth != 1)
    throw InputError(path, where + " is not a square map");
  const int z = channel_index(path, s, spec, "Z"), v = channel_index(path, s, spec, "V");
  const OIIO::ParamValue* m = spec.find_attribute("deepvox:world_to_clip", kMatrix44d);
  if (!m) throw InputError(path, where + " has no deepvox:world_to_clip matrix (double 4x4)");
  OIIO::DeepData d;
  if (!in.read_native_deep_image(s, 0, d))
    throw InputError(path, where + ": cannot read deep samples: " + in.geterror());
  DeepMapFace f;
  f.resolution = spec.width;
  std::copy_n(static_cast<const double*>(m->data()), 16, f.world_to_clip.begin());
  f.light = spec.get_int_attribute("deepvox:light");
  f.face = spec.get_int_attribute("deepvox:face");
  f.orthographic = spec.get_string_attribute("deepvox:projection") == "orthographic";
  const int64_t texels = int64_t(f.resolution) * f.resolution;
  f.offsets.assign(1, 0);
  for (int64_t t = 0; t < texels; ++t) {
    for (int k = 0; k < d.samples(t); ++k)
      f.nodes.push_back({d.deep_value(t, z, k), d.deep_value(t, v, k)});
    f.offsets.push_back(int64_t(f.nodes.size()));
  }
  return f;
}

}  // namespace

bool deep_exr_supported() {
  return true;
}

void write_deep_exr(const std::string& path, const DeepMapFile& file) {
  if (file.faces.empty()) throw InputError(path, "no deep shadow maps to write (no lights?)");
  std::vector<OIIO::ImageSpec> specs;
  for (const DeepMapFace& f : file.faces) {
    check_face(path, f);
    specs.push_back(face_spec(file, f));
  }
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw InputError(path, "OpenImageIO cannot create a writer: " + OIIO::geterror());
  if (!out->supports("deepdata") || (specs.size() > 1 && !out->supports("multiimage")))
    throw InputError(path, "this file type cannot hold deep subimages; use .exr");
  if (!out->open(path, int(specs.size()), specs.data()))
    throw InputError(path, "cannot write deep EXR: " + out->geterror());
  for (size_t i = 0; i < specs.size(); ++i) {
    if (i > 0 && !out->open(path, specs[i], OIIO::ImageOutput::AppendSubimage))
      throw InputError(path, "cannot write deep EXR: " + out->geterror());
    if (!out->write_deep_image(face_samples(specs[i], file.faces[i])))
      throw InputError(path, "cannot write deep EXR: " + out->geterror());
  }
  if (!out->close()) throw InputError(path, "cannot write deep EXR: " + out->geterror());
}

DeepMapFile read_deep_exr(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, "file not found");
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path, "cannot open as an image: " + OIIO::geterror());
  DeepMapFile file;
  for (int s = 0; in->seek_subimage(s, 0); ++s) {
    const OIIO::ImageSpec spec = in->spec();
    if (s == 0) {
      file.eps = spec.get_float_attribute("deepvox:eps");
      file.commit = spec.get_string_attribute("deepvox:commit");
    }
    file.faces.push_back(read_face(path, *in, s, spec));
  }
  return file;
}

}  // namespace dv
