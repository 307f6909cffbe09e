#include "io/gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "core/memory_limit.h"
#include "core/tangents.h"
#include "io/errors.h"
#include "io/gltf_accessor.h"
#include "io/gltf_schema.h"
#include "io/image_decode.h"

namespace prism {

bool is_supported_gltf_extension(const std::string& name) {
  static const std::set<std::string> kSupported = {"KHR_materials_emissive_strength", "KHR_materials_transmission",
                                                   "KHR_materials_ior", "KHR_materials_volume",
                                                   "KHR_lights_punctual", "KHR_texture_transform",
                                                   "KHR_materials_specular"};
  return kSupported.count(name) > 0 || is_metadata_gltf_extension(name);
}

// XMP metadata (authoring tool, licence, ...) attached to the asset or any of its objects: nothing
// in it changes what a render shows, so it needs no support and no warning.
bool is_metadata_gltf_extension(const std::string& name) { return name == "KHR_xmp" || name == "KHR_xmp_json_ld"; }

namespace {

constexpr int kMaxNodeDepth = 1024;

std::string quoted_name(const std::string& kind, int index, const std::string& name) {
  return kind + " " + std::to_string(index) + (name.empty() ? "" : " '" + name + "'");
}

// Keeps the encoded bytes of URI images (tinygltf has read the file or data URI) for
// OpenImageIO to decode later. Images in buffer views are left alone: tinygltf 2.7 hands over
// an unchecked pointer for those, so they are range-checked and read by the converter instead.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;
  if (bytes && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

// The stand-in for an image that cannot be read: one magenta texel, bright enough to be seen.
ImageDesc magenta_image() {
  ImageDesc img;
  img.width = img.height = 1;
  img.channels = 4;
  img.texels = {1.0f, 0.0f, 1.0f, 1.0f};
  return img;
}

double number(const tinygltf::Value& v, double fallback) { return v.IsNumber() ? v.GetNumberAsDouble() : fallback; }

class Converter {
 public:
  Converter(const tinygltf::Model& model, std::string file, Diagnostics& diag)
      : model_(model), file_(std::move(file)), diag_(diag) {}

  SceneDesc run() {
    check_extensions();
    desc_.source = file_;
    for (size_t m = 0; m < model_.materials.size(); ++m) desc_.materials.push_back(convert_material(int(m)));
    report_unrendered_features();
    for (int root : scene_roots()) visit(root, Transform(), 0);
    std::stable_sort(cameras_by_node_.begin(), cameras_by_node_.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& [node, cam] : cameras_by_node_) desc_.cameras.push_back(std::move(cam));
    if (desc_.instances.empty()) diag_.warn("the scene has no triangle meshes");
    if (!model_.lights.empty() && desc_.lights.empty())
      diag_.warn("KHR_lights_punctual lights are defined but no node of the scene places one");
    return std::move(desc_);
  }

 private:
  [[noreturn]] void fail(const std::string& element, const std::string& reason) const {
    throw InputError(file_, element, reason);
  }

  // Unsupported extensionsRequired were refused by check_gltf_schema.
  void check_extensions() {
    for (const auto& e : model_.extensionsUsed)
      if (!is_supported_gltf_extension(e)) diag_.warn("extension " + e + " is not supported yet and is ignored");
  }

  void report_unrendered_features() {
    if (!model_.animations.empty())
      diag_.warn(std::to_string(model_.animations.size()) + " animations ignored: the scene renders at rest");
    if (!model_.skins.empty()) diag_.warn(std::to_string(model_.skins.size()) + " skins ignored: meshes render unskinned");
  }

  // The nodes to start from: the default scene's, else scene 0's, else every parentless node.
  std::vector<int> scene_roots() {
    const int n_scenes = static_cast<int>(model_.scenes.size());
    int scene = model_.defaultScene;
    if (scene >= n_scenes) {
      diag_.warn("default scene " + std::to_string(scene) + " does not exist; using scene 0");
      scene = -1;
    }
    if (scene < 0 && n_scenes > 0) scene = 0;
    if (scene >= 0) return model_.scenes[scene].nodes;
    std::vector<bool> is_child(model_.nodes.size(), false);
    for (const auto& n : model_.nodes)
      for (int c : n.children)
        if (c >= 0 && c < static_cast<int>(is_child.size())) is_child[c] = true;
    std::vector<int> roots;
    for (size_t i = 0; i < model_.nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(static_cast<int>(i));
    if (!roots.empty()) diag_.warn("the file has no scenes; rendering every root node");
    return roots;
  }

  Transform local_transform(const tinygltf::Node& node, const std::string& where) const {
    auto finite = [&](const std::vector<double>& v, size_t want, const char* what) {
      if (!v.empty() && v.size() != want)
        fail(where, std::string(what) + " has " + std::to_string(v.size()) + " numbers, expected " + std::to_string(want));
      for (double x : v)
        if (!std::isfinite(x)) fail(where, std::string(what) + " has a non-finite value");
    };
    finite(node.matrix, 16, "matrix");
    finite(node.translation, 3, "translation");
    finite(node.rotation, 4, "rotation");
    finite(node.scale, 3, "scale");
    if (node.matrix.size() == 16) {
      std::array<double, 16> m{};
      std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
      return Transform::from_column_major(m);
    }
    Transform t;
    if (node.translation.size() == 3)
      t = Transform::translate(Vec3(float(node.translation[0]), float(node.translation[1]), float(node.translation[2])));
    if (node.rotation.size() == 4)
      t = t * Transform::rotate_quaternion(node.rotation[0], node.rotation[1], node.rotation[2], node.rotation[3]);
    if (node.scale.size() == 3)
      t = t * Transform::scale(Vec3(float(node.scale[0]), float(node.scale[1]), float(node.scale[2])));
    return t;
  }

  void visit(int index, const Transform& parent, int depth) {
    if (index < 0 || index >= static_cast<int>(model_.nodes.size()))
      fail("node reference", "node index " + std::to_string(index) + " out of range (" +
                                 std::to_string(model_.nodes.size()) + " nodes)");
    const tinygltf::Node& node = model_.nodes[index];
    const std::string where = quoted_name("node", index, node.name);
    if (on_path_.count(index)) fail(where, "node hierarchy has a cycle through this node");
    if (visited_.count(index)) fail(where, "node has more than one parent (glTF node hierarchies are trees)");
    if (depth > kMaxNodeDepth) fail(where, "node hierarchy is deeper than " + std::to_string(kMaxNodeDepth));
    visited_.insert(index);
    on_path_.insert(index);
    const Transform world = parent * local_transform(node, where);

    if (node.mesh >= 0) {
      if (node.mesh >= static_cast<int>(model_.meshes.size()))
        fail(where, "mesh index " + std::to_string(node.mesh) + " out of range");
      if (node.skin >= 0) diag_.warn("skinned meshes render in their bind pose");
      if (!world.is_invertible()) {
        diag_.warn(where + ": zero-scale transform; its mesh is not rendered");
      } else {
        InstanceDesc inst;
        inst.name = node.name;
        inst.mesh = scene_mesh(node.mesh);
        inst.object_to_world = world;
        if (inst.mesh >= 0) desc_.instances.push_back(std::move(inst));
      }
    }
    if (node.camera >= 0) {
      if (node.camera >= static_cast<int>(model_.cameras.size()))
        fail(where, "camera index " + std::to_string(node.camera) + " out of range");
      cameras_by_node_.emplace_back(index, convert_camera(node.camera, node.name, world));
    }
    if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end()) {
      const tinygltf::Value& light = it->second.Get("light");
      if (!light.IsInt() || light.GetNumberAsInt() < 0 || light.GetNumberAsInt() >= static_cast<int>(model_.lights.size()))
        fail(where, "KHR_lights_punctual light index missing or out of range");
      desc_.lights.push_back(convert_light(light.GetNumberAsInt(), world));
    }
    for (int child : node.children) visit(child, world, depth + 1);
    on_path_.erase(index);
  }

  CameraDesc convert_camera(int index, const std::string& node_name, const Transform& world) const {
    const tinygltf::Camera& c = model_.cameras[index];
    const std::string where = quoted_name("camera", index, c.name);
    CameraDesc cam;
    cam.name = !c.name.empty() ? c.name : node_name;
    cam.node_name = node_name;
    cam.camera_to_world = world;
    if (c.type == "orthographic") {
      const auto& o = c.orthographic;
      if (!(std::isfinite(o.xmag) && std::isfinite(o.ymag) && o.xmag != 0 && o.ymag != 0))
        fail(where, "orthographic xmag and ymag must be finite and non-zero");
      cam.projection = Projection::Orthographic;
      cam.xmag = float(std::abs(o.xmag));
      cam.ymag = float(std::abs(o.ymag));
      cam.znear = float(std::max(0.0, o.znear));
      cam.zfar = float(std::max(0.0, o.zfar));
    } else if (c.type == "perspective") {
      const auto& p = c.perspective;
      if (!(p.yfov > 0 && p.yfov < 3.14159265358979)) fail(where, "yfov must be in (0, pi) radians");
      cam.projection = Projection::Perspective;
      cam.yfov = float(p.yfov);
      if (p.aspectRatio > 0 && std::isfinite(p.aspectRatio)) cam.aspect_ratio = float(p.aspectRatio);
      cam.znear = float(std::max(0.0, p.znear));
      cam.zfar = p.zfar > p.znear && std::isfinite(p.zfar) ? float(p.zfar) : 0.0f;
    } else {
      fail(where, "unknown camera type '" + c.type + "'");
    }
    return cam;
  }

  PunctualLightDesc convert_light(int index, const Transform& world) const {
    const tinygltf::Light& l = model_.lights[index];
    const std::string where = quoted_name("KHR_lights_punctual light", index, l.name);
    PunctualLightDesc out;
    out.name = l.name;
    Rgb colour(1.0f);
    if (l.color.size() == 3) colour = Rgb(float(l.color[0]), float(l.color[1]), float(l.color[2]));
    if (!is_finite(colour) || min(colour, Rgb(0.0f)) != Rgb(0.0f)) fail(where, "color must be finite and non-negative");
    if (!(l.intensity >= 0 && std::isfinite(l.intensity))) fail(where, "intensity must be finite and non-negative");
    out.intensity = colour * float(l.intensity);
    if (!(l.range >= 0 && std::isfinite(l.range))) fail(where, "range must be positive (or absent)");
    out.range = float(l.range);
    out.position = world.point(Vec3(0, 0, 0));
    const Vec3 dir = world.vector(Vec3(0, 0, -1));
    if (!(length(dir) > 0)) fail(where, "its node's transform collapses the light direction");
    out.direction = normalize(dir);
    if (l.type == "point") {
      out.type = LightType::Point;
    } else if (l.type == "directional") {
      out.type = LightType::Directional;
    } else if (l.type == "spot") {
      out.type = LightType::Spot;
      const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
      if (!(inner >= 0 && inner < outer && outer <= 1.5707963267948966))
        fail(where, "spot angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
      out.cos_inner = float(std::cos(inner));
      out.cos_outer = float(std::cos(outer));
    } else {
      fail(where, "unknown light type '" + l.type + "'");
    }
    return out;
  }

  int scene_mesh(int gltf_mesh) {
    if (auto it = mesh_map_.find(gltf_mesh); it != mesh_map_.end()) return it->second;
    const tinygltf::Mesh& mesh = model_.meshes[gltf_mesh];
    MeshDesc out;
    out.name = mesh.name;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string where = quoted_name("mesh", gltf_mesh, mesh.name) + " primitive " + std::to_string(p);
      PrimitiveDesc prim;
      if (convert_primitive(mesh.primitives[p], where, prim)) out.primitives.push_back(std::move(prim));
    }
    const int index = out.primitives.empty() ? -1 : static_cast<int>(desc_.meshes.size());
    if (index >= 0) desc_.meshes.push_back(std::move(out));
    mesh_map_[gltf_mesh] = index;
    return index;
  }

  bool convert_primitive(const tinygltf::Primitive& p, const std::string& where, PrimitiveDesc& prim) {
    const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      diag_.warn("points and lines primitives are not rendered (mode " + std::to_string(mode) + ")");
      return false;
    }
    const auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end()) {
      diag_.warn(where + ": no POSITION attribute; skipped");
      return false;
    }
    if (!p.targets.empty()) diag_.warn("morph targets ignored: meshes render in their base shape");
    for (const auto& [name, accessor] : p.attributes)
      if (name.rfind("COLOR_", 0) == 0) diag_.warn("vertex colours (" + name + ") are not supported yet and are ignored");
    if (p.material < -1 || p.material >= static_cast<int>(model_.materials.size()))
      fail(where, "material index " + std::to_string(p.material) + " out of range");
    prim.material = p.material;

    const std::vector<float> positions = read_accessor_floats(model_, pos->second, 3, {TINYGLTF_COMPONENT_TYPE_FLOAT},
                                                              file_, where + " POSITION");
    const size_t n = positions.size() / 3;
    prim.positions.resize(n);
    for (size_t i = 0; i < n; ++i) {
      prim.positions[i] = {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
      if (!is_finite(prim.positions[i])) fail(where + " POSITION", "vertex " + std::to_string(i) + " is not finite");
    }
    if (auto it = p.attributes.find("NORMAL"); it != p.attributes.end()) {
      const std::vector<float> normals =
          read_accessor_floats(model_, it->second, 3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, file_, where + " NORMAL");
      if (normals.size() != positions.size()) fail(where + " NORMAL", "count differs from POSITION");
      prim.normals.resize(n);
      size_t zero = 0, not_unit = 0;
      for (size_t i = 0; i < n; ++i) {
        prim.normals[i] = {normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]};
        if (!is_finite(prim.normals[i])) fail(where + " NORMAL", "normal " + std::to_string(i) + " is not finite");
        const float len = length(prim.normals[i]);
        zero += len == 0;
        not_unit += len != 0 && std::abs(len - 1.0f) > 1e-3f;  // glTF 2.0 §3.7.2.1: normals are unit vectors
      }
      if (zero)
        diag_.warn(where + " NORMAL: " + std::to_string(zero) + " zero-length normals; the face normal shades there");
      if (not_unit) diag_.warn(where + " NORMAL: " + std::to_string(not_unit) + " normals are not unit length; renormalised");
    }
    if (auto it = p.attributes.find("TEXCOORD_0"); it != p.attributes.end()) {
      const std::vector<float> uvs = read_accessor_floats(
          model_, it->second, 2,
          {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
          file_, where + " TEXCOORD_0");
      if (uvs.size() / 2 != n) fail(where + " TEXCOORD_0", "count differs from POSITION");
      prim.uvs.resize(n);
      for (size_t i = 0; i < n; ++i) {
        prim.uvs[i] = {uvs[2 * i], uvs[2 * i + 1]};
        if (!std::isfinite(prim.uvs[i].x) || !std::isfinite(prim.uvs[i].y))
          fail(where + " TEXCOORD_0", "uv " + std::to_string(i) + " is not finite");
      }
    }

    if (auto it = p.attributes.find("TANGENT"); it != p.attributes.end()) {
      const std::vector<float> t =
          read_accessor_floats(model_, it->second, 4, {TINYGLTF_COMPONENT_TYPE_FLOAT}, file_, where + " TANGENT");
      if (t.size() / 4 != n) fail(where + " TANGENT", "count differs from POSITION");
      prim.tangents.resize(n);
      prim.tangent_signs.resize(n);
      for (size_t i = 0; i < n; ++i) {
        prim.tangents[i] = {t[4 * i], t[4 * i + 1], t[4 * i + 2]};
        if (!is_finite(prim.tangents[i]) || !std::isfinite(t[4 * i + 3]))
          fail(where + " TANGENT", "tangent " + std::to_string(i) + " is not finite");
        prim.tangent_signs[i] = t[4 * i + 3] < 0 ? -1.0f : 1.0f;
      }
    }

    std::vector<uint32_t> order;
    if (p.indices >= 0) {
      order = read_accessor_indices(model_, p.indices, file_, where + " indices");
      for (size_t k = 0; k < order.size(); ++k)
        if (order[k] >= n)
          fail(where + " indices", "index " + std::to_string(order[k]) + " at position " + std::to_string(k) +
                                       " is not below the vertex count " + std::to_string(n));
    } else {
      order.resize(n);
      for (size_t i = 0; i < n; ++i) order[i] = static_cast<uint32_t>(i);
    }
    prim.indices = triangulate(order, mode);
    // What the scene keeps per vertex and per triangle, and Embree's BVH (about 64 bytes a triangle).
    const uint64_t per_vertex = sizeof(Vec3) + (prim.normals.empty() ? 0 : sizeof(Vec3)) +
                                (prim.uvs.empty() ? 0 : sizeof(Vec2)) + (sizeof(Vec3) + sizeof(float));  // + tangents
    tally_.add(n * per_vertex + prim.indices.size() / 3 * (3 * sizeof(uint32_t) + 64), file_ + ": " + where);
    // glTF 2.0 §3.7.2.1: without TANGENT, tangents come from positions, normals and uvs.
    if (prim.tangents.empty() && !prim.normals.empty() && !prim.uvs.empty() && p.material >= 0 &&
        model_.materials[p.material].normalTexture.index >= 0)
      generate_tangents(prim);
    if (mode == TINYGLTF_MODE_TRIANGLES && order.size() % 3 != 0)
      diag_.warn(where + ": index count " + std::to_string(order.size()) + " is not a multiple of 3; the rest is ignored");
    return true;
  }

  // Triangle list from a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN index order (glTF 2.0 §3.7.2.1).
  static std::vector<uint32_t> triangulate(const std::vector<uint32_t>& v, int mode) {
    std::vector<uint32_t> tris;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      tris.assign(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 3 * 3));
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      // p_i = {v_i, v_(i+1+i%2), v_(i+2-i%2)}: odd triangles swap two vertices to keep the winding.
      for (size_t i = 0; i + 2 < v.size(); ++i) tris.insert(tris.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
    } else {
      for (size_t i = 1; i + 1 < v.size(); ++i) tris.insert(tris.end(), {v[i], v[i + 1], v[0]});
    }
    return tris;
  }

