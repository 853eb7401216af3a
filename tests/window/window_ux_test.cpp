// The window as a user lives in it, driven with synthetic X input (xdotool) on a virtual display: clicks on
// real widgets land while the image converges, Tab gives the image the whole window, Esc and Ctrl+Q quit,
// the A/B panel is a window that closes and the comparison stays on, a click selects the object the material
// editor edits, a drag across the image orbits by about 180 degrees, the wheel dollies, the path inspector
// holds the sample the user chose, and the heat-map views show their legend.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "live_window.h"
#include "private_root.h"

namespace fs = std::filesystem;
using wb::testing::awaitJson;
using wb::testing::LiveWindow;
using wb::testing::privateRoot;

namespace {

bool haveTools() {
  return std::string(WB_XVFB_RUN).size() > 0 && fs::exists(WB_XVFB_RUN) &&
         wb::testing::runCommand("command -v xdotool").code == 0;
}

fs::path tempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("wb_ux_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void writeFile(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

std::string readFile(const fs::path& p) {
  std::ifstream f(p);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

glm::vec3 vec3Of(const nlohmann::json& a) {
  return {a[0].get<float>(), a[1].get<float>(), a[2].get<float>()};
}

// A point of the image at (fx, fy) of its width and height, as xdotool's "X Y".
std::string imagePoint(const nlohmann::json& stats, double fx, double fy) {
  const auto& r = stats["widgets"]["image"];
  return std::to_string(int(r[0].get<double>() + fx * r[2].get<double>())) + " " +
         std::to_string(int(r[1].get<double>() + fy * r[3].get<double>()));
}

}  // namespace

#define REQUIRE_TOOLS() \
  if (!haveTools()) GTEST_SKIP() << "xvfb-run or xdotool not found (scripts/setup.sh installs them)"

// Input first: a checkbox, a combo and one of its items, and the image (the inspector's pixel) are clicked
// while the image converges at about a frame a second; each click's effect is on screen (wait_clicks: the
// frame that drew it finished) and in the state the stats show.
TEST(WindowUx, ClicksOnWidgetsLandWhileTheImageConverges) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("clicks");
  std::string script = "wait_samples 1 600\nstats " + (dir / "c0.json").string() + "\n";
  for (int i = 1; i <= 4; ++i) {
    script += "wait_clicks " + std::to_string(i) + " 600\nframes 2\nstats " +
              (dir / ("c" + std::to_string(i) + ".json")).string() + "\n";
  }
  writeFile(dir / "s.txt", script + "quit\n");
  LiveWindow w(dir, "--window 800x600 --set budget_ms=300 --script " + (dir / "s.txt").string());
  const auto c0 = w.awaitJson(dir / "c0.json");
  ASSERT_TRUE(c0.is_object()) << w.stop().output;
  ASSERT_TRUE(c0["widgets"].contains("preview")) << c0["widgets"].dump();
  EXPECT_EQ(w.xdotool("mousemove " + LiveWindow::centre(c0, "preview") + " click 1"), 0);
  const auto c1 = w.awaitJson(dir / "c1.json");
  ASSERT_TRUE(c1.is_object()) << w.stop().output;
  EXPECT_NE(c1["preview_enabled"], c0["preview_enabled"]) << "the checkbox click was lost";

  EXPECT_EQ(w.xdotool("mousemove " + LiveWindow::centre(c1, "param.tonemap") + " click 1"), 0);
  const auto c2 = w.awaitJson(dir / "c2.json");
  ASSERT_TRUE(c2.is_object()) << w.stop().output;
  const std::string before = c2["parameters"]["tonemap"];
  const std::string want = before == "aces" ? "reinhard" : "aces";
  ASSERT_TRUE(c2["widgets"].contains("param.tonemap." + want)) << "the combo did not open: " << c2["widgets"];
  EXPECT_EQ(w.xdotool("mousemove " + LiveWindow::centre(c2, "param.tonemap." + want) + " click 1"), 0);
  const auto c3 = w.awaitJson(dir / "c3.json");
  ASSERT_TRUE(c3.is_object()) << w.stop().output;
  EXPECT_EQ(c3["parameters"]["tonemap"], want) << "the combo item's click was lost";

  EXPECT_EQ(w.xdotool("mousemove " + imagePoint(c3, 0.25, 0.75) + " click 1"), 0);
  const auto c4 = w.awaitJson(dir / "c4.json");
  ASSERT_TRUE(c4.is_object()) << w.stop().output;
  ASSERT_TRUE(c4["inspect_pixel"].is_array()) << "the click on the image was lost";
  EXPECT_NEAR(c4["inspect_pixel"][0].get<double>(), 0.25 * c4["target_width"].get<double>(), 2.0);
  EXPECT_NEAR(c4["inspect_pixel"][1].get<double>(), 0.75 * c4["target_height"].get<double>(), 2.0);
  EXPECT_EQ(c4["clicks_presented"], 4);
  EXPECT_EQ(c4["click_screen_ns"].size(), 4u);
  const auto r = w.finish();
  EXPECT_EQ(r.code, 0) << r.output;
}

// Tab hides every panel and gives the image the whole window: the trace size follows the window's width.
// Esc quits (the script would otherwise wait on).
TEST(WindowUx, TabGivesTheImageTheWholeWindowAndEscQuits) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("tab");
  auto p = [&](const std::string& name) { return (dir / name).string(); };
  writeFile(dir / "s.txt", "wait_samples 2 600\nstats " + p("a.json") + "\nwait_file " + p("go") +
                               " 600\nframes 3\nstats " + p("b.json") + "\nwait_file " + p("go2") +
                               " 600\nframes 3\nstats " + p("c.json") + "\nwait_file " + p("never") +
                               " 300\n");
  LiveWindow w(dir, "--window 640x480 --script " + p("s.txt"));
  const auto a = w.awaitJson(dir / "a.json");
  ASSERT_TRUE(a.is_object()) << w.stop().output;
  EXPECT_EQ(w.xdotool("mousemove 500 200 key Tab"), 0);
  w.signal("go");
  const auto b = w.awaitJson(dir / "b.json");
  ASSERT_TRUE(b.is_object()) << w.stop().output;
  EXPECT_EQ(b["panel_visible"], false);
  EXPECT_FALSE(b["widgets"].contains("side_panel"));
  // The image had the view beside the panel; now it has the window's width (times the resolution scale).
  const double scale = a["target_height"].get<double>() / 480.0;
  EXPECT_NEAR(b["target_width"].get<double>(), 640.0 * scale, 2.0) << b.dump();
  EXPECT_LT(a["target_width"].get<double>(), 0.75 * b["target_width"].get<double>());
  // Tab again: the panel and the image beside it come back with the samples it had.
  EXPECT_EQ(w.xdotool("key Tab"), 0);
  w.signal("go2");
  const auto c = w.awaitJson(dir / "c.json");
  ASSERT_TRUE(c.is_object()) << w.stop().output;
  EXPECT_EQ(c["panel_visible"], true);
  EXPECT_EQ(c["target_width"], a["target_width"]);
  EXPECT_GE(c["samples"].get<int>(), a["samples"].get<int>()) << "going back to the size left restarted it";
  EXPECT_EQ(w.xdotool("key Escape"), 0);
  const auto r = w.finish();
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("wait_file"), std::string::npos) << "Esc did not quit:\n" << r.output;
}

