#pragma once
// Image names a hostile or unlucky user gives: every character YAML, JSON, shells or SQLite
// treat specially, in first place where that matters. Shared by the tests of every format.
#include <string>
#include <vector>

namespace aief::test {

// Names every output format must round-trip.
inline std::vector<std::string> odd_image_names() {
  return {"{b}.png",
          "[a].png",
          "a]b}.png",
          "\"quoted\"",
          "'single'",
          "\"q.png",
          "a:b.png",
          "a: b.png",
          "#hash.png",
          "-dash.png",
          "- item.png",
          "!bang.png",
          "&anchor.png",
          "*alias.png",
          "%percent.png",
          "@at.png",
          "`tick`.png",
          "? key.png",
          "|pipe.png",
          ">fold.png",
          "~",
          "null",
          "1.5",
          "true",
          "back\\slash.png",
          "ends\\",
          "ünïcödé 名前.png",
          " lead.png",
          "two  spaces .png",
          "new\nline.png",
          "tab\t.png",
          "cr\r.png",
          "del\x7f.png",
          "a,b.png",
          "sub/dir/x.png"};
}

// Names with a control character other than tab, newline and carriage return: OpenCV's YAML
// cannot hold them (io/features_files.hpp), every other format can.
inline std::vector<std::string> control_character_names() {
  return {"ctl\x01.png", "esc\x1b[0m.png", "unit\x1f"};
}

}  // namespace aief::test
