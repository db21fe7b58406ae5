// Files written together (core/atomic_file.hpp): all of them or none, whatever fails where.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>

#include "cutaway/core/atomic_file.hpp"
#include "cutaway/core/error.hpp"
#include "expect_error.hpp"
#include "run_command.hpp"

namespace fs = std::filesystem;
using namespace cutaway;

namespace {

// Every entry of `folder`: a file's content, or "<folder>" for a folder.
std::map<std::string, std::string> contents(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::string& text = files[entry.path().filename().string()];
    if (entry.is_directory()) {
      text = "<folder>";
      continue;
    }
    std::ifstream is(entry.path(), std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(is), {});
  }
  return files;
}

FileWriter text(const std::string& s) {
  return [s](std::ostream& os) { os << s; };
}

// A folder holding a.txt = "old a" and b.txt = "old b".
fs::path folderWithTwoFiles(const std::string& name) {
  const fs::path dir = test::scratchPath("atomic", name);
  fs::create_directories(dir);
  writeFileAtomically(dir / "a.txt", text("old a"));
  writeFileAtomically(dir / "b.txt", text("old b"));
  return dir;
}

}  // namespace

TEST(AtomicFiles, AllAreReplacedAndNothingElseIsLeft) {
  const fs::path dir = folderWithTwoFiles("all");
  writeFilesAtomically({{dir / "a.txt", text("new a")},
                        {dir / "b.txt", text("new b")},
                        {dir / "c.txt", text("new c")}});
  EXPECT_EQ(contents(dir), (std::map<std::string, std::string>{
                               {"a.txt", "new a"}, {"b.txt", "new b"}, {"c.txt", "new c"}}));
}

// The second writer fails: the first file's new content was written to its temporary only.
TEST(AtomicFiles, AWriterThatThrowsLeavesEveryFileAsItWas) {
  const fs::path dir = folderWithTwoFiles("writer");
  const auto before = contents(dir);
  EXPECT_THROW(writeFilesAtomically(
                   {{dir / "a.txt", text("new a")},
                    {dir / "b.txt", [](std::ostream&) { throw std::runtime_error("disk full"); }},
                    {dir / "c.txt", text("new c")}}),
               std::runtime_error);
  EXPECT_EQ(contents(dir), before);
}

// The last path cannot take a file (it is a folder): the two files already replaced get their
// old contents back, and the one that did not exist before is gone again.
TEST(AtomicFiles, APathThatFailsLateGivesTheEarlierOnesBack) {
  const fs::path dir = folderWithTwoFiles("late");
  fs::create_directory(dir / "d.txt");
  const auto before = contents(dir);
  try {
    writeFilesAtomically({{dir / "a.txt", text("new a")},
                          {dir / "new.txt", text("new")},
                          {dir / "b.txt", text("new b")},
                          {dir / "d.txt", text("new d")}});
    FAIL() << "a folder took a file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("d.txt"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(contents(dir), before);
}

TEST(AtomicFiles, APathNamedTwiceIsRefusedBeforeAnythingIsWritten) {
  const fs::path dir = folderWithTwoFiles("twice");
  const auto before = contents(dir);
  EXPECT_THROW(
      writeFilesAtomically(
          {{dir / "a.txt", text("one")}, {dir / "c.txt", text("c")}, {dir / "a.txt", text("two")}}),
      Error);
  EXPECT_EQ(contents(dir), before);
}

// A path that is a symbolic link (or a chain of them, one relative, one dangling) has the file
// it points to replaced, as open() would write through it; the links stay links.
TEST(AtomicFiles, ALinkHasTheFileItPointsToReplaced) {
  const fs::path dir = folderWithTwoFiles("links");
  fs::create_directories(dir / "sub");
  fs::create_symlink("a.txt", dir / "to-a");
  fs::create_symlink(dir / "to-a", dir / "to-to-a");
  fs::create_symlink("sub/new.txt", dir / "dangling");
  writeFilesAtomically({{dir / "to-to-a", text("new a")}, {dir / "dangling", text("new")}});
  EXPECT_TRUE(fs::is_symlink(dir / "to-a"));
  EXPECT_TRUE(fs::is_symlink(dir / "to-to-a"));
  EXPECT_TRUE(fs::is_symlink(dir / "dangling"));
  const std::map<std::string, std::string> expected{{"a.txt", "new a"},   {"b.txt", "old b"},
                                                    {"sub", "<folder>"},  {"to-a", "new a"},
                                                    {"to-to-a", "new a"}, {"dangling", "new"}};
  EXPECT_EQ(contents(dir), expected);
  EXPECT_EQ(contents(dir / "sub"), (std::map<std::string, std::string>{{"new.txt", "new"}}));
  // Two names of one file are one file named twice.
  test::expectError(
      [&] {
        writeFilesAtomically({{dir / "a.txt", text("x")}, {dir / "to-a", text("y")}});
      },
      {"named twice"});
  fs::create_symlink("loop", dir / "loop");
  test::expectError([&] { writeFileAtomically(dir / "loop", text("x")); },
                    {"too many levels of symbolic links"});
}

// A FIFO (or a device, or a link to one) is not replaced by a regular file: refused, as
// `cutaway render -o` onto one once reported success having replaced it.
TEST(AtomicFiles, AFifoOrALinkToOneIsRefused) {
  const fs::path dir = folderWithTwoFiles("fifo");
  ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0600), 0);
  fs::create_symlink("pipe", dir / "to-pipe");
  for (const char* name : {"pipe", "to-pipe"}) {
    test::expectError([&] { writeFileAtomically(dir / name, text("x")); },
                      {(dir / "pipe").string(), "is not a regular file"});
    test::expectError([&] { replaceFileAtomically(dir / name, [](const fs::path&) {}); },
                      {"is not a regular file"});
  }
  EXPECT_TRUE(fs::is_fifo(dir / "pipe"));
  EXPECT_TRUE(fs::is_symlink(dir / "to-pipe"));
}

// A program stopped by a signal while it writes (`timeout`, Ctrl-C, a closed terminal) leaves
// no temporary behind once it took removeTemporariesOnSignals(); it still ends by the signal.
TEST(AtomicFilesDeathTest, ASignalWhileWritingLeavesNoTemporary) {
  for (const int signal : {SIGTERM, SIGINT, SIGHUP}) {
    const fs::path dir = folderWithTwoFiles("signal-" + std::to_string(signal));
    EXPECT_EXIT(
        {
          removeTemporariesOnSignals();
          writeFilesAtomically(
              {{dir / "c.txt", text("new c")}, {dir / "a.txt", [&](std::ostream& os) {
                                                  os << "half of a";
                                                  os.flush();
                                                  std::raise(signal);
                                                }}});
        },
        ::testing::KilledBySignal(signal), "");
    EXPECT_EQ(contents(dir),
              (std::map<std::string, std::string>{{"a.txt", "old a"}, {"b.txt", "old b"}}))
        << "signal " << signal;
  }
}
