// The panel's logic without a window: the solver choice and the link
// tolerance restart the solve through the worker as the window does, the
// statistics follow the solver that runs, and the panel laid out headless
// (ImGui needs no renderer to lay out) fits its labels.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>

#include "mesh_builders.h"
#include "scene/camera_file.h"
#include "scene/scene_io.h"
#include "test_files.h"
#include "viewer/bake_action.h"
#include "viewer/panel.h"
#include "viewer/solver_worker.h"
#include "viewer/user_files.h"

namespace bounce {
namespace {

solver_settings hierarchical(double link_tolerance) {
  solver_settings o;
  o.method = solver_method::hierarchical;
  o.max_edge = 80;
  o.link_tolerance = link_tolerance;
  o.stop.remaining = 0.01;
  return o;
}

bool has_line(const std::vector<std::string>& lines, const std::string& part) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& l) { return l.find(part) != std::string::npos; });
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& l : lines) text += l + "\n";
  return text;
}

// The worker solving the Cornell box with the panel's hierarchical
// settings at `link_tolerance`, once it is idle.
std::shared_ptr<const worker_view> solved(solver_worker& worker, panel_state& panel, double link_tolerance) {
  panel.solver = hierarchical(link_tolerance);
  worker.load(test_support::default_cornell_box(), panel.solver);
  worker.wait_idle();
  return worker.latest();
}

// An ImGui context laid out headless (ImGui needs no renderer to lay
// out), display `width` x `height`, gone with the object.
struct headless_imgui {
  headless_imgui(float width, float height) {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(width, height);
    io.DeltaTime = 1.0f / 60.0f;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  }
  ~headless_imgui() { ImGui::DestroyContext(); }
  headless_imgui(const headless_imgui&) = delete;
  headless_imgui& operator=(const headless_imgui&) = delete;
};

// One frame of the panel.
void draw_frame(panel_state& panel, const worker_view& view) {
  ImGui::NewFrame();
  draw_panel(panel, view, 16.0);
  ImGui::Render();
}

TEST(Panel, ChoosingTheOtherSolverRestartsWithIt) {
  solver_worker worker;
  panel_state panel;
  const auto first = solved(worker, panel, 1e-4);
  ASSERT_TRUE(first->solution);
  EXPECT_EQ(first->settings.method, solver_method::hierarchical);
  EXPECT_GT(first->solution->stats.links, 0u);

  // The same solver again: nothing to do.
  EXPECT_FALSE(choose_solver(panel, solver_method::hierarchical).apply_mesh);
  // The other one: a restart with it, on the same scene, as the window sends it.
  const panel_actions act = choose_solver(panel, solver_method::progressive);
  EXPECT_TRUE(act.apply_mesh);
  EXPECT_EQ(panel.solver.method, solver_method::progressive);
  send_to_worker(act, panel, worker);
  worker.wait_idle();
  const auto second = worker.latest();
  ASSERT_TRUE(second->solution);
  EXPECT_EQ(second->settings.method, solver_method::progressive);
  EXPECT_EQ(second->run, first->run + 1);
  EXPECT_EQ(second->source, first->source);  // the scene is kept, not copied
  EXPECT_EQ(second->solution->stats.links, 0u);
  EXPECT_GT(second->solution->stats.steps, 0u);
  EXPECT_TRUE(second->converged);
  EXPECT_TRUE(second->error.empty()) << second->error;
  // The progressive solver shoots from patches: another mesh.
  EXPECT_NE(second->mesh, first->mesh);
  EXPECT_EQ(second->mesh_version, first->mesh_version + 1);

  // And back.
  send_to_worker(choose_solver(panel, solver_method::hierarchical), panel, worker);
  worker.wait_idle();
  const auto third = worker.latest();
  EXPECT_EQ(third->settings.method, solver_method::hierarchical);
  EXPECT_GT(third->solution->stats.links, 0u);
  EXPECT_TRUE(third->converged);
}

