#include "tools/picture_flags.hpp"

#include <filesystem>

#include "aief/error.hpp"
#include "io/drawing.hpp"

namespace aief::cli {

void check_picture_flag(const Args& args, const std::string& flag) {
  const auto path = args.get(flag);
  if (!path) return;
  if (!io::is_picture_file_name(*path))
    throw UsageError(flag + " " + *path +
                     ": a picture must end in .png (or another extension OpenCV writes: .jpg, "
                     ".bmp, .tif, .webp)");
  const std::filesystem::path folder = std::filesystem::path(*path).parent_path();
  std::error_code ec;
  if (!folder.empty() && !std::filesystem::is_directory(folder, ec))
    throw Error(flag + " " + *path + ": the folder '" + folder.string() + "' does not exist");
}

}  // namespace aief::cli
