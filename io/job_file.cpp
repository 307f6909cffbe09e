#include "io/job_file.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "io/duration_text.h"
#include "io/errors.h"
#include "io/json_parse.h"
#include "io/exr_image.h"
#include "io/image_decode.h"

namespace prism {

using nlohmann::json;

namespace {

class JobParser {
 public:
  JobParser(std::string file, Diagnostics& diag) : file_(std::move(file)), diag_(diag) {}

  JobFile parse(const json& root) {
    JobFile job;
    job.path = file_;
    expect_object(root, "$");
    warn_unknown(root, "$", {"scene", "output", "preview", "pixel_type", "compression", "multipart", "stamp", "aovs", "crop", "sample_range", "resolution", "spp", "max_depth", "max_diffuse_depth", "seed", "camera",
                             "integrator", "sampler", "light_sampler", "texture_filter", "allocation", "time", "checkpoint", "noise", "min_spp", "rr_start_depth", "split", "clamp_indirect", "caster_share",
                             "materials", "spheres", "lights", "environment"});
    const std::filesystem::path dir = std::filesystem::path(file_).parent_path();
    auto relative = [&](const std::string& p) {
      const std::filesystem::path path(p);
      return (path.is_absolute() || dir.empty() ? path : dir / path).lexically_normal().string();
    };
    if (root.contains("scene")) job.scene = relative(string_at(root["scene"], "$.scene"));
    if (root.contains("output")) job.output = relative(string_at(root["output"], "$.output"));
    if (root.contains("preview")) job.preview = relative(string_at(root["preview"], "$.preview"));
    if (root.contains("pixel_type")) {
      job.pixel_type = string_at(root["pixel_type"], "$.pixel_type");
      if (*job.pixel_type != "float" && *job.pixel_type != "half") fail("$.pixel_type", "expected \"float\" or \"half\"");
    }
    if (root.contains("compression")) {
      job.compression = string_at(root["compression"], "$.compression");
      if (!parse_exr_compression(*job.compression)) fail("$.compression", "expected \"zip\", \"piz\", \"dwaa\" or \"none\"");
    }
    if (root.contains("multipart")) job.multipart = bool_at(root["multipart"], "$.multipart");
    if (root.contains("stamp")) job.stamp = bool_at(root["stamp"], "$.stamp");
    if (root.contains("aovs")) {
      const json& a = root["aovs"];
      std::string list;
      if (a.is_string()) list = a.get<std::string>();
      else if (a.is_array())
        for (size_t i = 0; i < a.size(); ++i) list += "," + string_at(a[i], "$.aovs[" + std::to_string(i) + "]");
      else fail("$.aovs", "expected a list of AOV names or a comma-separated string");
      try {
        job.settings.aovs = parse_aovs(list);
      } catch (const std::invalid_argument& e) {
        fail("$.aovs", e.what());
      }
    }
    if (root.contains("crop")) {
      const json& c = root["crop"];
      if (!c.is_array() || c.size() != 4) fail("$.crop", "expected [x0, y0, x1, y1]");
      int v[4];
      for (int i = 0; i < 4; ++i) v[i] = int_at(c[size_t(i)], "$.crop[" + std::to_string(i) + "]", 0, 1 << 16);
      if (v[2] <= v[0] || v[3] <= v[1]) fail("$.crop", "expected x0 < x1 and y0 < y1");
      job.settings.crop = PixelWindow{v[0], v[1], v[2], v[3]};
    }
    if (root.contains("sample_range")) {
      const json& r = root["sample_range"];
      if (!r.is_array() || r.size() != 2) fail("$.sample_range", "expected [first sample, count]");
      if (root.contains("spp")) fail("$.sample_range", "give either \"spp\" or \"sample_range\" (its count), not both");
      job.settings.first_sample = uint64_t(int_at(r[0], "$.sample_range[0]", 0, std::numeric_limits<int>::max()));
      job.settings.spp = int_at(r[1], "$.sample_range[1]", 1, 1 << 30);
    }
    if (root.contains("resolution")) {
      const json& r = root["resolution"];
      if (!r.is_array() || r.size() != 2) fail("$.resolution", "expected [width, height]");
      job.settings.width = int_at(r[0], "$.resolution[0]", 1, 1 << 16);
      job.settings.height = int_at(r[1], "$.resolution[1]", 1, 1 << 16);
    }
    if (root.contains("spp")) job.settings.spp = int_at(root["spp"], "$.spp", 1, 1 << 30);
    if (root.contains("max_depth")) job.settings.max_depth = int_at(root["max_depth"], "$.max_depth", 0, 1 << 16);
    if (root.contains("max_diffuse_depth"))
      job.settings.max_diffuse_depth = int_at(root["max_diffuse_depth"], "$.max_diffuse_depth", 0, 1 << 16);
    if (root.contains("seed")) {
      const json& s = root["seed"];
      if (!s.is_number_unsigned() && !(s.is_number_integer() && s.get<int64_t>() >= 0))
        fail("$.seed", "expected a non-negative integer");
      job.settings.seed = s.get<uint64_t>();
    }
    if (root.contains("camera")) {
      const json& c = root["camera"];
      if (c.is_string()) job.settings.camera = c.get<std::string>();
      else job.settings.camera = std::to_string(int_at(c, "$.camera", 0, std::numeric_limits<int>::max()));
    }
    if (root.contains("integrator")) job.settings.integrator = string_at(root["integrator"], "$.integrator");
    if (root.contains("sampler")) job.settings.sampler = string_at(root["sampler"], "$.sampler");
    if (root.contains("light_sampler"))
      job.settings.light_sampler = string_at(root["light_sampler"], "$.light_sampler");
    if (root.contains("texture_filter"))
      job.settings.texture_filter = string_at(root["texture_filter"], "$.texture_filter");
    if (root.contains("allocation")) job.settings.allocation = string_at(root["allocation"], "$.allocation");
    if (root.contains("time")) job.settings.time_budget = duration_at(root["time"], "$.time");
    if (root.contains("checkpoint")) job.checkpoint_seconds = duration_at(root["checkpoint"], "$.checkpoint");
    if (root.contains("noise")) job.settings.noise_target = number_at(root["noise"], "$.noise", 1e-6, 1e6);
    if (root.contains("min_spp")) job.settings.min_spp = int_at(root["min_spp"], "$.min_spp", 1, 1 << 30);
    if (root.contains("rr_start_depth"))
      job.settings.rr_start_depth = int_at(root["rr_start_depth"], "$.rr_start_depth", 1, 1 << 30);
    if (root.contains("split")) job.settings.split = int_at(root["split"], "$.split", 1, kMaxSplit);
    if (root.contains("clamp_indirect"))
      job.settings.clamp_indirect = number_at(root["clamp_indirect"], "$.clamp_indirect", 0, 3.0e38);
    if (root.contains("caster_share"))
      job.settings.caster_share = number_at(root["caster_share"], "$.caster_share", 0, 0.9);
    if (root.contains("materials")) {
      const json& m = root["materials"];
      expect_object(m, "$.materials");
      for (const auto& [name, value] : m.items()) job.materials.push_back(material(name, value, "$.materials." + name));
    }
    if (root.contains("environment")) {
      const json& e = root["environment"];
      const std::string where = "$.environment";
      expect_object(e, where);
      warn_unknown(e, where, {"map", "color", "intensity", "rotation"});
      if (e.contains("map")) job.environment.map = relative(string_at(e["map"], where + ".map"));
      if (e.contains("color")) job.environment.color = vec3_at(e["color"], where + ".color", 0, 3.0e38);
      if (e.contains("intensity")) job.environment.intensity = number_at(e["intensity"], where + ".intensity", 0, 3.0e38);
      if (e.contains("rotation")) job.environment.rotation_degrees = number_at(e["rotation"], where + ".rotation", -1e6, 1e6);
      if (!job.environment.present()) fail(where, "needs a \"map\" or a \"color\"");
    }
    if (root.contains("lights")) {
      const json& list = root["lights"];
      if (!list.is_array()) fail("$.lights", "expected an array");
      for (size_t i = 0; i < list.size(); ++i) job.lights.push_back(light(list[i], i));
    }
    if (root.contains("spheres")) {
      const json& list = root["spheres"];
      if (!list.is_array()) fail("$.spheres", "expected an array");
      for (size_t i = 0; i < list.size(); ++i) job.spheres.push_back(sphere(list[i], i, job));
    }
    return job;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& why) const { throw InputError(file_, where, why); }

