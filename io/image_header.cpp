#include "io/image_header.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "io/encoded_bytes.hpp"

namespace aief::io {

namespace {

using Bytes = EncodedBytes;

std::optional<ImageHeader> make(const char* format, std::optional<std::uint64_t> width,
                                std::optional<std::uint64_t> height) {
  if (!width || !height) return std::nullopt;
  constexpr std::uint64_t kAbsurd =
      1ULL << 40;  // beyond any decoder: capped here, so no later product overflows
  return ImageHeader{format, static_cast<long long>(std::min(*width, kAbsurd)),
                     static_cast<long long>(std::min(*height, kAbsurd))};
}

// Bytes per sample of `bits`-bit samples as OpenCV decodes them (8 or 16 bits; 32: float).
int bytes_per_channel_of(std::uint64_t bits) { return bits <= 8 ? 1 : bits <= 16 ? 2 : 4; }

std::optional<ImageHeader> png_header(const Bytes& b) {
  if (!b.starts_with("IHDR", 12)) return std::nullopt;
  std::optional<ImageHeader> header = make("PNG", b.big_endian(16, 4), b.big_endian(20, 4));
  const std::optional<std::uint8_t> depth = b.at(24), colour = b.at(25);
  if (header && depth && colour) {
    // Colour types: 0 gray, 2 RGB, 3 palette (decoded as BGR), 4 gray + alpha (as BGRA), 6 RGBA.
    header->channels = *colour == 0 ? 1 : *colour == 2 || *colour == 3 ? 3 : 4;
    header->bytes_per_channel = *depth == 16 ? 2 : 1;
  }
  return header;
}

// Start-of-scan markers (FF DA) in the whole file. Inside entropy-coded data every FF is followed
// by 00 or a restart marker, so FF DA is always a marker.
long long count_jpeg_scans(const Bytes& b) {
  long long scans = 0;
  for (std::size_t i = 2; i + 1 < b.size(); ++i)
    if (*b.at(i) == 0xFF && *b.at(i + 1) == 0xDA) ++scans;
  return scans;
}

// Markers until the first start-of-frame (SOF0..SOF15 but DHT C4, JPG C8, DAC CC).
std::optional<ImageHeader> jpeg_header(const Bytes& b) {
  std::size_t at = 2;
  while (true) {
    if (b.at(at) != 0xFF) return std::nullopt;
    while (b.at(at) == 0xFF) ++at;  // fill bytes
    const std::optional<std::uint8_t> marker = b.at(at++);
    if (!marker) return std::nullopt;
    if (*marker == 0x01 || (*marker >= 0xD0 && *marker <= 0xD7)) continue;  // no length
    if (*marker == 0xD9 || *marker == 0xDA) return std::nullopt;  // EOI or scan before any frame
    const std::optional<std::uint64_t> length = b.big_endian(at, 2);
    if (!length || *length < 2) return std::nullopt;
    if (*marker >= 0xC0 && *marker <= 0xCF && *marker != 0xC4 && *marker != 0xC8 &&
        *marker != 0xCC) {
      std::optional<ImageHeader> header =
          make("JPEG", b.big_endian(at + 5, 2), b.big_endian(at + 3, 2));
      const std::optional<std::uint8_t> precision = b.at(at + 2), components = b.at(at + 7);
      if (header && precision && components) {
        header->channels = *components == 1 ? 1 : *components == 4 ? 4 : 3;
        header->bytes_per_channel = bytes_per_channel_of(*precision);
      }
      if (header) header->scans = count_jpeg_scans(b);
      return header;
    }
    at += *length;
  }
}

std::optional<ImageHeader> tiff_header(const Bytes& b) {
  const bool little = b.starts_with("II");
  auto read = [&](std::size_t at, int count) {
    return little ? b.little_endian(at, count) : b.big_endian(at, count);
  };
  const std::optional<std::uint64_t> version = read(2, 2);
  if (!version || (*version != 42 && *version != 43)) return std::nullopt;
  const bool big = *version == 43;  // BigTIFF: 8-byte offsets and counts
  const std::optional<std::uint64_t> ifd = big ? read(8, 8) : read(4, 4);
  if (!ifd || *ifd >= b.size()) return std::nullopt;
  const std::optional<std::uint64_t> entries = big ? read(*ifd, 8) : read(*ifd, 2);
  if (!entries) return std::nullopt;
  const std::size_t first = *ifd + (big ? 8 : 2), entry_size = big ? 20 : 12,
                    value_at = big ? 12 : 8;
  std::optional<std::uint64_t> width, height, bits, samples, tile_width, tile_height;
  // At most libtiff's 4096 entries (it refuses a directory of more): a bound on the walk.
  const std::uint64_t walked = std::min<std::uint64_t>(*entries, 4096);
  for (std::uint64_t i = 0; i < walked && first + i * entry_size + entry_size <= b.size(); ++i) {
    const std::size_t entry = first + static_cast<std::size_t>(i) * entry_size;
    const std::optional<std::uint64_t> tag = read(entry, 2), type = read(entry + 2, 2);
    // BitsPerSample (258: one SHORT per sample, held in the entry while they fit, else at the
    // offset it holds; the first is read) and SamplesPerPixel (277: a SHORT).
    if (tag && type && *type == 3 && (*tag == 258 || *tag == 277)) {
      const std::optional<std::uint64_t> count = big ? read(entry + 4, 8) : read(entry + 4, 4);
      const bool inline_values = count && *count * 2 <= (big ? 8u : 4u);
      const std::optional<std::uint64_t> offset = inline_values ? std::nullopt
                                                  : big         ? read(entry + value_at, 8)
                                                                : read(entry + value_at, 4);
      (*tag == 258 ? bits : samples) = inline_values ? read(entry + value_at, 2)
                                       : offset      ? read(*offset, 2)
                                                     : std::nullopt;
    }
    // ImageWidth (256), ImageLength (257), TileWidth (322), TileLength (323).
    if (!tag || !type || (*tag != 256 && *tag != 257 && *tag != 322 && *tag != 323)) continue;
    // SHORT (3) or LONG (4), or LONG8 (16) in BigTIFF; the value sits in the entry itself.
    const std::optional<std::uint64_t> value = *type == 3    ? read(entry + value_at, 2)
                                               : *type == 4  ? read(entry + value_at, 4)
                                               : *type == 16 ? read(entry + value_at, 8)
                                                             : std::nullopt;
    (*tag == 256 ? width : *tag == 257 ? height : *tag == 322 ? tile_width : tile_height) = value;
  }
  std::optional<ImageHeader> header = make("TIFF", width, height);
  if (header && (tile_width || tile_height)) {
    // A tiled TIFF: libtiff and OpenCV decode tile by tile, each into a buffer of a whole tile.
    const std::optional<ImageHeader> tile =
        make("TIFF", tile_width.value_or(0), tile_height.value_or(0));
    header->tile_width = tile->width;
    header->tile_height = tile->height;
  }
  if (header && bits) header->bytes_per_channel = bytes_per_channel_of(*bits);
  if (header && samples) header->channels = static_cast<int>(std::min<std::uint64_t>(*samples, 64));
  return header;
}

std::optional<ImageHeader> webp_header(const Bytes& b) {
  if (b.starts_with("VP8 ", 12)) {  // lossy: key frame start code, then 14-bit sizes
    if (!b.starts_with("\x9d\x01\x2a", 23)) return std::nullopt;
    const auto w = b.little_endian(26, 2), h = b.little_endian(28, 2);
    return make("WebP", w ? std::optional<std::uint64_t>(*w & 0x3FFF) : std::nullopt,
                h ? std::optional<std::uint64_t>(*h & 0x3FFF) : std::nullopt);
  }
  if (b.starts_with("VP8L",
                    12)) {  // lossless: signature 0x2F, then 14 bits each of width-1, height-1
    if (b.at(20) != 0x2F) return std::nullopt;
    const auto bits = b.little_endian(21, 4);
    if (!bits) return std::nullopt;
    return make("WebP", (*bits & 0x3FFF) + 1, ((*bits >> 14) & 0x3FFF) + 1);
  }
  if (b.starts_with("VP8X", 12)) {  // extended: 24-bit canvas width-1, height-1
    const auto w = b.little_endian(24, 3), h = b.little_endian(27, 3);
    if (!w || !h) return std::nullopt;
    return make("WebP", *w + 1, *h + 1);
  }
  return std::nullopt;
}

std::optional<ImageHeader> bmp_header(const Bytes& b) {
  const std::optional<std::uint64_t> info_size = b.little_endian(14, 4);
  if (!info_size) return std::nullopt;
  if (*info_size == 12)
    return make("BMP", b.little_endian(18, 2), b.little_endian(20, 2));  // OS/2 core header
  const auto w = b.little_endian(18, 4), h = b.little_endian(22, 4);
  if (!w || !h) return std::nullopt;
  // Signed 32-bit; a negative height means top-down rows.
  const long long width = static_cast<std::int32_t>(*w), height = static_cast<std::int32_t>(*h);
  if (width < 0) return std::nullopt;
  return ImageHeader{"BMP", width, height < 0 ? -height : height};
}

// PNM (P1..P6) and PFM (PF, Pf): whitespace-separated decimal width and height, '#' comments.
// PAM (P7): "WIDTH n" and "HEIGHT n" lines before ENDHDR.
std::optional<ImageHeader> netpbm_header(const Bytes& b) {
  const char kind = static_cast<char>(*b.at(1));
  std::size_t at = 2;
  auto skip_space = [&] {
    while (true) {
      const auto c = b.at(at);
      if (!c) return;
      if (*c == '#') {
        while (b.at(at) && *b.at(at) != '\n') ++at;
      } else if (std::isspace(*c) == 0) {
        return;
      }
      ++at;
    }
  };
  auto number = [&]() -> std::optional<std::uint64_t> {
    skip_space();
    std::uint64_t value = 0;
    int digits = 0;
    for (auto c = b.at(at); c && std::isdigit(*c) != 0 && digits < 12; c = b.at(++at), ++digits)
      value = value * 10 + (*c - '0');
    if (digits == 0 || digits == 12) return std::nullopt;
    return value;
  };
  if (kind != '7') {
    const std::optional<std::uint64_t> width = number();  // three statements: width is read first
    const std::optional<std::uint64_t> height = number();
    std::optional<ImageHeader> header =
        make(kind == 'F' || kind == 'f' ? "PFM" : "PNM", width, height);
    if (header && kind != 'F' && kind != 'f') {
      header->channels = kind == '3' || kind == '6' ? 3 : 1;
      // P2, P3, P5, P6 give the largest sample value next: above 255, 16-bit samples.
      const std::optional<std::uint64_t> max_value =
          kind == '1' || kind == '4' ? std::optional<std::uint64_t>(1) : number();
      header->bytes_per_channel = max_value && *max_value > 255 ? 2 : 1;
    }
    return header;
  }
  std::optional<std::uint64_t> width, height, depth, max_value;
  for (int token = 0; token < 64; ++token) {
    skip_space();
    if (b.starts_with("WIDTH", at)) {
      at += 5;
      width = number();
    } else if (b.starts_with("HEIGHT", at)) {
      at += 6;
      height = number();
    } else if (b.starts_with("DEPTH", at)) {
      at += 5;
      depth = number();
    } else if (b.starts_with("MAXVAL", at)) {
      at += 6;
      max_value = number();
    } else if (b.starts_with("ENDHDR", at) || !b.at(at)) {
      break;
    } else {
      while (b.at(at) && *b.at(at) != '\n') ++at;  // another field: TUPLTYPE
    }
  }
  std::optional<ImageHeader> header = make("PAM", width, height);
  if (header && depth) header->channels = static_cast<int>(std::min<std::uint64_t>(*depth, 64));
  if (header && max_value) header->bytes_per_channel = *max_value > 255 ? 2 : 1;
  return header;
}

// Radiance: text lines up to an empty one, then the resolution line, e.g. "-Y 480 +X 640".
std::optional<ImageHeader> hdr_header(const Bytes& b) {
  std::size_t at = 0;
  for (int lines = 0; lines < 256; ++lines) {
    const std::size_t start = at;
    while (b.at(at) && *b.at(at) != '\n') ++at;
    if (!b.at(at)) return std::nullopt;
    ++at;
    if (at - start == 1) break;  // the empty line
  }
  std::string line;
  while (b.at(at) && *b.at(at) != '\n' && line.size() < 64) line += static_cast<char>(*b.at(at++));
  char axis_1 = 0, axis_2 = 0, sign_1 = 0, sign_2 = 0;
  unsigned long long first = 0, second = 0;
  if (std::sscanf(line.c_str(), "%c%c %llu %c%c %llu", &sign_1, &axis_1, &first, &sign_2, &axis_2,
                  &second) != 6)
    return std::nullopt;
  if (axis_1 == 'Y' && axis_2 == 'X') return make("HDR", second, first);
  if (axis_1 == 'X' && axis_2 == 'Y') return make("HDR", first, second);
  return std::nullopt;
}

// J2K codestream: SOC, then the SIZ marker segment; the image area is Xsiz - XOsiz by Ysiz - YOsiz.
std::optional<ImageHeader> j2k_header(const Bytes& b, std::size_t at) {
  if (b.big_endian(at, 4) != 0xFF4FFF51u) return std::nullopt;
  const auto x = b.big_endian(at + 8, 4), y = b.big_endian(at + 12, 4),
             x0 = b.big_endian(at + 16, 4), y0 = b.big_endian(at + 20, 4);
  if (!x || !y || !x0 || !y0 || *x0 > *x || *y0 > *y) return std::nullopt;
  std::optional<ImageHeader> header = make("JPEG 2000", *x - *x0, *y - *y0);
  // Csiz components, each with Ssiz: its bit depth - 1 (bit 7: signed).
  const auto components = b.big_endian(at + 40, 2);
  const auto depth = b.at(at + 42);
  if (header && components && depth) {
    header->channels = static_cast<int>(std::min<std::uint64_t>(*components, 64));
    header->bytes_per_channel = bytes_per_channel_of((*depth & 0x7F) + 1u);
  }
  return header;
}

// JP2: boxes (32-bit length, type); the jp2h super box holds ihdr (height, then width).
std::optional<ImageHeader> jp2_header(const Bytes& b) {
  std::size_t at = 0;
  for (int boxes = 0; boxes < 64; ++boxes) {
    const auto length = b.big_endian(at, 4);
    if (!length) return std::nullopt;
    if (b.starts_with("jp2h", at + 4)) {
      at += 8;  // into the super box
      continue;
    }
    if (b.starts_with("ihdr", at + 4)) {
      // ihdr: height, width, NC components (2 bytes), BPC (bit depth - 1; 255: per component).
      std::optional<ImageHeader> header =
          make("JPEG 2000", b.big_endian(at + 12, 4), b.big_endian(at + 8, 4));
      const auto components = b.big_endian(at + 16, 2);
      const auto depth = b.at(at + 18);
      if (header && components && depth) {
        header->channels = static_cast<int>(std::min<std::uint64_t>(*components, 64));
        header->bytes_per_channel = *depth == 255 ? 2 : bytes_per_channel_of((*depth & 0x7F) + 1u);
      }
      return header;
    }
    if (*length < 8) return std::nullopt;
    at += *length;
  }
  return std::nullopt;
}

}  // namespace

std::optional<ImageHeader> read_image_header(const std::uint8_t* bytes, std::size_t size) {
  return read_image_header(EncodedBytes(bytes, size));
}

std::optional<ImageHeader> read_image_header(const EncodedBytes& b) {
  if (b.starts_with("\x89PNG\r\n\x1a\n")) return png_header(b);
  if (b.starts_with("\xFF\xD8")) return jpeg_header(b);
  if (b.starts_with(std::string_view("II*\0", 4)) || b.starts_with(std::string_view("MM\0*", 4)) ||
      b.starts_with(std::string_view("II+\0", 4)) || b.starts_with(std::string_view("MM\0+", 4)))
    return tiff_header(b);
  if (b.starts_with("RIFF") && b.starts_with("WEBP", 8)) return webp_header(b);
  if (b.starts_with("BM")) return bmp_header(b);
  if (b.starts_with("P") && b.at(1) && std::strchr("1234567Ff", *b.at(1)) != nullptr &&
      *b.at(1) != 0)
    return netpbm_header(b);
  if (b.starts_with("\x59\xA6\x6A\x95"))
    return make("Sun raster", b.big_endian(4, 4), b.big_endian(8, 4));
  if (b.starts_with("#?RADIANCE") || b.starts_with("#?RGBE")) return hdr_header(b);
  // OpenCV asks its DICOM decoder (GDCM) after the formats above and before its JPEG 2000 ones,
  // so bytes of a JPEG 2000 start that also carry DICOM's signature ("DICM" at offset 128) go to
  // GDCM, which aborts the process on a damaged file. aief does not read DICOM: refused here.
  if (b.starts_with("DICM", 128)) return std::nullopt;
  if (b.starts_with(std::string_view("\0\0\0\x0CjP  \r\n\x87\n", 12))) return jp2_header(b);
  if (b.starts_with("\xFF\x4F\xFF\x51")) return j2k_header(b, 0);
  return std::nullopt;
}

}  // namespace aief::io
