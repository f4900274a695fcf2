#pragma once
// A text file of names, one a line (a batch's image list, hloc's pairs.txt), read so that a
// wrong file gets an error instead of a run: a folder, a binary file (an image given as a list,
// /dev/zero), or a line longer than any path (PATH_MAX bytes) is refused with the reason. The
// file is read as a stream with one line in memory at a time, so a pipe (`--batch <(find ...)`)
// works and nothing grows without bound before the refusal.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace aief::io {

// The longest path the system can open (PATH_MAX): a list of paths has no longer line.
std::size_t longest_path();

// The lines of `path` without their '\n' (a final line without one included; a UTF-8 byte order
// mark at the start skipped). `what` names the
// file in errors ("batch list", "pairs file"); a line of `names_per_line` names separated by one
// byte may be that many longest paths long. Throws aief::Error: missing, unreadable, a folder,
// a NUL byte (with the image format when the bytes start like one), a line too long.
std::vector<std::string> read_text_list(const std::string& path, const std::string& what,
                                        int names_per_line = 1);

// The same checks, each line handed to `on_line` as it is read (a pairs file of a million lines is
// then never held whole); the line may be moved from.
void for_each_text_line(const std::string& path, const std::string& what, int names_per_line,
                        const std::function<void(std::string& line)>& on_line);

}  // namespace aief::io
