#include "io/npz_writer.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "io/option_record.hpp"
#include "io/temporary_files.hpp"

namespace aief::io {

namespace {

// One array: its numpy dtype ("<f4"), shape and raw little-endian bytes.
struct NpyArray {
  std::string name;
  std::string dtype;
  std::vector<std::size_t> shape;
  std::string bytes;
};

template <class T>
std::string raw_bytes(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()),
                     values.size() * sizeof(T));  // x86-64 and AArch64: little-endian
}

// numpy's .npy format 1.0: magic, header length, a Python dict literal padded to 64 bytes.
std::string npy_file(const NpyArray& array) {
  // As numpy writes it: "(n,)" for one dimension, "(n, m)" for two.
  std::string shape = "(";
  for (std::size_t i = 0; i < array.shape.size(); ++i)
    shape += (i ? ", " : "") + std::to_string(array.shape[i]);
  shape += array.shape.size() == 1 ? ",)" : ")";
  std::string header =
      "{'descr': '" + array.dtype + "', 'fortran_order': False, 'shape': " + shape + ", }";
  const std::size_t unpadded = 10 + header.size() + 1;
  header += std::string((64 - unpadded % 64) % 64, ' ') + "\n";
  std::string out("\x93NUMPY\x01\x00", 8);
  out += static_cast<char>(header.size() & 0xff);
  out += static_cast<char>(header.size() >> 8);
  return out + header + array.bytes;
}

std::uint32_t crc32(const std::string& bytes) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : bytes) c = table[(c ^ b) & 0xff] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

void put16(std::string& out, std::uint32_t v) {
  out += static_cast<char>(v & 0xff);
  out += static_cast<char>((v >> 8) & 0xff);
}
void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xffff);
  put16(out, v >> 16);
}

// A zip archive of stored (uncompressed) members, as numpy.savez writes (PKWARE APPNOTE 4.3).
std::string zip_stored(const std::vector<std::pair<std::string, std::string>>& members) {
  std::string out, directory;
  for (const auto& [name, data] : members) {
    const auto offset = static_cast<std::uint32_t>(out.size());
    const std::uint32_t crc = crc32(data);
    const auto size = static_cast<std::uint32_t>(data.size());
    put32(out, 0x04034b50);  // local file header
    put16(out, 20);          // version needed
    put16(out, 0);           // flags
    put16(out, 0);           // stored
    put16(out, 0);           // time
    put16(out, 0x21);        // date: 1980-01-01
    put32(out, crc);
    put32(out, size);
    put32(out, size);
    put16(out, static_cast<std::uint32_t>(name.size()));
    put16(out, 0);
    out += name + data;
    put32(directory, 0x02014b50);  // central directory entry
    put16(directory, 20);
    put16(directory, 20);
    put16(directory, 0);
    put16(directory, 0);
    put16(directory, 0);
    put16(directory, 0x21);
    put32(directory, crc);
    put32(directory, size);
    put32(directory, size);
    put16(directory, static_cast<std::uint32_t>(name.size()));
    put16(directory, 0);
    put16(directory, 0);
    put16(directory, 0);
    put16(directory, 0);
    put32(directory, 0);
    put32(directory, offset);
    directory += name;
  }
  const auto directory_offset = static_cast<std::uint32_t>(out.size());
  out += directory;
  put32(out, 0x06054b50);  // end of central directory
  put16(out, 0);
  put16(out, 0);
  put16(out, static_cast<std::uint32_t>(members.size()));
  put16(out, static_cast<std::uint32_t>(members.size()));
  put32(out, static_cast<std::uint32_t>(directory.size()));
  put32(out, directory_offset);
  put16(out, 0);
  return out;
}

// A bytes scalar ("|Sn"), as numpy.savez writes a Python bytes object.
NpyArray bytes_scalar(const std::string& name, const std::string& bytes) {
  return {name,
          "|S" + std::to_string(std::max<std::size_t>(bytes.size(), 1)),
          {},
          bytes.empty() ? std::string(1, '\0') : bytes};
}

// The members that record the source: stored uncompressed, so their bytes appear verbatim in the
// file.
std::vector<NpyArray> source_arrays(const SourceRecord& source) {
  const std::vector<std::int64_t> stat = {static_cast<std::int64_t>(source.bytes), source.mtime_ns};
  return {bytes_scalar("source_name", source.name), {"source_stat", "<i8", {2}, raw_bytes(stat)}};
}

