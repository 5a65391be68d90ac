#include "engine/io/gltf/gltf_read.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "engine/base/atomic_file.h"
#include "engine/base/error.h"

// The same settings as tiny_gltf_impl.cpp, which holds the implementation.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

namespace mostyle {
namespace {

// What tinygltf may read besides the file itself: a .gltf's buffers, within the memory limit.
struct FileBudget {
  size_t left = 0;
  bool allowed = false;  // no base folder: bytes from memory (a fuzzer, a test) reach no file
};

bool file_exists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}
// tinygltf's own expands "~" and "$VAR" with wordexp: a URI is a file name, nothing more.
std::string expand_nothing(const std::string& path, void*) { return path; }

bool read_buffer_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto* budget = static_cast<FileBudget*>(user);
  if (!budget->allowed) {
    if (err) *err += "external buffers are not read here: '" + path + "'";
    return false;
  }
  try {
    const std::string bytes = read_file(path, budget->left);
    budget->left -= bytes.size();
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const std::exception& e) {
    if (err) *err += e.what();
    return false;
  }
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not allowed while reading";
  return false;
}

// Images are not decoded (see tiny_gltf_impl.cpp).
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                void*) {
  return true;
}

// tinygltf's messages are lines; the first says what is wrong.
std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '.')) line.pop_back();
  if (line.size() > 200) line = line.substr(0, 200) + "...";
  return line;
}

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
  }
}

// One component as a double: floats as they are, normalized integers as glTF 2.0 3.11 maps them.
double read_component(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      uint8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    default: return 0.0;
  }
}

int component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    default: return 0;
  }
}

// An accessor's values: count x components, row-major. `what` names it in messages.
std::vector<double> read_accessor(const tinygltf::Model& model, int index, int expected_type, const std::string& what,
                                  const std::string& source) {
  const auto fail = [&](const std::string& why) { throw InputError(source + ": " + what + ": " + why); };
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    fail("accessor " + std::to_string(index) + " is not in the file");
  const tinygltf::Accessor& a = model.accessors[index];
  const int components = component_count(a.type);
  if (a.type != expected_type)
    fail("accessor " + std::to_string(index) + " has " + std::to_string(components) +
         " components per value, expected " + std::to_string(component_count(expected_type)));
  if (a.sparse.isSparse) fail("accessor " + std::to_string(index) + " is sparse, which mostyle does not read");
  const int size = component_size(a.componentType);
  if (size == 0) fail("accessor " + std::to_string(index) + " has a component type mostyle does not read");
  std::vector<double> out;
  if (a.count == 0) return out;
  if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model.bufferViews.size()))
    fail("accessor " + std::to_string(index) + " has no buffer view");
  const tinygltf::BufferView& view = model.bufferViews[a.bufferView];
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
    fail("buffer view " + std::to_string(a.bufferView) + " has no buffer");
  const std::vector<unsigned char>& data = model.buffers[view.buffer].data;
  const size_t element = static_cast<size_t>(size) * components;
  const size_t stride = view.byteStride ? view.byteStride : element;
  // Bounds in size_t without overflow: every term is checked against the buffer's size first.
  const size_t buffer_size = data.size();
  const auto outside = [&] { fail("accessor " + std::to_string(index) + " reaches outside its buffer"); };
  if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) outside();
  if (a.byteOffset > view.byteLength || stride < element) outside();
  const size_t room = view.byteLength - a.byteOffset;
  if (a.count > SIZE_MAX / stride || (a.count - 1) * stride + element > room) outside();
  out.resize(a.count * components);
  const unsigned char* base = data.data() + view.byteOffset + a.byteOffset;
  for (size_t i = 0; i < a.count; ++i)
    for (int c = 0; c < components; ++c)
      out[i * components + c] = read_component(base + i * stride + c * size, a.componentType, a.normalized);
  return out;
}

// Each node's parent, checked: glTF nodes form a forest (each node at most one parent).
std::vector<int> node_parents(const tinygltf::Model& model, const std::string& source) {
  const int n = static_cast<int>(model.nodes.size());
  std::vector<int> parent(n, -1);
  for (int i = 0; i < n; ++i) {
    for (int c : model.nodes[i].children) {
      if (c < 0 || c >= n) throw InputError(source + ": node " + std::to_string(i) + " has a child that is not in the file");
      if (parent[c] >= 0 || c == i)
        throw InputError(source + ": node " + std::to_string(c) + " has more than one parent");
      parent[c] = i;
    }
  }
  return parent;
}

