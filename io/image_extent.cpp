#include "io/image_extent.hpp"

#include <algorithm>
#include <cctype>
#include <optional>

#include "aief/error.hpp"

namespace aief::io {

namespace {

using Bytes = EncodedBytes;

// a * b, or the largest value when it does not fit.
std::uint64_t saturating_product(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > UINT64_MAX / a) return UINT64_MAX;
  return a * b;
}
std::uint64_t saturating_sum(std::uint64_t a, std::uint64_t b) {
  return b > UINT64_MAX - a ? UINT64_MAX : a + b;
}

bool is_letter(std::uint8_t c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

std::string hex_bytes(const Bytes& b, std::uint64_t at, int count) {
  static const char* digits = "0123456789ABCDEF";
  std::string text;
  for (int i = 0; i < count; ++i) {
    const std::uint8_t c = b.at(at + static_cast<std::uint64_t>(i)).value_or(0);
    text += std::string(i > 0 ? " " : "") + digits[c >> 4] + digits[c & 15];
  }
  return text;
}

// 8-byte signature, then per chunk: length, type (four letters, PNG specification §5.4), data,
// CRC. Before, a walk that met no IEND went on through the padding, 12 bytes a step (more than
// 120 s for 1.5 GB of zeros), then read the file whole.
std::uint64_t png_length(const Bytes& b, const std::string& name) {
  std::uint64_t at = 8;
  while (at + 12 <= b.size()) {
    const std::optional<std::uint64_t> length = b.big_endian(at, 4);
    bool named = length.has_value();
    for (std::uint64_t i = 4; i < 8 && named; ++i) named = is_letter(b.at(at + i).value_or(0));
    if (!named || *length > 0x7FFFFFFFu)
      throw Error("cannot read image '" + name + "': its PNG chunks end at byte " +
                  std::to_string(at) + " before any IEND chunk (there, a chunk of type " +
                  hex_bytes(b, at + 4, 4) + " and length " + std::to_string(length.value_or(0)) +
                  ", which no PNG holds: the file is damaged, or padded after its last chunk)");
    const bool end = b.starts_with("IEND", at + 4);
    at += 12 + *length;
    if (end) return std::min(at, b.size());
  }
  return b.size();  // cut short: the file holds no more than its chunks
}

// Marker segments (length after the marker) up to each scan; a scan's entropy-coded data runs to
// the next marker: every FF inside it is followed by 00 or a restart marker (D0..D7).
std::uint64_t jpeg_length(const Bytes& b) {
  std::uint64_t at = 2;
  while (true) {
    if (b.at(at) != 0xFF) return b.size();  // damaged: libjpeg skips to the next marker itself
    while (b.at(at) == 0xFF) ++at;          // fill bytes
    const std::optional<std::uint8_t> marker = b.at(at++);
    if (!marker) return b.size();
    if (*marker == 0xD9) return at;                                         // end of image
    if (*marker == 0x01 || (*marker >= 0xD0 && *marker <= 0xD7)) continue;  // no length
    const std::optional<std::uint64_t> length = b.big_endian(at, 2);
    if (!length || *length < 2) return b.size();
    at += *length;
    if (*marker != 0xDA) continue;
    while (true) {  // the scan's data
      const std::optional<std::uint64_t> marker_or_stuffing = b.find(0xFF, at);
      if (!marker_or_stuffing) return b.size();  // no end-of-image marker: cut short
      at = *marker_or_stuffing;
      const std::optional<std::uint8_t> next = b.at(at + 1);
      if (!next) return b.size();
      if (*next != 0x00 && (*next < 0xD0 || *next > 0xD7)) break;  // a marker
      at += 2;
    }
  }
}

std::uint64_t webp_length(const Bytes& b) {
  const std::optional<std::uint64_t> riff = b.little_endian(4, 4);
  return riff ? std::min(b.size(), *riff + 8 + (*riff & 1)) : b.size();
}

std::uint64_t bmp_length(const Bytes& b) {
  const std::optional<std::uint64_t> offset = b.little_endian(10, 4), info = b.little_endian(14, 4);
  if (!offset || !info) return b.size();
  const bool core = *info == 12;  // OS/2 core header: 16-bit sizes, never compressed
  const std::optional<std::uint64_t> width = core ? b.little_endian(18, 2) : b.little_endian(18, 4),
                                     height =
                                         core ? b.little_endian(20, 2) : b.little_endian(22, 4),
                                     bits = core ? b.little_endian(24, 2) : b.little_endian(28, 2),
                                     compression = core ? 0 : b.little_endian(30, 4),
                                     image_size = core ? 0 : b.little_endian(34, 4);
  if (!width || !height || !bits || !compression || !image_size) return b.size();
  std::uint64_t rows = *height;
  if (!core) {  // signed 32-bit; a negative height means top-down rows
    const long long signed_height = static_cast<std::int32_t>(*height);
    rows = static_cast<std::uint64_t>(signed_height < 0 ? -signed_height : signed_height);
  }
  std::uint64_t pixels_bytes = *image_size;
  // BI_RGB, BI_BITFIELDS, BI_ALPHABITFIELDS: rows of whole 32-bit words; compressed: the size
  // declared (0 there: unknown, the file whole).
  if (*compression == 0 || *compression == 3 || *compression == 6) {
    const std::uint64_t row_bits = saturating_product(*width, *bits);
    pixels_bytes = saturating_product(saturating_sum(row_bits, 31) / 32 * 4, rows);
  } else if (pixels_bytes == 0) {
    return b.size();
  }
  return std::min(b.size(), saturating_sum(*offset, pixels_bytes));
}

// Netpbm: magic, whitespace-separated numbers ('#' comments to the end of a line), then for the
// binary kinds one whitespace byte and the raster; PAM: "ENDHDR" and a newline, then the raster.
std::uint64_t netpbm_length(const ImageHeader& header, const Bytes& b) {
  const char kind = static_cast<char>(b.at(1).value_or(0));
  constexpr std::uint64_t kHeaderLimit = 1 << 16;  // the header parser reads no further
  std::uint64_t at = 2;
  auto skip_space = [&] {
    while (at < kHeaderLimit) {
      const std::optional<std::uint8_t> c = b.at(at);
      if (!c) return;
      if (*c == '#') {
        while (at < kHeaderLimit && b.at(at) && *b.at(at) != '\n') ++at;
      } else if (std::isspace(*c) == 0) {
        return;
      }
      ++at;
    }
  };
  auto skip_number = [&] {
    skip_space();
    while (at < kHeaderLimit && b.at(at) && std::isdigit(*b.at(at)) != 0) ++at;
  };
  const std::uint64_t pixels = saturating_product(static_cast<std::uint64_t>(header.width),
                                                  static_cast<std::uint64_t>(header.height));
  const std::uint64_t samples =
      saturating_product(pixels, static_cast<std::uint64_t>(kind == '3' || kind == '6' ? 3 : 1));
  if (kind == '7') {
    while (at < kHeaderLimit && b.at(at) && !b.starts_with("ENDHDR", at)) ++at;
    while (at < kHeaderLimit && b.at(at) && *b.at(at) != '\n') ++at;
    if (at >= kHeaderLimit || !b.at(at)) return b.size();
    const std::uint64_t raster = saturating_product(
        pixels, static_cast<std::uint64_t>(header.channels) * header.bytes_per_channel);
    return std::min(b.size(), saturating_sum(at + 1, raster));
  }
  skip_number();                                  // width
  skip_number();                                  // height
  if (kind != '1' && kind != '4') skip_number();  // largest sample value
  if (at >= kHeaderLimit) return b.size();
  if (kind == '4' || kind == '5' || kind == '6') {
    const std::uint64_t raster =
        kind == '4'
            ? saturating_product((static_cast<std::uint64_t>(header.width) + 7) / 8,
                                 static_cast<std::uint64_t>(header.height))
            : saturating_product(samples, static_cast<std::uint64_t>(header.bytes_per_channel));
    return std::min(b.size(), saturating_sum(at + 1, raster));
  }
  // Plain text: P1's samples are single digits (spaces optional), P2's and P3's numbers.
  std::uint64_t seen = 0;
  while (seen < samples) {
    const std::optional<std::uint8_t> c = b.at(at);
    if (!c) return b.size();
    if (std::isdigit(*c) != 0) {
      ++seen;
      ++at;
      if (kind != '1')
        while (b.at(at) && std::isdigit(*b.at(at)) != 0) ++at;
    } else {
      ++at;
    }
  }
  return std::min(at + 1, b.size());  // and the byte after: OpenCV reads a number to its end
}

// TIFF and BigTIFF: the first directory (entries of tag, type, count, value or offset), the
// values it points to, and the strips (StripOffsets 273, StripByteCounts 279) or tiles
// (TileOffsets 324, TileByteCounts 325) the image has: as libtiff, no more entries of those
// arrays than its size, RowsPerStrip (278) or TileWidth and TileLength (322, 323), and
// SamplesPerPixel (277) with PlanarConfiguration (284) make (a 16 x 16 image declaring 300 M
// strips in a file padded to 1.5 GB was read to 1.2 GB, walking 300 M entries).
std::uint64_t tiff_length(const ImageHeader& header, const Bytes& b) {
  const bool little = b.starts_with("II");
  auto read = [&](std::uint64_t at, int count) {
    return little ? b.little_endian(at, count) : b.big_endian(at, count);
  };
  const std::optional<std::uint64_t> version = read(2, 2);
  if (!version) return b.size();
  const bool big = *version == 43;
  const int offset_size = big ? 8 : 4;
  const std::optional<std::uint64_t> ifd = read(big ? 8 : 4, offset_size);
  const std::optional<std::uint64_t> entries = ifd ? read(*ifd, big ? 8 : 2) : std::nullopt;
  if (!entries || *entries > 4096) return b.size();  // libtiff refuses more than 4096 entries
  const std::uint64_t first = *ifd + (big ? 8 : 2), entry_size = big ? 20 : 12;
  std::uint64_t end = first + *entries * entry_size + static_cast<std::uint64_t>(offset_size);
  struct Array {
    std::uint64_t count = 0, at = 0;
    int value_size = 0;
  };
  Array offsets, byte_counts;
  // The layout's fields, as libtiff defaults them.
  std::uint64_t rows_per_strip = UINT32_MAX, tile_width = 0, tile_length = 0, samples = 1,
                planar = 1;
  for (std::uint64_t i = 0; i < *entries; ++i) {
    const std::uint64_t entry = first + i * entry_size;
    const std::optional<std::uint64_t> tag = read(entry, 2), type = read(entry + 2, 2),
                                       count = read(entry + 4, offset_size);
    if (!tag || !type || !count) return b.size();
    // Bytes per value of the TIFF 6 and BigTIFF field types (1 for an unknown type).
    static const int kTypeSize[19] = {1, 1, 1, 2, 4, 8, 1, 1, 2, 4, 8, 4, 8, 4, 1, 1, 8, 8, 8};
    const int value_size = *type < 19 ? kTypeSize[*type] : 1;
    const std::uint64_t bytes = saturating_product(*count, static_cast<std::uint64_t>(value_size));
    const std::uint64_t value_at = entry + (big ? 12 : 8);
    std::uint64_t values = value_at;
    if (bytes > static_cast<std::uint64_t>(offset_size)) {  // held elsewhere: at the offset
      const std::optional<std::uint64_t> offset = read(value_at, offset_size);
      if (!offset) return b.size();
      values = *offset;
    }
    const bool strips_or_tiles = *tag == 273 || *tag == 279 || *tag == 324 || *tag == 325;
    if (values != value_at && !strips_or_tiles) end = std::max(end, saturating_sum(values, bytes));
    if (*tag == 273 || *tag == 324) offsets = {*count, values, value_size};
    if (*tag == 279 || *tag == 325) byte_counts = {*count, values, value_size};
    if (*count == 1 && (*tag == 278 || *tag == 322 || *tag == 323 || *tag == 277 || *tag == 284))
      if (const std::optional<std::uint64_t> value = read(value_at, value_size)) {
        if (*tag == 278) rows_per_strip = *value;
        if (*tag == 322) tile_width = *value;
        if (*tag == 323) tile_length = *value;
        if (*tag == 277) samples = *value;
        if (*tag == 284) planar = *value;
      }
    if (*tag == 513) return b.size();  // old-style JPEG: its stream lies where this tag says
  }
  // Without byte counts libtiff guesses the strips' ends: the file whole.
  if (offsets.count == 0 || byte_counts.count == 0) return b.size();
  const auto width = static_cast<std::uint64_t>(std::max(header.width, 0LL)),
             height = static_cast<std::uint64_t>(std::max(header.height, 0LL));
  const auto across = [](std::uint64_t length, std::uint64_t step) {
    return step == 0 ? length : length / step + (length % step != 0);
  };
  std::uint64_t pieces =
      tile_width > 0 && tile_length > 0
          ? saturating_product(across(width, tile_width), across(height, tile_length))
          : across(height, std::max<std::uint64_t>(rows_per_strip, 1));
  if (planar == 2) pieces = saturating_product(pieces, std::max<std::uint64_t>(samples, 1));
  const std::uint64_t used = std::min({offsets.count, byte_counts.count, pieces});
  for (const Array* array : {&offsets, &byte_counts})
    end = std::max(end, saturating_sum(array->at, saturating_product(used, array->value_size)));
  for (std::uint64_t i = 0; i < used; ++i) {
    const std::optional<std::uint64_t> offset = read(offsets.at + i * offsets.value_size,
                                                     offsets.value_size),
                                       count = read(byte_counts.at + i * byte_counts.value_size,
                                                    byte_counts.value_size);
    if (!offset || !count) return b.size();
    end = std::max(end, saturating_sum(*offset, *count));
  }
  return std::min(end, b.size());
}

}  // namespace

std::uint64_t encoded_image_length(const ImageHeader& header, const EncodedBytes& bytes,
                                   const std::string& name) {
  if (header.format == "PNG") return png_length(bytes, name);
  if (header.format == "JPEG") return jpeg_length(bytes);
  if (header.format == "WebP") return webp_length(bytes);
  if (header.format == "BMP") return bmp_length(bytes);
  if (header.format == "PNM" || header.format == "PAM") return netpbm_length(header, bytes);
  if (header.format == "TIFF") return tiff_length(header, bytes);
  return bytes.size();
}

}  // namespace aief::io