// The A/B panel is a normal window: its close button closes it, Tab hides it, Revert closes it. The
// comparison stays on after an edit however slow the machine (its budget is cut to fit 20% of the edit
// instead): the second edit gets its verdict too.
TEST(WindowUx, TheABPanelClosesAndTheComparisonStaysOn) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("ab");
  const fs::path root = privateRoot(dir);
  const fs::path watched = root / "shaders/pathtracer/closesthit.rchit";
  const std::string original = readFile(watched);
  const std::string needle = "  sm.baseColor = baseColor.rgb;";
  ASSERT_NE(original.find(needle), std::string::npos);
  for (const char* factor : {"1.02", "1.04"}) {
    std::string text = original;
    text.replace(text.find(needle), needle.size(),
                 std::string("  sm.baseColor = baseColor.rgb * ") + factor + ";");
    writeFile(dir / (std::string("edit") + factor + ".rchit"), text);
  }
  auto p = [&](const std::string& name) { return (dir / name).string(); };
  writeFile(dir / "s.txt",
            "wait_samples 2 600\ncopy " + p("edit1.02.rchit") + " " + watched.string() +
                "\nwait_reload 600\nwait_samples 2 600\nframes 2\nstats " + p("ab1.json") + "\nwait_file " +
                p("go") + " 600\nframes 3\nstats " + p("closed.json") + "\ncopy " + p("edit1.04.rchit") +
                " " + watched.string() + "\nwait_reload 600\nwait_samples 2 600\nframes 2\nstats " +
                p("ab2.json") + "\nset panel off\nframes 2\nstats " + p("hidden.json") +
                "\nset panel on\nab_revert\nframes 2\nstats " + p("reverted.json") + "\nquit\n");
  LiveWindow w(dir, "--window 800x600 --script " + p("s.txt"), "WB_ROOT=" + root.string());
  const auto ab1 = w.awaitJson(dir / "ab1.json");
  ASSERT_TRUE(ab1.is_object()) << w.stop().output;
  EXPECT_EQ(ab1["ab_open"], true);
  ASSERT_TRUE(ab1["widgets"].contains("ab.close")) << ab1["widgets"].dump();
  EXPECT_EQ(w.xdotool("mousemove " + LiveWindow::centre(ab1, "ab.close") + " click 1"), 0);
  w.signal("go");
  const auto r = w.finish();
  ASSERT_EQ(r.code, 0) << r.output;
  const auto closed = awaitJson(dir / "closed.json", 1), ab2 = awaitJson(dir / "ab2.json", 1);
  const auto hidden = awaitJson(dir / "hidden.json", 1), reverted = awaitJson(dir / "reverted.json", 1);
  EXPECT_EQ(closed["ab_open"], false) << "the close button did not close the A/B panel";
  EXPECT_FALSE(closed["widgets"].contains("ab_panel"));
  // The second edit was compared too, within its budget, and the panel opened again with it.
  EXPECT_EQ(ab2["ab_enabled"], true) << ab2["ab_note"];
  ASSERT_GE(ab2["reloads"].size(), 2u);
  EXPECT_FALSE(ab2["reloads"][1]["ab"].empty()) << "the second edit got no verdict: " << ab2["ab_note"];
  EXPECT_EQ(ab2["ab_open"], true);
  ASSERT_TRUE(ab2["ab_budget"].is_object());
  EXPECT_GT(ab2["ab_budget"]["allowed_ms"].get<double>(), 0.0) << ab2["ab_budget"].dump();
  EXPECT_TRUE(ab2["widgets"].contains("ab_panel"));
  EXPECT_FALSE(hidden["widgets"].contains("ab_panel")) << "Tab (panel off) left the A/B panel on the image";
  EXPECT_EQ(reverted["ab_open"], false) << "Revert left the (unpinned) A/B panel open";
  EXPECT_TRUE(reverted["reloads"].back()["reverted"].get<bool>());
}