TEST(Panel, ANewLinkToleranceRestartsOnTheSameMesh) {
  solver_worker worker;
  panel_state panel;
  const auto coarse = solved(worker, panel, 1e-3);
  ASSERT_TRUE(coarse->solution);
  panel.solver.link_tolerance = 1e-5;
  panel_actions act;
  act.apply_mesh = true;  // what the slider asks for when it is let go
  send_to_worker(act, panel, worker);
  worker.wait_idle();
  const auto fine = worker.latest();
  EXPECT_EQ(fine->run, coarse->run + 1);
  // Nothing re-meshed: the solver starts again from the mesher's mesh (and
  // splits its elements where the new links need them).
  EXPECT_EQ(fine->mesh_version, coarse->mesh_version);
  EXPECT_EQ(fine->meshed_elements, coarse->meshed_elements);
  EXPECT_GE(fine->mesh->element_count(), coarse->mesh->element_count());
  EXPECT_EQ(fine->settings.link_tolerance, 1e-5);
  EXPECT_DOUBLE_EQ(fine->solution->stats.link_tolerance, 1e-5);
  EXPECT_TRUE(fine->solution->stats.remaining_final);
  EXPECT_GT(fine->solution->stats.links, coarse->solution->stats.links);
}

TEST(Panel, AdaptiveMeshingIsLeftOutOfHierarchicalRuns) {
  solver_settings s = hierarchical(1e-5);
  s.adaptive.enabled = true;
  EXPECT_FALSE(settings_to_run(s).adaptive.enabled);
  s.method = solver_method::progressive;
  EXPECT_TRUE(settings_to_run(s).adaptive.enabled);
}

TEST(Panel, TolerancesAreShownShort) {
  EXPECT_EQ(format_tolerance(1e-5), "1e-5");
  EXPECT_EQ(format_tolerance(2.5e-6), "2.5e-6");
  EXPECT_EQ(format_tolerance(1e-12), "1e-12");
  EXPECT_EQ(format_tolerance(0.01), "0.01");
}

TEST(Panel, StatisticsFollowTheSolverThatRuns) {
  solver_worker worker;
  worker.load(test_support::default_cornell_box(), hierarchical(1e-5));
  worker.pause();
  worker.step();  // the first links, at the coarsest tolerance: more to refine
  worker.wait_idle();
  auto view = worker.latest();
  ASSERT_TRUE(view->solution);
  std::vector<std::string> lines = statistics_lines(*view, 12.5);
  EXPECT_TRUE(has_line(lines, "hierarchical: paused")) << joined(lines);
  EXPECT_TRUE(has_line(lines, "steps 1, residual ")) << joined(lines);
  EXPECT_TRUE(has_line(lines, "links " + std::to_string(view->solution->stats.links) + " (")) << joined(lines);
  EXPECT_TRUE(has_line(lines, " MiB)")) << joined(lines);
  EXPECT_TRUE(has_line(lines, "refining to 1e-5")) << joined(lines);
  EXPECT_TRUE(has_line(lines, "frame 12.5 ms")) << joined(lines);
  EXPECT_FALSE(has_line(lines, "shots")) << joined(lines);

  worker.resume();
  worker.wait_idle();
  view = worker.latest();
  lines = statistics_lines(*view, 12.5);
  EXPECT_TRUE(has_line(lines, "hierarchical: converged")) << joined(lines);
  EXPECT_TRUE(has_line(lines, "link tolerance 1e-5, final")) << joined(lines);
  // 16 bytes a link.
  char mib[64];
  std::snprintf(mib, sizeof mib, "(%.1f MiB)", double(view->solution->stats.links) * 16.0 / (1024.0 * 1024.0));
  EXPECT_TRUE(has_line(lines, mib)) << joined(lines);

  solver_settings progressive = hierarchical(1e-5);
  progressive.method = solver_method::progressive;
  worker.load(test_support::default_cornell_box(), progressive);
  worker.wait_idle();
  lines = statistics_lines(*worker.latest(), 12.5);
  EXPECT_TRUE(has_line(lines, "progressive: converged")) << joined(lines);
  EXPECT_TRUE(has_line(lines, "shots ")) << joined(lines);
  EXPECT_TRUE(has_line(lines, "unshot ")) << joined(lines);
  EXPECT_FALSE(has_line(lines, "links")) << joined(lines);
}

