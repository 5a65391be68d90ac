#include "engine/io/gltf_io.h"

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
#include "engine/base/numbers.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/units.h"

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

// Writing.

namespace {

using json = nlohmann::ordered_json;

// Which joints carry translation keys: the roots, and joints whose position channels change.
std::vector<char> moving_joints(const Clip& clip) {
  const Skeleton& s = clip.skeleton;
  std::vector<char> moves(s.joints.size(), 0);
  for (size_t j = 0; j < s.joints.size(); ++j) {
    const Joint& joint = s.joints[j];
    if (joint.parent < 0) {
      moves[j] = 1;
      continue;
    }
    for (size_t c = 0; c < joint.channels.size() && !moves[j]; ++c) {
      if (!is_position(joint.channels[c])) continue;
      const int col = joint.first_channel + static_cast<int>(c);
      for (int f = 1; f < clip.frames() && !moves[j]; ++f)
        if (clip.motion(f, col) != clip.motion(0, col)) moves[j] = 1;
    }
  }
  return moves;
}

// Metres per file unit for writing: the clip's unit (kinematics/units.h), or 1 where nothing
// tells it (the file's numbers taken as metres).
double metres_scale(const Clip& clip) {
  const double metres = metres_per_unit(clip);
  return metres > 0.0 ? metres : 1.0;
}

// The rest pose: each joint's local translation at the first frame (the OFFSETs when there
// are no frames), no rotation. rest: joints x 3, metres (file units times `metres`).
Eigen::MatrixX3d rest_translations(const Clip& clip, double metres) {
  const Skeleton& s = clip.skeleton;
  const MotionMatrix frame0 =
      clip.frames() > 0 ? MotionMatrix(clip.motion.topRows(1)) : MotionMatrix::Zero(1, s.channel_count);
  Eigen::MatrixX3d rest(s.joints.size(), 3);
  for (size_t j = 0; j < s.joints.size(); ++j)
    rest.row(j) = metres * joint_local_translation(s.joints[j], frame0.data()).transpose();
  return rest;
}

// The joints as nodes 0 .. J-1 (children in skeleton order), then node J: the armature, the
// parent of the skeleton's roots, named after the animation.
json skeleton_nodes(const Skeleton& s, const Eigen::MatrixX3d& rest, const std::string& armature_name) {
  json nodes = json::array();
  json roots = json::array();
  const int joints = static_cast<int>(s.joints.size());
  for (int j = 0; j < joints; ++j) {
    json node;
    node["name"] = s.joints[j].name;
    if (!rest.row(j).isZero(0.0)) node["translation"] = {rest(j, 0), rest(j, 1), rest(j, 2)};
    json children = json::array();
    for (int c : s.children(j)) children.push_back(c);
    if (!children.empty()) node["children"] = children;
    nodes.push_back(node);
    if (s.joints[j].parent < 0) roots.push_back(j);
  }
  json armature;
  armature["name"] = armature_name;
  if (!roots.empty()) armature["children"] = roots;
  nodes.push_back(armature);
  return nodes;
}

// Inverse bind matrices of the rest pose, column-major, one per joint (End Sites too: the skin's
// joints are every joint, so Blender makes each a bone, not an Empty; our reader takes a leaf no
// animation keys back as an End Site): the inverse of a joint's rest world transform, a
// translation by minus its rest position (the armature node has no transform). rest: metres.
std::vector<float> inverse_bind_matrices(const Skeleton& s, const Eigen::MatrixX3d& rest) {
  std::vector<Eigen::Vector3d> world(s.joints.size());
  std::vector<float> out;
  out.reserve(16 * s.joints.size());
  for (size_t j = 0; j < s.joints.size(); ++j) {
    const Eigen::Vector3d local = rest.row(j).transpose();
    world[j] = s.joints[j].parent < 0 ? local : world[s.joints[j].parent] + local;
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.block<3, 1>(0, 3) = -world[j];
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) out.push_back(to_float32(m(r, c)));
  }
  return out;
}