// A click on the image selects the object under it (the material editor edits it); moving on only hovers.
// A drag across the image turns the orbit camera by about 180 degrees; the wheel dollies towards the target.
// Ctrl+Q quits.
TEST(WindowUx, ClickSelectsDragOrbitsWheelDolliesCtrlQQuits) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("select");
  auto p = [&](const std::string& name) { return (dir / name).string(); };
  std::string script = "wait_samples 1 600\nstats " + p("a.json") + "\n";
  for (const char* step : {"a2", "b", "c", "d", "e"})
    script += "wait_file " + p(std::string("go_") + step) + " 600\nframes 3\nstats " +
              p(std::string(step) + ".json") + "\n";
  writeFile(dir / "s.txt", script + "wait_file " + p("never") + " 300\n");
  LiveWindow w(dir, "--window 640x480 --script " + p("s.txt"));
  const auto a = w.awaitJson(dir / "a.json");
  ASSERT_TRUE(a.is_object()) << w.stop().output;
  // Hover the left edge (the red wall), then click the middle of the image (the back wall): the click selects
  // what is under it, and the name shown follows the cursor; then move back to the left edge.
  EXPECT_EQ(w.xdotool("mousemove " + imagePoint(a, 0.03, 0.5)), 0);
  w.signal("go_a2");
  const auto a2 = w.awaitJson(dir / "a2.json");
  ASSERT_TRUE(a2.is_object()) << w.stop().output;
  EXPECT_EQ(w.xdotool("mousemove " + imagePoint(a, 0.5, 0.5) + " click 1"), 0);
  w.signal("go_b");
  const auto b = w.awaitJson(dir / "b.json");
  ASSERT_TRUE(b.is_object()) << w.stop().output;
  EXPECT_EQ(w.xdotool("mousemove " + imagePoint(a, 0.03, 0.5)), 0);
  w.signal("go_c");
  const auto c = w.awaitJson(dir / "c.json");
  ASSERT_TRUE(c.is_object()) << w.stop().output;
  // A drag from 5% to 95% of the image's width, in steps, then three wheel steps forward.
  std::string drag = "mousemove " + imagePoint(a, 0.05, 0.5) + " mousedown 1";
  for (int i = 1; i <= 9; ++i) drag += " mousemove " + imagePoint(a, 0.05 + 0.1 * i, 0.5) + " sleep 0.05";
  EXPECT_EQ(w.xdotool(drag + " mouseup 1"), 0);
  w.signal("go_d");
  const auto d = w.awaitJson(dir / "d.json");
  ASSERT_TRUE(d.is_object()) << w.stop().output;
  EXPECT_EQ(w.xdotool("click 4 click 4 click 4"), 0);
  w.signal("go_e");
  const auto e = w.awaitJson(dir / "e.json");
  ASSERT_TRUE(e.is_object()) << w.stop().output;
  EXPECT_EQ(w.xdotool("key ctrl+q"), 0);
  const auto r = w.finish();
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("wait_file"), std::string::npos) << "Ctrl+Q did not quit:\n" << r.output;

  ASSERT_TRUE(a2["hover_object"].is_object()) << a2.dump();
  ASSERT_TRUE(b["selected_object"].is_object()) << b.dump();
  EXPECT_NE(b["selected_object"]["material"], a2["hover_object"]["material"])
      << "the middle is the back wall";
  EXPECT_EQ(b["selected_object"], b["hover_object"]) << "the click selects what is under the cursor";
  ASSERT_TRUE(c["hover_object"].is_object());
  EXPECT_NE(c["hover_object"]["material"], b["selected_object"]["material"])
      << "the left edge is another object (the red wall)";
  EXPECT_EQ(c["selected_object"], b["selected_object"]) << "hovering changed the selection";
  // The orbit: the forward direction turned by about 0.9 x 180 degrees about the vertical.
  const glm::vec3 f0 = vec3Of(c["parameters"]["camera"]["forward"]),
                  f1 = vec3Of(d["parameters"]["camera"]["forward"]);
  const float turned = glm::degrees(std::acos(glm::clamp(
      glm::dot(glm::normalize(glm::vec2(f0.x, f0.z)), glm::normalize(glm::vec2(f1.x, f1.z))), -1.0f, 1.0f)));
  EXPECT_NEAR(turned, 162.0f, 25.0f) << "a drag across 90% of the image";
  // The wheel: the eye moved forward along the unchanged view direction.
  const glm::vec3 e0 = vec3Of(d["parameters"]["camera"]["eye"]),
                  e1 = vec3Of(e["parameters"]["camera"]["eye"]);
  EXPECT_GT(glm::dot(e1 - e0, f1), 0.0f) << "the wheel did not dolly forward";
  EXPECT_NEAR(glm::dot(vec3Of(e["parameters"]["camera"]["forward"]), f1), 1.0f, 1e-4f);
}