// The panel laid out as the window first shows it: nothing runs past its
// right edge (a label cut off), for either solver.
TEST(Panel, LabelsFitThePanelForEitherSolver) {
  solver_worker worker;
  worker.load(test_support::default_cornell_box(), hierarchical(1e-4));
  worker.wait_idle();
  const auto view = worker.latest();
  const headless_imgui imgui(900, 900);
  for (const solver_method method : {solver_method::hierarchical, solver_method::progressive}) {
    panel_state panel;
    panel.solver = hierarchical(1e-4);
    panel.solver.method = method;
    panel.solver.adaptive.enabled = true;  // its controls too, where they are shown
    panel.still.integrator = 0;            // Whitted: its direct-light choice shown
    panel.still.window_size = false;       // the size fields shown
    for (int frame = 0; frame < 3; ++frame) {
      draw_frame(panel, *view);
      // Every section open, as if clicked: their headers' state by ID.
      ImGuiWindow* window = ImGui::FindWindowByName("Bounce");
      ASSERT_NE(window, nullptr);
      for (const char* header : {"Scene", "Solver", "Statistics", "Display", "Ray-traced still"})
        window->StateStorage.SetInt(window->GetID(header), 1);
    }
    const ImGuiWindow* window = ImGui::FindWindowByName("Bounce");
    const float room = window->Size.x - 2.0f * window->WindowPadding.x;
    EXPECT_LE(window->ContentSize.x, room + 0.5f) << name_of(method);
  }
}

// Esc closes what is open first, asks before quitting while work runs, and
// quits when nothing is open and nothing runs.
TEST(Panel, EscapeClosesWhatIsOpenBeforeQuitting) {
  panel_state panel;
  panel.show_help = true;
  panel.show_still = true;
  EXPECT_FALSE(escape(panel, true).quit);
  EXPECT_FALSE(panel.show_help);
  EXPECT_TRUE(panel.show_still);
  EXPECT_FALSE(escape(panel, true).quit);
  EXPECT_FALSE(panel.show_still);
  EXPECT_FALSE(escape(panel, true).quit);  // the solver runs: ask
  EXPECT_TRUE(panel.confirm_quit);
  EXPECT_FALSE(escape(panel, true).quit);  // Esc again closes the question
  EXPECT_FALSE(panel.confirm_quit);
  EXPECT_TRUE(escape(panel, false).quit);  // nothing open, nothing running
}

TEST(Panel, StoppingPointsReadAsPercentages) {
  EXPECT_EQ(format_percent(0.01), "1%");
  EXPECT_EQ(format_percent(0.001), "0.1%");
  EXPECT_EQ(format_percent(2.5e-4), "0.025%");
  EXPECT_EQ(format_percent(1e-8), "1.0e-6%");
  EXPECT_EQ(format_percent(1.0), "100%");
  EXPECT_EQ(format_percent(0.0123), "1.23%");
}