// Translation keys of one joint: frames x 3 floats, metres (file units times `metres`).
void append_translations(const Clip& clip, int joint, double metres, std::vector<float>* values) {
  for (int f = 0; f < clip.frames(); ++f) {
    const Eigen::Vector3d t =
        metres * joint_local_translation(clip.skeleton.joints[joint], clip.motion.row(f).data());
    values->insert(values->end(), {to_float32(t.x()), to_float32(t.y()), to_float32(t.z())});
  }
}

// Rotation keys of one joint: frames x 4 floats (x, y, z, w), signs continuous.
void append_rotations(const Clip& clip, int joint, std::vector<float>* values) {
  Eigen::Quaterniond previous = Eigen::Quaterniond::Identity();
  for (int f = 0; f < clip.frames(); ++f) {
    Eigen::Quaterniond q(joint_local_rotation(clip.skeleton.joints[joint], clip.motion.row(f).data()));
    q.normalize();
    // Continuous signs: q and -q are one rotation, but slerp between keys of opposite sign
    // takes the long way in readers that do not check.
    if (f > 0 && q.dot(previous) < 0) q.coeffs() = -q.coeffs();
    previous = q;
    values->insert(values->end(), {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
                                   static_cast<float>(q.w())});
  }
}

// The buffer as it is filled: views appended in order (each at a multiple of 4 bytes),
// accessors pointing into them.
struct BufferLayout {
  std::string* bin;
  json views = json::array();
  json accessors = json::array();

  // Appends `bytes` bytes as a new view (`target`: 34962 vertices, 34963 indices, 0 none);
  // returns its index, or -1 when there are none.
  int add_view(const void* data, size_t bytes, int target = 0) {
    if (bytes == 0) return -1;
    while (bin->size() % 4) bin->push_back('\0');
    const size_t at = bin->size();
    bin->append(static_cast<const char*>(data), bytes);
    json view = {{"buffer", 0}, {"byteOffset", at}, {"byteLength", bytes}};
    if (target != 0) view["target"] = target;
    views.push_back(std::move(view));
    return static_cast<int>(views.size()) - 1;
  }
  template <typename T>
  int add_view(const std::vector<T>& values, int target = 0) {
    return add_view(values.data(), values.size() * sizeof(T), target);
  }
  int add_accessor(json accessor) {
    accessors.push_back(std::move(accessor));
    return static_cast<int>(accessors.size()) - 1;
  }
};

// One animation: the translation keys of the moving joints, the rotation keys of every joint
// but End Sites, all on one key-time accessor.
json animation(const Clip& clip, const std::string& name, double metres, BufferLayout* buffer) {
  const Skeleton& s = clip.skeleton;
  const int joints = static_cast<int>(s.joints.size());
  const int frames = clip.frames();
  std::vector<float> times(frames);
  // On the snapped rate (a BVH's 0.008333 s is 1/120 s), so keys land on whole frames at it.
  const double fps = clip.fps();
  for (int f = 0; f < frames; ++f) times[f] = to_float32(f / fps);
  const int times_view = buffer->add_view(times);
  const int times_accessor =
      buffer->add_accessor({{"bufferView", times_view}, {"componentType", 5126}, {"count", frames},
                            {"type", "SCALAR"}, {"min", {times.front()}}, {"max", {times.back()}}});
  // Translations, then rotations, each in one buffer view; an accessor per joint.
  const std::vector<char> moves = moving_joints(clip);
  std::vector<float> values;
  std::vector<std::pair<int, size_t>> translations, rotations;  // joint, byte offset in its view
  for (int j = 0; j < joints; ++j) {
    if (!moves[j]) continue;
    translations.push_back({j, values.size() * 4});
    append_translations(clip, j, metres, &values);
  }
  const int translation_view = buffer->add_view(values);
  values.clear();
  for (int j = 0; j < joints; ++j) {
    if (s.joints[j].end_site) continue;
    rotations.push_back({j, values.size() * 4});
    append_rotations(clip, j, &values);
  }
  const int rotation_view = buffer->add_view(values);

  json samplers = json::array(), channels = json::array();
  const auto add_channel = [&](int joint, int view, size_t offset, const char* type, const char* path) {
    const int accessor = buffer->add_accessor(
        {{"bufferView", view}, {"byteOffset", offset}, {"componentType", 5126}, {"count", frames}, {"type", type}});
    const int sampler = static_cast<int>(samplers.size());
    samplers.push_back({{"input", times_accessor}, {"interpolation", "LINEAR"}, {"output", accessor}});
    channels.push_back({{"sampler", sampler}, {"target", {{"node", joint}, {"path", path}}}});
  };
  for (const auto& [joint, offset] : translations) add_channel(joint, translation_view, offset, "VEC3", "translation");
  for (const auto& [joint, offset] : rotations) add_channel(joint, rotation_view, offset, "VEC4", "rotation");
  return {{"name", name}, {"channels", channels}, {"samplers", samplers}};
}

