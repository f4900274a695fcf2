// CONTRIBUTING.md's recipes against the repository: each "Adding ..." section that says how many
// places a change touches ("touches 4 places", "touches six files") numbers exactly that many
// (a list "1. ..." or table rows "| 1 | ..."), and every file it names exists. A recipe that
// gains a step, or names a file since renamed (tools/cmd_sfm.cpp), fails here until it is
// rewritten. tests/test_cli_docs.cpp holds what the steps lead to (the synopsis, the commands).
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
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

}  // namespace
