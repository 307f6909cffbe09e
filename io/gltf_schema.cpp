#include "io/gltf_schema.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>

#include "io/errors.h"
#include "io/gltf_loader.h"
#include "io/json_parse.h"

namespace prism {
namespace {

using nlohmann::json;

// The JSON text of a .gltf, or of a .glb's first chunk (glTF 2.0 §4.4: a 12-byte header, then
// chunks of length, type and data; the first chunk must be JSON).
std::string json_text(const std::vector<unsigned char>& bytes, const std::string& file) {
  if (!is_glb(bytes)) return std::string(bytes.begin(), bytes.end());
  auto u32 = [&](size_t at) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
  };
  if (bytes.size() < 20) throw InputError(file, "GLB header", "the file ends inside the header");
  if (u32(4) != 2) throw InputError(file, "GLB header", "version " + std::to_string(u32(4)) + ", expected 2");
  const uint64_t length = u32(12);
  if (u32(16) != 0x4E4F534Au) throw InputError(file, "GLB chunk 0", "the first chunk is not JSON");
  if (length > bytes.size() - 20)
    throw InputError(file, "GLB chunk 0", "declares " + std::to_string(length) + " bytes of JSON; the file has " +
                                              std::to_string(bytes.size() - 20) + " after the header");
  return std::string(bytes.begin() + 20, bytes.begin() + 20 + static_cast<std::ptrdiff_t>(length));
}

std::string describe(const json& j) {
  switch (j.type()) {
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array";
    case json::value_t::string: return "a string";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::null: return "null";
    default: return j.dump();
  }
}

bool is_integer(const json& j) {
  if (j.is_number_integer()) return true;
  if (!j.is_number_float()) return false;
  const double d = j.get<double>();
  return std::isfinite(d) && d == std::floor(d) && std::abs(d) < 9.0e15;
}

int64_t integer_value(const json& j) {
  return j.is_number_unsigned() ? int64_t(std::min<uint64_t>(j.get<uint64_t>(), INT64_MAX))
         : j.is_number_integer() ? j.get<int64_t>()
                                 : int64_t(j.get<double>());
}

class Schema;

// One JSON object under check at `path`; each method checks one property if present.
class Obj {
 public:
  Obj(const Schema& schema, const json& j, std::string path);

  Obj& require(std::initializer_list<const char*> keys);
  Obj& string(const char* key);
  Obj& strings(const char* key);
  Obj& boolean(const char* key);
  Obj& number(const char* key);
  Obj& numbers(const char* key, size_t count = 0);
  Obj& integer(const char* key, int64_t lo, int64_t hi);
  Obj& one_of(const char* key, std::initializer_list<const char*> values);
  Obj& one_of(const char* key, std::initializer_list<int64_t> values);
  Obj& ref(const char* key, const char* array);
  Obj& refs(const char* key, const char* array);
  Obj& refs_in_object(const char* array);  // every property's value is an index into `array`
  template <class F>
  Obj& object(const char* key, F&& check) {
    if (const json* v = get(key)) {
      Obj o(schema_, *v, at(key));
      check(o);
    }
    return *this;
  }
  template <class F>
  Obj& objects(const char* key, F&& check, size_t min_items = 0) {
    if (const json* v = get(key)) {
      expect_array(*v, at(key), min_items);
      for (size_t i = 0; i < v->size(); ++i) {
        Obj o(schema_, (*v)[i], at(key) + "[" + std::to_string(i) + "]");
        check(o);
      }
    }
    return *this;
  }
  // The object under extensions.NAME, checked by `check`, when present.
  template <class F>
  Obj& extension(const char* name, F&& check) {
    if (const json* e = get("extensions"); e && e->contains(name)) {
      Obj o(schema_, (*e)[name], at("extensions") + "." + name);
      check(o);
    }
    return *this;
  }
  bool has_extension(const char* name) const {
    const json* e = get("extensions");
    return e && e->contains(name);
  }
  const json* get(const char* key) const {
    auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
  }
  std::string at(const char* key) const { return path_ + "." + key; }
  const std::string& path() const { return path_; }

 private:
  void expect_array(const json& v, const std::string& where, size_t min_items) const;
  void check_ref(const json& v, const std::string& where, const char* array) const;

  const Schema& schema_;
  const json& j_;
  std::string path_;
};

class Schema {
 public:
  Schema(const json& root, std::string file) : root_(root), file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& reason) const {
    throw InputError(file_, path, reason);
  }
  size_t count(const char* array) const {
    auto it = root_.find(array);
    return it != root_.end() && it->is_array() ? it->size() : 0;
  }
  size_t light_count() const {
    const json* lights = nullptr;
    if (auto e = root_.find("extensions"); e != root_.end() && e->is_object())
      if (auto k = e->find("KHR_lights_punctual"); k != e->end() && k->is_object())
        if (auto l = k->find("lights"); l != k->end() && l->is_array()) lights = &*l;
    return lights ? lights->size() : 0;
  }