// The shipped scenes are found from where the executable is, not from the
// current folder, and the built-in ones are always offered.
TEST(Panel, AssetScenesAreFoundNextToTheExecutable) {
  const std::vector<std::string> scenes = find_asset_scenes(std::filesystem::path(BOUNCE_BINARY_DIR) / "bounce");
  auto has = [&](const std::string& end) {
    return std::any_of(scenes.begin(), scenes.end(), [&](const std::string& s) { return s.ends_with(end); });
  };
  EXPECT_TRUE(has("assets/cornell_box/cornell_box.json")) << scenes.size();
  EXPECT_TRUE(has("assets/teapot/teapot.json"));
  EXPECT_TRUE(has("embedded:cornell_box/cornell_box.json"));
  EXPECT_TRUE(has("generated:box-room-60"));
  // Installed (cmake --install): bin/bounce finds share/bounce/assets.
  const test_support::scratch_dir scratch;
  const std::filesystem::path prefix = scratch.root / "install_prefix";
  std::filesystem::remove_all(prefix);
  std::filesystem::create_directories(prefix / "bin");
  std::filesystem::create_directories(prefix / "share/bounce/assets/room");
  std::ofstream(prefix / "share/bounce/assets/room/room.json") << "{}";
  const std::vector<std::string> installed = find_asset_scenes(prefix / "bin" / "bounce");
  EXPECT_TRUE(std::any_of(installed.begin(), installed.end(),
                          [](const std::string& s) { return s.ends_with("share/bounce/assets/room/room.json"); }));
  std::filesystem::remove_all(prefix);
  // Nowhere near a checkout: the built-in scenes remain.
  const std::vector<std::string> bare = find_asset_scenes("/nonexistent/bin/bounce");
  EXPECT_GE(bare.size(), 3u);
}

TEST(Panel, RecentScenesAreKeptMostRecentFirst) {
  const test_support::scratch_dir scratch;
  const std::filesystem::path home = scratch.root / "config";
  std::filesystem::remove_all(home);
  ::setenv("XDG_CONFIG_HOME", home.c_str(), 1);
  EXPECT_TRUE(read_recent_scenes().empty());
  remember_scene("/scenes/a.json");
  remember_scene("generated:interior-10k");
  remember_scene("embedded:cornell_box/cornell_box.json");  // the default is not listed
  std::vector<std::string> recent = remember_scene("/scenes/a.json");
  EXPECT_EQ(recent, (std::vector<std::string>{"/scenes/a.json", "generated:interior-10k"}));
  EXPECT_EQ(read_recent_scenes(), recent);  // kept on disk
  for (int i = 0; i < 15; ++i) recent = remember_scene("/scenes/" + std::to_string(i) + ".json");
  EXPECT_EQ(recent.size(), 10u);
  EXPECT_EQ(recent.front(), "/scenes/14.json");
  EXPECT_TRUE(std::filesystem::exists(home / "bounce" / "recent.txt"));
  ::unsetenv("XDG_CONFIG_HOME");
  std::filesystem::remove_all(home);
}

// The camera the panel copies reads back exactly, as options and as a file.
TEST(Panel, CopiedCamerasReadBackExactly) {
  camera cam;
  cam.eye = {278.123456789, 273.0, -800.5};
  cam.target = {0.1, 1.0 / 3.0, 2e-7};
  cam.up = {0.0, 1.0, 1e-3};
  cam.fov_y_degrees = 39.3077;
  cam.width = 1200;
  cam.height = 760;
  camera back;
  const std::string options = camera_command_line(cam);
  ASSERT_EQ(
      std::sscanf(options.c_str(), "--eye %lf,%lf,%lf --target %lf,%lf,%lf --up %lf,%lf,%lf --fov %lf --size %dx%d",
                  &back.eye.x, &back.eye.y, &back.eye.z, &back.target.x, &back.target.y, &back.target.z, &back.up.x,
                  &back.up.y, &back.up.z, &back.fov_y_degrees, &back.width, &back.height),
      12)
      << options;
  auto same = [](const camera& a, const camera& b) {
    return a.eye == b.eye && a.target == b.target && a.up == b.up && a.fov_y_degrees == b.fov_y_degrees &&
           a.width == b.width && a.height == b.height;
  };
  EXPECT_TRUE(same(back, cam)) << options;
  camera from_file;
  std::string error;
  ASSERT_TRUE(parse_camera_text(camera_json(cam), "copied", from_file, error)) << error;
  EXPECT_TRUE(same(from_file, cam)) << camera_json(cam);
}

