#include "engine/io/fbx/fbx_structure.h"

#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

#include "engine/io/bvh/bvh_read.h"
#include "engine/base/error.h"
#include "engine/io/fbx/fbx_read.h"
#include "tests/engine/io/fbx/fbx_ascii.h"
#include "tests/test_data.h"

using namespace mostyle;
using Catch::Matchers::Contains;

namespace {

// A binary FBX record, written by hand: name, properties (already encoded), nested records.
struct Record {
  std::string name;
  std::string properties;
  int property_count = 0;
  std::vector<Record> children;
};

template <typename T>
std::string le(T value) {
  std::string bytes(sizeof(T), '\0');
  std::memcpy(bytes.data(), &value, sizeof(T));
  return bytes;
}

Record record(std::string name, std::vector<std::string> properties = {}, std::vector<Record> children = {}) {
  Record r{std::move(name), "", static_cast<int>(properties.size()), std::move(children)};
  for (const std::string& p : properties) r.properties += p;
  return r;
}
std::string id(int64_t v) { return "L" + le(v); }
std::string text(const std::string& s) { return "S" + le(static_cast<uint32_t>(s.size())) + s; }

std::string header(uint64_t end, uint64_t count, uint64_t bytes, uint8_t name_length, bool wide) {
  std::string h = wide ? le(end) + le(count) + le(bytes)
                       : le(static_cast<uint32_t>(end)) + le(static_cast<uint32_t>(count)) + le(static_cast<uint32_t>(bytes));
  return h + static_cast<char>(name_length);
}

std::string encode(const Record& r, size_t at, bool wide) {
  const size_t header_size = wide ? 25 : 13;
  std::string body = r.name + r.properties;
  std::string nested;
  for (const Record& c : r.children) nested += encode(c, at + header_size + body.size() + nested.size(), wide);
  if (!r.children.empty()) nested += std::string(header_size, '\0');
  const size_t end = at + header_size + body.size() + nested.size();
  return header(end, r.property_count, r.properties.size(), static_cast<uint8_t>(r.name.size()), wide) + body + nested;
}

std::string binary_fbx(const std::vector<Record>& records, uint32_t version) {
  std::string out = std::string("Kaydara FBX Binary  ") + '\0' + "\x1a" + '\0' + le(version);
  const bool wide = version >= 7500;
  for (const Record& r : records) out += encode(r, out.size(), wide);
  return out + std::string(wide ? 25 : 13, '\0');
}

// Models 1 and 2 (2 under 1 under the root 0), an animation curve node connected to 1's property.
std::vector<Record> two_models(std::vector<Record> extra_connections = {}) {
  std::vector<Record> connections{record("C", {text("OO"), id(2), id(1)}), record("C", {text("OO"), id(1), id(0)}),
                                  record("C", {text("OP"), id(3), id(1), text("Lcl Rotation")})};
  for (Record& r : extra_connections) connections.push_back(std::move(r));
  return {record("FBXHeaderExtension", {}, {record("FBXVersion", {"I" + le<int32_t>(7400)})}),
          record("Objects", {},
                 {record("Model", {id(1), text("Model::a"), text("LimbNode")},
                         {record("Properties70", {}, {record("P", {text("Lcl Translation")})})}),
                  record("Model", {id(2), text("Model::b"), text("LimbNode")}),
                  record("AnimationCurveNode", {id(3), text("AnimCurveNode::R")})}),
          record("Connections", {}, connections)};
}

std::string ascii_models(int chain, const std::string& extra_connections = "") {
  std::string out = "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n\tFBXVersion: 7400\n}\nObjects:  {\n";
  std::string connections = "Connections:  {\n";
  for (int m = 1; m <= chain; ++m) {
    out += "\tModel: " + std::to_string(m) + ", \"Model::j" + std::to_string(m) + "\", \"LimbNode\" {\n\t}\n";
    connections += "\tC: \"OO\"," + std::to_string(m) + "," + std::to_string(m - 1) + "\n";
  }
  return out + "}\n" + connections + extra_connections + "}\n";
}

// The longest chain by brute force: every walk from every model, one step at a time; a walk
// longer than the number of models repeats one (a loop).
int brute_force_chain(int models, const std::vector<std::pair<int, int>>& edges) {
  int longest = 0;
  std::function<bool(int, int)> walk = [&](int model, int length) {
    if (length > models) return false;
    longest = std::max(longest, length);
    for (const auto& [child, parent] : edges)
      if (child == model && !walk(parent, length + 1)) return false;
    return true;
  };
  for (int m = 0; m < models; ++m)
    if (!walk(m, 1)) return -1;
  return longest;
}

}  // namespace

