#include "tools/picture_flags.hpp"

#include "aief/error.hpp"
#include "io/drawing.hpp"
#include "tools/output_extension.hpp"

namespace aief::cli {

void check_picture_flag(const Args& args, const std::string& flag) {
  const auto path = args.get(flag);
  if (!path) return;
  if (!io::is_picture_file_name(*path))
    throw UsageError(flag + " " + *path +
                     ": a picture must end in .png (or another extension OpenCV writes: .jpg, "
                     ".bmp, .tif, .webp)");
  check_output_folder(args, flag);
}

}  // namespace aief::cli