// A stick figure in the rest pose: for every joint with a parent, a thin double pyramid from
// the parent's rest position to its own, skinned wholly to the parent, so the mesh moves with
// the bones. Segments shorter than 1e-6 of the skeleton's extent are left out.
struct BoneMesh {
  std::vector<float> positions;   // vertices x 3, metres
  std::vector<int> joints;        // the joint each vertex follows
  std::vector<uint32_t> indices;  // triangles x 3, counter-clockwise seen from outside
};

BoneMesh bone_mesh(const Skeleton& s, const Eigen::MatrixX3d& rest) {
  std::vector<Eigen::Vector3d> world(s.joints.size());
  double extent = 0.0;
  for (size_t j = 0; j < s.joints.size(); ++j) {
    const Eigen::Vector3d local = rest.row(j).transpose();
    world[j] = s.joints[j].parent < 0 ? local : world[s.joints[j].parent] + local;
    extent = std::max(extent, (world[j] - world[0]).norm());
  }
  BoneMesh mesh;
  for (size_t j = 0; j < s.joints.size(); ++j) {
    const int p = s.joints[j].parent;
    if (p < 0) continue;
    const Eigen::Vector3d head = world[p], d = world[j] - head;
    const double length = d.norm();
    if (!(length > 1e-6 * extent) || !std::isfinite(length)) continue;
    // u, v: perpendicular to d, u x v along d.
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    Eigen::Index least;
    d.cwiseAbs().minCoeff(&least);
    axis(least) = 1.0;
    const Eigen::Vector3d dir = d / length;
    const Eigen::Vector3d u = dir.cross(axis).normalized(), v = dir.cross(u);
    const uint32_t first = static_cast<uint32_t>(mesh.joints.size());
    std::vector<Eigen::Vector3d> corners = {head, world[j]};
    const Eigen::Vector3d centre = head + 0.15 * d;
    const double r = 0.08 * length;
    for (const Eigen::Vector3d& offset : {u, v, Eigen::Vector3d(-u), Eigen::Vector3d(-v)})
      corners.push_back(centre + r * offset);
    for (const Eigen::Vector3d& c : corners) {
      mesh.positions.insert(mesh.positions.end(),
                            {to_float32(c.x()), to_float32(c.y()), to_float32(c.z())});
      mesh.joints.push_back(p);  // the skin's joints are the skeleton's, in order
    }
    for (uint32_t k = 0; k < 4; ++k) {
      const uint32_t a = first + 2 + k, b = first + 2 + (k + 1) % 4;
      mesh.indices.insert(mesh.indices.end(), {first + 1, a, b, first, b, a});
    }
  }
  return mesh;
}

