// The `shaders` command.
#include "app/cmd_shaders.h"
#include "../shader/test_util.h"

using namespace wb::shader::test;

TEST(ShadersCommand, DirectoryOk) {
  EXPECT_EQ(wb::app::runShadersCommand({"--no-cache", (dataDir() / "rt").string()}), 0);
  EXPECT_EQ(wb::app::runShadersCommand({"--json", "--no-cache", (dataDir() / "rt/rt.rchit").string()}), 0);
}

TEST(ShadersCommand, FailureIsNonZero) {
  TempDir t;
  writeFile(t / "bad.comp", "#version 460\nlayout(local_size_x = 1) in;\nvoid main() { nope(); }\n");
  testing::internal::CaptureStderr();
  EXPECT_EQ(wb::app::runShadersCommand({"--no-cache", "-D", "X=1", (t / "bad.comp").string()}), 1);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find((t / "bad.comp").string() + ":3: error:"), std::string::npos) << err;
  EXPECT_NE(wb::app::runShadersCommand({"--no-cache", (t / "missing.rgen").string()}), 0);
}