// A drag made while the window's loop is busy (frames of ~0.4 s: the whole drag falls between two polls of
// its events) turns the camera as far as a drag the loop follows: the drag starts where its button went
// down, not where the pointer is when the loop gets to it.
TEST(WindowUx, ADragBetweenTwoPollsKeepsItsStart) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("slow_drag");
  auto p = [&](const std::string& name) { return (dir / name).string(); };
  writeFile(dir / "s.txt", "wait_samples 1 600\nset budget_ms 400\nframes 2\nstats " + p("a.json") +
                               "\nwait_file " + p("go") + " 600\nframes 3\nstats " + p("b.json") +
                               "\nquit\n");
  LiveWindow w(dir, "--window 640x480 --script " + p("s.txt"));
  const auto a = w.awaitJson(dir / "a.json");
  ASSERT_TRUE(a.is_object()) << w.stop().output;
  std::string drag = "mousemove " + imagePoint(a, 0.05, 0.5) + " sleep 0.1 mousedown 1";
  for (int i = 1; i <= 9; ++i) drag += " mousemove " + imagePoint(a, 0.05 + 0.1 * i, 0.5) + " sleep 0.01";
  EXPECT_EQ(w.xdotool(drag + " mouseup 1"), 0);
  w.signal("go");
  const auto b = w.awaitJson(dir / "b.json");
  const auto r = w.finish();
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_TRUE(b.is_object());
  const glm::vec3 f0 = vec3Of(a["parameters"]["camera"]["forward"]),
                  f1 = vec3Of(b["parameters"]["camera"]["forward"]);
  const float turned = glm::degrees(std::acos(glm::clamp(
      glm::dot(glm::normalize(glm::vec2(f0.x, f0.z)), glm::normalize(glm::vec2(f1.x, f1.z))), -1.0f, 1.0f)));
  EXPECT_NEAR(turned, 162.0f, 25.0f) << "a drag across 90% of the image while the loop was busy";
}

