#include "engine/io/gltf/gltf_write.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "engine/base/atomic_file.h"
#include "engine/base/error.h"
#include "engine/base/numbers.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/units.h"

namespace mostyle {
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