TEST(Panel, BookmarksAreKeptPerScene) {
  const test_support::scratch_dir scratch;
  const std::filesystem::path home = scratch.root / "config";
  std::filesystem::remove_all(home);
  ::setenv("XDG_CONFIG_HOME", home.c_str(), 1);
  camera a, b;
  a.eye = {1, 2, 3};
  b.eye = {4, 5, 6};
  save_bookmarks("/scenes/room.json", {{"view 1", a}, {"door", b}});
  save_bookmarks("generated:interior-10k", {{"view 1", b}});
  const std::vector<camera_bookmark> room = read_bookmarks("/scenes/room.json");
  ASSERT_EQ(room.size(), 2u);
  EXPECT_EQ(room[1].name, "door");
  EXPECT_EQ(room[1].view.eye, b.eye);
  EXPECT_EQ(read_bookmarks("generated:interior-10k").size(), 1u);
  EXPECT_TRUE(read_bookmarks("/scenes/other.json").empty());
  save_bookmarks("/scenes/room.json", {});
  EXPECT_TRUE(read_bookmarks("/scenes/room.json").empty());
  EXPECT_EQ(read_bookmarks("generated:interior-10k").size(), 1u);
  ::unsetenv("XDG_CONFIG_HOME");
  std::filesystem::remove_all(home);
}

// The panel docks at the window's right edge, full height, and leaves the
// rest to the view; hidden, it draws nothing. Its width stays where the
// view keeps room.
TEST(Panel, DocksAtTheRightEdgeAndHides) {
  panel_layout layout;
  EXPECT_FLOAT_EQ(docked_width(layout, 1280.0f), 400.0f);
  layout.width = 10.0f;
  EXPECT_FLOAT_EQ(docked_width(layout, 1280.0f), 300.0f);
  layout.width = 5000.0f;
  EXPECT_FLOAT_EQ(docked_width(layout, 1280.0f), 1120.0f);  // the view keeps 160 pixels
  layout.visible = false;
  EXPECT_FLOAT_EQ(docked_width(layout, 1280.0f), 0.0f);

  solver_worker worker;
  worker.load(test_support::default_cornell_box(), hierarchical(1e-4));
  worker.wait_idle();
  const auto view = worker.latest();
  const headless_imgui imgui(1280, 900);
  panel_state panel;
  for (int frame = 0; frame < 2; ++frame) draw_frame(panel, *view);
  const ImGuiWindow* window = ImGui::FindWindowByName("Bounce");
  ASSERT_NE(window, nullptr);
  EXPECT_FLOAT_EQ(window->Pos.x, 1280.0f - 400.0f);
  EXPECT_FLOAT_EQ(window->Pos.y, 0.0f);
  EXPECT_FLOAT_EQ(window->Size.x, 400.0f);
  EXPECT_FLOAT_EQ(window->Size.y, 900.0f);
  panel.layout.visible = false;
  draw_frame(panel, *view);
  EXPECT_FALSE(ImGui::FindWindowByName("Bounce")->Active);
}

// The layout reads back as saved; a missing or broken file gives the
// defaults.
TEST(Panel, LayoutIsRememberedAndABrokenFileIsIgnored) {
  test_support::scratch_dir dir;
  ::setenv("XDG_CONFIG_HOME", dir.root.c_str(), 1);
  EXPECT_TRUE(read_panel_layout().visible);
  EXPECT_FLOAT_EQ(read_panel_layout().width, 400.0f);
  save_panel_layout({false, 512.0f});
  EXPECT_FALSE(read_panel_layout().visible);
  EXPECT_FLOAT_EQ(read_panel_layout().width, 512.0f);
  std::ofstream(dir.path("bounce/panel.json")) << "{\"visible\": 3, \"width\": -1e300";
  EXPECT_TRUE(read_panel_layout().visible);
  EXPECT_FLOAT_EQ(read_panel_layout().width, 400.0f);
  ::unsetenv("XDG_CONFIG_HOME");
}

