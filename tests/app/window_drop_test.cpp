// A file dropped on the window opens, as from a file manager: the drop is
// made over XDND by tests/app/xdnd_drop (no X tool can make one) on a real
// window under an X server of its own (x_server.h).
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "test_files.h"
#include "x_server.h"

namespace bounce {
namespace {

using test_support::read_text;
using test_support::scratch_dir;
using test_support::x_server;

// A lit floor: small enough to solve in a moment at --max-edge 0.5.
constexpr const char* small_scene = R"({
  "materials": {"floor": {"rho": [0.6, 0.6, 0.6]}, "lamp": {"ke": [4, 4, 4]}},
  "surfaces": [
    {"name": "floor", "polygon": [[0, 0, 0], [0, 0, 2], [2, 0, 2], [2, 0, 0]], "material": "floor"},
    {"name": "lamp", "polygon": [[0.7, 0.5, 0.7], [1.3, 0.5, 0.7], [1.3, 0.5, 1.3], [0.7, 0.5, 1.3]], "material": "lamp"}
  ]
})";

std::string quoted(const std::string& s) {
  return "'" + s + "'";
}

std::string read_first_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

// The start of a shell script that runs `bounce view ARGS` in the
// background on `server`, with the test's own configuration folder and
// what it says in bounce.txt; its process id is $bounce.
std::string script_starting_view(const x_server& server, const scratch_dir& dir, const std::string& args) {
  std::string script = "export DISPLAY=" + server.display() + "\n";
  script += "XDG_CONFIG_HOME=" + quoted(dir.path("config")) + " ASAN_OPTIONS=detect_leaks=0 ";
  script += quoted(BOUNCE_EXE) + " view " + args + " >" + quoted(dir.path("bounce.txt")) + " 2>&1 &\n";
  return script + "bounce=$!\n";
}

// `bounce view ARGS` with `key` tapped on its window (titled `title`) once
// it shows: the view's exit status (-1: it did not exit), what it said, and
// the tapping tool's status and words.
struct tapped_view {
  int status = -1;
  std::string said, tap_status, tap_said, command;
};
tapped_view view_with_a_tap(const x_server& server, const scratch_dir& dir, const std::string& args,
                            const std::string& title, const std::string& key, int timeout_seconds) {
  std::string script = script_starting_view(server, dir, args);
  script += quoted(X_KEY_TAP_EXE) + " " + quoted(title) + " " + key + " " + std::to_string(timeout_seconds) + " >" +
            quoted(dir.path("tap.txt")) + " 2>&1\n";
  script += "echo $? > " + quoted(dir.path("tap_status.txt")) + "\n";
  script += "wait $bounce\n";  // the script's status: bounce's
  tapped_view r;
  r.command = "sh " + dir.write("run.sh", script);
  const int status = std::system(r.command.c_str());
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.said = read_text(dir.path("bounce.txt"));
  r.tap_status = read_first_line(dir.path("tap_status.txt"));
  r.tap_said = read_text(dir.path("tap.txt"));
  return r;
}

// Dropping second.json on the window showing first.json opens it: the title
// becomes "second.json - Bounce" and it heads the recent list.
TEST(Window, ADroppedFileOpens) {
  if (!test_support::have_xvfb() || std::system("command -v xwininfo >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "Xvfb or xwininfo is not installed (third_party/install-deps.sh installs them)";
  scratch_dir dir;
  x_server server(dir.path("xvfb.log"));
  ASSERT_TRUE(server.ok()) << server.error();
  const std::string first = dir.write("first.json", small_scene);
  const std::string second = dir.write("second.json", small_scene);
  // On the test's own X server: start the window on first.json, drop second.json
  // on it (the tool waits up to 60 s for the window), then poll the window
  // tree (at most 60 s, and only while bounce runs: its window goes with
  // it) for the new title, and let the scripted run end (exiting 0).
  std::string script = script_starting_view(server, dir, quoted(first) + " --max-edge 0.5 --frames 600 --exit");
  script += quoted(XDND_DROP_EXE) + " 'first.json - Bounce' " + quoted(second) + " 60 >" +
            quoted(dir.path("drop.txt")) + " 2>&1\n";
  script += "echo $? > " + quoted(dir.path("drop_status.txt")) + "\n";
  script +=
      "for i in $(seq 600); do\n"
      "  if xwininfo -root -tree | grep -q 'second.json - Bounce'; then echo found > " +
      quoted(dir.path("title.txt")) +
      "; break; fi\n"
      "  kill -0 $bounce 2>/dev/null || break\n"
      "  sleep 0.1\n"
      "done\n"
      "wait $bounce\n";  // the script's status: bounce's
  const std::string command = "sh " + dir.write("run.sh", script);
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command << "\n" << read_text(dir.path("bounce.txt"));
  EXPECT_EQ(read_first_line(dir.path("drop_status.txt")), "0") << read_text(dir.path("drop.txt"));
  EXPECT_TRUE(std::filesystem::exists(dir.path("title.txt")))
      << "no window titled 'second.json - Bounce' after the drop\nbounce said:\n"
      << read_text(dir.path("bounce.txt"));
  EXPECT_EQ(read_first_line(dir.path("config/bounce/recent.txt")),
            std::filesystem::path(second).lexically_normal().string());
}

// A key tapped faster than a frame is not lost: Tab pressed and released
// back to back (both reach the window between two frames) hides the
// panel, and the layout is saved hidden. ImGui 1.86 reads keys once a
// frame; before the window queued its events, such a tap never arrived.
TEST(Window, AKeyTappedBetweenTwoFramesIsDelivered) {
  if (!test_support::have_xvfb()) GTEST_SKIP() << "Xvfb is not installed (third_party/install-deps.sh installs it)";
  scratch_dir dir;
  x_server server(dir.path("xvfb.log"));
  ASSERT_TRUE(server.ok()) << server.error();
  const std::string scene = dir.write("tap.json", small_scene);
  const tapped_view run = view_with_a_tap(server, dir, quoted(scene) + " --max-edge 0.5 --frames 300 --exit",
                                          "tap.json - Bounce", "Tab", 60);
  ASSERT_EQ(run.status, 0) << run.command << "\n" << run.said;
  EXPECT_EQ(run.tap_status, "0") << run.tap_said;
  const std::string layout = read_text(dir.path("config/bounce/panel.json"));
  EXPECT_NE(layout.find("\"visible\": false"), std::string::npos) << "panel.json: " << layout;
}

// Ctrl+Q quits at once whatever the solver is doing: on a 100k-triangle
// interior the worker is meshing, linking or iterating for many seconds,
// and the window goes without waiting for its step to end (before, the
// process waited: 4.0 s measured 8 s into this scene).
TEST(Window, CtrlQQuitsWithoutWaitingForTheSolver) {
  if (!test_support::have_xvfb()) GTEST_SKIP() << "Xvfb is not installed (third_party/install-deps.sh installs it)";
  scratch_dir dir;
  x_server server(dir.path("xvfb.log"));
  ASSERT_TRUE(server.ok()) << server.error();
  const tapped_view run =
      view_with_a_tap(server, dir, "generated:interior-100k", "interior-100k - Bounce", "ctrl+q", 120);
  ASSERT_EQ(run.status, 0) << run.command << "\n" << run.said;
  EXPECT_EQ(run.tap_status, "0") << run.tap_said;
  EXPECT_NE(run.said.find("quit without waiting for the work under way"), std::string::npos) << run.said;
}

}  // namespace
}  // namespace bounce