// The nodes parents first: depth-first from the roots (new_index: each node's place in that
// order). A node never reached sits on a cycle: InputError.
std::vector<int> parents_first(const tinygltf::Model& model, const std::vector<int>& parent,
                               std::vector<int>& new_index, const std::string& source) {
  const int n = static_cast<int>(model.nodes.size());
  new_index.assign(n, -1);
  std::vector<int> order;
  for (int r = 0; r < n; ++r) {
    if (parent[r] >= 0) continue;
    std::vector<int> stack{r};
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      new_index[i] = static_cast<int>(order.size());
      order.push_back(i);
      const auto& ch = model.nodes[i].children;
      for (auto it = ch.rbegin(); it != ch.rend(); ++it) stack.push_back(*it);
    }
  }
  if (static_cast<int>(order.size()) != n) throw InputError(source + ": the node hierarchy has a cycle");
  return order;
}

// Node i's name and rest transform (from its matrix, a mirror as a negative x scale, or its
// translation, rotation and scale). Throws InputError on a transform that is not finite.
SceneNode scene_node(const tinygltf::Node& gn, int i, const std::string& source) {
  SceneNode node;
  node.name = gn.name.empty() ? "node " + std::to_string(i) : gn.name;
  if (gn.matrix.size() == 16) {
    Eigen::Matrix4d m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = gn.matrix[4 * c + r];  // column-major
    if (!m.allFinite()) throw InputError(source + ": node '" + node.name + "' has a matrix that is not finite");
    node.translation = m.block<3, 1>(0, 3);
    Eigen::Matrix3d l = m.block<3, 3>(0, 0);
    for (int c = 0; c < 3; ++c) {
      node.scale(c) = l.col(c).norm();
      if (node.scale(c) > 0) l.col(c) /= node.scale(c);
    }
    if (l.determinant() < 0) {  // a mirror: one negative scale
      node.scale(0) = -node.scale(0);
      l.col(0) = -l.col(0);
    }
    node.rotation = Eigen::Quaterniond(l).normalized();
  } else {
    if (gn.translation.size() == 3) node.translation = Eigen::Vector3d(gn.translation[0], gn.translation[1], gn.translation[2]);
    if (gn.rotation.size() == 4)
      node.rotation = Eigen::Quaterniond(gn.rotation[3], gn.rotation[0], gn.rotation[1], gn.rotation[2]);
    if (gn.scale.size() == 3) node.scale = Eigen::Vector3d(gn.scale[0], gn.scale[1], gn.scale[2]);
    if (!node.translation.allFinite() || !node.rotation.coeffs().allFinite() || !node.scale.allFinite())
      throw InputError(source + ": node '" + node.name + "' has a transform that is not finite");
    const double qn = node.rotation.norm();
    node.rotation = qn > 0 ? Eigen::Quaterniond(node.rotation.coeffs() / qn) : Eigen::Quaterniond::Identity();
  }
  return node;
}

// Channel ci of animation ga as a key track on the nodes in their new order (into `track`);
// false for a channel that moves no skeleton (morph weights, an extension's target) or has no
// keys. Throws InputError on a channel the file cannot back.
bool read_track(const tinygltf::Model& model, const tinygltf::Animation& ga, size_t ci, const std::vector<int>& new_index,
                const std::string& where, const std::string& source, KeyTrack& track) {
  const int n = static_cast<int>(model.nodes.size());
  const tinygltf::AnimationChannel& ch = ga.channels[ci];
  TrackTarget target;
  if (ch.target_path == "translation") target = TrackTarget::kTranslation;
  else if (ch.target_path == "rotation") target = TrackTarget::kRotation;
  else if (ch.target_path == "scale") target = TrackTarget::kScale;
  else return false;  // morph weights: not a skeleton's
  if (ch.target_node < 0) return false;  // an extension's target (KHR_animation_pointer)
  const std::string channel = where + ", channel " + std::to_string(ci);
  if (ch.target_node >= n) throw InputError(source + ": " + channel + " targets a node that is not in the file");
  if (ch.sampler < 0 || ch.sampler >= static_cast<int>(ga.samplers.size()))
    throw InputError(source + ": " + channel + " has a sampler that is not in the animation");
  const tinygltf::AnimationSampler& s = ga.samplers[ch.sampler];
  track.node = new_index[ch.target_node];
  track.target = target;
  if (s.interpolation == "STEP") track.interpolation = KeyInterpolation::kStep;
  else if (s.interpolation == "CUBICSPLINE") track.interpolation = KeyInterpolation::kCubicSpline;
  else if (s.interpolation == "LINEAR" || s.interpolation.empty()) track.interpolation = KeyInterpolation::kLinear;
  else throw InputError(source + ": " + channel + " has interpolation '" + first_line(s.interpolation) +
                        "', expected LINEAR, STEP or CUBICSPLINE");
  track.times = read_accessor(model, s.input, TINYGLTF_TYPE_SCALAR, channel + " (key times)", source);
  const int width = target == TrackTarget::kRotation ? 4 : 3;
  const std::vector<double> values = read_accessor(
      model, s.output, width == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, channel + " (values)", source);
  const size_t rows = values.size() / width;
  const size_t expected = track.interpolation == KeyInterpolation::kCubicSpline ? 3 * track.times.size()
                                                                                  : track.times.size();
  if (rows != expected)
    throw InputError(source + ": " + channel + " has " + std::to_string(rows) + " values for " +
                     std::to_string(track.times.size()) + " key times");
  if (track.times.empty()) return false;
  track.values = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      values.data(), static_cast<Eigen::Index>(rows), width);
  return true;
}

