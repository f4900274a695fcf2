// Which images a batch takes and what it names them (io/batch_inputs.hpp), where their outputs
// go (io/batch_output_names.hpp), and which list files are refused (io/text_list.hpp): the
// rules on their own, without running a batch.
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/types.h>

#include "aief/error.hpp"
#include "io/batch_inputs.hpp"
#include "io/batch_output_names.hpp"
#include "io/pairs_file.hpp"
#include "io/text_list.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using aief::io::BatchInput;

std::vector<std::string> names_of(const std::vector<BatchInput>& inputs) {
  std::vector<std::string> names;
  for (const BatchInput& input : inputs) names.push_back(input.name);
  return names;
}

void touch(const fs::path& path) { std::ofstream(path) << "x"; }

// The message of the aief::Error `run` throws, or "" when it throws none.
template <typename Run>
std::string error_of(Run run) {
  try {
    run();
  } catch (const aief::Error& e) {
    return e.what();
  }
  return "";
}

TEST(BatchInputs, AFolderGivesItsImagesByPathBelowItFollowingFolderLinksButNotCycles) {
  aief::test::TempFolder temp("aief_listing");
  const fs::path root = temp.path() / "images", elsewhere = temp.path() / "elsewhere";
  fs::create_directories(root / "sub");
  fs::create_directories(elsewhere);
  for (const char* name : {"b.PNG", "a.jpg", "sub/c.tiff", "notes.txt", "sub/d.json"})
    touch(root / name);
  touch(elsewhere / "e.png");
  fs::create_directory_symlink(elsewhere, root / "linked");   // followed, named as listed
  fs::create_directory_symlink(root, root / "sub" / "loop");  // a cycle: not followed
  fs::create_symlink(temp.path() / "missing.png",
                     root / "gone.png");  // broken: listed, reported when read
  const std::vector<BatchInput> inputs = aief::io::list_batch_inputs(root.string());
  EXPECT_EQ(names_of(inputs),
            (std::vector<std::string>{"a.jpg", "b.PNG", "gone.png", "linked/e.png", "sub/c.tiff"}));
  EXPECT_EQ(inputs[3].path, (root / "linked" / "e.png").string());
}

TEST(BatchInputs, AListGivesItsLinesAsNamesSortedOnceEach) {
  aief::test::TempFolder temp("aief_listing");
  const std::string list = temp.file("list.txt");
  std::ofstream(list) << "./z.png\r\n# a comment\n\nsub//./y.png  \n/abs/x.png\nz.png\nlast.png";
  const std::vector<BatchInput> inputs = aief::io::list_batch_inputs(list);
  EXPECT_EQ(names_of(inputs),
            (std::vector<std::string>{"/abs/x.png", "last.png", "sub/y.png", "z.png"}));
  EXPECT_EQ(inputs[2].path, "sub//./y.png");
  EXPECT_EQ(aief::io::name_of_listed_path("a/../b.png"),
            "a/../b.png");  // ".." stays: the output names escape it
}

// The frames of one video (--entropy-threshold carried): before, frame_10.png came before
// frame_2.png in a folder, and a list written in frame order was sorted the same way.
TEST(BatchInputs, FramesKeepTheListsOrderAndAFoldersNaturalOrder) {
  const aief::test::TempFolder temp("aief_batch_inputs");
  const fs::path folder = temp.path() / "video";
  fs::create_directories(folder);
  for (const char* name : {"frame_0.png", "frame_1.png", "frame_2.png", "frame_10.png",
                           "frame_11.png", "frame_9.png", "frame_100.png"})
    touch(folder / name);
  using aief::io::InputOrder;
  EXPECT_EQ(names_of(aief::io::list_batch_inputs(folder.string(), InputOrder::frames)),
            (std::vector<std::string>{"frame_0.png", "frame_1.png", "frame_2.png", "frame_9.png",
                                      "frame_10.png", "frame_11.png", "frame_100.png"}));
  // Sorting by name (shards) stays byte order.
  EXPECT_EQ(names_of(aief::io::list_batch_inputs(folder.string())).at(2), "frame_10.png");
  const fs::path list = temp.path() / "frames.txt";
  std::ofstream(list) << "video/frame_2.png\nvideo/frame_10.png\nvideo/frame_1.png\n"
                         "video/frame_2.png\n";
  EXPECT_EQ(
      names_of(aief::io::list_batch_inputs(list.string(), InputOrder::frames)),
      (std::vector<std::string>{"video/frame_2.png", "video/frame_10.png", "video/frame_1.png"}));
  EXPECT_NE(aief::io::frame_order_of(folder.string()).find("natural order"), std::string::npos);
  EXPECT_NE(aief::io::frame_order_of(list.string()).find("the list's order"), std::string::npos);
  using aief::io::natural_less;
  EXPECT_TRUE(natural_less("a2", "a10"));
  EXPECT_FALSE(natural_less("a10", "a2"));
  EXPECT_TRUE(natural_less("a2.png", "a02.png"));  // equal numbers: fewer leading zeros first
  EXPECT_FALSE(natural_less("a02.png", "a2.png"));
  EXPECT_FALSE(natural_less("a2", "a2"));
  EXPECT_TRUE(natural_less("a", "a0"));
  EXPECT_TRUE(natural_less("b9/x", "b10/a"));
  EXPECT_TRUE(natural_less("x99999999999999999999998", "x99999999999999999999999"));
}