  MaterialDesc convert_material(int index) {
    const tinygltf::Material& m = model_.materials[index];
    const std::string where = quoted_name("material", index, m.name);
    MaterialDesc out;
    out.name = m.name;
    const auto& pbr = m.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() == 4) {
      out.base_color = Rgb(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]), float(pbr.baseColorFactor[2]));
      out.base_alpha = float(pbr.baseColorFactor[3]);
    }
    out.metallic = float(pbr.metallicFactor);
    out.roughness = float(pbr.roughnessFactor);
    if (m.emissiveFactor.size() == 3)
      out.emissive = Rgb(float(m.emissiveFactor[0]), float(m.emissiveFactor[1]), float(m.emissiveFactor[2]));
    out.double_sided = m.doubleSided;
    if (!is_finite(out.base_color) || !is_finite(out.emissive) || !std::isfinite(out.base_alpha))
      fail(where, "colour factors must be finite");
    out.base_color = max(out.base_color, Rgb(0.0f));
    out.emissive = max(out.emissive, Rgb(0.0f));

    for (const auto& [name, value] : m.extensions) {
      if (name == "KHR_materials_emissive_strength") {
        out.emissive_strength = non_negative(value.Get("emissiveStrength"), 1.0, where + " emissiveStrength");
      } else if (name == "KHR_materials_transmission") {
        out.transmission = float(std::min(1.0, non_negative(value.Get("transmissionFactor"), 0.0, where + " transmissionFactor")));
        out.transmission_texture = texture_info(value.Get("transmissionTexture"), ColorSpace::Linear, where + " transmissionTexture");
      } else if (name == "KHR_materials_ior") {
        const double ior = number(value.Get("ior"), 1.5);
        if (!(ior >= 1.0 && std::isfinite(ior))) fail(where, "KHR_materials_ior ior must be a finite number >= 1");
        out.ior = float(ior);
      } else if (name == "KHR_materials_specular") {
        out.specular = float(non_negative(value.Get("specularFactor"), 1.0, where + " specularFactor"));
        out.specular_texture = texture_info(value.Get("specularTexture"), ColorSpace::Linear, where + " specularTexture");
        const tinygltf::Value& c = value.Get("specularColorFactor");
        if (c.IsArray() && c.ArrayLen() == 3)
          for (int k = 0; k < 3; ++k) out.specular_color[k] = float(non_negative(c.Get(k), 1.0, where + " specularColorFactor"));
        out.specular_color_texture =
            texture_info(value.Get("specularColorTexture"), ColorSpace::Srgb, where + " specularColorTexture");
      } else if (name == "KHR_materials_volume") {
        // thicknessFactor is a rasteriser's stand-in for the distance travelled inside: prism
        // measures the real path length. Only its zero/non-zero meaning is used: 0 (the default)
        // makes the material thin-walled, as the extension specifies.
        out.volume = non_negative(value.Get("thicknessFactor"), 0.0, where + " thicknessFactor") > 0;
        if (value.Has("thicknessTexture")) diag_.warn("KHR_materials_volume thicknessTexture ignored: prism measures the real thickness");
        const tinygltf::Value& colour = value.Get("attenuationColor");
        if (colour.IsArray() && colour.ArrayLen() == 3) {
          for (int c = 0; c < 3; ++c) out.attenuation_color[c] = float(std::clamp(number(colour.Get(c), 1.0), 0.0, 1.0));
        }
        if (value.Has("attenuationDistance")) {
          const double d = number(value.Get("attenuationDistance"), -1.0);
          if (!(d > 0)) fail(where, "KHR_materials_volume attenuationDistance must be positive");
          out.attenuation_distance = float(d);  // may round to +inf: no absorption
        }
      } else if (!is_metadata_gltf_extension(name)) {
        diag_.warn("extension " + name + " is not supported yet and is ignored");
      }
    }
    out.base_color_texture = texture_ref(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                         pbr.baseColorTexture.extensions, ColorSpace::Srgb, where + " baseColorTexture");
    out.emissive_texture = texture_ref(m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions,
                                       ColorSpace::Srgb, where + " emissiveTexture");
    out.metallic_roughness_texture =
        texture_ref(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                    pbr.metallicRoughnessTexture.extensions, ColorSpace::Linear, where + " metallicRoughnessTexture");
    if (out.volume && out.transmission <= 0 && !out.transmission_texture.present())
      diag_.warn("KHR_materials_volume without transmission has no visible effect (the surface is opaque)");
    out.normal_texture = texture_ref(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions,
                                     ColorSpace::Linear, where + " normalTexture");
    out.normal_scale = float(m.normalTexture.scale);
    if (!std::isfinite(out.normal_scale)) fail(where, "normalTexture scale must be finite");
    if (m.occlusionTexture.index >= 0)
      diag_.warn("occlusionTexture ignored: a path tracer computes occlusion itself");
    if (m.alphaMode == "MASK") {
      out.alpha_mode = MaterialDesc::AlphaMode::Mask;
      out.alpha_cutoff = float(m.alphaCutoff);
      if (!(out.alpha_cutoff >= 0 && std::isfinite(out.alpha_cutoff))) fail(where, "alphaCutoff must be >= 0");
    } else if (m.alphaMode == "BLEND") {
      out.alpha_mode = MaterialDesc::AlphaMode::Blend;
    } else if (m.alphaMode != "OPAQUE") {
      fail(where, "unknown alphaMode '" + m.alphaMode + "'");
    }
    return out;
  }

  double non_negative(const tinygltf::Value& v, double fallback, const std::string& where) const {
    const double x = number(v, fallback);
    if (!(x >= 0 && std::isfinite(x))) fail(where, "must be a finite non-negative number");
    return x;
  }

  // A textureInfo object inside an extension ({"index": i, "texCoord": n, "extensions": ...}).
  TextureRef texture_info(const tinygltf::Value& v, ColorSpace space, const std::string& where) {
    if (!v.IsObject() || !v.Has("index")) return {};
    const tinygltf::Value& index = v.Get("index");
    if (!index.IsInt()) fail(where, "index must be an integer");
    const int texcoord = v.Has("texCoord") && v.Get("texCoord").IsInt() ? v.Get("texCoord").GetNumberAsInt() : 0;
    tinygltf::ExtensionMap none;
    if (v.Has("extensions") && v.Get("extensions").Has("KHR_texture_transform"))
      none["KHR_texture_transform"] = v.Get("extensions").Get("KHR_texture_transform");
    return texture_ref(index.GetNumberAsInt(), texcoord, none, space, where);
  }

  TextureRef texture_ref(int texture, int texcoord, const tinygltf::ExtensionMap& extensions, ColorSpace space,
                         const std::string& where) {
    TextureRef ref;
    if (texture < 0) return ref;
    if (texture >= static_cast<int>(model_.textures.size()))
      fail(where, "texture index " + std::to_string(texture) + " out of range");
    if (auto it = extensions.find("KHR_texture_transform"); it != extensions.end()) {
      ref.transform = texture_transform(it->second, where + " KHR_texture_transform");
      if (it->second.Has("texCoord") && it->second.Get("texCoord").IsInt()) texcoord = it->second.Get("texCoord").GetNumberAsInt();
    }
    if (texcoord != 0) diag_.warn("textures on TEXCOORD_1 and above are read with TEXCOORD_0");
    const auto key = std::make_pair(texture, space == ColorSpace::Srgb);
    if (auto it = texture_map_.find(key); it != texture_map_.end()) {
      ref.texture = it->second;
      if (ref.texture < 0) ref = TextureRef{};
      return ref;
    }
    const tinygltf::Texture& t = model_.textures[texture];
    const std::string twhere = quoted_name("texture", texture, t.name);
    if (t.source < 0) {
      diag_.warn(twhere + ": no image prism can decode (image extensions are not supported); texture ignored");
      texture_map_[key] = -1;
      return ref;
    }
    if (t.source >= static_cast<int>(model_.images.size()))
      fail(twhere, "image index " + std::to_string(t.source) + " out of range");
    TextureDesc desc;
    desc.image = scene_image(t.source, space);
    if (t.sampler >= 0) {
      if (t.sampler >= static_cast<int>(model_.samplers.size()))
        fail(twhere, "sampler index " + std::to_string(t.sampler) + " out of range");
      const tinygltf::Sampler& s = model_.samplers[t.sampler];
      desc.wrap_s = wrap_mode(s.wrapS);
      desc.wrap_t = wrap_mode(s.wrapT);
      desc.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
    }
    ref.texture = static_cast<int>(desc_.textures.size());
    desc_.textures.push_back(desc);
    texture_map_[key] = ref.texture;
    return ref;
  }

  // KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv, with the extension's
  // rotation matrix [cos sin; -sin cos] (counter-clockwise in uv, where v points down the image).
  std::array<float, 6> texture_transform(const tinygltf::Value& v, const std::string& where) const {
    auto pair = [&](const char* key, double fallback, double out[2]) {
      out[0] = out[1] = fallback;
      const tinygltf::Value& a = v.Get(key);
      if (!a.IsArray()) return;
      if (a.ArrayLen() != 2) fail(where, std::string(key) + " must have 2 numbers");
      for (int i = 0; i < 2; ++i) out[i] = number(a.Get(i), fallback);
    };
    double offset[2], scale[2];
    pair("offset", 0.0, offset);
    pair("scale", 1.0, scale);
    const double rotation = number(v.Get("rotation"), 0.0);
    for (double x : {offset[0], offset[1], scale[0], scale[1], rotation})
      if (!std::isfinite(x)) fail(where, "values must be finite");
    const double c = std::cos(rotation), s = std::sin(rotation);
    return {float(c * scale[0]), float(s * scale[1]), float(offset[0]), float(-s * scale[0]), float(c * scale[1]), float(offset[1])};
  }

  static WrapMode wrap_mode(int gl) {
    if (gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return WrapMode::ClampToEdge;
    if (gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return WrapMode::MirroredRepeat;
    return WrapMode::Repeat;
  }

  int scene_image(int gltf_image, ColorSpace space) {
    const auto key = std::make_pair(gltf_image, space == ColorSpace::Srgb);
    if (auto it = image_map_.find(key); it != image_map_.end()) return it->second;
    const tinygltf::Image& img = model_.images[gltf_image];
    const std::string where = quoted_name("image", gltf_image, img.name.empty() ? img.uri.substr(0, 64) : img.name);
    ImageDesc out;
    // A bufferView past its buffer is a broken file (an error); image bytes that are missing or
    // do not decode are a broken texture, which renders magenta so it shows (unless --strict).
    const auto [data, size] = img.bufferView >= 0 ? buffer_view_bytes(model_, img.bufferView, file_, where)
                                                  : std::make_pair(img.image.data(), img.image.size());
    std::string problem;
    if (size == 0) {
      problem = img.uri.rfind("data:", 0) == 0 || img.uri.empty() ? "no image data"
                                                                  : "the file '" + img.uri + "' is missing or empty";
    } else {
      try {
        out = decode_image(data, size, space, file_, where);
      } catch (const InputError& e) {
        problem = e.reason();
      }
    }
    if (!problem.empty()) {
      diag_.substitute(file_, where, problem, "its textures render magenta");
      out = magenta_image();
    }
    out.name = img.name.empty() ? img.uri : img.name;
    tally_.add(out.memory_bytes(), file_ + ": " + where);
    const int index = static_cast<int>(desc_.images.size());
    desc_.images.push_back(std::move(out));
    image_map_[key] = index;
    return index;
  }

  const tinygltf::Model& model_;
  std::string file_;
  Diagnostics& diag_;
  SceneDesc desc_;
  std::set<int> on_path_, visited_;
  std::map<int, int> mesh_map_;
  std::map<std::pair<int, bool>, int> texture_map_, image_map_;
  std::vector<std::pair<int, CameraDesc>> cameras_by_node_;
  MemoryTally tally_;
};

}  // namespace