  void run() {
    Obj root(*this, root_, "$");
    root.require({"asset"})
        .object("asset", [](Obj& a) { a.require({"version"}).string("version").string("minVersion").string("generator").string("copyright"); })
        .strings("extensionsUsed")
        .strings("extensionsRequired")
        .ref("scene", "scenes")
        .objects("scenes", [](Obj& s) { s.string("name").refs("nodes", "nodes"); })
        .objects("nodes", [this](Obj& n) { node(n); })
        .objects("meshes", [this](Obj& m) { mesh(m); })
        .objects("accessors", [this](Obj& a) { accessor(a); })
        .objects("bufferViews", [](Obj& v) {
          v.require({"buffer", "byteLength"}).string("name").ref("buffer", "buffers").integer("byteOffset", 0, INT64_MAX)
              .integer("byteLength", 1, INT64_MAX).integer("byteStride", 4, 252).one_of("target", {34962, 34963});
        })
        .objects("buffers", [](Obj& b) { b.require({"byteLength"}).string("name").string("uri").integer("byteLength", 1, INT64_MAX); })
        .objects("materials", [this](Obj& m) { material(m); })
        .objects("textures", [](Obj& t) { t.string("name").ref("sampler", "samplers").ref("source", "images"); })
        .objects("images", [](Obj& i) { i.string("name").string("uri").string("mimeType").ref("bufferView", "bufferViews"); })
        .objects("samplers", [](Obj& s) {
          s.string("name").one_of("magFilter", {9728, 9729}).one_of("minFilter", {9728, 9729, 9984, 9985, 9986, 9987})
              .one_of("wrapS", {33071, 33648, 10497}).one_of("wrapT", {33071, 33648, 10497});
        })
        .objects("cameras", [](Obj& c) { camera(c); })
        .objects("skins", [](Obj& s) {
          s.require({"joints"}).string("name").ref("inverseBindMatrices", "accessors").ref("skeleton", "nodes").refs("joints", "nodes");
        })
        .objects("animations", [](Obj& a) {
          a.require({"channels", "samplers"}).string("name")
              .objects("channels", [](Obj& c) {
                c.require({"sampler", "target"}).integer("sampler", 0, INT64_MAX).object("target", [](Obj& t) {
                  t.require({"path"}).ref("node", "nodes").string("path");
                });
              }, 1)
              .objects("samplers", [](Obj& s) {
                s.require({"input", "output"}).ref("input", "accessors").ref("output", "accessors").one_of("interpolation", {"LINEAR", "STEP", "CUBICSPLINE"});
              }, 1);
        })
        .extension("KHR_lights_punctual", [](Obj& e) {
          e.objects("lights", [](Obj& l) {
            l.require({"type"}).string("name").one_of("type", {"directional", "point", "spot"}).numbers("color", 3)
                .number("intensity").number("range").object("spot", [](Obj& s) { s.number("innerConeAngle").number("outerConeAngle"); });
          });
        });
    required_extensions();
  }

 private:
  static void camera(Obj& c) {
    c.require({"type"}).string("name").one_of("type", {"perspective", "orthographic"})
        .object("perspective", [](Obj& p) { p.require({"yfov", "znear"}).number("yfov").number("znear").number("zfar").number("aspectRatio"); })
        .object("orthographic", [](Obj& o) { o.require({"xmag", "ymag", "zfar", "znear"}).number("xmag").number("ymag").number("zfar").number("znear"); });
  }

  void node(Obj& n) {
    n.string("name").ref("camera", "cameras").refs("children", "nodes").ref("skin", "skins").numbers("matrix", 16)
        .ref("mesh", "meshes").numbers("rotation", 4).numbers("scale", 3).numbers("translation", 3).numbers("weights")
        .extension("KHR_lights_punctual", [this](Obj& e) {
          e.require({"light"});
          const json& light = *e.get("light");
          if (!is_integer(light) || integer_value(light) < 0) fail(e.at("light"), "expected an index, got " + describe(light));
          if (uint64_t(integer_value(light)) >= light_count())
            fail(e.at("light"), std::to_string(integer_value(light)) + " is out of range (the file has " +
                                    std::to_string(light_count()) + " KHR_lights_punctual lights)");
        });
  }