  void expect_object(const json& j, const std::string& where) const {
    if (!j.is_object()) fail(where, "expected an object");
  }

  void warn_unknown(const json& j, const std::string& where, const std::set<std::string>& known) {
    for (const auto& [key, value] : j.items())
      if (!known.count(key)) diag_.warn(file_ + ": " + where + "." + key + ": unknown key, ignored");
  }

  std::string string_at(const json& j, const std::string& where) const {
    if (!j.is_string()) fail(where, "expected a string");
    return j.get<std::string>();
  }

  // Seconds, as a number or as text such as "30s", "2m", "1h30m".
  double duration_at(const json& j, const std::string& where) const {
    std::optional<double> seconds;
    if (j.is_number()) seconds = j.get<double>();
    else if (j.is_string()) seconds = parse_duration(j.get<std::string>());
    if (!seconds || !(*seconds > 0) || !std::isfinite(*seconds))
      fail(where, "expected a positive duration in seconds, or text such as \"30s\", \"2m\", \"1h30m\"");
    return *seconds;
  }

  bool bool_at(const json& j, const std::string& where) const {
    if (!j.is_boolean()) fail(where, "expected true or false");
    return j.get<bool>();
  }

  int int_at(const json& j, const std::string& where, int lo, int hi) const {
    if (!j.is_number_integer()) fail(where, "expected an integer");
    const auto v = j.get<int64_t>();
    if (v < lo || v > hi) fail(where, "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
    return static_cast<int>(v);
  }

  float number_at(const json& j, const std::string& where, double lo, double hi) const {
    if (!j.is_number()) fail(where, "expected a number");
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < lo || v > hi) {
      std::ostringstream range;
      range << "must be a finite number between " << lo << " and " << hi;
      fail(where, range.str());
    }
    return static_cast<float>(v);
  }

