#include "engine/prepare/major_skeleton.h"

#include <algorithm>
#include <cctype>

#include "engine/base/error.h"
#include "engine/kinematics/kinematics.h"
#include "engine/prepare/rig_structure.h"

namespace mostyle {
namespace {

constexpr int kParents[kMajorJointCount] = {-1, 0, 1, 2, 2, 4, 5, 6, 2, 8, 9, 10,
                                            0, 12, 13, 14, 0, 16, 17, 18};
constexpr const char* kNames[kMajorJointCount] = {
    "hips",           "spine",       "chest",       "head",        "left_shoulder",
    "left_elbow",     "left_wrist",  "left_hand",   "right_shoulder", "right_elbow",
    "right_wrist",    "right_hand",  "left_hip",    "left_knee",   "left_ankle",
    "left_toe",       "right_hip",   "right_knee",  "right_ankle", "right_toe"};
constexpr double kZeroBone = 1e-6;  // relative to skeleton size
// The hips stand at least this share of the rest pose's height above its lowest joint.
constexpr double kMinHipsHeight = 0.25;
// The joints a blend cannot do without: the hips, both hips, knees and ankles.
constexpr int kNeeded[] = {0, 12, 13, 14, 16, 17, 18};

enum class Side { kNone, kLeft, kRight };

struct NameParts {
  Side side = Side::kNone;
  std::string part;  // lower case, letters and digits only, side words removed
};

std::string lower(const std::string& s) {
  std::string out;
  for (char c : s) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Splits a joint name into its side and body part: "LeftUpLeg" -> (left, "upleg"),
// "UpperArm_L" -> (left, "upperarm"), "mixamorig:RightHand" -> (right, "hand"),
// "Bip01 L Thigh" -> (left, "thigh"), "lShldr" -> (left, "shldr"), "LHipJoint" -> (left, "hipjoint").
NameParts split_name(const std::string& raw) {
  std::string name = raw;
  const size_t colon = name.rfind(':');  // namespaces: "mixamorig:Hips"
  if (colon != std::string::npos) name = name.substr(colon + 1);
  // Words: split on separators and lower-to-upper case changes.
  std::vector<std::string> words;
  std::string word;
  auto flush = [&] {
    if (!word.empty()) words.push_back(lower(word));
    word.clear();
  };
  for (size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (!std::isalnum(static_cast<unsigned char>(c))) {
      flush();
      continue;
    }
    if (std::isupper(static_cast<unsigned char>(c)) && !word.empty() &&
        std::islower(static_cast<unsigned char>(word.back())))
      flush();
    // "LHipJoint": a lone capital L/R before a capitalized word.
    if (std::isupper(static_cast<unsigned char>(c)) && word.size() == 1 &&
        std::isupper(static_cast<unsigned char>(word[0])) && i + 1 < name.size() &&
        std::islower(static_cast<unsigned char>(name[i + 1])))
      flush();
    word += c;
  }
  flush();
  NameParts parts;
  std::string joined;
  for (size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    if (parts.side == Side::kNone && (w == "left" || w == "l")) {
      parts.side = Side::kLeft;
      continue;
    }
    if (parts.side == Side::kNone && (w == "right" || w == "r")) {
      parts.side = Side::kRight;
      continue;
    }
    // Prefixes that name the rig, not the part: 3ds Max Biped's "Bip01" / "Bip001", Mixamo's
    // "mixamorig" (also "mixamorig1", and without the colon: "mixamorigHips"), Blender Rigify's
    // deform bones "DEF-thigh.L".
    const bool rig_prefix = (w.rfind("bip", 0) == 0 && w.find_first_not_of("0123456789", 3) == std::string::npos) ||
                            (w.rfind("mixamorig", 0) == 0 &&
                             w.find_first_not_of("0123456789", 9) == std::string::npos) ||
                            (w == "def" && i == 0);
    if (rig_prefix || (w == "joint" && i == 0)) continue;
    joined += w;
  }
  parts.part = joined;
  return parts;
}

// Body-part spellings per role, most specific first. Matched against NameParts::part.
struct Role {
  int major_left;   // or the centre joint
  int major_right;  // -1 for centre joints
  std::vector<std::string> parts;
};

const std::vector<Role>& roles() {
  static const std::vector<Role> kRoles = {
      // Kinect v1 (the canonical set's model) names its joints HipCenter, ShoulderCenter,
      // ShoulderLeft (the upper arm), WristLeft, HandLeft, AnkleLeft, FootLeft (the toe): the
      // more specific spellings come first so that CMU's LeftHand / LeftFoot (wrist / ankle,
      // no such joints) still map, and a spelling never matches the canonical parent itself.
      {0, -1, {"hips", "hip", "pelvis", "hipcenter", "spinebase", "root", "hipsroot"}},
      // Unreal's mannequins number their spine spine_01 .. spine_03 (UE4) or spine_05 (UE5), the
      // clavicles on the last; Blender Rigify's deform spine is spine.001 .. spine.003.
      {1, -1, {"spine", "abdomen", "spine0", "spinemid", "lowerback", "torso", "waist", "spine01", "spine001"}},
      {2, -1, {"chest", "spine2", "spine1", "upperchest", "thorax", "spine3", "upperback", "chest2",
               "shouldercenter", "spineshoulder", "spine05", "spine04", "spine03", "spine02", "spine003",
               "spine002"}},
      {3, -1, {"head"}},
      {4, 8, {"upperarm", "arm", "shldr", "uparm", "humerus", "shoulderjoint", "shoulder"}},
      {5, 9, {"forearm", "lowerarm", "elbow", "radius", "lowarm"}},
      {6, 10, {"wrist", "hand"}},
      {7, 11, {"handmiddle1", "handindex1", "fingerbase", "handend", "fingers", "finger1",
               "finger0", "middle1", "mid1", "index1", "middle01", "index01", "fmiddle01", "handtip",
               "handsite", "hand"}},
      {12, 16, {"upleg", "upperleg", "thigh", "femur", "hip", "uleg", "hipjoint", "buttock"}},
      {13, 17, {"leg", "lowerleg", "shin", "knee", "calf", "tibia", "lleg", "lowleg"}},
      {14, 18, {"ankle", "foot"}},
      {15, 19, {"toebase", "toe", "toes", "toe0", "ball", "toes0", "foot"}},
  };
  return kRoles;
}

}  // namespace

const char* major_joint_name(int major) {
  return major >= 0 && major < kMajorJointCount ? kNames[major] : "?";
}

int major_joint_from_name(const std::string& name) {
  for (int i = 0; i < kMajorJointCount; ++i)
    if (name == kNames[i]) return i;
  return -1;
}

int major_joint_parent(int major) { return kParents[major]; }

MappingOverrides parse_mapping_overrides(const std::string& text, const std::string& source) {
  MappingOverrides out;
  out.source = source;
  size_t start = 0;
  int line_number = 0;
  while (start <= text.size()) {
    size_t end = text.find_first_of("\r\n", start);
    if (end == std::string::npos) end = text.size();
    ++line_number;
    std::string line = text.substr(start, end - start);
    if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') ++end;
    start = end + 1;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line = line.substr(0, hash);
    auto trim = [](std::string s) {
      const size_t a = s.find_first_not_of(" \t");
      if (a == std::string::npos) return std::string();
      const size_t b = s.find_last_not_of(" \t");
      return s.substr(a, b - a + 1);
    };
    line = trim(line);
    if (line.empty()) continue;
    const size_t eq = line.find('=');
    const std::string where = source + ":" + std::to_string(line_number) + ": ";
    if (eq == std::string::npos)
      throw InputError(where + "expected 'canonical_joint = FileJoint', found '" + line + "'");
    const std::string key = trim(line.substr(0, eq));
    const std::string value = trim(line.substr(eq + 1));
    const int major = major_joint_from_name(key);
    if (major < 0)
      throw InputError(where + "expected a canonical joint name (hips, spine, chest, head, "
                               "left_shoulder .. right_toe), found '" + key + "'");
    if (value.empty()) throw InputError(where + "expected a joint name after '=', found nothing");
    for (size_t i = 0; i < out.entries.size(); ++i) {
      if (out.entries[i].first == major)
        throw InputError(where + key + " is mapped a second time (first on line " +
                         std::to_string(out.lines[i]) + ")");
    }
    out.entries.emplace_back(major, value);
    out.lines.push_back(line_number);
  }
  return out;
}

namespace {

// The canonical joints by the name rules alone.
MajorMapping map_by_names(const Skeleton& skeleton) {
  MajorMapping m;
  const int n = static_cast<int>(skeleton.joints.size());
  std::vector<NameParts> parts(n);
  for (int i = 0; i < n; ++i)
    if (!skeleton.joints[i].end_site) parts[i] = split_name(skeleton.joints[i].name);
  const std::vector<Eigen::Vector3d> rest = rest_positions(skeleton);
  double size = 0, floor = 0, top = 0;
  for (const auto& p : rest) {
    size = std::max(size, (p - rest[0]).norm());
    floor = std::min(floor, p.y() - rest[0].y());
    top = std::max(top, p.y() - rest[0].y());
  }
  // A pelvis stands well above the feet: a joint named "root" on the floor (a rig's ground
  // node, an IK rig's root) is no hips. Only that spelling is doubted: a rest pose may also be
  // no standing body (bones along their local axes with every rotation zero).
  const auto too_low_for_hips = [&](int i) { return rest[i].y() - rest[0].y() - floor < kMinHipsHeight * (top - floor); };
  auto is_descendant = [&](int joint, int ancestor) {
    for (int p = skeleton.joints[joint].parent; p >= 0; p = skeleton.joints[p].parent)
      if (p == ancestor) return true;
    return false;
  };
  // Roles are listed parents first, so a canonical parent is mapped before its children.
  for (const Role& role : roles()) {
    for (int side = 0; side < (role.major_right < 0 ? 1 : 2); ++side) {
      const int major = side == 0 ? role.major_left : role.major_right;
      const Side wanted = role.major_right < 0 ? Side::kNone : (side == 0 ? Side::kLeft : Side::kRight);
      const int parent_major = kParents[major];
      const int parent_joint = parent_major >= 0 ? m.joint[parent_major] : -1;
      for (const std::string& spelling : role.parts) {
        int found = -1;
        for (int i = 0; i < n && found < 0; ++i) {
          if (skeleton.joints[i].end_site || parts[i].part != spelling) continue;
          if (parts[i].side != wanted) continue;
          if (major == 0 && spelling == "root" && too_low_for_hips(i)) continue;
          if (parent_joint >= 0 && !is_descendant(i, parent_joint)) continue;
          if (std::find(m.joint.begin(), m.joint.end(), i) != m.joint.end()) continue;
          if (parent_joint >= 0 && (rest[i] - rest[parent_joint]).norm() <= kZeroBone * size) continue;
          found = i;
        }
        if (found >= 0) {
          m.joint[major] = found;
          m.source[major] = MajorSource::kName;
          break;
        }
      }
    }
  }
  return m;
}

// The body parts whose joints the structure may fill, each with the joints that make it whole
// by name: a part the names read whole is left as they read it.
struct BodyPart {
  std::vector<int> joints;  // canonical, parents first
  std::vector<int> core;    // all of these by name: whole
  std::vector<int> any_of;  // and one of these (when not empty)
};
const std::vector<BodyPart>& body_parts() {
  static const std::vector<BodyPart> kParts = {
      {{0, 1, 2, 3}, {0, 3}, {1, 2}},
      {{4, 5, 6, 7}, {4, 5, 6}, {}},
      {{8, 9, 10, 11}, {8, 9, 10}, {}},
      {{12, 13, 14, 15}, {12, 13, 14}, {}},
      {{16, 17, 18, 19}, {16, 17, 18}, {}},
  };
  return kParts;
}

bool whole(const MajorMapping& m, const BodyPart& part) {
  for (int major : part.core)
    if (!m.has(major)) return false;
  if (part.any_of.empty()) return true;
  return std::any_of(part.any_of.begin(), part.any_of.end(), [&](int major) { return m.has(major); });
}

// Canonical joint a is canonical joint b or above it.
bool canonical_above(int a, int b) {
  for (int up = b; up >= 0; up = kParents[up])
    if (up == a) return true;
  return false;
}

// Fills the missing joints of every part the names leave incomplete from the structure, where
// the structure's joint agrees with the part's named joints (the same joint for the same role,
// or below a named joint above it and above a named joint below it). Returns how many it filled.
int fill_from_structure(const Skeleton& skeleton, const RigStructure& structure, MajorMapping& m) {
  auto is_ancestor = [&](int a, int j) {
    for (int up = skeleton.joints[j].parent; up >= 0; up = skeleton.joints[up].parent)
      if (up == a) return true;
    return false;
  };
  int filled = 0;
  for (const BodyPart& part : body_parts()) {
    if (whole(m, part)) continue;
    for (int major : part.joints) {
      const int j = structure.joint[major];
      if (m.has(major) || j < 0) continue;
      if (std::find(m.joint.begin(), m.joint.end(), j) != m.joint.end()) continue;
      bool agrees = true;
      for (int other : part.joints) {
        if (other == major || m.source[other] != MajorSource::kName) continue;
        const int named = m.joint[other];
        if (named == structure.joint[other]) continue;
        if (canonical_above(other, major)) agrees = agrees && is_ancestor(named, j);
        else if (canonical_above(major, other)) agrees = agrees && is_ancestor(j, named);
      }
      if (!agrees) continue;
      m.joint[major] = j;
      m.source[major] = MajorSource::kStructure;
      ++filled;
    }
  }
  return filled;
}

void apply_overrides(const Skeleton& skeleton, const MappingOverrides& overrides, MajorMapping& m) {
  // Overrides first clear every role they name, so that "a = X" and "b = Y" can swap two joints
  // the name rules had put the other way round.
  for (const auto& entry : overrides.entries) {
    m.joint[entry.first] = -1;
    m.source[entry.first] = MajorSource::kMappingFile;
  }
  for (size_t e = 0; e < overrides.entries.size(); ++e) {
    const auto& [major, name] = overrides.entries[e];
    const int line = e < overrides.lines.size() ? overrides.lines[e] : 0;
    const std::string where = overrides.source + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": ";
    if (name == "-") continue;
    const int j = skeleton.find(name);
    if (j < 0) {
      std::string names;
      for (const Joint& joint : skeleton.joints) {
        if (joint.end_site) continue;
        names += (names.empty() ? "" : ", ") + joint.name;
      }
      throw InputError(where + "expected a joint of the skeleton for " + kNames[major] + ", found '" + name +
                       "' (the skeleton has " + names + ")");
    }
    for (int other = 0; other < kMajorJointCount; ++other) {
      if (other != major && m.joint[other] == j)
        throw InputError(where + "joint '" + name + "' is already " + kNames[other] + "; a joint plays one role (name " +
                         kNames[other] + " too, or write '" + kNames[other] + " = -')");
    }
    m.joint[major] = j;
  }
}

// MajorMapping::how: "14 by name, 6 by structure (structure: ...); missing: left_hand, right_hand".
std::string describe(const MajorMapping& m, const std::string& structure) {
  int count[4] = {0, 0, 0, 0};
  std::string missing;
  for (int i = 0; i < kMajorJointCount; ++i) {
    if (m.has(i)) ++count[static_cast<int>(m.source[i])];
    else missing += std::string(missing.empty() ? "" : ", ") + kNames[i];
  }
  std::string out;
  const auto part = [&](MajorSource source, const char* words) {
    const int c = count[static_cast<int>(source)];
    if (c == 0) return;
    out += (out.empty() ? "" : ", ") + std::to_string(c) + words;
  };
  part(MajorSource::kName, " by name");
  part(MajorSource::kStructure, " by structure");
  part(MajorSource::kMappingFile, " from the mapping file");
  if (out.empty()) out = "no major joint found";
  if (!structure.empty()) out += " (structure: " + structure + ")";
  if (!missing.empty()) out += "; missing: " + missing;
  return out;
}

// Left and right of every sided role swapped (the names' sides mirrored).
void swap_sides(MajorMapping& m) {
  for (int left : {4, 5, 6, 7, 12, 13, 14, 15}) {
    std::swap(m.joint[left], m.joint[left + 4]);
    std::swap(m.source[left], m.source[left + 4]);
  }
}

MajorMapping map_major(const Skeleton& skeleton, const MotionMatrix* motion, const MappingOverrides* overrides) {
  MajorMapping m = map_by_names(skeleton);
  std::string structure_summary, swapped;
  const RigStructure structure = find_rig_structure(skeleton, motion, &m);
  if (structure.names_sides < 0) {
    // The names' left lies on the body's right (named from the viewer's side, or a mirrored
    // rig): the body's sides win, for the named joints too.
    swap_sides(m);
    swapped = std::string("the names' left and right are swapped: their left lies on the body's right, as told by ") +
              facing_cue_name(structure.facing);
  }
  // What the structure showed is told where it gave a joint, or where a needed joint is still
  // missing (why it could not give it).
  const int filled = fill_from_structure(skeleton, structure, m);
  if (filled > 0 || !has_needed_joints(m)) structure_summary = structure.summary;
  if (!swapped.empty()) structure_summary = swapped + (structure_summary.empty() ? "" : "; " + structure_summary);
  if (!m.has(0)) {
    // No pelvis by name or structure: the first joint with position channels carries the trajectory.
    for (int i = 0; i < static_cast<int>(skeleton.joints.size()) && !m.has(0); ++i) {
      for (Channel c : skeleton.joints[i].channels) {
        if (!is_position(c)) continue;
        m.joint[0] = i;
        m.source[0] = MajorSource::kStructure;
      }
    }
  }
  if (overrides) apply_overrides(skeleton, *overrides, m);
  m.how = describe(m, structure_summary);
  return m;
}

}  // namespace

const char* major_source_name(MajorSource source) {
  switch (source) {
    case MajorSource::kNone: return "none";
    case MajorSource::kName: return "name";
    case MajorSource::kStructure: return "structure";
    case MajorSource::kMappingFile: return "mapping file";
  }
  return "?";
}

bool has_needed_joints(const MajorMapping& m) {
  return std::all_of(std::begin(kNeeded), std::end(kNeeded), [&](int major) { return m.has(major); });
}

MajorMapping map_major_joints(const Skeleton& skeleton, const MappingOverrides* overrides) {
  return map_major(skeleton, nullptr, overrides);
}

MajorMapping map_major_joints(const Clip& clip, const MappingOverrides* overrides) {
  return map_major(clip.skeleton, &clip.motion, overrides);
}

std::vector<int> shared_major_joints(const MajorMapping& a, const std::string& source_a,
                                     const MajorMapping& b, const std::string& source_b) {
  std::vector<int> shared;
  std::string required_missing, other_missing;
  const bool same = source_a == source_b;
  for (int i = 0; i < kMajorJointCount; ++i) {
    if (a.has(i) && b.has(i)) {
      shared.push_back(i);
      continue;
    }
    const std::string who = same || (!a.has(i) && !b.has(i)) ? (same ? source_a : "both")
                                                               : (!a.has(i) ? source_a : source_b);
    const bool required = std::find(std::begin(kNeeded), std::end(kNeeded), i) != std::end(kNeeded);
    std::string& list = required ? required_missing : other_missing;
    list += std::string(list.empty() ? "" : ", ") + kNames[i] + " (" + who + ")";
  }
  if (!required_missing.empty() || static_cast<int>(shared.size()) < kMinimumSharedJoints) {
    std::string message = (same ? source_a : source_a + " and " + source_b) +
                          ": too few major joints to blend: a blend needs the hips, both hips, knees "
                          "and ankles, and at least " + std::to_string(kMinimumSharedJoints) +
                          " joints in all, found " + std::to_string(shared.size()) + "; missing: ";
    message += required_missing.empty() ? other_missing
                                        : required_missing + (other_missing.empty() ? "" : "; also missing: " + other_missing);
    // How the joints of each file that lacks a needed one were found (what its structure showed).
    if (!has_needed_joints(a) && !a.how.empty()) message += "; " + source_a + ": " + a.how;
    if (!same && !has_needed_joints(b) && !b.how.empty()) message += "; " + source_b + ": " + b.how;
    message += "; name them in a mapping file (--mapping-a / --mapping-b, see assets/mappings/README.md)";
    throw InputError(message);
  }
  return shared;
}

std::vector<int> subset_parents(const std::vector<int>& joints) {
  std::vector<int> parents(joints.size(), -1);
  for (size_t i = 0; i < joints.size(); ++i) {
    for (int p = kParents[joints[i]]; p >= 0; p = kParents[p]) {
      auto it = std::find(joints.begin(), joints.end(), p);
      if (it != joints.end()) {
        parents[i] = static_cast<int>(it - joints.begin());
        break;
      }
    }
  }
  return parents;
}

}  // namespace mostyle