  void mesh(Obj& m) {
    m.string("name").numbers("weights").objects("primitives", [this](Obj& p) {
      p.require({"attributes"}).ref("indices", "accessors").ref("material", "materials").integer("mode", 0, 6)
          .object("attributes", [](Obj& a) { a.refs_in_object("accessors"); })
          .objects("targets", [](Obj& t) { t.refs_in_object("accessors"); });
      draco_only(p);
    }, 1);
  }

  // KHR_draco_mesh_compression keeps the geometry in a compressed bufferView; a file may also
  // carry uncompressed accessors as a fallback. Without one there is nothing prism can read.
  void draco_only(Obj& p) const {
    if (!p.has_extension("KHR_draco_mesh_compression")) return;
    const json* attributes = p.get("attributes");
    auto pos = attributes->find("POSITION");
    const json& accessors = root_["accessors"];
    if (pos == attributes->end() || !accessors[pos->get<size_t>()].contains("bufferView"))
      fail(p.path(), "the geometry is Draco-compressed (KHR_draco_mesh_compression), which prism cannot decode");
  }

  void accessor(Obj& a) {
    a.require({"componentType", "count", "type"}).string("name").ref("bufferView", "bufferViews")
        .integer("byteOffset", 0, INT64_MAX).one_of("componentType", {5120, 5121, 5122, 5123, 5125, 5126})
        .boolean("normalized").integer("count", 1, INT64_MAX)
        .one_of("type", {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}).numbers("max").numbers("min")
        .object("sparse", [](Obj& s) {
          s.require({"count", "indices", "values"}).integer("count", 1, INT64_MAX)
              .object("indices", [](Obj& i) {
                i.require({"bufferView", "componentType"}).ref("bufferView", "bufferViews").integer("byteOffset", 0, INT64_MAX)
                    .one_of("componentType", {5121, 5123, 5125});
              })
              .object("values", [](Obj& v) { v.require({"bufferView"}).ref("bufferView", "bufferViews").integer("byteOffset", 0, INT64_MAX); });
        });
  }

  static void texture_info(Obj& t) {
    t.require({"index"}).ref("index", "textures").integer("texCoord", 0, INT64_MAX).extension("KHR_texture_transform", [](Obj& x) {
      x.numbers("offset", 2).number("rotation").numbers("scale", 2).integer("texCoord", 0, INT64_MAX);
    });
  }

  void material(Obj& m) {
    m.string("name").numbers("emissiveFactor", 3).one_of("alphaMode", {"OPAQUE", "MASK", "BLEND"}).number("alphaCutoff")
        .boolean("doubleSided").object("emissiveTexture", texture_info)
        .object("normalTexture", [](Obj& t) { texture_info(t); t.number("scale"); })
        .object("occlusionTexture", [](Obj& t) { texture_info(t); t.number("strength"); })
        .object("pbrMetallicRoughness", [](Obj& p) {
          p.numbers("baseColorFactor", 4).number("metallicFactor").number("roughnessFactor")
              .object("baseColorTexture", texture_info).object("metallicRoughnessTexture", texture_info);
        })
        .extension("KHR_materials_emissive_strength", [](Obj& e) { e.number("emissiveStrength"); })
        .extension("KHR_materials_transmission", [](Obj& e) { e.number("transmissionFactor").object("transmissionTexture", texture_info); })
        .extension("KHR_materials_ior", [](Obj& e) { e.number("ior"); })
        .extension("KHR_materials_volume", [](Obj& e) {
          e.number("thicknessFactor").object("thicknessTexture", texture_info).number("attenuationDistance").numbers("attenuationColor", 3);
        })
        .extension("KHR_materials_specular", [](Obj& e) {
          e.number("specularFactor").object("specularTexture", texture_info).numbers("specularColorFactor", 3)
              .object("specularColorTexture", texture_info);
        });
  }

  void required_extensions() const {
    auto it = root_.find("extensionsRequired");
    if (it == root_.end()) return;
    std::string unsupported;
    for (const auto& e : *it)
      if (!is_supported_gltf_extension(e.get<std::string>())) unsupported += (unsupported.empty() ? "" : ", ") + e.get<std::string>();
    if (!unsupported.empty()) fail("$.extensionsRequired", "prism does not support " + unsupported);
  }

  const json& root_;
  std::string file_;
};

Obj::Obj(const Schema& schema, const json& j, std::string path) : schema_(schema), j_(j), path_(std::move(path)) {
  if (!j.is_object()) schema_.fail(path_, "expected an object, got " + describe(j));
  if (const json* e = get("extensions"); e && !e->is_object())
    schema_.fail(at("extensions"), "expected an object, got " + describe(*e));
}

Obj& Obj::require(std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (!get(k)) schema_.fail(path_, "the required property '" + std::string(k) + "' is missing");
  return *this;
}