  Vec3 vec3_at(const json& j, const std::string& where, double lo, double hi) const {
    if (!j.is_array() || j.size() != 3) fail(where, "expected an array of 3 numbers");
    return {number_at(j[0], where + "[0]", lo, hi), number_at(j[1], where + "[1]", lo, hi),
            number_at(j[2], where + "[2]", lo, hi)};
  }

  MaterialEdit material(const std::string& name, const json& j, const std::string& where) {
    expect_object(j, where);
    warn_unknown(j, where, {"base_color", "metallic", "roughness", "emissive", "emissive_strength", "double_sided",
                            "transmission", "ior", "volume", "attenuation_color", "attenuation_distance"});
    MaterialEdit m;
    m.name = name;
    constexpr double kMax = 3.0e38;
    if (j.contains("base_color")) m.base_color = vec3_at(j["base_color"], where + ".base_color", 0, 1);
    if (j.contains("metallic")) m.metallic = number_at(j["metallic"], where + ".metallic", 0, 1);
    if (j.contains("roughness")) m.roughness = number_at(j["roughness"], where + ".roughness", 0, 1);
    if (j.contains("emissive")) m.emissive = vec3_at(j["emissive"], where + ".emissive", 0, kMax);
    if (j.contains("emissive_strength"))
      m.emissive_strength = number_at(j["emissive_strength"], where + ".emissive_strength", 0, kMax);
    if (j.contains("double_sided")) m.double_sided = bool_at(j["double_sided"], where + ".double_sided");
    if (j.contains("transmission")) m.transmission = number_at(j["transmission"], where + ".transmission", 0, 1);
    if (j.contains("ior")) m.ior = number_at(j["ior"], where + ".ior", 1, 1e3);
    if (j.contains("volume")) m.volume = bool_at(j["volume"], where + ".volume");
    if (j.contains("attenuation_color"))
      m.attenuation_color = vec3_at(j["attenuation_color"], where + ".attenuation_color", 0, 1);
    if (j.contains("attenuation_distance")) {
      m.attenuation_distance = number_at(j["attenuation_distance"], where + ".attenuation_distance", 0, kMax);
      if (!(*m.attenuation_distance > 0)) fail(where + ".attenuation_distance", "must be positive");
    }
    return m;
  }