// Frames named by seconds ran as 0.0, 0.1, 0.2, 0.3, 0.033333, ...: natural order read the
// fraction's digits as a whole number. A decimal fraction after a number is read by its value.
TEST(BatchInputs, FramesNamedBySecondsRunInTheOrderOfTheirValues) {
  const aief::test::TempFolder temp("aief_batch_seconds");
  const fs::path folder = temp.path() / "video";
  fs::create_directories(folder);
  // 30 frames a second, named by their time in seconds.
  const std::vector<std::string> expected = {
      "0.0.png", "0.033333.png", "0.066667.png", "0.1.png", "0.133333.png", "0.166667.png",
      "0.2.png", "0.233333.png", "0.266667.png", "0.3.png", "0.333333.png", "0.366667.png"};
  for (const std::string& name : expected) touch(folder / name);
  using aief::io::InputOrder;
  EXPECT_EQ(names_of(aief::io::list_batch_inputs(folder.string(), InputOrder::frames)), expected);
  EXPECT_NE(aief::io::frame_order_of(folder.string()).find("0.05 before 0.1"), std::string::npos);
  using aief::io::natural_less;
  EXPECT_TRUE(natural_less("1500000000.05.png", "1500000000.1.png"));
  EXPECT_FALSE(natural_less("1500000000.1.png", "1500000000.05.png"));
  EXPECT_TRUE(natural_less("0.0.png", "0.033333.png"));
  EXPECT_TRUE(natural_less("0.033333.png", "0.1.png"));
  EXPECT_TRUE(natural_less("0.3.png", "0.366667.png"));
  EXPECT_TRUE(natural_less("1.png", "1.5.png"));     // no fraction: .0
  EXPECT_TRUE(natural_less("0.1.png", "0.10.png"));  // equal values: fewer digits first
  EXPECT_FALSE(natural_less("0.10.png", "0.1.png"));
  EXPECT_TRUE(natural_less("t9.5.png", "t10.25.png"));
  EXPECT_TRUE(natural_less("frame.2.png", "frame.10.png"));  // a '.' before a number: no fraction
}

TEST(BatchInputs, ShardsSplitTheSortedListExactly) {
  std::vector<BatchInput> all;
  for (int i = 0; i < 7; ++i) all.push_back({std::to_string(i), std::to_string(i)});
  EXPECT_EQ(names_of(aief::io::shard_of(all, 1, 3)), (std::vector<std::string>{"1", "4"}));
  EXPECT_EQ(names_of(aief::io::shard_of(all, 0, 3)), (std::vector<std::string>{"0", "3", "6"}));
  EXPECT_TRUE(aief::io::shard_of(all, 5, 9).size() == 1 && aief::io::shard_of(all, 8, 9).empty());
}

TEST(BatchOutputNames, MirrorFoldersAndEscapeOneToOneInsideTheOutputFolder) {
  using aief::io::batch_output_path;
  EXPECT_EQ(batch_output_path("out", "sub/x.png", "json"), "out/sub/x.png.json");
  EXPECT_EQ(batch_output_path("out", "/abs/x.png", "npz"), "out/%2F/abs/x.png.npz");
  EXPECT_EQ(batch_output_path("out", "../x.png", "yml"), "out/%2E%2E/x.png.yml");
  EXPECT_EQ(batch_output_path("out", "%2E%2E/x.png", "yml"), "out/%252E%252E/x.png.yml");
  EXPECT_NE(batch_output_path("out", "a/b.png", "json"),
            batch_output_path("out", "a__b.png", "json"));
}

TEST(BatchOutputNames, AnOutputThatWouldBeAnotherOutputsFolderIsRefusedNamingBoth) {
  const std::vector<BatchInput> nesting = {{"a.png", "a.png"},
                                           {"a.png.json/b.png", "a.png.json/b.png"}};
  const std::string message =
      error_of([&] { aief::io::check_batch_outputs_do_not_nest(nesting, "out", "json"); });
  EXPECT_NE(message.find("a.png.json/b.png"), std::string::npos) << message;
  EXPECT_NE(message.find("another input's output file"), std::string::npos) << message;
  EXPECT_EQ(error_of([&] { aief::io::check_batch_outputs_do_not_nest(nesting, "out", "npz"); }),
            "");
}