AnimatedScene scene_from_model(const tinygltf::Model& model, const std::string& source) {
  AnimatedScene scene;
  scene.source = source;
  scene.metres_per_unit = 1.0;  // glTF 2.0, "Coordinate System and Units": lengths are metres
  const int n = static_cast<int>(model.nodes.size());
  const std::vector<int> parent = node_parents(model, source);
  std::vector<int> new_index;
  for (int i : parents_first(model, parent, new_index, source)) {
    SceneNode node = scene_node(model.nodes[i], i, source);
    node.parent = parent[i] < 0 ? -1 : new_index[parent[i]];
    scene.nodes.push_back(std::move(node));
  }
  // The skins' joints (the skeleton every animation is read on; scene_animation.h). A joint
  // index outside the file is the file's fault, but the skin is not needed to read the motion.
  std::vector<char> skin_joint(n, 0);
  for (const tinygltf::Skin& skin : model.skins)
    for (int j : skin.joints)
      if (j >= 0 && j < n) skin_joint[new_index[j]] = 1;
  for (int i = 0; i < n; ++i)
    if (skin_joint[i]) scene.skin_joints.push_back(i);
  for (size_t ai = 0; ai < model.animations.size(); ++ai) {
    const tinygltf::Animation& ga = model.animations[ai];
    SceneTake take;
    take.name = ga.name.empty() ? "animation " + std::to_string(ai + 1) : ga.name;
    const std::string where = "animation '" + take.name + "'";
    for (size_t ci = 0; ci < ga.channels.size(); ++ci) {
      KeyTrack track;
      if (read_track(model, ga, ci, new_index, where, source, track)) take.tracks.push_back(std::move(track));
    }
    scene.takes.push_back(std::move(take));
  }
  if (scene.takes.empty()) throw InputError(source + ": has no animation");
  return scene;
}

// How deep the JSON's arrays and objects nest (strings skipped). tinygltf turns "extras" into
// its own values recursively: a file nesting thousands deep would take the stack with it.
int json_depth(std::string_view text) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == '[' || c == '{') deepest = std::max(deepest, ++depth);
    else if (c == ']' || c == '}') --depth;
  }
  return deepest;
}

// The JSON of a GLB (its first chunk) or the whole text of a .gltf; "" when the GLB is cut.
std::string_view gltf_json(std::string_view bytes) {
  if (bytes.size() < 4 || bytes.substr(0, 4) != "glTF") return bytes;
  if (bytes.size() < 20) return {};
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return bytes.substr(20, std::min<size_t>(length, bytes.size() - 20));
}

constexpr int kMaxJsonDepth = 256;

}  // namespace

AnimatedScene parse_gltf(std::string_view bytes, const std::string& source, const std::string& base_dir,
                         size_t max_bytes) {
  if (bytes.size() > UINT32_MAX) throw InputError(source + ": is larger than 4 GB, more than glTF can hold");
  if (json_depth(gltf_json(bytes)) > kMaxJsonDepth)
    throw InputError(source + ": not a readable glTF file: its JSON nests deeper than " +
                     std::to_string(kMaxJsonDepth) + " levels");
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try {
    tinygltf::TinyGLTF loader;
    FileBudget budget{max_bytes > bytes.size() ? max_bytes - bytes.size() : 0, !base_dir.empty()};
    tinygltf::FsCallbacks fs{&file_exists, &expand_nothing, &read_buffer_file, &refuse_write, &budget};
    loader.SetFsCallbacks(fs);
    loader.SetImageLoader(&skip_image, nullptr);
    const bool glb = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
    if (glb) {
      ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                       static_cast<unsigned>(bytes.size()), base_dir);
    } else {
      ok = loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()),
                                      base_dir);
    }
  } catch (const std::bad_alloc&) {
    throw InputError(source + ": cannot read: out of memory");
  } catch (const std::exception& e) {
    throw InputError(source + ": not a readable glTF file: " + first_line(e.what()));
  }
  if (!ok) throw InputError(source + ": not a readable glTF file: " + (err.empty() ? "unknown error" : first_line(err)));
  return scene_from_model(model, source);
}

AnimatedScene read_gltf_file(const std::string& path, size_t max_bytes) {
  const std::string bytes = read_file(path, max_bytes);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parse_gltf(bytes, path, dir.empty() ? "." : dir, max_bytes);
}

}  // namespace mostyle