std::uint32_t get16(const std::string& in, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(in[at])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(in[at + 1])) << 8;
}
std::uint32_t get32(const std::string& in, std::size_t at) {
  return get16(in, at) | get16(in, at + 2) << 16;
}

// The data of a stored member of a zip written by zip_stored (local headers one after the other),
// nullopt when there is none of that name.
std::optional<std::string> stored_member(const std::string& zip, const std::string& name) {
  constexpr std::size_t kLocalHeader = 30;
  std::size_t at = 0;
  while (at + kLocalHeader <= zip.size() && get32(zip, at) == 0x04034b50) {
    const std::size_t size = get32(zip, at + 18), name_length = get16(zip, at + 26),
                      extra = get16(zip, at + 28);
    const std::size_t data = at + kLocalHeader + name_length + extra;
    if (data + size > zip.size()) return std::nullopt;
    if (zip.compare(at + kLocalHeader, name_length, name) == 0 && name_length == name.size())
      return zip.substr(data, size);
    at = data + size;
  }
  return std::nullopt;
}

// The bytes of an .npy bytes scalar (format 1.0), its NUL padding removed.
std::optional<std::string> npy_bytes_scalar(const std::string& npy) {
  constexpr std::size_t kPreamble = 10;  // magic, version, header length
  if (npy.size() < kPreamble || npy.compare(0, 6, "\x93NUMPY") != 0) return std::nullopt;
  const std::size_t data = kPreamble + get16(npy, 8);
  if (data > npy.size() || npy.find("'descr': '|S", kPreamble) >= data) return std::nullopt;
  std::string bytes = npy.substr(data);
  bytes.erase(bytes.find_last_not_of('\0') + 1);
  return bytes;
}

}  // namespace

OutputRecord npz_file_record(const std::string& path, const SourceRecord& source) {
  std::ifstream in(path, std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  OutputRecord record;
  // A complete zip ends with its end-of-central-directory record (22 bytes, no comment).
  record.of_source = file.size() >= 22 && file.compare(file.size() - 22, 4, "PK\x05\x06") == 0;
  for (const NpyArray& array : source_arrays(source))
    record.of_source = record.of_source && file.find(npy_file(array)) != std::string::npos;
  if (const std::optional<std::string> member = stored_member(file, "options.npy"))
    record.options = npy_bytes_scalar(*member);
  return record;
}

std::string features_npz(const Features& features, const ExtractorOptions& options,
                         const std::optional<SourceRecord>& source) {
  const std::size_t n = features.keypoints.size();
  std::vector<float> xy, size, angle, response;
  std::vector<std::int32_t> octave;
  std::vector<std::uint8_t> descriptors;
  for (std::size_t i = 0; i < n; ++i) {
    const Keypoint& kp = features.keypoints[i];
    xy.insert(xy.end(), {kp.x, kp.y});
    size.push_back(kp.size);
    angle.push_back(kp.angle_deg);
    response.push_back(kp.response);
    octave.push_back(kp.octave);
    descriptors.insert(descriptors.end(), features.descriptors[i].begin(),
                       features.descriptors[i].end());
  }
  const std::vector<std::int64_t> image_size = {features.image_width, features.image_height};
  std::vector<NpyArray> arrays = {
      {"keypoints", "<f4", {n, 2}, raw_bytes(xy)},
      {"descriptors", "|u1", {n, kDescriptorBytes}, raw_bytes(descriptors)},
      {"scores", "<f4", {n}, raw_bytes(response)},
      {"size", "<f4", {n}, raw_bytes(size)},
      {"angle", "<f4", {n}, raw_bytes(angle)},
      {"octave", "<i4", {n}, raw_bytes(octave)},
      {"image_size", "<i8", {2}, raw_bytes(image_size)},
      bytes_scalar("options", option_record_json(options)),
  };
  if (source)
    for (NpyArray& array : source_arrays(*source)) arrays.push_back(std::move(array));
  std::vector<std::pair<std::string, std::string>> members;
  for (const NpyArray& array : arrays) members.emplace_back(array.name + ".npy", npy_file(array));
  return zip_stored(members);
}

void write_features_npz(const std::string& path, const Features& features,
                        const ExtractorOptions& options,
                        const std::optional<SourceRecord>& source) {
  write_file_atomically(path, features_npz(features, options, source));
}

}  // namespace aief::io
