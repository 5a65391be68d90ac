#pragma once
// What mostyle checks of an FBX file before assimp reads it. assimp walks an FBX file's records
// and its node hierarchy recursively: a file whose records nest thousands deep, or whose models
// are connected in a loop (a model its own ancestor), would take the stack with it. Real files
// nest a handful of records deep and their skeletons are tens of bones deep.
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mostyle {

// How deep records may nest (real files: Objects > Model > Properties70 > P, 4 deep).
inline constexpr int kMaxFbxRecordDepth = 64;
// How long a chain of models may be, root to deepest bone (real skeletons: tens).
inline constexpr int kMaxFbxModelChain = 256;

// The parts of an FBX file's structure that decide how deep assimp recurses.
struct FbxStructure {
  int record_depth = 0;                   // deepest record nesting; top-level records are depth 1
  std::vector<std::string> models;        // ids of the Model objects, as written
  std::vector<std::pair<std::string, std::string>> parents;  // "OO" connections: (child, parent)
};

// Scans binary or ASCII FBX bytes, without assimp. A structure it cannot follow (a record that
// runs past the end, a file cut short) ends the scan there: what was read is returned, and
// assimp reports the damage.
FbxStructure scan_fbx_structure(std::string_view bytes);

// The longest chain of models, child to parent, in the structure's "OO" connections (1 for a
// model without a parent model), or -1 when the models are connected in a loop.
int longest_model_chain(const FbxStructure& structure);

// Throws InputError "SOURCE: not a readable FBX file: ..." when the records nest deeper than
// kMaxFbxRecordDepth, the models loop, or a chain of models is longer than kMaxFbxModelChain.
void check_fbx_structure(std::string_view bytes, const std::string& source);

}  // namespace mostyle
