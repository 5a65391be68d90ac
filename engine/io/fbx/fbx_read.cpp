#include "engine/io/fbx/fbx_read.h"

#include <assimp/config.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <new>
#include <unordered_map>

#include "engine/base/atomic_file.h"
#include "engine/base/error.h"
#include "engine/io/fbx/fbx_structure.h"

namespace mostyle {
namespace {

std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '.')) line.pop_back();
  if (line.size() > 200) line = line.substr(0, 200) + "...";
  return line.empty() ? "unknown error" : line;
}

// Keys as a track, dropping a key whose time does not follow the previous one (assimp merges
// the curves' key times; a file with repeated times gives repeated keys).
template <typename Key, typename Value>
KeyTrack make_track(int node, TrackTarget target, const Key* keys, unsigned count, double ticks_per_second,
                    Value value) {
  KeyTrack track;
  track.node = node;
  track.target = target;
  track.interpolation = KeyInterpolation::kLinear;
  const int width = target == TrackTarget::kRotation ? 4 : 3;
  std::vector<double> values;
  for (unsigned k = 0; k < count; ++k) {
    const double t = keys[k].mTime / ticks_per_second;
    if (!track.times.empty() && !(t > track.times.back())) continue;
    track.times.push_back(t);
    value(keys[k], &values);
  }
  track.values = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      values.data(), static_cast<Eigen::Index>(track.times.size()), width);
  return track;
}

AnimatedScene scene_from_assimp(const aiScene& ai, const std::string& source) {
  AnimatedScene scene;
  scene.source = source;
  if (ai.mRootNode == nullptr) throw InputError(source + ": not a readable FBX file: it has no nodes");
  std::unordered_map<std::string, int> by_name;
  // Parents first, depth-first, siblings in file order.
  std::vector<std::pair<const aiNode*, int>> stack{{ai.mRootNode, -1}};
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    SceneNode sn;
    sn.name = node->mName.C_Str();
    sn.parent = parent;
    aiVector3D scaling, position;
    aiQuaternion rotation;
    node->mTransformation.Decompose(scaling, rotation, position);
    sn.translation = Eigen::Vector3d(position.x, position.y, position.z);
    sn.rotation = Eigen::Quaterniond(rotation.w, rotation.x, rotation.y, rotation.z);
    sn.scale = Eigen::Vector3d(scaling.x, scaling.y, scaling.z);
    if (!sn.translation.allFinite() || !sn.rotation.coeffs().allFinite() || !sn.scale.allFinite())
      throw InputError(source + ": node '" + sn.name + "' has a transform that is not finite");
    const double qn = sn.rotation.norm();
    sn.rotation = qn > 0 ? Eigen::Quaterniond(sn.rotation.coeffs() / qn) : Eigen::Quaterniond::Identity();
    // assimp marks each FBX model's kind in its metadata: "IsNull" is false for a LimbNode (and
    // for a mesh's model, which carries meshes); its own root node has none.
    bool is_null = true;
    sn.limb = node->mMetaData != nullptr && node->mMetaData->Get("IsNull", is_null) && !is_null &&
              node->mNumMeshes == 0;
    const int index = static_cast<int>(scene.nodes.size());
    by_name.emplace(sn.name, index);
    scene.nodes.push_back(std::move(sn));
    for (unsigned c = node->mNumChildren; c-- > 0;)
      if (node->mChildren[c] != nullptr) stack.push_back({node->mChildren[c], index});
  }
  scene.scene_root = 0;
  // The nodes the meshes' deformers move (the skeleton every take is read on; scene_animation.h).
  std::vector<char> skin_joint(scene.nodes.size(), 0);
  for (unsigned m = 0; m < ai.mNumMeshes; ++m) {
    const aiMesh* mesh = ai.mMeshes[m];
    if (mesh == nullptr || mesh->mBones == nullptr) continue;
    for (unsigned b = 0; b < mesh->mNumBones; ++b) {
      if (mesh->mBones[b] == nullptr) continue;
      const auto it = by_name.find(mesh->mBones[b]->mName.C_Str());
      if (it != by_name.end()) skin_joint[static_cast<size_t>(it->second)] = 1;
    }
  }
  for (size_t i = 0; i < skin_joint.size(); ++i)
    if (skin_joint[i]) scene.skin_joints.push_back(static_cast<int>(i));

  for (unsigned a = 0; a < ai.mNumAnimations; ++a) {
    const aiAnimation* anim = ai.mAnimations[a];
    if (anim == nullptr) continue;
    SceneTake take;
    take.name = anim->mName.length > 0 ? anim->mName.C_Str() : "animation " + std::to_string(a + 1);
    // assimp's FBX keys count frames of the file's time mode; 0 would mean "not given".
    const double tps = anim->mTicksPerSecond > 0 && std::isfinite(anim->mTicksPerSecond) ? anim->mTicksPerSecond : 30.0;
    if (scene.frame_rate == 0 && anim->mTicksPerSecond > 0) scene.frame_rate = tps;
    for (unsigned c = 0; c < anim->mNumChannels; ++c) {
      const aiNodeAnim* ch = anim->mChannels[c];
      if (ch == nullptr) continue;
      const auto it = by_name.find(ch->mNodeName.C_Str());
      if (it == by_name.end())
        throw InputError(source + ": animation '" + take.name + "' keys node '" + ch->mNodeName.C_Str() +
                         "', which the file does not have");
      const int node = it->second;
      if (ch->mNumPositionKeys > 0 && ch->mPositionKeys != nullptr)
        take.tracks.push_back(make_track(node, TrackTarget::kTranslation, ch->mPositionKeys, ch->mNumPositionKeys, tps,
                                         [](const aiVectorKey& k, std::vector<double>* v) {
                                           v->insert(v->end(), {k.mValue.x, k.mValue.y, k.mValue.z});
                                         }));
      if (ch->mNumRotationKeys > 0 && ch->mRotationKeys != nullptr)
        take.tracks.push_back(make_track(node, TrackTarget::kRotation, ch->mRotationKeys, ch->mNumRotationKeys, tps,
                                         [](const aiQuatKey& k, std::vector<double>* v) {
                                           v->insert(v->end(), {k.mValue.x, k.mValue.y, k.mValue.z, k.mValue.w});
                                         }));
      if (ch->mNumScalingKeys > 0 && ch->mScalingKeys != nullptr)
        take.tracks.push_back(make_track(node, TrackTarget::kScale, ch->mScalingKeys, ch->mNumScalingKeys, tps,
                                         [](const aiVectorKey& k, std::vector<double>* v) {
                                           v->insert(v->end(), {k.mValue.x, k.mValue.y, k.mValue.z});
                                         }));
    }
    scene.takes.push_back(std::move(take));
  }
  if (scene.takes.empty()) throw InputError(source + ": has no animation");
  return scene;
}

}  // namespace

