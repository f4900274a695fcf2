// CONTRIBUTING.md's recipes against the repository: each "Adding ..." section that says how many
// places a change touches ("touches 4 places", "touches six files") numbers exactly that many
// (a list "1. ..." or table rows "| 1 | ..."), and every file it names exists. A recipe that
// gains a step, or names a file since renamed (tools/cmd_sfm.cpp), fails here until it is
// rewritten. And each recipe is held against a thing of its kind that exists today (a kernel, a
// descriptor, an option, a format, a command, a record field): every file of the code's folders
// that names it is a place that thing's change touched, and must be one the recipe names (its
// paths with `foo` read as that thing's name, or a folder it names for the algorithm's code), so
// a recipe that misses a real place fails here. tests/test_cli_docs.cpp holds what the steps lead
// to (the synopsis, the commands).
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

const std::filesystem::path kRoot = std::filesystem::path(AIEF_SAMPLE_DIR) / ".." / "..";

std::string contributing() {
  std::ifstream in(kRoot / "CONTRIBUTING.md");
  EXPECT_TRUE(in) << "no CONTRIBUTING.md";
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The "## Adding ..." sections, by title.
std::map<std::string, std::string> recipes(const std::string& text) {
  std::map<std::string, std::string> sections;
  std::istringstream in(text);
  std::string title;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("## ", 0) == 0) title = line.rfind("## Adding ", 0) == 0 ? line.substr(3) : "";
    if (!title.empty()) sections[title] += line + "\n";
  }
  return sections;
}

int number_of(const std::string& word) {
  static const std::map<std::string, int> words = {
      {"one", 1}, {"two", 2},   {"three", 3}, {"four", 4}, {"five", 5},
      {"six", 6}, {"seven", 7}, {"eight", 8}, {"nine", 9}, {"ten", 10}};
  const auto found = words.find(word);
  return found != words.end() ? found->second : std::stoi(word);
}

// The steps a section numbers: "1. " list items and "| 1 |" table rows at the start of a line.
int numbered_steps(const std::string& section) {
  static const std::regex step(R"((^|\n)(\d+)\. |(^|\n)\| (\d+) \|)");
  int most = 0;
  for (auto it = std::sregex_iterator(section.begin(), section.end(), step);
       it != std::sregex_iterator(); ++it) {
    const int n = std::stoi((*it)[2].matched ? (*it)[2].str() : (*it)[4].str());
    EXPECT_EQ(n, most + 1) << "steps out of order in\n" << section;
    most = n;
  }
  return most;
}

TEST(Contributing, EachRecipeNumbersAsManyPlacesAsItSays) {
  const std::map<std::string, std::string> sections = recipes(contributing());
  ASSERT_GE(sections.size(), 5u);  // a kernel, an option, a file format, a command, a record field
  static const std::regex stated(R"(touches\s+(\d+|[a-z]+)\s+(files|places))");
  for (const auto& [title, section] : sections) {
    SCOPED_TRACE(title);
    std::smatch count;
    ASSERT_TRUE(std::regex_search(section, count, stated)) << "no count of places stated";
    EXPECT_EQ(numbered_steps(section), number_of(count[1].str())) << section;
  }
}