TEST(TextList, AFolderABinaryFileAndEndlessLinesAreRefusedNamingTheReason) {
  aief::test::TempFolder temp("aief_listing");
  const auto refusal = [](const std::string& path) {
    return error_of([&] { aief::io::read_text_list(path, "batch list"); });
  };
  EXPECT_NE(refusal(temp.path().string()).find("is a folder, not a text file of names"),
            std::string::npos);
  const std::vector<std::uint8_t> png = aief::test::png_declaring(64, 48);
  std::ofstream(temp.file("image.png"), std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  EXPECT_NE(refusal(temp.file("image.png")).find("is a PNG image, not a text file of names"),
            std::string::npos)
      << refusal(temp.file("image.png"));
  EXPECT_NE(refusal("/dev/zero").find("binary file"), std::string::npos) << refusal("/dev/zero");
  std::ofstream(temp.file("long.txt")) << "a.png\n"
                                       << std::string(aief::io::longest_path() + 1, 'x') << "\n";
  EXPECT_NE(refusal(temp.file("long.txt")).find("line 2 is longer than"), std::string::npos)
      << refusal(temp.file("long.txt"));
  std::ofstream(temp.file("nul.txt")) << "a.png\nb" << '\0' << ".png\n" << std::string(70000, 'c');
  EXPECT_NE(refusal(temp.file("nul.txt")).find("NUL byte"), std::string::npos)
      << refusal(temp.file("nul.txt"));
  EXPECT_NE(refusal(temp.file("missing.txt")).find("cannot read batch list"), std::string::npos);
  // A pairs line holds two names: twice as long is still a list.
  std::ofstream(temp.file("pairs.txt"))
      << std::string(aief::io::longest_path(), 'a') << " " << std::string(100, 'b') << "\n";
  EXPECT_EQ(aief::io::read_text_list(temp.file("pairs.txt"), "pairs file", 2).size(), 1u);
  // The batch and the pairs reader go through it.
  EXPECT_THROW(aief::io::list_batch_inputs(temp.file("image.png")), aief::Error);
}

// `colmap --pairs /dev/null` wrote a database of no pairs and exited 0 without a word; `match
// --pairs` "matched" 0 pairs. A pairs file of no line but blank ones is refused; one whose lines
// were all skipped says so in its notes.
TEST(PairsFile, AnEmptyFileIsRefused) {
  const aief::test::TempFolder folder("aief_pairs_none");
  std::ofstream(folder.path() / "empty.txt") << "\n  \n";
  std::string message;
  try {
    aief::io::read_pairs(folder.file("empty.txt"));
  } catch (const aief::Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("names no pair (2 line(s), all blank)"), std::string::npos) << message;
  std::ofstream(folder.path() / "selves.txt") << "a.png a.png\n";
  EXPECT_EQ(aief::io::read_pairs(folder.file("selves.txt")).notes.size(), 1u);
}

// A list or pairs file saved with a UTF-8 byte order mark (Windows editors): the mark is skipped,
// not read as part of the first name. Was: the first image "\xEF\xBB\xBFa.png" not found, named
// with an invisible character.
TEST(TextList, AUtf8ByteOrderMarkIsSkipped) {
  const aief::test::TempFolder folder("aief_text_list_bom");
  std::ofstream(folder.path() / "list.txt") << "\xEF\xBB\xBF"
                                            << "a.png\nb.png\n";
  EXPECT_EQ(aief::io::read_text_list(folder.file("list.txt"), "batch list"),
            (std::vector<std::string>{"a.png", "b.png"}));
  std::ofstream(folder.path() / "pairs.txt") << "\xEF\xBB\xBF"
                                             << "a.png b.png\n";
  const aief::io::PairsList pairs = aief::io::read_pairs(folder.file("pairs.txt"));
  ASSERT_EQ(pairs.names.size(), 2u);
  EXPECT_EQ(pairs.names[0], "a.png");
  std::ofstream(folder.path() / "inside.txt") << "a.png\n\xEF\xBB\xBF"
                                              << "b.png\n";  // kept
  EXPECT_EQ(aief::io::read_text_list(folder.file("inside.txt"), "batch list")[1],
            "\xEF\xBB\xBF"
            "b.png");
}

TEST(TextList, APipeIsReadAsAStream) {
  aief::test::TempFolder temp("aief_listing");
  const std::string fifo = temp.file("list.fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] { std::ofstream(fifo) << "b.png\na.png"; });  // `--batch <(find ...)`
  const std::vector<std::string> lines = aief::io::read_text_list(fifo, "batch list");
  writer.join();
  EXPECT_EQ(lines, (std::vector<std::string>{"b.png", "a.png"}));
}

}  // namespace