SceneDesc load_gltf_from_memory(const std::vector<unsigned char>& bytes, const std::string& base_dir,
                                const std::string& name, Diagnostics& diag) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_encoded_image, nullptr);
  if (base_dir.empty()) {
    // No file system: a reference to an external file is treated as a missing file.
    tinygltf::FsCallbacks none{};
    none.FileExists = [](const std::string&, void*) { return false; };
    none.ExpandFilePath = [](const std::string& path, void*) { return path; };
    none.ReadWholeFile = [](std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
      if (err) *err += "external file '" + path + "' is not available when loading from memory\n";
      return false;
    };
    none.WriteWholeFile = [](std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; };
    loader.SetFsCallbacks(none);
  }
  tinygltf::Model model;
  std::string err, warn;
  bool ok;
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) throw InputError(name, "", "file is larger than 4 GiB");
  check_gltf_schema(bytes, name);
  if (is_glb(bytes)) {
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), base_dir);
  } else {
    const std::string text(bytes.begin(), bytes.end());
    ok = loader.LoadASCIIFromString(&model, &err, &warn, text.data(), static_cast<unsigned int>(text.size()), base_dir);
  }
  auto trim = [](std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    return s;
  };
  if (!ok || !err.empty()) throw InputError(name, "", "not a loadable glTF file: " + trim(err.empty() ? warn : err));
  for (size_t start = 0, end; start < warn.size(); start = end + 1) {
    end = std::min(warn.find('\n', start), warn.size());
    if (const std::string line = trim(warn.substr(start, end - start)); !line.empty()) diag.warn("glTF parser: " + line);
  }
  return Converter(model, name, diag).run();
}

SceneDesc load_gltf(const std::string& path, Diagnostics& diag) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "", "no such file");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path, "", "cannot open for reading");
  // One read of the whole file: a character at a time through istreambuf_iterator took 40 ms for
  // a 9 MB glb (textures inside), more than tinygltf's parse of it.
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError(path, "", "cannot read its size");
  std::vector<unsigned char> bytes(static_cast<size_t>(size));
  in.seekg(0);
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size))
    throw InputError(path, "", "cannot read the whole file");
  const std::string base = std::filesystem::path(path).parent_path().string();
  return load_gltf_from_memory(bytes, base.empty() ? "." : base, path, diag);
}

}  // namespace prism