  // A KHR_lights_punctual light in the job: "type", "color", "intensity" (cd or lux), "position",
  // "direction" (where it shines), "range", and "inner_cone_angle" / "outer_cone_angle" (radians).
  PunctualLightDesc light(const json& j, size_t index) {
    const std::string where = "$.lights[" + std::to_string(index) + "]";
    expect_object(j, where);
    warn_unknown(j, where, {"name", "type", "color", "intensity", "position", "direction", "range", "inner_cone_angle",
                            "outer_cone_angle"});
    PunctualLightDesc l;
    l.name = j.contains("name") ? string_at(j["name"], where + ".name") : "light " + std::to_string(index);
    const std::string type = j.contains("type") ? string_at(j["type"], where + ".type") : "";
    if (type == "point") l.type = LightType::Point;
    else if (type == "spot") l.type = LightType::Spot;
    else if (type == "directional") l.type = LightType::Directional;
    else fail(where + ".type", "expected \"point\", \"spot\" or \"directional\"");
    const Rgb colour = j.contains("color") ? vec3_at(j["color"], where + ".color", 0, 3.0e38) : Rgb(1.0f);
    const float intensity = j.contains("intensity") ? number_at(j["intensity"], where + ".intensity", 0, 3.0e38) : 1.0f;
    l.intensity = colour * intensity;
    if (j.contains("position")) l.position = vec3_at(j["position"], where + ".position", -3.0e38, 3.0e38);
    else if (l.type != LightType::Directional) fail(where, "missing \"position\"");
    if (j.contains("direction")) {
      const Vec3 d = vec3_at(j["direction"], where + ".direction", -3.0e38, 3.0e38);
      if (!(length(d) > 0)) fail(where + ".direction", "must not be zero");
      l.direction = normalize(d);
    } else if (l.type != LightType::Point) {
      fail(where, "missing \"direction\"");
    }
    if (j.contains("range")) l.range = number_at(j["range"], where + ".range", 0, 3.0e38);
    const float inner = j.contains("inner_cone_angle") ? number_at(j["inner_cone_angle"], where + ".inner_cone_angle", 0, 1.5707964) : 0.0f;
    const float outer = j.contains("outer_cone_angle") ? number_at(j["outer_cone_angle"], where + ".outer_cone_angle", 0, 1.5707964) : 0.7853982f;
    if (l.type == LightType::Spot && !(inner < outer)) fail(where, "inner_cone_angle must be below outer_cone_angle");
    l.cos_inner = std::cos(inner);
    l.cos_outer = std::cos(outer);
    return l;
  }

  JobSphere sphere(const json& j, size_t index, JobFile& job) {
    const std::string where = "$.spheres[" + std::to_string(index) + "]";
    expect_object(j, where);
    warn_unknown(j, where, {"name", "center", "radius", "material"});
    JobSphere s;
    s.name = j.contains("name") ? string_at(j["name"], where + ".name") : "sphere " + std::to_string(index);
    if (!j.contains("center")) fail(where, "missing \"center\"");
    if (!j.contains("radius")) fail(where, "missing \"radius\"");
    s.center = vec3_at(j["center"], where + ".center", -3.0e38, 3.0e38);
    s.radius = number_at(j["radius"], where + ".radius", 0, 3.0e38);
    if (!(s.radius > 0)) fail(where + ".radius", "must be positive");
    if (j.contains("material")) {
      const json& m = j["material"];
      if (m.is_string()) {
        s.material = m.get<std::string>();
      } else if (m.is_object()) {
        // An inline material becomes a job material named after the sphere.
        s.material = "(sphere " + std::to_string(index) + ")";
        job.materials.push_back(material(s.material, m, where + ".material"));
      } else {
        fail(where + ".material", "expected a material name or an object");
      }
    }
    return s;
  }

