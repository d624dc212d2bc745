#include "gltf/gltf_accessors.h"

#include <cstring>
#include <string>

namespace tray {

namespace {

using tinygltf::Accessor;

bool addOverflows(uint64_t a, uint64_t b, uint64_t& out) {
  return __builtin_add_overflow(a, b, &out);
}
bool mulOverflows(uint64_t a, uint64_t b, uint64_t& out) {
  return __builtin_mul_overflow(a, b, &out);
}

/// Element size including the column padding of small matrices (glTF 2.0 §3.6.2.4 "Data
/// Alignment": each matrix column starts on a 4-byte boundary).
uint64_t elementSize(const Accessor& a) {
  uint64_t c = componentSize(a.componentType);
  if (a.type == TINYGLTF_TYPE_MAT2 && c == 1) return 8;
  if (a.type == TINYGLTF_TYPE_MAT3 && c == 1) return 12;
  if (a.type == TINYGLTF_TYPE_MAT3 && c == 2) return 24;
  return c * componentCount(a.type);
}

/// Checks that `count` elements of `elemSize` bytes with `stride` starting at byte `offset`
/// of bufferView `view` lie inside it; returns the failure as text, "" if fine.
std::string checkRange(const GltfContext& ctx, int view, uint64_t offset, uint64_t stride,
                       uint64_t count, uint64_t elemSize) {
  const auto& bv = ctx.model.bufferViews[size_t(view)];
  uint64_t span, end;
  if (mulOverflows(stride, count - 1, span) || addOverflows(span, elemSize, span) ||
      addOverflows(offset, span, end) || end > bv.byteLength)
    return "reads past the end of bufferView " + std::to_string(view);
  return "";
}

uint64_t strideOf(const Accessor& a, const tinygltf::BufferView& bv) {
  return bv.byteStride ? bv.byteStride : elementSize(a);
}

const unsigned char* viewData(const GltfContext& ctx, int view, uint64_t offset) {
  const auto& bv = ctx.model.bufferViews[size_t(view)];
  return ctx.model.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset + offset;
}

uint32_t readUnsigned(const unsigned char* p, int componentType) {
  if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return *p;
  if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
    uint16_t v;
    std::memcpy(&v, p, 2);
    return v;
  }
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

/// One component as float; normalized integers per glTF 2.0 §3.11 ("Animations", the table
/// of normalized integer conversions): signed values clamp at -1.
float readComponent(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? *p / 255.0f : float(*p);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0f : float(v);
    }
    default:  // UNSIGNED_INT; never normalized (checked)
      return float(readUnsigned(p, type));
  }
}

