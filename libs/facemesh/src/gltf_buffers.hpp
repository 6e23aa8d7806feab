#pragma once
// Private: appending buffer views and accessors to a tinygltf model (one buffer, 4-byte aligned
// views); shared by the glTF writers (gltf.cpp, gltf_morph.cpp).
#include <cstddef>
#include <cstring>
#include <vector>

#include <tiny_gltf.h>

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

}  // namespace emoface::facemesh::detail
