#pragma once
// Private: appending buffer views and accessors to a tinygltf model (one buffer, 4-byte aligned
// views); shared by the glTF writers (gltf.cpp, gltf_morph.cpp).
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace emoface::facemesh::detail {

inline int add_view(tinygltf::Model& model, const void* data, std::size_t bytes, int target) {
  auto& buffer = model.buffers[0].data;
  while (buffer.size() % 4) buffer.push_back(0);
  const std::size_t offset = buffer.size();
  buffer.resize(offset + bytes);
  std::memcpy(buffer.data() + offset, data, bytes);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = bytes;
  if (target) view.target = target;
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

inline int add_accessor(tinygltf::Model& model, int view, int component, std::size_t count, int type,
                 std::vector<double> min = {}, std::vector<double> max = {}) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = component;
  a.count = count;
  a.type = type;
  a.minValues = std::move(min);
  a.maxValues = std::move(max);
  model.accessors.push_back(a);
  return static_cast<int>(model.accessors.size()) - 1;
}

/// Per-component bounds of packed xyz floats (lo/hi get 3 values).
inline void vec3_bounds(const std::vector<float>& xyz, std::vector<double>& lo,
                        std::vector<double>& hi) {
  lo.assign(3, 1e300);
  hi.assign(3, -1e300);
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], static_cast<double>(xyz[i]));
    hi[i % 3] = std::max(hi[i % 3], static_cast<double>(xyz[i]));
  }
}

/// A dense VEC3 float accessor (bounds when asked: POSITION needs them).
inline int add_vec3(tinygltf::Model& model, const std::vector<float>& xyz, bool with_bounds,
                    int target = TINYGLTF_TARGET_ARRAY_BUFFER) {
  std::vector<double> lo, hi;
  if (with_bounds) vec3_bounds(xyz, lo, hi);
  const int v = add_view(model, xyz.data(), xyz.size() * sizeof(float), target);
  return add_accessor(model, v, TINYGLTF_COMPONENT_TYPE_FLOAT, xyz.size() / 3, TINYGLTF_TYPE_VEC3,
                      lo, hi);
}

/// A morph-target delta (packed xyz floats, one row per vertex): a sparse accessor (indices and
/// values of the rows with a component above `eps`) when that takes fewer bytes and `allow_sparse`,
/// else dense. `sparse` tells which was written.
inline int add_delta(tinygltf::Model& model, const std::vector<float>& xyz, double eps,
                     bool with_bounds, bool allow_sparse, bool& sparse) {
  const std::size_t n = xyz.size() / 3;
  std::vector<std::uint32_t> idx;
  std::vector<float> vals;
  for (std::size_t v = 0; v < n; ++v) {
    const float* p = &xyz[v * 3];
    if (std::fabs(p[0]) > eps || std::fabs(p[1]) > eps || std::fabs(p[2]) > eps) {
      idx.push_back(static_cast<std::uint32_t>(v));
      vals.insert(vals.end(), p, p + 3);
    }
  }
  // glTF: a sparse accessor needs count >= 1; an all-zero delta stores one zero row
  if (idx.empty()) {
    idx.push_back(0);
    vals.assign(3, 0.0f);
  }
  const bool u16 = n <= 65535;
  const std::size_t sparse_bytes = idx.size() * (u16 ? 2 : 4) + vals.size() * 4 + 8;
  sparse = allow_sparse && sparse_bytes < xyz.size() * 4;
  if (!sparse) return add_vec3(model, xyz, with_bounds);
  std::vector<double> lo, hi;
  if (with_bounds) {
    // bounds over all n rows: the implicit zeros count too
    std::vector<float> with_zero = vals;
    if (idx.size() < n) with_zero.insert(with_zero.end(), {0.0f, 0.0f, 0.0f});
    vec3_bounds(with_zero, lo, hi);
  }
  int iv;
  if (u16) {
    std::vector<std::uint16_t> i16(idx.begin(), idx.end());
    iv = add_view(model, i16.data(), i16.size() * 2, 0);
  } else {
    iv = add_view(model, idx.data(), idx.size() * 4, 0);
  }
  const int vv = add_view(model, vals.data(), vals.size() * 4, 0);
  const int a =
      add_accessor(model, -1, TINYGLTF_COMPONENT_TYPE_FLOAT, n, TINYGLTF_TYPE_VEC3, lo, hi);
  auto& acc = model.accessors[static_cast<std::size_t>(a)];
  acc.sparse.isSparse = true;
  acc.sparse.count = static_cast<int>(idx.size());
  acc.sparse.indices.bufferView = iv;
  acc.sparse.indices.byteOffset = 0;
  acc.sparse.indices.componentType =
      u16 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  acc.sparse.values.bufferView = vv;
  acc.sparse.values.byteOffset = 0;
  return a;
}

}  // namespace emoface::facemesh::detail
