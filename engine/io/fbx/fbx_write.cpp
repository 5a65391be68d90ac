#include "engine/io/fbx/fbx_write.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <unordered_set>
#include <vector>

#include "engine/base/atomic_file.h"
#include "engine/base/error.h"
#include "engine/base/numbers.h"
#include "engine/io/fbx/fbx_binary.h"
#include "engine/kinematics/euler.h"
#include "engine/kinematics/kinematics.h"
#include "engine/kinematics/units.h"

namespace mostyle {
namespace {

// Object ids: any 64-bit value but 0, which is the scene's root. Counting from here keeps a
// file the same from one run to the next.
constexpr int64_t kFirstId = 1000000;
// KeyAttrFlags of a linear key (FbxAnimCurveDef::eInterpolationLinear).
constexpr int32_t kLinearKey = 0x00000004;
// KeyAttrDataFloat's third value: the right and next-left tangent weights, two 16-bit fractions
// of 9999 (3333 each: a third), packed into the float's bits, as the FBX SDK writes them.
constexpr uint32_t kDefaultWeights = 0x0D050D05;

// "Name" of class "Model" as binary FBX names objects: "Name\x00\x01Model".
std::string object_name(const std::string& name, const char* cls) { return name + std::string("\0\1", 2) + cls; }

// A Properties70 entry: P: name, type, label, flags, values.
FbxRecord property(const std::string& name, const std::string& type, const std::string& label,
                   const std::string& flags, std::vector<FbxProperty> values = {}) {
  std::vector<FbxProperty> p = {fbx_string(name), fbx_string(type), fbx_string(label), fbx_string(flags)};
  for (FbxProperty& v : values) p.push_back(std::move(v));
  return FbxRecord("P", std::move(p));
}
FbxRecord int_property(const std::string& name, int32_t v) {
  return property(name, "int", "Integer", "", {fbx_int32(v)});
}
FbxRecord enum_property(const std::string& name, int32_t v) { return property(name, "enum", "", "", {fbx_int32(v)}); }
FbxRecord bool_property(const std::string& name, bool v) { return property(name, "bool", "", "", {fbx_int32(v)}); }
FbxRecord double_property(const std::string& name, double v) {
  return property(name, "double", "Number", "", {fbx_double(v)});
}
FbxRecord time_property(const std::string& name, int64_t v) {
  return property(name, "KTime", "Time", "", {fbx_int64(v)});
}
FbxRecord string_property(const std::string& name, const std::string& v, const std::string& label = "") {
  return property(name, "KString", label, "", {fbx_string(v)});
}
FbxRecord vector_property(const std::string& name, const std::string& type, const std::string& label,
                          const std::string& flags, const Eigen::Vector3d& v) {
  return property(name, type, label, flags, {fbx_double(v.x()), fbx_double(v.y()), fbx_double(v.z())});
}

// Centimetres per file unit: the unit the skeleton's file states, else the one its size suggests;
// 1 (FBX's own centimetre) when neither tells.
double unit_scale_factor(const Clip& clip) {
  const double metres = metres_per_unit(clip);
  return metres > 0.0 ? 100.0 * metres : 1.0;
}

// FBX's Euler order enum (0 XYZ, 1 XZY, 2 YZX, 3 YXZ, 4 ZXY, 5 ZYX: the order the rotations
// apply, eEulerXYZ being Rz Ry Rx) for channels in `order` (kZXY: Rz Rx Ry, applied Y first).
int fbx_rotation_order(EulerOrder order) {
  switch (order) {
    case EulerOrder::kXYZ: return 5;
    case EulerOrder::kXZY: return 2;
    case EulerOrder::kYXZ: return 4;
    case EulerOrder::kYZX: return 1;
    case EulerOrder::kZXY: return 3;
    case EulerOrder::kZYX: return 0;
  }
  return 0;
}

// One animated property of one joint: three curves (X, Y, Z) of a value per frame.
struct CurveSet {
  int joint = -1;
  bool rotation = false;                  // Lcl Rotation (degrees), else Lcl Translation
  std::array<std::vector<float>, 3> xyz;  // frames values each
};

// The order a joint's rotation channels give, when they are three distinct axes.
bool channel_order(const Joint& joint, EulerOrder* order, std::array<int, 3>* columns) {
  std::string letters;
  for (size_t c = 0; c < joint.channels.size(); ++c) {
    if (!is_rotation(joint.channels[c])) continue;
    if (letters.size() == 3) return false;
    (*columns)[letters.size()] = joint.first_channel + static_cast<int>(c);
    letters.push_back("XYZ"[channel_axis(joint.channels[c])]);
  }
  return letters.size() == 3 && parse_euler_order(letters, order);
}

// A joint's rotation curves in the order it is written in (*order), unwrapped frame to frame.
CurveSet rotation_curves(const Clip& clip, int j, EulerOrder* order) {
  const Joint& joint = clip.skeleton.joints[j];
  std::array<int, 3> columns{};
  const bool as_channels = channel_order(joint, order, &columns);
  if (!as_channels) *order = EulerOrder::kZXY;
  const std::array<int, 3> axes = euler_axes(*order);
  CurveSet set;
  set.joint = j;
  set.rotation = true;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (int f = 0; f < clip.frames(); ++f) {
    Eigen::Vector3d angles;
    if (as_channels) {
      for (int d = 0; d < 3; ++d) angles[d] = clip.motion(f, columns[d]);
      if (f > 0) angles = euler_near(angles, previous);
    } else {
      const Eigen::Matrix3d r = joint_local_rotation(joint, clip.motion.row(f).data());
      angles = f > 0 ? matrix_to_euler_near(*order, r, previous) : matrix_to_euler(*order, r);
    }
    previous = angles;
    for (int d = 0; d < 3; ++d) set.xyz[axes[d]].push_back(to_float32(angles[d]));
  }
  return set;
}

// Whether a joint's translation is keyed: a root, or a joint whose position channels change.
bool translation_moves(const Clip& clip, int j) {
  const Joint& joint = clip.skeleton.joints[j];
  if (joint.parent < 0) return true;
  for (size_t c = 0; c < joint.channels.size(); ++c) {
    if (!is_position(joint.channels[c])) continue;
    const int col = joint.first_channel + static_cast<int>(c);
    for (int f = 1; f < clip.frames(); ++f)
      if (clip.motion(f, col) != clip.motion(0, col)) return true;
  }
  return false;
}

CurveSet translation_curves(const Clip& clip, int j) {
  CurveSet set;
  set.joint = j;
  for (int f = 0; f < clip.frames(); ++f) {
    const Eigen::Vector3d t = joint_local_translation(clip.skeleton.joints[j], clip.motion.row(f).data());
    for (int d = 0; d < 3; ++d) set.xyz[d].push_back(to_float32(t[d]));
  }
  return set;
}

FbxRecord header_extension(int version) {
  FbxRecord h("FBXHeaderExtension");
  h.add("FBXHeaderVersion", {fbx_int32(1003)});
  h.add("FBXVersion", {fbx_int32(version)});
  h.add("EncryptionType", {fbx_int32(0)});
  FbxRecord& stamp = h.add("CreationTimeStamp");  // kFbxCreationTime's moment
  for (const auto& [name, value] : std::vector<std::pair<const char*, int>>{
           {"Version", 1000}, {"Year", 1970}, {"Month", 1}, {"Day", 1}, {"Hour", 10}, {"Minute", 0}, {"Second", 0},
           {"Millisecond", 0}})
    stamp.add(name, {fbx_int32(value)});
  h.add("Creator", {fbx_string("mostyle")});
  FbxRecord& info = h.add("SceneInfo", {fbx_string(object_name("GlobalInfo", "SceneInfo")), fbx_string("UserData")});
  info.add("Type", {fbx_string("UserData")});
  info.add("Version", {fbx_int32(100)});
  FbxRecord& props = info.add("Properties70");
  props.children.push_back(string_property("Original|ApplicationVendor", "mostyle"));
  props.children.push_back(string_property("Original|ApplicationName", "mostyle"));
  props.children.push_back(string_property("LastSaved|ApplicationVendor", "mostyle"));
  props.children.push_back(string_property("LastSaved|ApplicationName", "mostyle"));
  return h;
}

FbxRecord global_settings(const Clip& clip, double fps, int64_t stop) {
  FbxRecord g("GlobalSettings");
  g.add("Version", {fbx_int32(1000)});
  FbxRecord& p = g.add("Properties70");
  // Y up, Z towards the viewer, X right: right-handed, as BVH files are.
  for (const auto& [name, value] : std::vector<std::pair<const char*, int>>{{"UpAxis", 1},
                                                                           {"UpAxisSign", 1},
                                                                           {"FrontAxis", 2},
                                                                           {"FrontAxisSign", 1},
                                                                           {"CoordAxis", 0},
                                                                           {"CoordAxisSign", 1},
                                                                           {"OriginalUpAxis", 1},
                                                                           {"OriginalUpAxisSign", 1}})
    p.children.push_back(int_property(name, value));
  const double unit = unit_scale_factor(clip);
  p.children.push_back(double_property("UnitScaleFactor", unit));
  p.children.push_back(double_property("OriginalUnitScaleFactor", unit));
  p.children.push_back(enum_property("TimeMode", fbx_time_mode(fps)));
  p.children.push_back(enum_property("TimeProtocol", 2));
  p.children.push_back(enum_property("SnapOnFrameMode", 0));
  p.children.push_back(time_property("TimeSpanStart", 0));
  p.children.push_back(time_property("TimeSpanStop", stop));
  p.children.push_back(double_property("CustomFrameRate", fps));
  return g;
}

FbxRecord documents(int64_t id, const std::string& take) {
  FbxRecord d("Documents");
  d.add("Count", {fbx_int32(1)});
  FbxRecord& doc = d.add("Document", {fbx_int64(id), fbx_string("Scene"), fbx_string("Scene")});
  FbxRecord& p = doc.add("Properties70");
  p.children.push_back(property("SourceObject", "object", "", ""));
  p.children.push_back(string_property("ActiveAnimStackName", take));
  doc.add("RootNode", {fbx_int64(0)});
  return d;
}

// The file's objects and how they connect, built in one pass.
struct Scene {
  FbxRecord objects{"Objects"};
  FbxRecord connections{"Connections"};
  int64_t next_id = kFirstId;
  int models = 0, attributes = 0, curve_nodes = 0, curves = 0;