TEST_CASE("FBX structure: binary records written by hand, 32- and 64-bit headers", "[fbx]") {
  for (const uint32_t version : {7400u, 7500u}) {
    INFO("version " << version);
    const FbxStructure s = scan_fbx_structure(binary_fbx(two_models(), version));
    CHECK(s.record_depth == 4);  // Objects > Model > Properties70 > P
    CHECK(s.models == std::vector<std::string>{"1", "2"});
    CHECK(s.parents == std::vector<std::pair<std::string, std::string>>{{"2", "1"}, {"1", "0"}});
    CHECK(longest_model_chain(s) == 2);
    CHECK_NOTHROW(check_fbx_structure(binary_fbx(two_models(), version), "hand.fbx"));

    // 1 under 2 as well: a loop.
    const std::string loop = binary_fbx(two_models({record("C", {text("OO"), id(1), id(2)})}), version);
    CHECK(longest_model_chain(scan_fbx_structure(loop)) == -1);
    CHECK_THROWS_WITH(parse_fbx(loop, "loop.fbx"),
                      Contains("loop.fbx: not a readable FBX file: its models are connected in a loop"));

    // A record 100 deep.
    Record deep = record("Leaf", {id(7)});
    for (int d = 1; d < 100; ++d) deep = record("Nest", {}, {deep});
    const std::string nested = binary_fbx({deep}, version);
    CHECK(scan_fbx_structure(nested).record_depth == 100);
    CHECK_THROWS_WITH(parse_fbx(nested, "deep.fbx"),
                      Contains("deep.fbx: not a readable FBX file: its records nest 100 deep, more than 64"));

    // Cut short anywhere: the scan stops where the records stop, and never reads past the end.
    const std::string whole = binary_fbx(two_models(), version);
    for (size_t cut = 0; cut < whole.size(); ++cut) {
      const FbxStructure part = scan_fbx_structure(std::string_view(whole).substr(0, cut));
      CHECK(part.models.size() <= 2);
      CHECK(part.record_depth <= 4);
    }
  }
}

TEST_CASE("FBX structure: ASCII tokens as assimp reads them (comments, strings, lines)", "[fbx]") {
  const std::string text = ascii_models(3,
                                        "\t; C: \"OO\",1,3 { a comment: no connection, no scope\n"
                                        "\tC: \"OO\",\n\t\t9,\n\t\t3 ; a connection over three lines\n"
                                        "\tC: \"OP\",2,1, \"Lcl Rotation {\"\n");
  const FbxStructure s = scan_fbx_structure(text);
  CHECK(s.record_depth == 2);
  CHECK(s.models == std::vector<std::string>{"1", "2", "3"});
  CHECK(s.parents == std::vector<std::pair<std::string, std::string>>{{"1", "0"}, {"2", "1"}, {"3", "2"}, {"9", "3"}});
  CHECK(longest_model_chain(s) == 3);  // 9 is not a model

  const std::string loop = ascii_models(3, "\tC: \"OO\",1,3\n");
  CHECK_THROWS_WITH(parse_fbx(loop, "loop.fbx"),
                    Contains("loop.fbx: not a readable FBX file: its models are connected in a loop"));
  // Ids as assimp reads them: the number the leading digits make, whatever bytes follow them
  // (\x16 here, as a fuzzer found) and with leading zeros.
  const std::string hidden_loop = ascii_models(3, "\tC: \"OO\",001,3\x16\x16\x16\n");
  CHECK(scan_fbx_structure(hidden_loop).parents.back() == std::pair<std::string, std::string>{"1", "3"});
  CHECK_THROWS_WITH(parse_fbx(hidden_loop, "hidden.fbx"),
                    Contains("hidden.fbx: not a readable FBX file: its models are connected in a loop"));
  const std::string self = ascii_models(3, "\tC: \"OO\",2,2\n");
  CHECK_THROWS_WITH(check_fbx_structure(self, "self.fbx"), Contains("self.fbx: not a readable FBX file"));

  std::string deep = "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n}\n";
  for (int d = 0; d < 5000; ++d) deep += "A: {\n";
  CHECK(scan_fbx_structure(deep).record_depth == 5000);
  CHECK_THROWS_WITH(parse_fbx(deep, "deep.fbx"), Contains("deep.fbx: not a readable FBX file: its records nest 5000 deep"));

  CHECK_NOTHROW(check_fbx_structure(ascii_models(kMaxFbxModelChain), "long.fbx"));
  CHECK_THROWS_WITH(check_fbx_structure(ascii_models(kMaxFbxModelChain + 1), "longer.fbx"),
                    Contains("longer.fbx: not a readable FBX file: a chain of 257 models, more than the 256"));
}