// The inspector holds the sample the user picks on its slider: with two records kept and more samples
// traced, the chosen one is still shown (its record held) after it left the kept ones.
TEST(WindowUx, TheInspectorHoldsTheChosenSample) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("held");
  auto p = [&](const std::string& name) { return (dir / name).string(); };
  writeFile(dir / "s.txt",
            "set inspect_samples 2\nset inspect_pixel 40,60\nwait_samples 3 600\nframes 2\nstats " +
                p("a.json") + "\nwait_file " + p("go") + " 600\nframes 3\nstats " + p("b.json") +
                "\nwait_samples 8 600\nframes 2\nstats " + p("c.json") + "\nquit\n");
  LiveWindow w(dir, "--window 800x700 --set budget_ms=100 --script " + p("s.txt"));
  const auto a = w.awaitJson(dir / "a.json");
  ASSERT_TRUE(a.is_object()) << w.stop().output;
  ASSERT_TRUE(a["widgets"].contains("inspect_sample")) << a["widgets"].dump();
  // The slider's left end: the oldest kept sample.
  const auto& s = a["widgets"]["inspect_sample"];
  EXPECT_EQ(w.xdotool("mousemove " + std::to_string(int(s[0].get<double>() + 3)) + " " +
                      std::to_string(int(s[1].get<double>() + s[3].get<double>() / 2)) + " click 1"),
            0);
  w.signal("go");
  const auto r = w.finish();
  ASSERT_EQ(r.code, 0) << r.output;
  const auto b = awaitJson(dir / "b.json", 1), c = awaitJson(dir / "c.json", 1);
  const int chosen = b["inspect_shown"];
  ASSERT_GE(chosen, 0) << "the slider click chose no sample";
  EXPECT_EQ(c["inspect_shown"], chosen) << "the choice followed the newest sample";
  EXPECT_TRUE(c["inspect_shown_vertices"].is_number()) << "the chosen sample's record was dropped";
  EXPECT_EQ(c["inspect_shown_kept"], false) << "with 2 kept of 8 the chosen one has aged out";
}