  int64_t id() { return next_id++; }
  void connect(int64_t child, int64_t parent) {
    connections.add("C", {fbx_string("OO"), fbx_int64(child), fbx_int64(parent)});
  }
  void connect(int64_t child, int64_t parent, const std::string& property) {
    connections.add("C", {fbx_string("OP"), fbx_int64(child), fbx_int64(parent), fbx_string(property)});
  }

  // A Model of type `type` ("LimbNode", "Null") with its NodeAttribute; returns the model's id.
  int64_t add_model(const std::string& name, const char* type, std::vector<FbxRecord> properties, int64_t parent) {
    const int64_t model = id(), attribute = id();
    FbxRecord& m = objects.add("Model", {fbx_int64(model), fbx_string(object_name(name, "Model")), fbx_string(type)});
    m.add("Version", {fbx_int32(232)});
    m.add("Properties70").children = std::move(properties);
    m.add("Shading", {fbx_bool(true)});
    m.add("Culling", {fbx_string("CullingOff")});
    FbxRecord& a = objects.add("NodeAttribute", {fbx_int64(attribute), fbx_string(object_name(name, "NodeAttribute")),
                                                 fbx_string(type)});
    a.add("TypeFlags", {fbx_string(std::string(type) == "LimbNode" ? "Skeleton" : "Null")});
    ++models;
    ++attributes;
    connect(model, parent);
    connect(attribute, model);
    return model;
  }