// A screenshot or still saved without a name gets one of its own: the
// scene's name, the kind and the time, numbered when taken.
TEST(Panel, UnnamedPicturesNeverOverwriteEachOther) {
  test_support::scratch_dir dir;
  const std::filesystem::path here = std::filesystem::current_path();
  std::filesystem::current_path(dir.root);
  const std::string first = dated_file_name("/somewhere/cornell_box.json", "screenshot", ".png");
  EXPECT_TRUE(first.starts_with("cornell_box-screenshot-")) << first;
  EXPECT_TRUE(first.ends_with(".png")) << first;
  std::ofstream(first) << "x";
  const std::string second = dated_file_name("/somewhere/cornell_box.json", "screenshot", ".png");
  EXPECT_NE(second, first);
  EXPECT_FALSE(std::filesystem::exists(second));
  EXPECT_TRUE(dated_file_name("generated:box-room-60", "still", ".pfm").starts_with("box-room-60-still-"));
  std::filesystem::current_path(here);
}

// "Bake to file" writes what the window shows at the window's exposure.
TEST(Panel, BakeToFileWritesTheShownSolution) {
  test_support::scratch_dir dir;
  solver_worker worker;
  panel_state panel;
  EXPECT_EQ(bake_shown_solution(worker_view{}, dir.path("early.glb"), 1.0), "bake: no solution to bake yet");
  const std::shared_ptr<const worker_view> view = solved(worker, panel, 1e-3);
  const std::string path = dir.path("shown.glb");
  const std::string message = bake_shown_solution(*view, path, 2.5);
  EXPECT_EQ(message, "baked: " + path + " (exposure 2.5)");
  const std::string bytes = test_support::read_text(path);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_NE(bytes.find("KHR_materials_unlit"), std::string::npos);
  EXPECT_EQ(bake_shown_solution(*view, dir.path("shown.png"), 2.5).rfind("bake: ", 0), 0u);
}

// The status says what the run does: under its stopping point with links
// not final, the hierarchical solver is refining links, not solving.
TEST(Panel, TheStatusTellsRefiningLinksFromSolving) {
  worker_view view;
  view.settings.method = solver_method::hierarchical;
  view.settings.stop.remaining = 0.01;
  auto solution = std::make_shared<radiosity_snapshot>();
  solution->stats.remaining = 4e-6;
  solution->stats.remaining_final = false;
  view.solution = solution;
  view.running = true;
  EXPECT_EQ(run_state(view), "refining links");
  solution->stats.remaining = 0.2;
  EXPECT_EQ(run_state(view), "solving");
  solution->stats.remaining = 4e-6;
  solution->stats.remaining_final = true;
  view.running = false;
  view.converged = true;
  EXPECT_EQ(run_state(view), "converged");
  view.converged = false;
  EXPECT_EQ(run_state(view), "paused");
  view.settings.method = solver_method::progressive;
  solution->stats.remaining_final = false;
  view.running = true;
  EXPECT_EQ(run_state(view), "solving");
}

// The import report groups the scene's warnings with their counts, and
// its header says "new" until the section has been opened.
TEST(Panel, TheImportReportGroupsWarningsAndIsNewUntilRead) {
  worker_view view;
  std::vector<std::string> warnings;
  for (int line = 1; line <= 300; ++line)
    warnings.push_back("m.obj:" + std::to_string(line) + ": degenerate face (zero area) dropped");
  warnings.push_back("m.mtl:2: 'Ka' is not used by Bounce; ignored");
  view.warnings = std::make_shared<const std::vector<std::string>>(warnings);
  const headless_imgui imgui(1280, 900);
  panel_state panel;
  draw_frame(panel, view);
  ASSERT_EQ(panel.warning_groups.size(), 2u);
  EXPECT_EQ(panel.warning_groups[0].count, 300u);
  EXPECT_EQ(panel.warnings_read, nullptr);  // closed: unread
  ImGuiWindow* window = ImGui::FindWindowByName("Bounce");
  ASSERT_NE(window, nullptr);
  window->StateStorage.SetInt(window->GetID("###import"), 1);  // opened, as if clicked
  draw_frame(panel, view);
  EXPECT_EQ(panel.warnings_read, view.warnings);
}

}  // namespace
}  // namespace bounce