  std::string file_;
  Diagnostics& diag_;
};

void apply_edit(const MaterialEdit& e, MaterialDesc& m) {
  if (e.base_color) m.base_color = *e.base_color;
  if (e.metallic) m.metallic = *e.metallic;
  if (e.roughness) m.roughness = *e.roughness;
  if (e.emissive) m.emissive = *e.emissive;
  if (e.emissive_strength) m.emissive_strength = *e.emissive_strength;
  if (e.double_sided) m.double_sided = *e.double_sided;
  if (e.transmission) m.transmission = *e.transmission;
  if (e.ior) m.ior = *e.ior;
  if (e.volume) m.volume = *e.volume;
  if (e.attenuation_color) m.attenuation_color = *e.attenuation_color;
  if (e.attenuation_distance) m.attenuation_distance = *e.attenuation_distance;
}

}  // namespace

void apply_environment(const EnvironmentSpec& spec, SceneDesc& scene) {
  if (!spec.present()) return;
  EnvironmentDesc& env = scene.environment;
  env.present = true;
  env.color = spec.color.value_or(Rgb(1.0f)) * spec.intensity.value_or(1.0f);
  env.rotation = spec.rotation_degrees.value_or(0.0f) * 3.14159265358979f / 180.0f;
  env.image = -1;
  env.source.clear();
  if (spec.map) {
    // A half-float EXR keeps its halves: an 8K map then takes 192 MiB instead of 384.
    ImageDesc img = read_image_file(*spec.map, ColorSpace::Auto, TexelStorage::Compact);
    // Every stored value, whatever the storage, as the renderer will read it.
    const auto unusable = [](float v) { return !std::isfinite(v) || v < 0; };
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        if (const Rgba t = img.texel(x, y); unusable(t.rgb.x) || unusable(t.rgb.y) || unusable(t.rgb.z) || unusable(t.a))
          throw InputError(*spec.map, "environment map", "has negative or non-finite pixels");
    env.image = static_cast<int>(scene.images.size());
    env.source = *spec.map;
    scene.images.push_back(std::move(img));
  }
}

JobFile parse_job_json(const std::string& text, const std::string& path, Diagnostics& diag) {
  return JobParser(path, diag).parse(parse_json(text, path));
}

JobFile parse_job_file(const std::string& path, Diagnostics& diag) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open job file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_job_json(text.str(), path, diag);
}

void apply_job_edits(const JobFile& job, SceneDesc& scene) {
  for (const MaterialEdit& e : job.materials) {
    bool matched = false;
    for (MaterialDesc& m : scene.materials) {
      if (m.name != e.name) continue;
      apply_edit(e, m);
      matched = true;
    }
    if (!matched) {
      // A material the job defines: glTF defaults, then the job's fields.
      MaterialDesc m;
      m.name = e.name;
      apply_edit(e, m);
      scene.materials.push_back(m);
    }
  }
  scene.lights.insert(scene.lights.end(), job.lights.begin(), job.lights.end());
  for (size_t i = 0; i < job.spheres.size(); ++i) {
    const JobSphere& js = job.spheres[i];
    SphereDesc s;
    s.name = js.name;
    s.center = js.center;
    s.radius = js.radius;
    if (!js.material.empty()) {
      s.material = scene.find_material(js.material);
      if (s.material < 0)
        throw InputError(job.path, "$.spheres[" + std::to_string(i) + "].material",
                         "no material named '" + js.material + "' in the scene or the job");
    }
    scene.spheres.push_back(s);
  }
}

}  // namespace prism