AnimatedScene parse_fbx(std::string_view bytes, const std::string& source) {
  try {
    Assimp::Importer importer;
    // One transform per node: pre/post-rotations, pivots and offsets folded in, no helper nodes.
    importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
    importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_MATERIALS, false);
    importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_TEXTURES, false);
    importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_CAMERAS, false);
    importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_LIGHTS, false);
    importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_READ_ANIMATIONS, true);
    // Every curve the file keys is a track, also one key equal to the node's own transform (a
    // one-frame take of a joint at rest), which assimp would otherwise drop: the nodes a take keys
    // are the skeleton's joints (scene_skeleton), and a one-frame pose must keep them all.
    importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_OPTIMIZE_EMPTY_ANIMATION_CURVES, false);
    // Only FBX: the hint alone would let assimp try its other importers on a file that is not.
    const bool binary = bytes.size() >= 18 && bytes.substr(0, 18) == "Kaydara FBX Binary";
    const bool ascii = !binary && bytes.substr(0, 4096).find("FBXHeaderExtension") != std::string_view::npos;
    if (!binary && !ascii) throw InputError(source + ": not a readable FBX file: no FBX header");
    check_fbx_structure(bytes, source);  // what would make assimp recurse without end
    const aiScene* ai = importer.ReadFileFromMemory(bytes.data(), bytes.size(), 0, "fbx");
    if (ai == nullptr) throw InputError(source + ": not a readable FBX file: " + first_line(importer.GetErrorString()));
    return scene_from_assimp(*ai, source);
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw InputError(source + ": cannot read: out of memory");
  } catch (const std::exception& e) {
    throw InputError(source + ": not a readable FBX file: " + first_line(e.what()));
  } catch (...) {
    throw InputError(source + ": not a readable FBX file");
  }
}

AnimatedScene read_fbx_file(const std::string& path, size_t max_bytes) {
  const std::string bytes = read_file(path, max_bytes);
  return parse_fbx(bytes, path);
}

}  // namespace mostyle