void checkSparse(const GltfContext& ctx, int index, const Accessor& a) {
  const std::string name = nameOf("accessor", index, a.name) + " sparse ";
  const auto& s = a.sparse;
  const int views = int(ctx.model.bufferViews.size());
  if (s.count < 1 || uint64_t(s.count) > a.count)
    ctx.fail(name + "count " + std::to_string(s.count) + " is not in 1.." +
             std::to_string(a.count));
  if (s.indices.bufferView < 0 || s.indices.bufferView >= views)
    ctx.fail(name + "indices refer to missing bufferView " + std::to_string(s.indices.bufferView));
  if (s.values.bufferView < 0 || s.values.bufferView >= views)
    ctx.fail(name + "values refer to missing bufferView " + std::to_string(s.values.bufferView));
  int ic = s.indices.componentType;
  if (ic != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ic != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      ic != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    ctx.fail(name + "indices have component type " + std::to_string(ic) +
             " (expected unsigned byte, short or int)");
  if (s.indices.byteOffset < 0 || s.values.byteOffset < 0)
    ctx.fail(name + "has a negative byteOffset");
  // Sparse data is tightly packed (glTF 2.0 §3.6.2.3 "Sparse Accessors").
  uint64_t isize = componentSize(ic), vsize = elementSize(a);
  std::string problem =
      checkRange(ctx, s.indices.bufferView, uint64_t(s.indices.byteOffset), isize, s.count, isize);
  if (problem.empty())
    problem =
        checkRange(ctx, s.values.bufferView, uint64_t(s.values.byteOffset), vsize, s.count, vsize);
  if (!problem.empty()) ctx.fail(name + problem);
  if (uint64_t(s.indices.byteOffset) % isize != 0 ||
      (ctx.model.bufferViews[size_t(s.indices.bufferView)].byteOffset % isize) != 0)
    ctx.fail(name + "indices are not aligned to their component size");
  const unsigned char* p = viewData(ctx, s.indices.bufferView, uint64_t(s.indices.byteOffset));
  int64_t previous = -1;
  for (int i = 0; i < s.count; ++i) {
    uint32_t v = readUnsigned(p + i * isize, ic);
    if (int64_t(v) <= previous || v >= a.count)
      ctx.fail(name + "index " + std::to_string(v) + " at position " + std::to_string(i) +
               " is out of range or not strictly increasing");
    previous = v;
  }
}

void checkAccessor(const GltfContext& ctx, int index) {
  const Accessor& a = ctx.model.accessors[size_t(index)];
  const std::string name = nameOf("accessor", index, a.name);
  int csize = componentSize(a.componentType);
  if (csize == 0) ctx.fail(name + " has invalid componentType " + std::to_string(a.componentType));
  if (componentCount(a.type) == 0) ctx.fail(name + " has an invalid type");
  if (a.count < 1) ctx.fail(name + " has count 0");
  if (a.count > kMaxAccessorCount)
    ctx.fail(name + " has " + std::to_string(a.count) + " elements (limit " +
             std::to_string(kMaxAccessorCount) + ")");
  if (a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                       a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    ctx.fail(name + " is normalized but its components are float or unsigned int");
  if (a.bufferView >= int(ctx.model.bufferViews.size()) || a.bufferView < -1)
    ctx.fail(name + " refers to missing bufferView " + std::to_string(a.bufferView));
  if (a.bufferView >= 0) {
    const auto& bv = ctx.model.bufferViews[size_t(a.bufferView)];
    if (a.byteOffset % csize != 0 || (bv.byteOffset + a.byteOffset) % csize != 0)
      ctx.fail(name + " byteOffset is not aligned to its component size " + std::to_string(csize));
    uint64_t stride = strideOf(a, bv);
    if (bv.byteStride && (bv.byteStride < elementSize(a) || bv.byteStride % csize != 0))
      ctx.fail(name + " does not fit the byteStride " + std::to_string(bv.byteStride) +
               " of bufferView " + std::to_string(a.bufferView));
    std::string problem =
        checkRange(ctx, a.bufferView, a.byteOffset, stride, a.count, elementSize(a));
    if (!problem.empty()) ctx.fail(name + " " + problem);
  } else if (a.byteOffset != 0) {
    ctx.fail(name + " has a byteOffset but no bufferView");
  }
  if (a.sparse.isSparse) checkSparse(ctx, index, a);
}

}  // namespace

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

void checkBufferViews(const GltfContext& ctx) {
  const auto& m = ctx.model;
  for (size_t i = 0; i < m.bufferViews.size(); ++i) {
    const auto& bv = m.bufferViews[i];
    const std::string name = nameOf("bufferView", int(i), bv.name);
    if (bv.buffer < 0 || size_t(bv.buffer) >= m.buffers.size())
      ctx.fail(name + " refers to missing buffer " + std::to_string(bv.buffer));
    if (bv.byteLength < 1) ctx.fail(name + " has byteLength 0");
    uint64_t end;
    if (addOverflows(bv.byteOffset, bv.byteLength, end) ||
        end > m.buffers[size_t(bv.buffer)].data.size())
      ctx.fail(name + " (bytes " + std::to_string(bv.byteOffset) + "+" +
               std::to_string(bv.byteLength) + ") runs past the end of buffer " +
               std::to_string(bv.buffer) + " (" +
               std::to_string(m.buffers[size_t(bv.buffer)].data.size()) + " bytes)");
    // tinygltf already refuses strides that are not a multiple of 4 or above 252.
    if (bv.byteStride != 0 && bv.byteStride < 4) ctx.fail(name + " has byteStride below 4");
  }
}

void checkAccessors(const GltfContext& ctx) {
  for (size_t i = 0; i < ctx.model.accessors.size(); ++i) checkAccessor(ctx, int(i));
}

namespace {

/// The accessor's elements as floats, normalized per glTF 2.0 §3.11 when `normalized`.
std::vector<float> readElements(const GltfContext& ctx, int index, bool normalized) {
  const Accessor& a = ctx.model.accessors[size_t(index)];
  const int n = componentCount(a.type), csize = componentSize(a.componentType);
  std::vector<float> out(a.count * size_t(n), 0.0f);
  auto readElement = [&](const unsigned char* p, float* dst) {
    for (int c = 0; c < n; ++c) dst[c] = readComponent(p + c * csize, a.componentType, normalized);
  };
  if (a.bufferView >= 0) {
    const auto& bv = ctx.model.bufferViews[size_t(a.bufferView)];
    uint64_t stride = strideOf(a, bv);
    const unsigned char* base = viewData(ctx, a.bufferView, a.byteOffset);
    for (size_t i = 0; i < a.count; ++i) readElement(base + i * stride, &out[i * size_t(n)]);
  }
  if (a.sparse.isSparse) {
    const auto& s = a.sparse;
    int isize = componentSize(s.indices.componentType);
    const unsigned char* idx = viewData(ctx, s.indices.bufferView, uint64_t(s.indices.byteOffset));
    const unsigned char* val = viewData(ctx, s.values.bufferView, uint64_t(s.values.byteOffset));
    for (int i = 0; i < s.count; ++i) {
      uint32_t target = readUnsigned(idx + size_t(i) * isize, s.indices.componentType);
      readElement(val + size_t(i) * elementSize(a), &out[size_t(target) * n]);
    }
  }
  return out;
}

/// First component of accessor `a`'s data (already read, unnormalized) outside its declared
/// min/max; "" if none. Declared bounds are rounded to float first, as glTF-Validator does.
std::string firstOutOfBounds(const Accessor& a, const std::vector<float>& data) {
  const size_t n = size_t(componentCount(a.type));
  for (size_t i = 0; i < data.size(); ++i) {
    const size_t c = i % n;
    const float v = data[i];
    if (c < a.minValues.size() && v < float(a.minValues[c]))
      return "element " + std::to_string(i / n) + " component " + std::to_string(c) + " is " +
             std::to_string(v) + ", below min " + std::to_string(float(a.minValues[c]));
    if (c < a.maxValues.size() && v > float(a.maxValues[c]))
      return "element " + std::to_string(i / n) + " component " + std::to_string(c) + " is " +
             std::to_string(v) + ", above max " + std::to_string(float(a.maxValues[c]));
  }
  return "";
}

}  // namespace

std::vector<float> readFloats(const GltfContext& ctx, int index) {
  return readElements(ctx, index, ctx.model.accessors[size_t(index)].normalized);
}

void warnAccessorBounds(const GltfContext& ctx) {
  for (size_t i = 0; i < ctx.model.accessors.size(); ++i) {
    const Accessor& a = ctx.model.accessors[i];
    if (a.minValues.empty() && a.maxValues.empty()) continue;
    // glTF 2.0 §5.1.7: min/max hold the data's bounds after sparse substitution, unnormalized.
    const std::string where = firstOutOfBounds(a, readElements(ctx, int(i), false));
    if (!where.empty())
      ctx.warn(nameOf("accessor", int(i), a.name) + " has data outside its declared min/max (" +
               where + "); rendered from the data as stored");
  }
}

std::vector<uint32_t> readIndices(const GltfContext& ctx, int index) {
  const Accessor& a = ctx.model.accessors[size_t(index)];
  // Floats cannot hold 32-bit indices exactly: read unsigned integers directly.
  std::vector<uint32_t> out(a.count, 0);
  if (a.bufferView >= 0) {
    const auto& bv = ctx.model.bufferViews[size_t(a.bufferView)];
    uint64_t stride = strideOf(a, bv);
    const unsigned char* base = viewData(ctx, a.bufferView, a.byteOffset);
    for (size_t i = 0; i < a.count; ++i) out[i] = readUnsigned(base + i * stride, a.componentType);
  }
  if (a.sparse.isSparse) {
    const auto& s = a.sparse;
    int isize = componentSize(s.indices.componentType), vsize = componentSize(a.componentType);
    const unsigned char* idx = viewData(ctx, s.indices.bufferView, uint64_t(s.indices.byteOffset));
    const unsigned char* val = viewData(ctx, s.values.bufferView, uint64_t(s.values.byteOffset));
    for (int i = 0; i < s.count; ++i)
      out[readUnsigned(idx + size_t(i) * isize, s.indices.componentType)] =
          readUnsigned(val + size_t(i) * vsize, a.componentType);
  }
  return out;
}

}  // namespace tray