// Every heat-map view shows its colour bar (the ramp from blue to red, with its scale) over the image, the
// cost views too once their cost data is there; the beauty view shows none.
TEST(WindowUx, HeatMapViewsShowALegend) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("legend");
  auto p = [&](const std::string& name) { return (dir / name).string(); };
  std::string script = "wait_samples 1 600\n";
  for (const std::string view :
       {"bounces", "rr_end", "variance", "nan_source", "cost", "inefficiency", "beauty"}) {
    // The cost variant restarts the samples: its summary (the views' scale) comes with them.
    script += "set view " + view + "\n" + (view == "cost" ? "wait_samples 3 600\n" : "") +
              "frames 2\nstats " + p(view + ".json") + "\nscreenshot " + p(view + ".png") + "\nframes 1\n";
  }
  writeFile(dir / "s.txt", script + "quit\n");
  LiveWindow w(dir, "--window 640x480 --script " + p("s.txt"));
  const auto r = w.finish();
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* view : {"bounces", "rr_end", "variance", "nan_source", "cost", "inefficiency"}) {
    const auto j = awaitJson(dir / (std::string(view) + ".json"), 1);
    if (std::string(view) == "cost") {
      ASSERT_TRUE(j["cost"].is_object()) << "no cost data: " << j["cost"];
    }
    ASSERT_TRUE(j["widgets"].contains("legend")) << view << " has no legend";
    const auto& l = j["widgets"]["legend"];
    int width = 0, height = 0, n = 0;
    unsigned char* px = stbi_load(p(std::string(view) + ".png").c_str(), &width, &height, &n, 4);
    ASSERT_NE(px, nullptr);
    size_t blue = 0, red = 0;
    for (int y = int(l[1].get<double>()); y < int(l[1].get<double>() + l[3].get<double>()) && y < height;
         ++y) {
      for (int x = int(l[0].get<double>()); x < int(l[0].get<double>() + l[2].get<double>()) && x < width;
           ++x) {
        const unsigned char* c = px + 4 * (size_t(y) * width + x);
        blue += c[2] > c[0] + 40 && c[2] > c[1] + 40;
        red += c[0] > 180 && c[1] < 100 && c[2] < 80;
      }
    }
    stbi_image_free(px);
    EXPECT_GT(blue, 10u) << view << ": no blue end of the ramp in the legend";
    EXPECT_GT(red, 10u) << view << ": no red end of the ramp in the legend";
  }
  EXPECT_FALSE(awaitJson(dir / "beauty.json", 1)["widgets"].contains("legend"));
}

// A mode round trip keeps the path tracer's samples: switching to a hybrid mode and back resumes its image
// (its samples go on from where they were), unless something that alters it changed meanwhile.
TEST(WindowUx, AModeRoundTripResumesThePathTracersSamples) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("roundtrip");
  auto p = [&](const std::string& name) { return (dir / name).string(); };
  writeFile(dir / "s.txt", "wait_samples 3 600\nstats " + p("before.json") +
                               "\nswitch_mode hybrid\nwait_mode 600\nframes 3\nstats " + p("hybrid.json") +
                               "\nswitch_mode pathtrace\nwait_mode 600\nframes 1\nstats " + p("back.json") +
                               "\nswitch_mode hybrid\nwait_mode 600\nset max_bounces 3\nframes 3\nstats " +
                               p("changed.json") +
                               "\nswitch_mode pathtrace\nwait_mode 600\nframes 1\nstats " + p("back2.json") +
                               "\nquit\n");
  LiveWindow w(dir, "--window 640x480 --script " + p("s.txt"));
  const auto r = w.finish();
  ASSERT_EQ(r.code, 0) << r.output;
  const auto before = awaitJson(dir / "before.json", 1), hybrid = awaitJson(dir / "hybrid.json", 1);
  const auto back = awaitJson(dir / "back.json", 1), changed = awaitJson(dir / "changed.json", 1);
  const auto back2 = awaitJson(dir / "back2.json", 1);
  EXPECT_EQ(hybrid["mode"], "hybrid");
  EXPECT_GE(hybrid["pathtrace_samples_kept"].get<int>(), before["samples"].get<int>())
      << "the panel says what going back resumes";
  EXPECT_EQ(back["mode"], "pathtrace");
  EXPECT_GE(back["samples"].get<int>(), before["samples"].get<int>())
      << "the path tracer's samples were lost";
  // A change that alters the path tracer's image while the hybrid mode shows: going back restarts it.
  EXPECT_EQ(changed["pathtrace_samples_kept"], 0);
  EXPECT_LT(back2["samples"].get<int>(), before["samples"].get<int>());
}