// The stick figure as mesh 0 of `doc`, skinned by skin 0; nothing when it has no segment.
// Returns whether a mesh was written.
bool add_bone_mesh(const Skeleton& s, const Eigen::MatrixX3d& rest, BufferLayout* buffer, json* doc) {
  const BoneMesh mesh = bone_mesh(s, rest);
  const size_t vertices = mesh.joints.size();
  if (vertices == 0) return false;
  Eigen::Vector3f low = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity()), high = -low;
  for (size_t i = 0; i < vertices; ++i) {
    const Eigen::Vector3f v(mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]);
    low = low.cwiseMin(v);
    high = high.cwiseMax(v);
  }
  const int position_view = buffer->add_view(mesh.positions, 34962);
  const int position = buffer->add_accessor({{"bufferView", position_view}, {"componentType", 5126},
                                             {"count", vertices}, {"type", "VEC3"},
                                             {"min", {low.x(), low.y(), low.z()}},
                                             {"max", {high.x(), high.y(), high.z()}}});
  // JOINTS_0 as unsigned bytes while every joint index fits, else unsigned shorts.
  int joints_accessor = -1;
  if (s.joints.size() <= 256) {
    std::vector<uint8_t> j(4 * vertices, 0);
    for (size_t i = 0; i < vertices; ++i) j[4 * i] = static_cast<uint8_t>(mesh.joints[i]);
    joints_accessor = buffer->add_accessor({{"bufferView", buffer->add_view(j, 34962)}, {"componentType", 5121},
                                            {"count", vertices}, {"type", "VEC4"}});
  } else {
    std::vector<uint16_t> j(4 * vertices, 0);
    for (size_t i = 0; i < vertices; ++i) j[4 * i] = static_cast<uint16_t>(mesh.joints[i]);
    joints_accessor = buffer->add_accessor({{"bufferView", buffer->add_view(j, 34962)}, {"componentType", 5123},
                                            {"count", vertices}, {"type", "VEC4"}});
  }
  std::vector<float> weights(4 * vertices, 0.0f);
  for (size_t i = 0; i < vertices; ++i) weights[4 * i] = 1.0f;
  const int weights_accessor = buffer->add_accessor({{"bufferView", buffer->add_view(weights, 34962)},
                                                     {"componentType", 5126}, {"count", vertices}, {"type", "VEC4"}});
  int indices_accessor = -1;
  if (vertices <= 65535) {
    const std::vector<uint16_t> i16(mesh.indices.begin(), mesh.indices.end());
    indices_accessor = buffer->add_accessor({{"bufferView", buffer->add_view(i16, 34963)}, {"componentType", 5123},
                                             {"count", i16.size()}, {"type", "SCALAR"}});
  } else {
    indices_accessor = buffer->add_accessor({{"bufferView", buffer->add_view(mesh.indices, 34963)},
                                             {"componentType", 5125}, {"count", mesh.indices.size()},
                                             {"type", "SCALAR"}});
  }
  json primitive = {{"attributes", {{"POSITION", position}, {"JOINTS_0", joints_accessor},
                                    {"WEIGHTS_0", weights_accessor}}},
                    {"indices", indices_accessor}};
  (*doc)["meshes"] = json::array({{{"name", "bones"}, {"primitives", json::array({primitive})}}});
  return true;
}

}  // namespace

// Whether text is UTF-8 (glTF's names are JSON strings, which hold UTF-8 only).
static bool is_utf8(const std::string& text) {
  size_t i = 0;
  while (i < text.size()) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const int more = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
    if (more < 0 || i + static_cast<size_t>(more) >= text.size() + (more == 0 ? 1 : 0)) return false;
    for (int k = 1; k <= more; ++k)
      if ((static_cast<unsigned char>(text[i + static_cast<size_t>(k)]) >> 6) != 0x2) return false;
    i += static_cast<size_t>(more) + 1;
  }
  return true;
}

