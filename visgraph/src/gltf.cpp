// glTF reader (detail/gltf.hpp) on tinygltf (Debian's libtinygltf, which carries
// the implementation; images are never decoded: attenuvis needs geometry only).
#include <attenuvis/visgraph/detail/gltf.hpp>
#include <attenuvis/visgraph/limits.hpp>

#include <attenuvis/io/input_file.hpp>

#include <Eigen/Geometry>
#include <tiny_gltf.h>

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>
#include <stdexcept>

namespace attenuvis::visgraph {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& where, const std::string& what) {
  throw std::runtime_error(path + (where.empty() ? "" : ": " + where) + ": " + what);
}

bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

Eigen::Matrix4d local_transform(const tinygltf::Node& node) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (node.matrix.size() == 16) {
    for (int k = 0; k < 16; ++k) m(k % 4, k / 4) = node.matrix[static_cast<std::size_t>(k)];  // column-major
    return m;
  }
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  if (node.translation.size() == 3) a.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
  if (node.rotation.size() == 4)
    a.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized());
  if (node.scale.size() == 3) a.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
  return a.matrix();
}

// Element `i` of an accessor: a pointer to its bytes, bounds checked.
class AccessorView {
 public:
  AccessorView(const tinygltf::Model& model, int index, const std::string& path, const std::string& where) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) fail(path, where, "no such accessor");
    acc_ = &model.accessors[static_cast<std::size_t>(index)];
    if (acc_->bufferView < 0 || static_cast<std::size_t>(acc_->bufferView) >= model.bufferViews.size())
      fail(path, where, "accessor without a buffer view (sparse accessors are not supported)");
    const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(acc_->bufferView)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) fail(path, where, "no such buffer");
    const auto& data = model.buffers[static_cast<std::size_t>(view.buffer)].data;
    const int stride = acc_->ByteStride(view);
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(acc_->componentType)) *
                     tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(acc_->type));
    if (stride <= 0 || size <= 0) fail(path, where, "accessor with an invalid component type or stride");
    stride_ = static_cast<std::size_t>(stride);
    base_ = data.data() + view.byteOffset + acc_->byteOffset;
    const std::size_t end = view.byteOffset + acc_->byteOffset + (acc_->count ? stride_ * (acc_->count - 1) + static_cast<std::size_t>(size) : 0);
    if (end > data.size()) fail(path, where, "accessor reaches past the end of its buffer");
  }
  std::size_t count() const { return acc_->count; }
  const tinygltf::Accessor& accessor() const { return *acc_; }
  const unsigned char* at(std::size_t i) const { return base_ + i * stride_; }

 private:
  const tinygltf::Accessor* acc_ = nullptr;
  const unsigned char* base_ = nullptr;
  std::size_t stride_ = 0;
};

std::uint32_t read_index(const AccessorView& v, std::size_t i) {
  const unsigned char* p = v.at(i);
  switch (v.accessor().componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t x; std::memcpy(&x, p, 2); return x; }
    default: { std::uint32_t x; std::memcpy(&x, p, 4); return x; }
  }
}

void add_primitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const Eigen::Matrix4d& transform,
                   std::uint32_t group, Mesh& mesh, const std::string& path, const std::string& where) {
  if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      prim.mode != TINYGLTF_MODE_TRIANGLE_FAN)
    return;  // points and lines bound no volume
  const auto position = prim.attributes.find("POSITION");
  if (position == prim.attributes.end()) fail(path, where, "primitive without POSITION");
  const AccessorView pos(model, position->second, path, where + " POSITION");
  if (pos.accessor().type != TINYGLTF_TYPE_VEC3 || pos.accessor().componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    fail(path, where, "POSITION must be float VEC3 (quantized positions are not supported)");
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (std::size_t i = 0; i < pos.count(); ++i) {
    float xyz[3];
    std::memcpy(xyz, pos.at(i), sizeof xyz);
    const Eigen::Vector4d p = transform * Eigen::Vector4d(xyz[0], xyz[1], xyz[2], 1.0);
    if (!p.allFinite()) fail(path, where, "vertex " + std::to_string(i) + " is not finite");
    for (int c = 0; c < 3; ++c) check_coordinate(p[c], path + ": " + where + " vertex " + std::to_string(i));
    mesh.vertices.emplace_back(p.x(), -p.z(), p.y());  // y-up -> z-up
  }
  std::vector<std::uint32_t> idx;
  if (prim.indices >= 0) {
    const AccessorView ind(model, prim.indices, path, where + " indices");
    if (ind.accessor().type != TINYGLTF_TYPE_SCALAR) fail(path, where, "indices must be scalars");
    for (std::size_t i = 0; i < ind.count(); ++i) {
      const std::uint32_t k = read_index(ind, i);
      if (k >= pos.count()) fail(path, where, "index " + std::to_string(k) + " out of range (" + std::to_string(pos.count()) + " vertices)");
      idx.push_back(k);
    }
  } else {
    for (std::size_t i = 0; i < pos.count(); ++i) idx.push_back(static_cast<std::uint32_t>(i));
  }
  // A mirroring transform (negative determinant) reverses the winding.
  const bool flip = transform.topLeftCorner<3, 3>().determinant() < 0;
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (flip) std::swap(b, c);
    mesh.triangles.push_back({base + a, base + b, base + c});
    mesh.triangle_group.push_back(group);
  };
  if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
    for (std::size_t i = 0; i + 2 < idx.size(); i += 3) add(idx[i], idx[i + 1], idx[i + 2]);
  } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t i = 0; i + 2 < idx.size(); ++i)
      i % 2 ? add(idx[i + 1], idx[i], idx[i + 2]) : add(idx[i], idx[i + 1], idx[i + 2]);
  } else {
    for (std::size_t i = 1; i + 1 < idx.size(); ++i) add(idx[0], idx[i], idx[i + 1]);
  }
}

}  // namespace