// Samples are kept where they stay valid: while an edit's comparison is pending the old pipeline's
// accumulation is set aside, so Revert goes on with it; a rebuild whose image is identical (a branch never
// taken) keeps the accumulation too.
TEST(WindowUx, RevertAndAnIdenticalRebuildKeepTheSamples) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("kept");
  const fs::path root = privateRoot(dir);
  const fs::path watched = root / "shaders/pathtracer/closesthit.rchit";
  const std::string original = readFile(watched);
  const std::string needle = "  sm.baseColor = baseColor.rgb;";
  ASSERT_NE(original.find(needle), std::string::npos);
  std::string changed = original, identical = original;
  changed.replace(changed.find(needle), needle.size(), "  sm.baseColor = baseColor.rgb * 1.05;");
  identical.replace(identical.find(needle), needle.size(),
                    needle + "\n  if (gl_LaunchIDEXT.x == 0xFFFFFFFFu) sm.baseColor = vec3(0.0);");
  writeFile(dir / "changed.rchit", changed);
  writeFile(dir / "identical.rchit", identical);
  auto p = [&](const std::string& name) { return (dir / name).string(); };
  writeFile(dir / "s.txt", "wait_samples 4 600\nstats " + p("before.json") + "\ncopy " + p("changed.rchit") +
                               " " + watched.string() + "\nwait_reload 600\nframes 3\nstats " +
                               p("edited.json") + "\nab_revert\nframes 1\nstats " + p("reverted.json") +
                               "\ncopy " + p("identical.rchit") + " " + watched.string() +
                               "\nwait_reload 600\nframes 3\nstats " + p("identical.json") + "\nquit\n");
  LiveWindow w(dir, "--window 640x480 --script " + p("s.txt"), "WB_ROOT=" + root.string());
  const auto r = w.finish();
  ASSERT_EQ(r.code, 0) << r.output;
  const auto before = awaitJson(dir / "before.json", 1), edited = awaitJson(dir / "edited.json", 1);
  const auto reverted = awaitJson(dir / "reverted.json", 1), same = awaitJson(dir / "identical.json", 1);
  ASSERT_TRUE(edited["ab"].is_object()) << edited.dump();
  EXPECT_EQ(edited["ab"]["image_verdict"], "changed");
  EXPECT_LT(edited["samples"].get<int>(), before["samples"].get<int>()) << "the edit's image starts over";
  EXPECT_GE(reverted["samples"].get<int>(), before["samples"].get<int>())
      << "Revert threw the old pipeline's samples away: " << reverted["ab_note"];
  EXPECT_TRUE(reverted["reloads"].back()["reverted"].get<bool>());
  ASSERT_TRUE(same["ab"].is_object()) << same.dump();
  EXPECT_EQ(same["ab"]["image_verdict"], "identical") << same["ab"].dump();
  EXPECT_GE(same["samples"].get<int>(), reverted["samples"].get<int>())
      << "an identical rebuild threw the samples away: " << same["ab_note"];
}