std::string format_gltf(const Clip& clip, const std::string& animation_name, const std::string& bin_uri,
                        std::string* bin, const GltfWriteOptions& options) {
  const Skeleton& s = clip.skeleton;
  for (const Joint& joint : s.joints)
    if (!is_utf8(joint.name))
      throw InputError(clip.source + ": joint name " + quoted_bytes(joint.name) +
                       " is not UTF-8 text, which glTF's names must be; rename it to write glTF");
  const int joints = static_cast<int>(s.joints.size());
  bin->clear();
  json doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", "mostyle"}};
  doc["scene"] = 0;
  const double metres = metres_scale(clip);
  const Eigen::MatrixX3d rest = rest_translations(clip, metres);
  json nodes = skeleton_nodes(s, rest, animation_name);
  json scene_nodes = json::array({joints});
  BufferLayout buffer{bin};
  if (joints > 0) {
    json joint_list = json::array();
    for (int j = 0; j < joints; ++j) joint_list.push_back(j);
    const int ibm = buffer.add_accessor({{"bufferView", buffer.add_view(inverse_bind_matrices(s, rest))},
                                         {"componentType", 5126}, {"count", joint_list.size()}, {"type", "MAT4"}});
    doc["skins"] = json::array(
        {{{"name", animation_name}, {"inverseBindMatrices", ibm}, {"skeleton", joints}, {"joints", joint_list}}});
    if (options.bone_mesh && add_bone_mesh(s, rest, &buffer, &doc)) {
      // A skinned mesh's node is a root without a transform: the joints place its vertices.
      scene_nodes.push_back(static_cast<int>(nodes.size()));
      nodes.push_back({{"name", animation_name + " bones"}, {"mesh", 0}, {"skin", 0}});
    }
  }
  doc["scenes"] = json::array({{{"nodes", scene_nodes}}});
  doc["nodes"] = nodes;
  if (clip.frames() > 0) doc["animations"] = json::array({animation(clip, animation_name, metres, &buffer)});
  if (!bin->empty()) {
    doc["accessors"] = buffer.accessors;
    doc["bufferViews"] = buffer.views;
    json buffer_json = {{"byteLength", bin->size()}};
    if (!bin_uri.empty()) buffer_json["uri"] = bin_uri;
    doc["buffers"] = json::array({buffer_json});
  }
  // Joint names are bytes from a file: invalid UTF-8 is replaced, not thrown on.
  return doc.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string format_glb(const Clip& clip, const std::string& animation_name, const GltfWriteOptions& options) {
  std::string bin;
  std::string text = format_gltf(clip, animation_name, "", &bin, options);
  // GLB (glTF 2.0 section 4.4): chunks 4-byte aligned; JSON padded with spaces, BIN with zeros.
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin += '\0';
  const auto u32 = [](std::string* out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out->push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  };
  const size_t total = 12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size());
  if (total > UINT32_MAX) throw InputError(clip.source + ": the animation is larger than 4 GB, more than a GLB holds");
  std::string out;
  out.reserve(total);
  out += "glTF";
  u32(&out, 2);
  u32(&out, static_cast<uint32_t>(total));
  u32(&out, static_cast<uint32_t>(text.size()));
  out += "JSON";
  out += text;
  if (!bin.empty()) {
    u32(&out, static_cast<uint32_t>(bin.size()));
    out.append("BIN\0", 4);
    out += bin;
  }
  return out;
}

void write_gltf_file(const Clip& clip, const std::string& path, const GltfWriteOptions& options) {
  const std::filesystem::path p(path);
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  const std::string name = p.stem().string();
  if (ext == ".glb") {
    write_file_atomically(path, format_glb(clip, name, options));
  } else if (ext == ".gltf") {
    const std::string bin_name = name + ".bin";
    std::string bin;
    const std::string text = format_gltf(clip, name, bin_name, &bin, options);
    if (!bin.empty()) write_file_atomically((p.parent_path() / bin_name).string(), bin);
    write_file_atomically(path, text);
  } else {
    throw InputError(path + ": cannot write glTF: the name must end in .glb or .gltf");
  }
}

}  // namespace mostyle
