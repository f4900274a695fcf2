#pragma once
// Whether bytes are UTF-8: file names are bytes on Linux, while SQLite's TEXT, JSON and
// Python's str assume UTF-8. Writers use it to say when a name will read back only as bytes.
#include <string>
#include <string_view>

namespace aief::io {

// Well-formed UTF-8 (RFC 3629): no overlong forms, no surrogates, nothing above U+10FFFF.
bool is_valid_utf8(std::string_view text);

// The text with every byte that is not part of well-formed UTF-8 written as \xHH: for messages.
std::string escape_non_utf8(std::string_view text);

}  // namespace aief::io