Obj& Obj::string(const char* key) {
  if (const json* v = get(key); v && !v->is_string()) schema_.fail(at(key), "expected a string, got " + describe(*v));
  return *this;
}

Obj& Obj::strings(const char* key) {
  if (const json* v = get(key)) {
    expect_array(*v, at(key), 0);
    for (size_t i = 0; i < v->size(); ++i)
      if (!(*v)[i].is_string()) schema_.fail(at(key) + "[" + std::to_string(i) + "]", "expected a string, got " + describe((*v)[i]));
  }
  return *this;
}

Obj& Obj::boolean(const char* key) {
  if (const json* v = get(key); v && !v->is_boolean()) schema_.fail(at(key), "expected true or false, got " + describe(*v));
  return *this;
}

Obj& Obj::number(const char* key) {
  if (const json* v = get(key); v && !v->is_number()) schema_.fail(at(key), "expected a number, got " + describe(*v));
  return *this;
}

Obj& Obj::numbers(const char* key, size_t count) {
  if (const json* v = get(key)) {
    expect_array(*v, at(key), 0);
    if (count && v->size() != count)
      schema_.fail(at(key), "expected " + std::to_string(count) + " numbers, got " + std::to_string(v->size()));
    for (size_t i = 0; i < v->size(); ++i)
      if (!(*v)[i].is_number()) schema_.fail(at(key) + "[" + std::to_string(i) + "]", "expected a number, got " + describe((*v)[i]));
  }
  return *this;
}

Obj& Obj::integer(const char* key, int64_t lo, int64_t hi) {
  if (const json* v = get(key)) {
    if (!is_integer(*v)) schema_.fail(at(key), "expected an integer, got " + describe(*v));
    const int64_t x = integer_value(*v);
    if (x < lo || x > hi)
      schema_.fail(at(key), std::to_string(x) + " is out of range (" + std::to_string(lo) +
                                (hi == INT64_MAX ? " or more)" : " to " + std::to_string(hi) + ")"));
  }
  return *this;
}

Obj& Obj::one_of(const char* key, std::initializer_list<const char*> values) {
  if (const json* v = get(key)) {
    string(key);
    std::string list;
    for (const char* value : values) {
      if (v->get<std::string>() == value) return *this;
      list += (list.empty() ? "" : ", ") + std::string(value);
    }
    schema_.fail(at(key), "'" + v->get<std::string>() + "' is not one of " + list);
  }
  return *this;
}

Obj& Obj::one_of(const char* key, std::initializer_list<int64_t> values) {
  if (const json* v = get(key)) {
    if (!is_integer(*v)) schema_.fail(at(key), "expected an integer, got " + describe(*v));
    std::string list;
    for (int64_t value : values) {
      if (integer_value(*v) == value) return *this;
      list += (list.empty() ? "" : ", ") + std::to_string(value);
    }
    schema_.fail(at(key), std::to_string(integer_value(*v)) + " is not one of " + list);
  }
  return *this;
}

Obj& Obj::ref(const char* key, const char* array) {
  if (const json* v = get(key)) check_ref(*v, at(key), array);
  return *this;
}

Obj& Obj::refs(const char* key, const char* array) {
  if (const json* v = get(key)) {
    expect_array(*v, at(key), 0);
    for (size_t i = 0; i < v->size(); ++i) check_ref((*v)[i], at(key) + "[" + std::to_string(i) + "]", array);
  }
  return *this;
}

Obj& Obj::refs_in_object(const char* array) {
  for (const auto& [key, value] : j_.items()) check_ref(value, path_ + "." + key, array);
  return *this;
}

void Obj::expect_array(const json& v, const std::string& where, size_t min_items) const {
  if (!v.is_array()) schema_.fail(where, "expected an array, got " + describe(v));
  if (v.size() < min_items) schema_.fail(where, "expected at least " + std::to_string(min_items) + " items, got none");
}

void Obj::check_ref(const json& v, const std::string& where, const char* array) const {
  if (!is_integer(v) || integer_value(v) < 0) schema_.fail(where, "expected an index (an integer of 0 or more), got " + describe(v));
  const size_t n = schema_.count(array);
  if (uint64_t(integer_value(v)) >= n)
    schema_.fail(where, std::to_string(integer_value(v)) + " is out of range (the file has " + std::to_string(n) + " " + array + ")");
}

}  // namespace

bool is_glb(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

void check_gltf_schema(const std::vector<unsigned char>& bytes, const std::string& file) {
  const json doc = parse_json(json_text(bytes, file), file);
  Schema(doc, file).run();
}

}  // namespace prism