bool looks_like_gltf(const std::string& head) {
  if (head.compare(0, 4, "glTF") == 0) return true;
  const auto first = head.find_first_not_of(" \t\r\n");
  return first != std::string::npos && head[first] == '{' && head.find("\"asset\"") != std::string::npos &&
         head.find("\"CityObjects\"") == std::string::npos;
}

namespace {
// Buffers and images a .gltf names by uri are read with the same checks as the
// scene file itself: a uri of /dev/zero or a FIFO would be read for ever.
// tinygltf's own FileExists opens the file, which blocks on a FIFO: stat only.
bool file_exists(const std::string& path, void*) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0;
}

bool read_whole_regular_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  try {
    const std::string text = io::read_input_file(path, kMaxSceneFileBytes);
    out->assign(text.begin(), text.end());
    return true;
  } catch (const std::exception& e) {
    if (err) *err += e.what() + std::string("\n");
    return false;
  }
}
}  // namespace

Mesh load_gltf(const std::string& path) {
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &tinygltf::ExpandFilePath, &read_whole_regular_file,
                         &tinygltf::WriteWholeFile, nullptr});
  loader.SetImageLoader(skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  std::string head(4, '\0');
  io::require_readable_input(path, kMaxSceneFileBytes);
  {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) fail(path, "", std::string("cannot open: ") + std::strerror(errno));
    head.resize(std::fread(head.data(), 1, 4, f));
    std::fclose(f);
  }
  const bool ok = head == "glTF" ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                                 : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) fail(path, "", "not a readable glTF 2.0 file: " + (err.empty() ? warn : err));
  Mesh mesh;
  const std::function<void(int, const Eigen::Matrix4d&, int)> visit = [&](int n, const Eigen::Matrix4d& parent, int depth) {
    if (n < 0 || static_cast<std::size_t>(n) >= model.nodes.size()) fail(path, "", "node " + std::to_string(n) + " does not exist");
    if (depth > 64) fail(path, "node " + std::to_string(n), "node hierarchy deeper than 64 (a cycle?)");
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(n)];
    const Eigen::Matrix4d transform = parent * local_transform(node);
    if (node.mesh >= 0) {
      if (static_cast<std::size_t>(node.mesh) >= model.meshes.size()) fail(path, "node " + std::to_string(n), "no such mesh");
      const tinygltf::Mesh& m = model.meshes[static_cast<std::size_t>(node.mesh)];
      const std::string name = !node.name.empty() ? node.name : !m.name.empty() ? m.name : "node " + std::to_string(n);
      const auto group = static_cast<std::uint32_t>(mesh.add_group(name));
      for (std::size_t p = 0; p < m.primitives.size(); ++p)
        add_primitive(model, m.primitives[p], transform, group, mesh, path,
                      "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p));
    }
    for (int child : node.children) visit(child, transform, depth + 1);
  };
  std::vector<int> roots;
  const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (static_cast<std::size_t>(scene) < model.scenes.size()) roots = model.scenes[static_cast<std::size_t>(scene)].nodes;
  else {  // no scene: every node that is nobody's child
    std::vector<char> child(model.nodes.size(), 0);
    for (const tinygltf::Node& node : model.nodes)
      for (int c : node.children)
        if (c >= 0 && static_cast<std::size_t>(c) < child.size()) child[static_cast<std::size_t>(c)] = 1;
    for (std::size_t n = 0; n < model.nodes.size(); ++n)
      if (!child[n]) roots.push_back(static_cast<int>(n));
  }
  for (int r : roots) visit(r, Eigen::Matrix4d::Identity(), 0);
  if (mesh.triangles.empty()) fail(path, "", "no triangles in the default scene");
  return mesh;
}

}  // namespace attenuvis::visgraph
