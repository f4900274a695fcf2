#pragma once
// A small streaming JSON writer: enough for result files, no dependency. Numbers are written
// with enough digits to read back the same float or double.
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace aief::io {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}

  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(std::string_view name);  // inside an object, before each value

  JsonWriter& value(std::string_view text);
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  JsonWriter& value(double number);
  JsonWriter& value(float number);
  JsonWriter& value(int number);
  JsonWriter& value(long long number);
  JsonWriter& value(bool flag);

  // key + value in one call.
  template <class T>
  JsonWriter& field(std::string_view name, const T& v) {
    key(name);
    return value(v);
  }

  // Line breaks after array elements at this depth or above keep big files readable.
  void set_newline_depth(int depth) { newline_depth_ = depth; }

 private:
  void before_value();
  // A container's opening and closing bracket, '{' / '}' or '[' / ']'.
  JsonWriter& open(char bracket);
  JsonWriter& close(char bracket);
  std::ostream& out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
  int newline_depth_ = 2;
};

std::string hex_of(const std::uint8_t* bytes, std::size_t count);

}  // namespace aief::io