TEST_CASE("FBX structure: the longest chain of models against brute force", "[fbx]") {
  std::mt19937 random(17);
  for (int trial = 0; trial < 500; ++trial) {
    const int models = 1 + static_cast<int>(random() % 7);
    const int edge_count = static_cast<int>(random() % (models + 2));
    FbxStructure s;
    std::vector<std::pair<int, int>> edges;
    for (int m = 0; m < models; ++m) s.models.push_back(std::to_string(m));
    for (int e = 0; e < edge_count; ++e) {
      const int child = static_cast<int>(random() % models), parent = static_cast<int>(random() % (models + 1));
      s.parents.emplace_back(std::to_string(child), std::to_string(parent));  // `models` is not a model
      if (parent < models) edges.emplace_back(child, parent);
    }
    INFO("trial " << trial);
    CHECK(longest_model_chain(s) == brute_force_chain(models, edges));
  }
}

TEST_CASE("FBX structure: a CMU skeleton as ASCII FBX, its chain the BVH's deepest joint", "[fbx]") {
  const Clip clip = read_bvh_file(test::asset("motions/cmu142_walk_happy.bvh"));
  int deepest = 0, joints = 0;
  for (size_t j = 0; j < clip.skeleton.joints.size(); ++j) {
    if (clip.skeleton.joints[j].end_site) continue;
    ++joints;
    int depth = 1;
    for (int p = clip.skeleton.joints[j].parent; p >= 0; p = clip.skeleton.joints[p].parent) ++depth;
    deepest = std::max(deepest, depth);
  }
  const FbxStructure s = scan_fbx_structure(test::format_fbx_ascii(clip, "walk"));
  CHECK(static_cast<int>(s.models.size()) == joints);
  CHECK(longest_model_chain(s) == deepest);
  CHECK(s.record_depth <= 4);
}

TEST_CASE("FBX structure: Blender's binary files pass the checks", "[fbx][shared]") {
  MOSTYLE_REQUIRE_SHARED_MOTIONS();
  for (const char* name : {"formats/cmu142_walk_joy.fbx", "formats/cmu142_walk_happy_30fps.fbx"}) {
    std::ifstream in(test::shared_motion(name), std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    const FbxStructure s = scan_fbx_structure(bytes.str());
    INFO(name << ": depth " << s.record_depth << ", " << s.models.size() << " models, chain "
              << longest_model_chain(s));
    CHECK(s.record_depth >= 3);
    CHECK(s.record_depth <= 8);
    CHECK(s.models.size() >= 31);  // the 31 joints of the BVH, and Blender's armature
    CHECK(longest_model_chain(s) >= 8);
    CHECK(longest_model_chain(s) <= 16);
    CHECK_NOTHROW(check_fbx_structure(bytes.str(), name));
  }
}