TEST(Contributing, EveryFileItNamesExists) {
  const std::string text = contributing();
  // A repository path in backticks: folders and a file with an extension, no pattern or
  // placeholder (foo, *, {a,b}, <set>) and no build output.
  static const std::regex path(R"(`([a-z_.][A-Za-z0-9_./-]*/[A-Za-z0-9_.-]+\.[a-z]+)`)");
  int checked = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), path); it != std::sregex_iterator();
       ++it) {
    const std::string name = (*it)[1].str();
    if (name.find("foo") != std::string::npos || name.rfind("build/", 0) == 0) continue;
    EXPECT_TRUE(std::filesystem::exists(kRoot / name)) << name << " is named but does not exist";
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

// A thing of each recipe's kind that exists today: the name the recipe's `foo` stands for, and
// what names it in code.
struct Example {
  const char* recipe;
  const char* foo;
  const char* named_by;  // a regular expression
};
const Example kExamples[] = {
    {"Adding a kernel", "integral_image_row", R"(\bintegral_image_row\b)"},
    {"Adding a descriptor", "box",
     R"(\bBoxOnIntegralBand\b|box_on_integral_band|DescriptorKind::box\b|AIEF_NAME\(box,)"},
    {"Adding an option", "detection_smoothing", R"(\bdetection_smoothing\b)"},
    {"Adding a file format", "npz", R"(\bnpz_writer\b|\bwrite_features_npz\b|\bnpz_file_record\b)"},
    {"Adding a command", "merge", R"(\brun_merge\b|\bcmd_merge\b)"},
    {"Adding a field to a result record", "auto_threshold_effectiveness",
     R"(\bauto_threshold_effectiveness\b)"},
};

// The code's folders, where a change of each kind is made (tests, docs and benchmarks aside).
std::vector<std::string> code_files() {
  static const char* const folders[] = {"core",   "include", "io",       "tools", "python",
                                        "opencv", "simd",    "parallel", "cmake"};
  static const std::set<std::string> extensions = {".cpp", ".hpp",  ".h",    ".py",
                                                   ".pyi", ".json", ".cmake"};
  std::vector<std::string> files;
  for (const char* folder : folders)
    for (const auto& entry : std::filesystem::recursive_directory_iterator(kRoot / folder)) {
      const std::string relative = std::filesystem::relative(entry.path(), kRoot).generic_string();
      if (entry.is_regular_file() && extensions.count(entry.path().extension().string()) &&
          relative.rfind("python/tests/", 0) != 0)
        files.push_back(relative);
    }
  return files;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at))
    text.replace(at, from.size(), to), at += to.size();
  return text;
}

// The places a recipe names, as patterns over repository paths: each backticked path with `foo`
// read as `name`, `<x>` as any name, `{a,b}` as either, `*` as anything; a folder named as the
// algorithm's ("the code in `core/`", "the caller in `core/`") as every file below it.
std::vector<std::regex> places_named(const std::string& section, const std::string& name) {
  static const std::regex path(R"(`([a-z_.][A-Za-z0-9_./<>{},*-]*/[A-Za-z0-9_.<>{},*-]*)`)");
  std::vector<std::regex> places;
  for (auto it = std::sregex_iterator(section.begin(), section.end(), path);
       it != std::sregex_iterator(); ++it) {
    std::string pattern;
    bool in_choice = false, in_name = false;
    for (char c : replace_all((*it)[1].str(), "foo", name)) {
      if (in_name) {
        in_name = c != '>';
      } else if (c == '<') {
        pattern += "[A-Za-z0-9_]+", in_name = true;
      } else if (c == '{') {
        pattern += "(", in_choice = true;
      } else if (c == '}') {
        pattern += ")", in_choice = false;
      } else if (c == ',' && in_choice) {
        pattern += "|";
      } else if (c == '*') {
        pattern += "[^/]*";
      } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '/') {
        pattern += c;
      } else {
        pattern += std::string("\\") + c;
      }
    }
    if (pattern.back() == '/') {  // a folder: only as "the code (the caller) in `core/`"
      const std::string before = section.substr(0, static_cast<std::size_t>(it->position()));
      if (!std::regex_search(before, std::regex(R"((code|caller) in $)"))) continue;
      pattern += ".*";
    }
    places.emplace_back(pattern);
  }
  return places;
}

TEST(Contributing, EachRecipeNamesEveryPlaceAThingOfItsKindTouches) {
  const std::map<std::string, std::string> sections = recipes(contributing());
  const std::vector<std::string> files = code_files();
  ASSERT_GT(files.size(), 300u);
  for (const Example& example : kExamples) {
    SCOPED_TRACE(example.recipe);
    const auto section = sections.find(example.recipe);
    ASSERT_NE(section, sections.end()) << "no section '" << example.recipe << "'";
    const std::vector<std::regex> places = places_named(section->second, example.foo);
    const std::regex named_by(example.named_by);
    int naming = 0;
    for (const std::string& file : files) {
      std::ifstream in(kRoot / file);
      const std::string text((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      if (!std::regex_search(text, named_by)) continue;
      ++naming;
      const bool named = std::any_of(places.begin(), places.end(), [&](const std::regex& place) {
        return std::regex_match(file, place);
      });
      EXPECT_TRUE(named) << file << " names " << example.foo << " (" << example.named_by
                         << "), a place the recipe does not name";
    }
    EXPECT_GE(naming, 3) << example.foo << " is named in " << naming
                         << " files: is it still there?";
  }
}

}  // namespace
