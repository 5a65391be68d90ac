#include "engine/io/fbx/fbx_binary.h"

#include <zlib.h>

#include <cstring>
#include <limits>

#include "engine/base/error.h"

namespace mostyle {
namespace {

constexpr char kHeader[] = "Kaydara FBX Binary  ";  // then '\0', 0x1A, 0x00 and the version
// The footer: its code (which goes with kFbxFileId and kFbxCreationTime), and its closing magic.
constexpr char kFooterCode[] = "\xfa\xbc\xab\x09\xd0\xc8\xd4\x66\xb1\x76\xfb\x83\x1c\xf7\x26\x7e";
constexpr char kFooterMagic[] = "\xf8\x5a\x8c\x6a\xde\xf5\xd9\x7e\xec\xe9\x0c\xe3\x75\x8f\x29\x0b";

// Little-endian, as FBX and this machine are.
template <typename T>
void put(std::string* out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out->append(bytes, sizeof(T));
}

template <typename T>
void patch(std::string* out, size_t at, T value) {
  std::memcpy(out->data() + at, &value, sizeof(T));
}

FbxProperty scalar(char type, const void* value, size_t size) {
  FbxProperty p;
  p.bytes.push_back(type);
  p.bytes.append(static_cast<const char*>(value), size);
  return p;
}

template <typename T>
FbxProperty array(char type, const std::vector<T>& values, bool compress) {
  const size_t raw_size = values.size() * sizeof(T);
  if (values.size() > std::numeric_limits<uint32_t>::max() || raw_size > std::numeric_limits<uint32_t>::max())
    throw InputError("an FBX array of " + std::to_string(values.size()) + " values is more than one record holds");
  std::string data(reinterpret_cast<const char*>(values.data()), raw_size);
  uint32_t encoding = 0;
  if (compress && raw_size > kFbxCompressAbove) {
    uLongf packed_size = compressBound(static_cast<uLong>(raw_size));
    std::string packed(packed_size, '\0');
    if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size, reinterpret_cast<const Bytef*>(data.data()),
                  static_cast<uLong>(raw_size), Z_DEFAULT_COMPRESSION) == Z_OK &&
        packed_size < raw_size) {
      packed.resize(packed_size);
      data = std::move(packed);
      encoding = 1;
    }
  }
  FbxProperty p;
  p.bytes.push_back(type);
  put<uint32_t>(&p.bytes, static_cast<uint32_t>(values.size()));
  put<uint32_t>(&p.bytes, encoding);
  put<uint32_t>(&p.bytes, static_cast<uint32_t>(data.size()));
  p.bytes += data;
  return p;
}

// A null record: the header's fields all zero.
void put_null_record(std::string* out, bool wide) { out->append(wide ? 25 : 13, '\0'); }

// Whether a record's children end with a null record: when it has any, or no properties, and
// always for animation stacks and layers (as the FBX SDK writes them).
bool closes_with_null(const FbxRecord& r) {
  return !r.children.empty() || r.properties.empty() || r.name == "AnimationStack" || r.name == "AnimationLayer";
}

void put_record(std::string* out, const FbxRecord& r, bool wide, const std::string& source) {
  if (r.name.size() > 255) throw InputError(source + ": an FBX record name is longer than 255 bytes: " + r.name);
  const size_t start = out->size();
  size_t property_bytes = 0;
  for (const FbxProperty& p : r.properties) property_bytes += p.bytes.size();
  if (wide) {
    put<uint64_t>(out, 0);  // end offset, patched below
    put<uint64_t>(out, r.properties.size());
    put<uint64_t>(out, property_bytes);
  } else {
    put<uint32_t>(out, 0);
    put<uint32_t>(out, static_cast<uint32_t>(r.properties.size()));
    put<uint32_t>(out, static_cast<uint32_t>(property_bytes));
  }
  out->push_back(static_cast<char>(r.name.size()));
  *out += r.name;
  for (const FbxProperty& p : r.properties) *out += p.bytes;
  for (const FbxRecord& child : r.children) put_record(out, child, wide, source);
  if (closes_with_null(r)) put_null_record(out, wide);
  const size_t end = out->size();
  if (!wide && (end > std::numeric_limits<uint32_t>::max() || property_bytes > std::numeric_limits<uint32_t>::max()))
    throw InputError(source + ": the FBX file would pass 4 GB, more than FBX 7.4 holds");
  if (wide) patch<uint64_t>(out, start, end);
  else patch<uint32_t>(out, start, static_cast<uint32_t>(end));
}

}  // namespace

FbxProperty fbx_bool(bool value) {
  const uint8_t b = value ? 1 : 0;
  return scalar('C', &b, 1);
}
FbxProperty fbx_int32(int32_t value) { return scalar('I', &value, 4); }
FbxProperty fbx_double(double value) { return scalar('D', &value, 8); }
FbxProperty fbx_int64(int64_t value) { return scalar('L', &value, 8); }

FbxProperty fbx_string(const std::string& value) {
  if (value.size() > std::numeric_limits<uint32_t>::max()) throw InputError("an FBX string is longer than 4 GB");
  FbxProperty p;
  p.bytes.push_back('S');
  put<uint32_t>(&p.bytes, static_cast<uint32_t>(value.size()));
  p.bytes += value;
  return p;
}

FbxProperty fbx_raw(const std::string& value) {
  FbxProperty p = fbx_string(value);
  p.bytes[0] = 'R';
  return p;
}

FbxProperty fbx_floats(const std::vector<float>& values, bool compress) { return array('f', values, compress); }
FbxProperty fbx_int64s(const std::vector<int64_t>& values, bool compress) { return array('l', values, compress); }
FbxProperty fbx_int32s(const std::vector<int32_t>& values, bool compress) { return array('i', values, compress); }

FbxRecord& FbxRecord::add(std::string n, std::vector<FbxProperty> p) {
  children.emplace_back(std::move(n), std::move(p));
  return children.back();
}

std::string encode_fbx_binary(const std::vector<FbxRecord>& records, int version, const std::string& source) {
  if (version < 7100 || version > 7500)
    throw InputError(source + ": FBX version " + std::to_string(version) + " is not written; 7100 to 7500 are");
  const bool wide = version >= 7500;
  std::string out(kHeader, sizeof kHeader);  // with its '\0'
  out.push_back('\x1a');
  out.push_back('\0');
  put<uint32_t>(&out, static_cast<uint32_t>(version));
  for (const FbxRecord& r : records) put_record(&out, r, wide, source);
  put_null_record(&out, wide);
  // The footer: its code, four zero bytes, zeros up to the next multiple of 16 (16 when already
  // there), the version, 120 zero bytes, the magic.
  out.append(kFooterCode, 16);
  out.append(4, '\0');
  const size_t pad = 16 - out.size() % 16;
  out.append(pad, '\0');
  put<uint32_t>(&out, static_cast<uint32_t>(version));
  out.append(120, '\0');
  out.append(kFooterMagic, 16);
  return out;
}

}  // namespace mostyle
