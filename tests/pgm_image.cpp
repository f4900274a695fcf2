#include "tests/pgm_image.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "aief/error.hpp"

namespace aief::test {

namespace {

// The header's next decimal field, skipping white space and '#' comments (the netpbm rules).
long long header_number(std::string_view bytes, std::size_t& pos, const char* what) {
  for (;;) {
    while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    if (pos < bytes.size() && bytes[pos] == '#') {
      while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
      continue;
    }
    break;
  }
  long long value = 0;
  const std::size_t start = pos;
  while (pos < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[pos])) &&
         value < (1LL << 32))
    value = value * 10 + (bytes[pos++] - '0');
  if (pos == start) throw Error(std::string("PGM header: no ") + what);
  return value;
}

}  // namespace

GrayImage parse_pgm(std::string_view bytes) {
  if (bytes.size() < 2 || bytes[0] != 'P' || bytes[1] != '5')
    throw Error("not a binary PGM: the file does not start with P5");
  std::size_t pos = 2;
  const long long width = header_number(bytes, pos, "width");
  const long long height = header_number(bytes, pos, "height");
  const long long maxval = header_number(bytes, pos, "maxval");
  if (width < 1 || height < 1 || width > (1 << 16) || height > (1 << 16))
    throw Error("PGM size " + std::to_string(width) + "x" + std::to_string(height) +
                " is outside 1..65536");
  if (maxval != 255)
    throw Error("PGM maxval " + std::to_string(maxval) + " is not 255 (8-bit gray only)");
  if (pos >= bytes.size() || !std::isspace(static_cast<unsigned char>(bytes[pos])))
    throw Error("PGM header: no white space after maxval");
  ++pos;  // exactly one white-space byte, then the pixels
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (bytes.size() - pos < n)
    throw Error("PGM " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                std::to_string(n) + " pixel bytes, has " + std::to_string(bytes.size() - pos));
  GrayImage image(static_cast<int>(width), static_cast<int>(height));
  std::copy_n(bytes.data() + pos, n, reinterpret_cast<char*>(image.data()));
  return image;
}

GrayImage read_pgm(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error("cannot open " + path);
  std::ostringstream bytes;
  bytes << file.rdbuf();
  try {
    return parse_pgm(bytes.str());
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
}

std::string format_pgm(const GrayImage& image) {
  std::string bytes =
      "P5\n" + std::to_string(image.width()) + " " + std::to_string(image.height()) + "\n255\n";
  bytes.append(reinterpret_cast<const char*>(image.data()),
               static_cast<std::size_t>(image.width()) * image.height());
  return bytes;
}

}  // namespace aief::test
