#include "engine/io/fbx/fbx_structure.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>

#include "engine/base/error.h"

namespace mostyle {
namespace {

constexpr std::string_view kBinaryMagic = "Kaydara FBX Binary  ";

template <typename T>
T read_le(std::string_view bytes, size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));  // FBX is little-endian, as this machine
  return value;
}

// The value of the property at `at` as text (an id: 'L' or 'I', or a string 'S'), "" for other
// types or when it runs past `end`.
std::string property_text(std::string_view bytes, size_t at, size_t end, size_t* next) {
  *next = end;
  if (at >= end) return "";
  const char type = bytes[at++];
  if (type == 'L' && at + 8 <= end) {
    *next = at + 8;
    return std::to_string(read_le<int64_t>(bytes, at));
  }
  if (type == 'I' && at + 4 <= end) {
    *next = at + 4;
    return std::to_string(read_le<int32_t>(bytes, at));
  }
  if ((type == 'S' || type == 'R') && at + 4 <= end) {
    const uint32_t length = read_le<uint32_t>(bytes, at);
    if (length > end - at - 4) return "";
    *next = at + 4 + length;
    return std::string(bytes.substr(at + 4, length));
  }
  return "";
}

// The first `count` properties of a record as text.
std::vector<std::string> property_texts(std::string_view bytes, size_t at, size_t end, int count) {
  std::vector<std::string> texts;
  for (int i = 0; i < count && at < end; ++i) texts.push_back(property_text(bytes, at, end, &at));
  return texts;
}

// A record's meaning to the scan: a Model's id, or a connection, by the scope it is in.
// An object's id as assimp reads it from text: the number its leading digits make ("1000",
// "01000" and "1000" followed by bytes that are not digits are one id), its decimal digits
// without leading zeros. A token that does not start with a digit, or whose number does not fit
// 64 bits (assimp refuses both), is kept as it is.
std::string object_id(const std::string& token) {
  uint64_t value = 0;
  size_t digits = 0;
  for (; digits < token.size() && token[digits] >= '0' && token[digits] <= '9'; ++digits) {
    const uint64_t digit = static_cast<uint64_t>(token[digits] - '0');
    if (value > (UINT64_MAX - digit) / 10) return token;
    value = value * 10 + digit;
  }
  return digits == 0 ? token : std::to_string(value);
}

void note_record(const std::string& scope, std::string_view name, const std::vector<std::string>& values,
                 FbxStructure* out) {
  if (scope == "Objects" && name == "Model" && !values.empty() && !values[0].empty())
    out->models.push_back(object_id(values[0]));
  if (scope == "Connections" && (name == "C" || name == "Connect") && values.size() >= 3 && values[0] == "OO")
    out->parents.emplace_back(object_id(values[1]), object_id(values[2]));
}

// Binary records: a header (end offset, property count, property bytes, name length; 32-bit
// fields before version 7500, 64-bit after), the name, the properties, then nested records
// ended by a header of zeros. Walked with a stack of the open records' ends.
FbxStructure scan_binary(std::string_view bytes) {
  FbxStructure out;
  if (bytes.size() < 27) return out;
  const bool wide = read_le<uint32_t>(bytes, 23) >= 7500;
  const size_t header = wide ? 25 : 13;
  std::vector<std::pair<uint64_t, std::string>> open;  // end offset and name of each open record
  size_t pos = 27;
  while (pos + header <= bytes.size()) {
    const uint64_t end = wide ? read_le<uint64_t>(bytes, pos) : read_le<uint32_t>(bytes, pos);
    const uint64_t count = wide ? read_le<uint64_t>(bytes, pos + 8) : read_le<uint32_t>(bytes, pos + 4);
    const uint64_t property_bytes = wide ? read_le<uint64_t>(bytes, pos + 16) : read_le<uint32_t>(bytes, pos + 8);
    const uint8_t name_length = static_cast<uint8_t>(bytes[pos + header - 1]);
    if (end == 0 && count == 0 && property_bytes == 0 && name_length == 0) {  // a list's end
      if (open.empty()) break;                                                 // the file's records end
      pos = open.back().first;
      open.pop_back();
      continue;
    }
    const size_t properties = pos + header + name_length;
    if (end <= pos || end > bytes.size() || properties > end || property_bytes > end - properties ||
        (!open.empty() && end > open.back().first))
      break;  // damaged: assimp says where
    const std::string_view name = bytes.substr(pos + header, name_length);
    const std::string scope = open.empty() ? "" : open.back().second;
    if (scope == "Objects" || scope == "Connections")
      note_record(scope, name, property_texts(bytes, properties, properties + property_bytes, 3), &out);
    out.record_depth = std::max(out.record_depth, static_cast<int>(open.size()) + 1);
    const size_t children = properties + property_bytes;
    if (children < end) {
      open.emplace_back(end, std::string(name));
      pos = children;
    } else {
      pos = end;
    }
    while (!open.empty() && pos >= open.back().first) {  // a list without its end marker
      pos = open.back().first;
      open.pop_back();
    }
  }
  return out;
}

