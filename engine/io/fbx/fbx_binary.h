#pragma once
// The binary FBX container: a tree of named records, each with typed properties, as bytes
// (versions 7100 to 7500). What a file says lives in fbx_write.h; this file only lays it out:
// the 27-byte header ("Kaydara FBX Binary  \0", 0x1A 0x00, the version as uint32), every record
// as (end offset, property count, property bytes, name length: uint32 each before 7500, uint64
// from 7500 on; the name as one byte's length), its properties, its children and a null record
// closing a list of children, a null record closing the file, and the footer.
#include <cstdint>
#include <string>
#include <vector>

namespace mostyle {

// One property, its type code and value already encoded: Y int16, C bool, I int32, F float,
// D double, L int64, S string, R raw bytes; arrays f, d, l, i, b (float, double, int64, int32,
// bool) with length, encoding (0 as they are, 1 zlib) and byte count.
struct FbxProperty {
  std::string bytes;  // the type code and the value, as the file holds them
};

FbxProperty fbx_bool(bool value);
FbxProperty fbx_int32(int32_t value);
FbxProperty fbx_double(double value);
FbxProperty fbx_int64(int64_t value);
FbxProperty fbx_string(const std::string& value);  // 'S'; a class-qualified name holds "\x00\x01"
FbxProperty fbx_raw(const std::string& value);     // 'R'
// Arrays: zlib-compressed (encoding 1) when they take more than kFbxCompressAbove bytes and
// `compress` is set, else stored as they are (encoding 0).
inline constexpr size_t kFbxCompressAbove = 128;
FbxProperty fbx_floats(const std::vector<float>& values, bool compress = true);
FbxProperty fbx_int64s(const std::vector<int64_t>& values, bool compress = true);
FbxProperty fbx_int32s(const std::vector<int32_t>& values, bool compress = true);

struct FbxRecord {
  std::string name;  // at most 255 bytes
  std::vector<FbxProperty> properties;
  std::vector<FbxRecord> children;

  FbxRecord() = default;
  FbxRecord(std::string n, std::vector<FbxProperty> p = {}, std::vector<FbxRecord> c = {})
      : name(std::move(n)), properties(std::move(p)), children(std::move(c)) {}
  // Appends a child and returns it.
  FbxRecord& add(std::string n, std::vector<FbxProperty> p = {});
};

// The file: header, `records` at the top level, the closing null record, the footer.
// `version`: 7100 to 7500. A record ends with a null record when it has children or no
// properties (as the FBX SDK writes them). Throws InputError naming `source` when the file
// would pass 4 GB below version 7500 (its offsets are 32-bit), a name is longer than 255 bytes,
// or the version is outside 7100 to 7500. O(size).
std::string encode_fbx_binary(const std::vector<FbxRecord>& records, int version, const std::string& source);

// The file id and creation time a file carries (the top-level records FileId and CreationTime):
// the pair the footer's code was made for. FBX readers that check the three against each other
// accept this pair, the one Blender's exporter writes too.
inline constexpr char kFbxFileId[] = "\x28\xb3\x2a\xeb\xb6\x24\xcc\xc2\xbf\xc8\xb0\x2a\xa9\x2b\xfc\xf1";
inline constexpr char kFbxCreationTime[] = "1970-01-01 10:00:00:000";

// 46186158000: FBX's time unit (KTime) per second.
inline constexpr int64_t kFbxTicksPerSecond = 46186158000LL;

}  // namespace mostyle
