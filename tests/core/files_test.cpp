// core/files.h: reads only regular files; writes complete files or none, and says why not.
#include "core/files.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

#include "core/error.h"
#include "tests/core/test_dir.h"

namespace photovr {
namespace {

namespace fs = std::filesystem;

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

size_t entriesIn(const fs::path& dir) {
  return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(Files, WrittenFileIsCompleteAndNoTemporaryRemains) {
  const fs::path dir = testing::freshTestDir("photovr_files");
  writeFileAtomically((dir / "a.txt").string(), std::string("hello"));
  EXPECT_EQ(readRegularFile((dir / "a.txt").string(), "text"), "hello");
  EXPECT_EQ(entriesIn(dir), 1u);
}

// The rename's reason is reported (it was "Success": the message was read after another
// call had reset the error code) and the temporary file is removed.
TEST(Files, AFolderInTheWayIsAnErrorWithItsReason) {
  const fs::path dir = testing::freshTestDir("photovr_files");
  fs::create_directories(dir / "taken");
  const std::string error = errorOf([&] { writeFileAtomically((dir / "taken").string(), "x"); });
  EXPECT_NE(error.find("taken: cannot move the finished file into place: "), std::string::npos)
      << error;
  EXPECT_EQ(error.find("Success"), std::string::npos) << error;
  EXPECT_EQ(entriesIn(dir), 1u);  // only the folder
}

TEST(Files, AFileWhereAFolderShouldBeIsAnError) {
  const fs::path dir = testing::freshTestDir("photovr_files");
  std::ofstream(dir / "plain") << "x";
  EXPECT_NE(errorOf([&] {
              writeFileAtomically((dir / "plain" / "a.txt").string(), "x");
            }).find("a.txt: cannot write"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { createOutputFolder((dir / "plain").string()); }).find("plain: "),
            std::string::npos);
  createOutputFolder((dir / "new" / "deeper").string());
  EXPECT_TRUE(fs::is_directory(dir / "new" / "deeper"));
}

TEST(Files, OnlyRegularFilesAreRead) {
  const fs::path dir = testing::freshTestDir("photovr_files");
  EXPECT_NE(errorOf([&] {
              readRegularFile(dir.string(), "pose script");
            }).find("not a regular file (a folder, FIFO or device), expected pose script"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { readRegularFile("/dev/null", "recording"); }).find("/dev/null: "),
            std::string::npos);
  EXPECT_NE(errorOf([&] { readRegularFile((dir / "none").string(), "x"); }).find("file not found"),
            std::string::npos);
  std::ofstream(dir / "big") << std::string(100, 'x');
  EXPECT_NE(errorOf([&] { readRegularFile((dir / "big").string(), "x", 99); }).find("larger than"),
            std::string::npos);
}

// `timeout` ends a render with SIGTERM; the temporary files it was writing (several at
// once: writeFiles) go with it, and one already finished is not in the list any more.
TEST(Files, TemporaryFilesAreRemovedWhenASignalEndsTheProcess) {
  const fs::path dir = testing::freshTestDir("photovr_files");
  const std::string a = (dir / ".tmp.1.a.exr").string(), b = (dir / ".tmp.1.b.exr").string(),
                    done = (dir / ".tmp.1.done.exr").string();
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    for (const std::string& f : {a, b, done}) std::ofstream(f) << "half";
    { const InFlightFile finished(done); }
    const InFlightFile guardA(a), guardB(b);
    raise(SIGTERM);
    _exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  EXPECT_FALSE(fs::exists(a));
  EXPECT_FALSE(fs::exists(b));
  EXPECT_TRUE(fs::exists(done));  // released before the signal: someone else's to keep
}

}  // namespace
}  // namespace photovr