// ASCII: tokens as assimp's tokenizer makes them (';' comments to the end of the line, quoted
// strings, braces, keys ending in ':', values between commas and white space). A statement is a
// key and the values after it; '{' opens a scope named by its statement's key.
FbxStructure scan_ascii(std::string_view bytes) {
  FbxStructure out;
  std::vector<std::string> scopes;
  std::string key;
  std::vector<std::string> values;
  std::string token;
  bool in_string = false, in_comment = false;
  const auto end_statement = [&] {
    if (key.empty()) return;
    out.record_depth = std::max(out.record_depth, static_cast<int>(scopes.size()) + 1);
    note_record(scopes.empty() ? "" : scopes.back(), key, values, &out);
    key.clear();
    values.clear();
  };
  const auto end_token = [&](bool is_key) {
    if (token.empty()) return;
    if (is_key) {
      end_statement();
      key = token;
    } else {
      if (token.size() >= 2 && token.front() == '"' && token.back() == '"') token = token.substr(1, token.size() - 2);
      values.push_back(token);
    }
    token.clear();
  };
  for (const char c : bytes) {
    if (in_comment) {
      in_comment = c != '\n' && c != '\r';
      continue;
    }
    if (in_string) {
      token += c;
      in_string = c != '"';
      continue;
    }
    switch (c) {
      case '"':
        token += c;
        in_string = true;
        break;
      case ';':
        end_token(false);
        in_comment = true;
        break;
      case ':':
        end_token(true);
        break;
      case '{': {
        end_token(false);
        const std::string scope = key;
        end_statement();
        scopes.push_back(scope);  // a brace without a key nests too
        out.record_depth = std::max(out.record_depth, static_cast<int>(scopes.size()));
        break;
      }
      case '}':
        end_token(false);
        end_statement();
        if (!scopes.empty()) scopes.pop_back();
        break;
      case ' ': case '\t': case '\n': case '\r': case ',':
        end_token(false);
        break;
      default:
        token += c;
    }
  }
  end_token(false);
  end_statement();
  return out;
}

}  // namespace

FbxStructure scan_fbx_structure(std::string_view bytes) {
  return bytes.substr(0, kBinaryMagic.size()) == kBinaryMagic ? scan_binary(bytes) : scan_ascii(bytes);
}

int longest_model_chain(const FbxStructure& structure) {
  std::unordered_map<std::string, int> index;
  for (const std::string& id : structure.models) index.emplace(id, static_cast<int>(index.size()));
  std::vector<std::vector<int>> parents(index.size());
  for (const auto& [child, parent] : structure.parents) {
    const auto c = index.find(child), p = index.find(parent);
    if (c != index.end() && p != index.end()) parents[c->second].push_back(p->second);
  }
  // Depth-first, without recursion: 0 not seen, -1 on the path being walked, else the chain's length.
  std::vector<int> chain(parents.size(), 0);
  int longest = 0;
  for (size_t start = 0; start < parents.size(); ++start) {
    if (chain[start] != 0) continue;
    std::vector<std::pair<int, size_t>> path{{static_cast<int>(start), 0}};
    chain[start] = -1;
    while (!path.empty()) {
      auto& [model, next] = path.back();
      if (next < parents[model].size()) {
        const int parent = parents[model][next++];
        if (chain[parent] == -1) return -1;
        if (chain[parent] == 0) {
          chain[parent] = -1;
          path.emplace_back(parent, 0);
        }
        continue;
      }
      int length = 1;
      for (const int parent : parents[model]) length = std::max(length, chain[parent] + 1);
      chain[model] = length;
      longest = std::max(longest, length);
      path.pop_back();
    }
  }
  return longest;
}

void check_fbx_structure(std::string_view bytes, const std::string& source) {
  const FbxStructure structure = scan_fbx_structure(bytes);
  if (structure.record_depth > kMaxFbxRecordDepth)
    throw InputError(source + ": not a readable FBX file: its records nest " + std::to_string(structure.record_depth) +
                     " deep, more than " + std::to_string(kMaxFbxRecordDepth));
  const int chain = longest_model_chain(structure);
  if (chain < 0) throw InputError(source + ": not a readable FBX file: its models are connected in a loop");
  if (chain > kMaxFbxModelChain)
    throw InputError(source + ": not a readable FBX file: a chain of " + std::to_string(chain) +
                     " models, more than the " + std::to_string(kMaxFbxModelChain) + " a skeleton has");
}

}  // namespace mostyle
