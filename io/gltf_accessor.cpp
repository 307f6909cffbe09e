#include "io/gltf_accessor.h"

#include <algorithm>
#include <cstring>

#include "core/memory_limit.h"
#include "io/errors.h"

namespace prism {
namespace {

// Larger element counts are refused before anything is allocated.
constexpr uint64_t kMaxElements = uint64_t(1) << 31;

int component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return 8;
    default: return 0;
  }
}

std::string component_name(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "component type " + std::to_string(type);
  }
}

// One component as a double; normalised integers per glTF 2.0 §3.11.
double decode(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v; std::memcpy(&v, p, 1);
      return normalized ? std::max(double(v) / 127.0, -1.0) : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      uint8_t v; std::memcpy(&v, p, 1);
      return normalized ? double(v) / 255.0 : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v; std::memcpy(&v, p, 2);
      return normalized ? std::max(double(v) / 32767.0, -1.0) : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v; std::memcpy(&v, p, 2);
      return normalized ? double(v) / 65535.0 : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v; std::memcpy(&v, p, 4);
      return double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      int32_t v; std::memcpy(&v, p, 4);
      return double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v; std::memcpy(&v, p, 4);
      return double(v);
    }
    default: return 0.0;
  }
}

// A run of `count` elements of `elem_size` bytes starting at `offset` in a buffer view, spaced by
// the view's byteStride when `strided` (vertex attributes) or packed (sparse indices and values).
struct Strided {
  const unsigned char* base = nullptr;
  uint64_t stride = 0;
};

Strided view_range(const tinygltf::Model& model, int view, uint64_t offset, uint64_t count, uint64_t elem_size,
                   bool strided, const std::string& file, const std::string& what) {
  auto [data, size] = buffer_view_bytes(model, view, file, what);
  const uint64_t declared_stride = strided ? model.bufferViews[view].byteStride : 0;
  const uint64_t stride = declared_stride ? declared_stride : elem_size;
  if (declared_stride > 252)  // glTF 2.0 bufferView.byteStride maximum
    throw InputError(file, what, "bufferView " + std::to_string(view) + " byteStride " + std::to_string(declared_stride) +
                                     " exceeds 252");
  if (declared_stride && declared_stride < elem_size)
    throw InputError(file, what, "bufferView " + std::to_string(view) + " byteStride " + std::to_string(declared_stride) +
                                     " is smaller than the element size " + std::to_string(elem_size));
  // count <= 2^31 and stride <= 252 keep this product far from overflow.
  const uint64_t needed = count == 0 ? 0 : offset + (count - 1) * stride + elem_size;
  if (offset > size || needed > size)
    throw InputError(file, what, "needs " + std::to_string(needed) + " bytes of bufferView " + std::to_string(view) +
                                     ", which has " + std::to_string(size));
  return {data + offset, stride};
}

