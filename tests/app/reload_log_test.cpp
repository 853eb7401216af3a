// The JSON of a reload event (watch --log, the window's history): frame times that did not happen are null,
// and file names or errors that are not UTF-8 are written, not thrown on.
#include <gtest/gtest.h>

#include "app/reload_log.h"
#include "common/json_text.h"

namespace {

TEST(ReloadLog, MissingFramesAreNullNotZero) {
  wb::live::ReloadEvent e;
  e.frames.firstNewFrame = 12.5;  // only the first new frame exists
  const auto j = wb::app::reloadEventJson(e);
  EXPECT_TRUE(j["frame_ms_median_before"].is_null()) << j.dump();
  EXPECT_TRUE(j["frame_ms_max_during_rebuild"].is_null()) << j.dump();
  EXPECT_TRUE(j["frame_ms_max_before_same_span"].is_null()) << j.dump();
  EXPECT_DOUBLE_EQ(j["first_new_frame_ms"].get<double>(), 12.5);
  e.frames.medianBefore = 0.25;
  EXPECT_DOUBLE_EQ(wb::app::reloadEventJson(e)["frame_ms_median_before"].get<double>(), 0.25);
}

TEST(ReloadLog, InvalidUtf8IsReplacedNotThrown) {
  wb::live::ReloadEvent e;
  e.filesChanged = {"/tmp/\xff\xfe.rchit"};
  e.ok = false;
  e.error = "closesthit.rchit:1: error: '\xc3' : unexpected token";
  std::string line;
  ASSERT_NO_THROW(line = wb::jsonText(wb::app::reloadEventJson(e)));
  const auto back = nlohmann::json::parse(line);
  EXPECT_EQ(back["files_changed"][0], "/tmp/\xef\xbf\xbd\xef\xbf\xbd.rchit");  // U+FFFD twice
  EXPECT_NE(back["error"].get<std::string>().find("unexpected token"), std::string::npos);
}

}  // namespace