  // A curve node ("T" or "R") on `model`'s Lcl property and its three curves, in `layer`.
  void add_curves(const CurveSet& set, int64_t model, int64_t layer, const std::vector<int64_t>& times,
                  bool compress) {
    const int64_t node = id();
    FbxRecord& n = objects.add("AnimationCurveNode", {fbx_int64(node),
                                                      fbx_string(object_name(set.rotation ? "R" : "T", "AnimCurveNode")),
                                                      fbx_string("")});
    FbxRecord& p = n.add("Properties70");
    static const char* const kChannels[3] = {"d|X", "d|Y", "d|Z"};
    for (int d = 0; d < 3; ++d) p.children.push_back(property(kChannels[d], "Number", "", "A", {fbx_double(set.xyz[d][0])}));
    ++curve_nodes;
    connect(node, layer);
    connect(node, model, set.rotation ? "Lcl Rotation" : "Lcl Translation");
    for (int d = 0; d < 3; ++d) {
      const int64_t curve = id();
      FbxRecord& c = objects.add("AnimationCurve", {fbx_int64(curve), fbx_string(object_name("", "AnimCurve")),
                                                    fbx_string("")});
      c.add("Default", {fbx_double(set.xyz[d][0])});
      c.add("KeyVer", {fbx_int32(4009)});
      c.add("KeyTime", {fbx_int64s(times, compress)});
      c.add("KeyValueFloat", {fbx_floats(set.xyz[d], compress)});
      float weights;
      std::memcpy(&weights, &kDefaultWeights, 4);
      c.add("KeyAttrFlags", {fbx_int32s({kLinearKey}, compress)});
      c.add("KeyAttrDataFloat", {fbx_floats({0.0f, 0.0f, weights, 0.0f}, compress)});
      c.add("KeyAttrRefCount", {fbx_int32s({static_cast<int32_t>(times.size())}, compress)});
      ++curves;
      connect(curve, node, kChannels[d]);
    }
  }
};

// Model properties of joint j: its rest translation, no rotation, its Euler order.
std::vector<FbxRecord> joint_properties(const Eigen::Vector3d& rest, int rotation_order) {
  return {enum_property("RotationOrder", rotation_order),
          bool_property("RotationActive", true),
          enum_property("InheritType", 1),
          int_property("DefaultAttributeIndex", 0),
          vector_property("Lcl Translation", "Lcl Translation", "", "A", rest),
          vector_property("Lcl Rotation", "Lcl Rotation", "", "A", Eigen::Vector3d::Zero()),
          vector_property("Lcl Scaling", "Lcl Scaling", "", "A", Eigen::Vector3d::Ones()),
          vector_property("PreRotation", "Vector3D", "Vector", "", Eigen::Vector3d::Zero())};
}

// A name for the armature that no joint has (readers find nodes by name).
std::string armature_name(const Skeleton& s, const std::string& take) {
  std::unordered_set<std::string> names;
  for (const Joint& j : s.joints) names.insert(j.name);
  std::string name = take.empty() ? "Armature" : take;
  while (names.count(name)) name += " armature";
  return name;
}

// The armature, the joints and their curves, connected; the stack and layer the curves are in.
Scene skeleton_scene(const Clip& clip, const std::string& take, int64_t stop, double fps,
                     const FbxWriteOptions& options) {
  const Skeleton& s = clip.skeleton;
  const int joints = static_cast<int>(s.joints.size());
  Scene scene;
  const int64_t armature = scene.add_model(armature_name(s, take), "Null",
                                           {enum_property("InheritType", 1), int_property("DefaultAttributeIndex", 0)},
                                           0);
  const int64_t stack = scene.id(), layer = scene.id();
  FbxRecord& st = scene.objects.add("AnimationStack", {fbx_int64(stack), fbx_string(object_name(take, "AnimStack")),
                                                       fbx_string("")});
  FbxRecord& sp = st.add("Properties70");
  sp.children = {time_property("LocalStart", 0), time_property("LocalStop", stop), time_property("ReferenceStart", 0),
                 time_property("ReferenceStop", stop)};
  scene.objects.add("AnimationLayer", {fbx_int64(layer), fbx_string(object_name("BaseLayer", "AnimLayer")),
                                       fbx_string("")});
  scene.connect(layer, stack);

  std::vector<int64_t> times(clip.frames());
  for (int f = 0; f < clip.frames(); ++f)
    times[f] = std::llround(static_cast<double>(f) * static_cast<double>(kFbxTicksPerSecond) / fps);
  const MotionMatrix frame0 = clip.motion.topRows(1);
  std::vector<int64_t> model(joints, 0);
  for (int j = 0; j < joints; ++j) {
    const Joint& joint = s.joints[j];
    EulerOrder order = EulerOrder::kZXY;
    CurveSet rotation;
    if (!joint.end_site) rotation = rotation_curves(clip, j, &order);
    const Eigen::Vector3d rest = joint_local_translation(joint, frame0.data());
    model[j] = scene.add_model(joint.name, "LimbNode", joint_properties(rest, fbx_rotation_order(order)),
                               joint.parent < 0 ? armature : model[joint.parent]);
    if (translation_moves(clip, j)) scene.add_curves(translation_curves(clip, j), model[j], layer, times, options.compress);
    if (!joint.end_site) scene.add_curves(rotation, model[j], layer, times, options.compress);
  }
  return scene;
}

FbxRecord definitions(const Scene& scene) {
  FbxRecord d("Definitions");
  d.add("Version", {fbx_int32(100)});
  const std::vector<std::pair<const char*, int>> counts = {{"GlobalSettings", 1},
                                                           {"Model", scene.models},
                                                           {"NodeAttribute", scene.attributes},
                                                           {"AnimationStack", 1},
                                                           {"AnimationLayer", 1},
                                                           {"AnimationCurveNode", scene.curve_nodes},
                                                           {"AnimationCurve", scene.curves}};
  int total = 0;
  for (const auto& c : counts) total += c.second;
  d.add("Count", {fbx_int32(total)});
  for (const auto& [type, count] : counts) d.add("ObjectType", {fbx_string(type)}).add("Count", {fbx_int32(count)});
  return d;
}

FbxRecord takes(const std::string& take, int64_t stop) {
  FbxRecord t("Takes");
  t.add("Current", {fbx_string(take)});
  FbxRecord& one = t.add("Take", {fbx_string(take)});
  one.add("FileName", {fbx_string(take + ".tak")});
  one.add("LocalTime", {fbx_int64(0), fbx_int64(stop)});
  one.add("ReferenceTime", {fbx_int64(0), fbx_int64(stop)});
  return t;
}

}  // namespace

int fbx_time_mode(double fps) {
  static const std::pair<double, int> kModes[] = {{120, 1}, {100, 2}, {60, 3}, {50, 4}, {48, 5},
                                                  {30, 6},  {25, 10}, {24, 11}, {96, 15}, {72, 16}};
  for (const auto& [rate, mode] : kModes)
    if (fps == rate) return mode;
  return 14;
}

std::string format_fbx(const Clip& clip, const std::string& take_name, const FbxWriteOptions& options) {
  const Skeleton& s = clip.skeleton;
  if (s.joints.empty()) throw InputError(clip.source + ": has no joints to write as FBX");
  if (clip.frames() == 0) throw InputError(clip.source + ": has no frames to write as FBX");
  const double fps = clip.fps();
  if (!(fps > 0) || !std::isfinite(fps)) throw InputError(clip.source + ": the frame rate is not a positive number");
  std::unordered_set<std::string_view> names;
  for (const Joint& j : s.joints) {
    if (j.end_site) continue;  // not written: no key moves an End Site
    if (j.name.find('\0') != std::string::npos)
      throw InputError(clip.source + ": joint name " + quoted_bytes(j.name) + " holds a NUL byte, which FBX names cannot");
    // FBX readers (assimp, game engines' importers) match a take's curves to joints by name: one
    // of two joints of one name would lose its motion.
    if (!names.insert(j.name).second)
      throw InputError(clip.source + ": two joints are named " + quoted_bytes(j.name) +
                       ", and FBX readers tell joints apart by name; rename one to write FBX");
  }
  if (!clip.motion.allFinite()) throw InputError(clip.source + ": a value is not a finite number");
  // KeyTime is a 64-bit count of ticks: about 6.3 years at most.
  if (static_cast<double>(clip.frames() - 1) / fps * static_cast<double>(kFbxTicksPerSecond) > 9e18)
    throw InputError(clip.source + ": lasts longer than FBX's key times reach");
  const int64_t stop = std::llround(static_cast<double>(clip.frames() - 1) * static_cast<double>(kFbxTicksPerSecond) / fps);
  Scene scene = skeleton_scene(clip, take_name, stop, fps, options);
  std::vector<FbxRecord> records;
  records.push_back(header_extension(options.version));
  records.emplace_back("FileId", std::vector<FbxProperty>{fbx_raw(std::string(kFbxFileId, 16))});
  records.emplace_back("CreationTime", std::vector<FbxProperty>{fbx_string(kFbxCreationTime)});
  records.emplace_back("Creator", std::vector<FbxProperty>{fbx_string("mostyle")});
  records.push_back(global_settings(clip, fps, stop));
  records.push_back(documents(scene.id(), take_name));
  records.emplace_back("References");
  records.push_back(definitions(scene));
  records.push_back(std::move(scene.objects));
  records.push_back(std::move(scene.connections));
  records.push_back(takes(take_name, stop));
  return encode_fbx_binary(records, options.version, clip.source);
}

void write_fbx_file(const Clip& clip, const std::string& path, const FbxWriteOptions& options) {
  write_file_atomically(path, format_fbx(clip, std::filesystem::path(path).stem().string(), options));
}

}  // namespace mostyle