// Decodes accessor `index` into count x comps doubles.
std::vector<double> read_accessor(const tinygltf::Model& model, int index, int comps, const std::vector<int>& allowed,
                                  const std::string& file, const std::string& what) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    throw InputError(file, what, "accessor index " + std::to_string(index) + " out of range (" +
                                     std::to_string(model.accessors.size()) + " accessors)");
  const tinygltf::Accessor& acc = model.accessors[index];
  const std::string where = what + " (accessor " + std::to_string(index) + ")";
  const int n = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(acc.type));
  if (n != comps)
    throw InputError(file, where, "has " + std::to_string(n) + " components per element, expected " + std::to_string(comps));
  if (std::find(allowed.begin(), allowed.end(), acc.componentType) == allowed.end())
    throw InputError(file, where, "component type " + component_name(acc.componentType) + " is not allowed here");
  if (acc.count > kMaxElements)
    throw InputError(file, where, "declares " + std::to_string(acc.count) + " elements, more than prism accepts");
  const int csize = component_size(acc.componentType);
  const uint64_t elem = uint64_t(csize) * comps;
  // The ranges and the memory estimate are checked before anything is allocated, so a declared
  // count is never trusted: doubles while decoding, then floats kept.
  Strided s;
  if (acc.bufferView >= 0) s = view_range(model, acc.bufferView, acc.byteOffset, acc.count, elem, true, file, where);
  require_memory(acc.count * comps * (sizeof(double) + sizeof(float)), file + ": " + where);
  std::vector<double> out(acc.count * comps, 0.0);  // no bufferView: zeros (glTF 2.0 §3.6.2.3)
  if (acc.bufferView >= 0) {
    for (size_t i = 0; i < acc.count; ++i)
      for (int c = 0; c < comps; ++c)
        out[i * comps + c] = decode(s.base + i * s.stride + uint64_t(c) * csize, acc.componentType, acc.normalized);
  }
  if (acc.sparse.isSparse) {
    const auto& sp = acc.sparse;
    if (sp.count < 0 || uint64_t(sp.count) > acc.count)
      throw InputError(file, where, "sparse count " + std::to_string(sp.count) + " exceeds the accessor count");
    const int isize = component_size(sp.indices.componentType);
    if (isize == 0 || sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
      throw InputError(file, where, "sparse indices have an invalid component type");
    const Strided idx = view_range(model, sp.indices.bufferView, uint64_t(std::max(0, sp.indices.byteOffset)),
                                   uint64_t(sp.count), uint64_t(isize), false, file, where + " sparse indices");
    const Strided val = view_range(model, sp.values.bufferView, uint64_t(std::max(0, sp.values.byteOffset)),
                                   uint64_t(sp.count), elem, false, file, where + " sparse values");
    for (int k = 0; k < sp.count; ++k) {
      const auto target = static_cast<uint64_t>(decode(idx.base + uint64_t(k) * isize, sp.indices.componentType, false));
      if (target >= acc.count)
        throw InputError(file, where, "sparse index " + std::to_string(target) + " is out of range");
      for (int c = 0; c < comps; ++c)
        out[target * comps + c] = decode(val.base + uint64_t(k) * elem + uint64_t(c) * csize, acc.componentType, acc.normalized);
    }
  }
  return out;
}

}  // namespace

std::pair<const unsigned char*, size_t> buffer_view_bytes(const tinygltf::Model& model, int index,
                                                          const std::string& file, const std::string& what) {
  if (index < 0 || index >= static_cast<int>(model.bufferViews.size()))
    throw InputError(file, what, "bufferView index " + std::to_string(index) + " out of range (" +
                                     std::to_string(model.bufferViews.size()) + " bufferViews)");
  const tinygltf::BufferView& bv = model.bufferViews[index];
  if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model.buffers.size()))
    throw InputError(file, what, "bufferView " + std::to_string(index) + " names buffer " + std::to_string(bv.buffer) +
                                     ", which does not exist");
  const auto& data = model.buffers[bv.buffer].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    throw InputError(file, what, "bufferView " + std::to_string(index) + " (offset " + std::to_string(bv.byteOffset) +
                                     ", length " + std::to_string(bv.byteLength) + ") runs past the end of buffer " +
                                     std::to_string(bv.buffer) + " (" + std::to_string(data.size()) + " bytes)");
  return {data.data() + bv.byteOffset, bv.byteLength};
}

std::vector<float> read_accessor_floats(const tinygltf::Model& model, int index, int components,
                                        const std::vector<int>& allowed, const std::string& file,
                                        const std::string& what) {
  const std::vector<double> d = read_accessor(model, index, components, allowed, file, what);
  return std::vector<float>(d.begin(), d.end());
}

std::vector<uint32_t> read_accessor_indices(const tinygltf::Model& model, int index, const std::string& file,
                                            const std::string& what) {
  const std::vector<double> d =
      read_accessor(model, index, 1,
                    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                    file, what);
  std::vector<uint32_t> out(d.size());
  for (size_t i = 0; i < d.size(); ++i) out[i] = static_cast<uint32_t>(d[i]);
  return out;
}

}  // namespace prism
