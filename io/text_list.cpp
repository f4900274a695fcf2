#include "io/text_list.hpp"

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>

#include <sys/stat.h>

#include "aief/error.hpp"
#include "io/image_header.hpp"

namespace aief::io {

namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

}  // namespace

std::size_t longest_path() {
#ifdef PATH_MAX
  return PATH_MAX;
#else
  return 4096;
#endif
}

void for_each_text_line(const std::string& path, const std::string& what, int names_per_line,
                        const std::function<void(std::string& line)>& on_line) {
  const std::string named = what + " '" + path + "'";
  // PATH_MAX counts the terminating NUL; names on one line are one byte apart.
  const std::size_t longest_line = static_cast<std::size_t>(names_per_line) * longest_path() - 1;
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0)
    throw Error("cannot read " + named + ": " + std::strerror(errno));
  if (S_ISDIR(info.st_mode))
    throw Error(named + " is a folder, not a text file of names (one per line)");
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw Error("cannot read " + named + ": " + std::strerror(errno));

  std::size_t lines_read = 0;
  std::string line;
  char block[64 * 1024];
  bool first_block = true;
  for (std::size_t got; (got = std::fread(block, 1, sizeof block, file.get())) > 0;
       first_block = false) {
    if (first_block && std::memchr(block, '\0', got)) {
      const std::optional<ImageHeader> image =
          read_image_header(reinterpret_cast<const std::uint8_t*>(block), got);
      throw Error(named +
                  (image ? " is a " + image->format + " image"
                         : " is a binary file (it holds a NUL byte)") +
                  ", not a text file of names (one per line)");
    }
    // A UTF-8 byte order mark (Windows editors write one) is no part of the first name.
    const bool byte_order_mark =
        first_block && got >= 3 && std::memcmp(block, "\xEF\xBB\xBF", 3) == 0;
    for (std::size_t i = byte_order_mark ? 3 : 0; i < got; ++i) {
      const char c = block[i];
      if (c == '\n') {
        ++lines_read;
        on_line(line);
        line.clear();
        continue;
      }
      if (c == '\0')
        throw Error(named + " line " + std::to_string(lines_read + 1) +
                    " holds a NUL byte: a binary file, not a text file of names (one per line)");
      if (line.size() >= longest_line)
        throw Error(named + " line " + std::to_string(lines_read + 1) + " is longer than " +
                    std::to_string(longest_line) + " bytes, more than " +
                    (names_per_line == 1 ? "a path" : std::to_string(names_per_line) + " paths") +
                    " can be (PATH_MAX " + std::to_string(longest_path()) +
                    "): not a text file of names");
      line += c;
    }
  }
  if (std::ferror(file.get())) throw Error("cannot read " + named + ": " + std::strerror(errno));
  if (!line.empty()) on_line(line);
}

std::vector<std::string> read_text_list(const std::string& path, const std::string& what,
                                        int names_per_line) {
  std::vector<std::string> lines;
  for_each_text_line(path, what, names_per_line,
                     [&](std::string& line) { lines.push_back(std::move(line)); });
  return lines;
}

}  // namespace aief::io