// Both accumulations set aside survive each other: Tab while an edit's comparison is pending parks the size
// left without losing the old pipeline's samples, so Revert after Tab and back goes on with them; Revert
// while the other size shows keeps the old pipeline's samples for when its size comes back.
TEST(WindowUx, TabDuringAPendingComparisonKeepsTheOldSamples) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("kept_tab");
  const fs::path root = privateRoot(dir);
  const fs::path watched = root / "shaders/pathtracer/closesthit.rchit";
  const std::string original = readFile(watched);
  const std::string needle = "  sm.baseColor = baseColor.rgb;";
  ASSERT_NE(original.find(needle), std::string::npos);
  std::string first = original, second = original;
  first.replace(first.find(needle), needle.size(), "  sm.baseColor = baseColor.rgb * 1.05;");
  second.replace(second.find(needle), needle.size(), "  sm.baseColor = baseColor.rgb * 1.1;");
  writeFile(dir / "first.rchit", first);
  writeFile(dir / "second.rchit", second);
  auto p = [&](const std::string& name) { return (dir / name).string(); };
  auto edit = [&](const std::string& file) {
    return "copy " + p(file) + " " + watched.string() + "\nwait_reload 600\nframes 3\n";
  };
  // The script says it is ready for a Tab (a stats file), then waits until the test has sent it.
  auto tab = [&](const std::string& go) {
    return "stats " + p(go + ".json") + "\nwait_file " + p(go) + " 600\nframes 3\n";
  };
  writeFile(dir / "s.txt",
            "wait_samples 4 600\nstats " + p("before.json") + "\n" + edit("first.rchit") + tab("go1") +
                "wait_samples +1 600\n" + tab("go2") + "ab_revert\nframes 1\nstats " + p("reverted.json") +
                "\nwait_samples +1 600\nstats " + p("before2.json") + "\n" + edit("second.rchit") +
                tab("go3") + "ab_revert\nframes 1\n" + tab("go4") + "stats " + p("back.json") + "\nquit\n");
  LiveWindow w(dir, "--window 640x480 --script " + p("s.txt"), "WB_ROOT=" + root.string());
  for (const std::string go : {"go1", "go2", "go3", "go4"}) {
    ASSERT_TRUE(w.awaitJson(dir / (go + ".json")).is_object()) << go << "\n" << w.stop().output;
    EXPECT_EQ(w.xdotool("mousemove 500 200 key Tab"), 0);
    w.signal(go);
  }
  const auto r = w.finish();
  ASSERT_EQ(r.code, 0) << r.output;
  const auto before = awaitJson(dir / "before.json", 1), reverted = awaitJson(dir / "reverted.json", 1);
  const auto before2 = awaitJson(dir / "before2.json", 1), back = awaitJson(dir / "back.json", 1);
  EXPECT_EQ(reverted["target_width"], before["target_width"]);
  EXPECT_GE(reverted["samples"].get<int>(), before["samples"].get<int>())
      << "Tab during the comparison lost the old pipeline's samples: " << reverted["ab_note"];
  EXPECT_EQ(back["target_width"], before2["target_width"]);
  EXPECT_GE(back["samples"].get<int>(), before2["samples"].get<int>())
      << "Revert while the other size showed lost the old pipeline's samples";
}

// A pixel picked by a click keeps its point of the scene when the image changes size (Tab): the middle of
// the image stays the middle.
TEST(WindowUx, APickedPixelFollowsTheImageThroughTab) {
  REQUIRE_TOOLS();
  const auto dir = tempDir("pickedtab");
  auto p = [&](const std::string& name) { return (dir / name).string(); };
  writeFile(dir / "s.txt", "wait_samples 1 600\nstats " + p("a.json") +
                               "\nwait_clicks 1 600\nframes 2\nstats " + p("b.json") + "\nwait_file " +
                               p("go") + " 600\nframes 3\nstats " + p("c.json") + "\nquit\n");
  LiveWindow w(dir, "--window 640x480 --script " + p("s.txt"));
  const auto a = w.awaitJson(dir / "a.json");
  ASSERT_TRUE(a.is_object()) << w.stop().output;
  EXPECT_EQ(w.xdotool("mousemove " + imagePoint(a, 0.5, 0.5) + " click 1"), 0);
  const auto b = w.awaitJson(dir / "b.json");
  ASSERT_TRUE(b.is_object()) << w.stop().output;
  EXPECT_EQ(w.xdotool("key Tab"), 0);
  w.signal("go");
  const auto r = w.finish();
  ASSERT_EQ(r.code, 0) << r.output;
  const auto c = awaitJson(dir / "c.json", 1);
  ASSERT_TRUE(b["inspect_pixel"].is_array());
  EXPECT_NEAR(b["inspect_pixel"][0].get<double>(), 0.5 * b["target_width"].get<double>(), 2.0);
  ASSERT_GT(c["target_width"].get<int>(), b["target_width"].get<int>()) << "Tab did not widen the image";
  EXPECT_NEAR(c["inspect_pixel"][0].get<double>(), 0.5 * c["target_width"].get<double>(), 2.0)
      << c["inspect_pixel"];
  EXPECT_NEAR(c["inspect_pixel"][1].get<double>(), 0.5 * c["target_height"].get<double>(), 2.0)
      << c["inspect_pixel"];
}
