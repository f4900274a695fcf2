#include "tools/output_extension.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "aief/error.hpp"

namespace aief::cli {

void check_output_folder(const Args& args, const std::string& flag) {
  const auto path = args.get(flag);
  if (!path) return;
  const std::filesystem::path folder = std::filesystem::path(*path).parent_path();
  std::error_code ec;
  if (!folder.empty() && !std::filesystem::is_directory(folder, ec))
    throw Error(args.spelled(flag) + " " + *path + ": the folder '" + folder.string() +
                "' does not exist");
}

void check_output_extension(const Args& args, const std::string& flag, std::string_view extension,
                            std::string_view format) {
  const auto path = args.get(flag);
  if (!path) return;
  const bool ends_so =
      path->size() > extension.size() &&
      std::equal(extension.rbegin(), extension.rend(), path->rbegin(), [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) ==
               std::tolower(static_cast<unsigned char>(b));
      });
  if (!ends_so)
    throw UsageError(args.spelled(flag) + " " + *path + ": this command writes " +
                     std::string(format) + ", so the file's name must end in " +
                     std::string(extension));
}

}  // namespace aief::cli
