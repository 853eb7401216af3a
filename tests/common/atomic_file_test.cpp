// Files written whole or not at all (common/atomic_file.h), numbers in decimal only (common/numbers.h) and
// environment variables refused naming the variable (common/env.h). A full disk here is /dev/full (every
// write fails with ENOSPC, as on a full disk); the end-to-end tests on a full tmpfs are in
// tests/app/faults_test.cpp.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <string>

#include "common/atomic_file.h"
#include "common/env.h"
#include "common/file_io.h"
#include "common/numbers.h"
#include "temp_folder.h"

namespace fs = std::filesystem;

namespace {

fs::path tempDir(const std::string& name) {
  return wb::testing::tempFolder("wb_atomic", name);
}

std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string failureOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(AtomicFile, ReplacesTheFileAndKeepsItsPermissions) {
  const fs::path dir = tempDir("replace");
  const fs::path p = dir / "a.json";
  wb::writeFileAtomically(p, "first\n", "--stats");
  EXPECT_EQ(read(p), "first\n");
  ASSERT_EQ(::chmod(p.c_str(), 0640), 0);
  wb::writeFileAtomically(p, std::string(100000, 'x'), "--stats");
  EXPECT_EQ(read(p), std::string(100000, 'x'));
  struct stat st {};
  ASSERT_EQ(::stat(p.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.path().filename() != "a.json" ? 1 : 0;
  EXPECT_EQ(entries, 0u) << "a temporary file was left";
}

TEST(AtomicFile, ASymbolicLinkKeepsPointingAtTheNewContent) {
  const fs::path dir = tempDir("link");
  wb::writeFileAtomically(dir / "target.txt", "old", "");
  fs::create_symlink(dir / "target.txt", dir / "link.txt");
  wb::writeFileAtomically(dir / "link.txt", "new", "");
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(read(dir / "target.txt"), "new");
}

TEST(AtomicFile, AFullDiskSaysSoNamingWhatAndThePath) {
  // /dev/full is not a regular file: it is written in place, and every write fails with ENOSPC.
  const std::string why = failureOf([] { wb::writeFileAtomically("/dev/full", "data", "--stats"); });
  EXPECT_EQ(why, "--stats: cannot write '/dev/full': No space left on device (the disk is full)");
}

// A named pipe in an output's place is written in place, and one without a reader is an error, never a wait;
// in a cache's place it is replaced by the file (a cache folder holds regular files only).
TEST(AtomicFile, ANamedPipeIsNeverWaitedOn) {
  const fs::path dir = tempDir("fifo");
  ASSERT_EQ(::mkfifo((dir / "out.json").c_str(), 0644), 0);
  EXPECT_NE(failureOf([&] {
              wb::writeFileAtomically(dir / "out.json", "data", "--stats");
            }).find("--stats: cannot write"),
            std::string::npos);
  ASSERT_EQ(::mkfifo((dir / "entry.wbspv").c_str(), 0644), 0);
  wb::writeFileAtomically(dir / "entry.wbspv", "spirv", "shader cache", wb::FileKind::Cache);
  EXPECT_TRUE(fs::is_regular_file(dir / "entry.wbspv"));
  EXPECT_EQ(read(dir / "entry.wbspv"), "spirv");
}

TEST(AtomicFile, AMissingFolderIsNamed) {
  const fs::path dir = tempDir("missing");
  const std::string why = failureOf([&] { wb::writeFileAtomically(dir / "no" / "x.png", "data", ""); });
  EXPECT_NE(why.find("cannot write '" + (dir / "no" / "x.png").string() + "': cannot create a file in '" +
                     (dir / "no").string() + "'"),
            std::string::npos)
      << why;
  EXPECT_FALSE(fs::exists(dir / "no"));
}

TEST(AtomicFile, AFolderIsNotAFile) {
  const fs::path dir = tempDir("folder");
  EXPECT_NE(failureOf([&] { wb::writeFileAtomically(dir, "data", "--out"); }).find("is a directory"),
            std::string::npos);
}

TEST(AppendLog, AppendsWholeLinesAndReportsTheFirstFailureOnce) {
  const fs::path dir = tempDir("log");
  {
    wb::AppendLog log(dir / "log.jsonl", "--log");
    EXPECT_TRUE(log.writeLine("{\"a\":1}"));
    EXPECT_TRUE(log.writeLine("{\"b\":2}"));
    EXPECT_FALSE(log.failed());
  }
  wb::AppendLog again(dir / "log.jsonl", "--log");
  EXPECT_TRUE(again.writeLine("{\"c\":3}"));
  EXPECT_EQ(read(dir / "log.jsonl"), "{\"a\":1}\n{\"b\":2}\n{\"c\":3}\n");

  wb::AppendLog full("/dev/full", "--log");
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(full.writeLine("one"));
  EXPECT_FALSE(full.writeLine("two"));
  const std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_TRUE(full.failed());
  EXPECT_EQ(
      full.error(),
      "--log: cannot append to '/dev/full': No space left on device (the disk is full); later lines are "
      "not written");
  EXPECT_EQ(said, "workbench: error: " + full.error() + "\n") << "reported once";
  EXPECT_NE(failureOf([&] { wb::AppendLog(dir / "no" / "log.jsonl", "--log"); }).find("--log: cannot write"),
            std::string::npos);
}

TEST(RequireWritableFile, AnExistingFileNeedsAFolderThatTakesNewFiles) {
  const fs::path dir = tempDir("require");
  std::ofstream(dir / "x.json") << "old";
  EXPECT_NO_THROW(wb::requireWritableFile(dir / "x.json", "--stats"));
  EXPECT_NO_THROW(wb::requireWritableFile(dir / "new" / "y.json", "--stats"));  // makes new/
  EXPECT_TRUE(fs::is_directory(dir / "new"));
  EXPECT_FALSE(fs::exists(dir / "new" / "y.json"));
  EXPECT_EQ(read(dir / "x.json"), "old");
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(entries, 1u) << "the probe was left";
  EXPECT_NO_THROW(wb::requireWritableFile("/dev/null", "--stats"));  // a device is written in place
}

TEST(Numbers, DecimalOnly) {
  for (const char* ok : {"0", "16", "-0.5", ".5", "2.", "1e-3", "+3", "1E+2"})
    EXPECT_TRUE(wb::parseDecimal(ok).has_value()) << ok;
  EXPECT_EQ(*wb::parseDecimal("1e-3"), 1e-3);
  for (const char* bad :
       {"0x10", "nan", "inf", "-inf", "1e999", " 5", "5 ", "", ".", "e5", "1e", "1,5", "0x1p3", "--1", "5f"})
    EXPECT_FALSE(wb::parseDecimal(bad).has_value()) << bad;
  EXPECT_EQ(*wb::parseDecimalUnsigned("010"), 10u) << "decimal, not octal";
  EXPECT_EQ(*wb::parseDecimalUnsigned("18446744073709551615"), UINT64_MAX);
  for (const char* bad : {"-1", "+1", "0x10", "1.0", "18446744073709551616", "", " 1"})
    EXPECT_FALSE(wb::parseDecimalUnsigned(bad).has_value()) << bad;
}

TEST(Environment, AValueAVariableCannotTakeIsRefusedNamingIt) {
  ::setenv("WB_TEST_SWITCH", "banana", 1);
  EXPECT_EQ(failureOf([] { wb::env::choice("WB_TEST_SWITCH"); }),
            "WB_TEST_SWITCH=banana: expected 0 or 1 (or unset)");
  EXPECT_NE(failureOf([] { wb::env::enabled("WB_TEST_SWITCH"); }), "") << "garbage was counted as on";
  ::setenv("WB_TEST_SWITCH", "1", 1);
  EXPECT_TRUE(wb::env::enabled("WB_TEST_SWITCH"));
  ::setenv("WB_TEST_SWITCH", "", 1);
  EXPECT_FALSE(wb::env::choice("WB_TEST_SWITCH").has_value());
  ::setenv("WB_TEST_NUMBER", "0x10", 1);
  EXPECT_NE(failureOf([] { wb::env::number("WB_TEST_NUMBER"); }).find("WB_TEST_NUMBER=0x10"),
            std::string::npos);
  ::unsetenv("WB_TEST_SWITCH");
  ::unsetenv("WB_TEST_NUMBER");
  const std::optional<std::string> validation = wb::env::get("WB_VALIDATION");  // ctest sets it
  ::setenv("WB_VALIDATION", "abc", 1);
  EXPECT_NE(failureOf([] { wb::env::checkWorkbenchVariables(); }).find("WB_VALIDATION=abc"),
            std::string::npos);
  if (validation) {
    ::setenv("WB_VALIDATION", validation->c_str(), 1);
  } else {
    ::unsetenv("WB_VALIDATION");
  }
  ::setenv("WB_REBUILD_YIELD", "-5", 1);
  EXPECT_NE(failureOf([] { wb::env::checkWorkbenchVariables(); }).find("WB_REBUILD_YIELD=-5"),
            std::string::npos);
  ::unsetenv("WB_REBUILD_YIELD");
  EXPECT_EQ(failureOf([] { wb::env::checkWorkbenchVariables(); }), "");
}
