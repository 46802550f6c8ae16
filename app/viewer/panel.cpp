#include "viewer/panel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include <imgui.h>

#include "scene/camera_file.h"

namespace bounce {

const std::vector<std::pair<std::string, std::string>>& shortcuts() {
  static const std::vector<std::pair<std::string, std::string>> keys = {
      {"left drag", "orbit about the point under the cursor"},
      {"1 / 3 / 7 (keypad or row)", "front / right / top view; with Ctrl the opposite"},
      {"right drag / shift + left drag", "pan"},
      {"wheel", "zoom"},
      {"W A S D, Q E", "fly forward, left, back, right, down, up"},
      {"F", "frame the scene"},
      {"C", "restore the scene's camera"},
      {"Space", "pause / resume the solver"},
      {"N", "one step (progressive: one shot)"},
      {"R", "restart the solver"},
      {"G", "element wireframe"},
      {"P", "screenshot"},
      {"T", "ray trace a still of the current camera"},
      {"H", "this help"},
      {"Tab / F1", "hide or show the panel"},
      {"Esc", "close the open window; else quit (asks while working)"},
      {"Ctrl+Q", "quit at once"},
  };
  return keys;
}

float docked_width(const panel_layout& layout, float window_width) {
  if (!layout.visible) return 0.0f;
  return std::clamp(layout.width, std::min(300.0f, window_width), std::max(300.0f, window_width - 160.0f));
}

std::vector<std::string> find_scenes(const std::string& folder) {
  std::vector<std::string> found;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(folder, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec))
    if (it->path().extension() == ".json") found.push_back(it->path().string());
  std::sort(found.begin(), found.end());
  return found;
}

namespace {

// A point of a plot against time; points of one segment are joined.
struct plot_point {
  double seconds;
  double value;
  std::uint64_t segment = 0;
};

// A plot of values over time on a log scale, with its axes: the quantity's
// name on top, percentages at the top, middle and bottom of the y axis,
// seconds under both ends of the x axis. A new segment starts with a faint
// vertical mark instead of a line: when the hierarchical solver refines its
// links it measures its residual anew, and a line jumping back up would
// read as divergence. `event` names the marks under the plot.
void log_plot(const char* title, const std::vector<plot_point>& points, float lo, float hi, double end,
              const char* event) {
  ImGui::TextWrapped("%s", title);
  const ImGuiStyle& style = ImGui::GetStyle();
  const std::string labels[3] = {format_percent(std::pow(10.0, double(hi))),
                                 format_percent(std::pow(10.0, double(lo + hi) / 2.0)),
                                 format_percent(std::pow(10.0, double(lo)))};
  float axis = 0.0f;
  for (const std::string& l : labels) axis = std::max(axis, ImGui::CalcTextSize(l.c_str()).x);
  axis += style.ItemInnerSpacing.x;
  const float height = 80.0f, line = ImGui::GetTextLineHeight();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImU32 text = ImGui::GetColorU32(ImGuiCol_Text), curve = ImGui::GetColorU32(ImGuiCol_PlotLines);
  const ImU32 mark = ImGui::GetColorU32(ImGuiCol_TextDisabled);
  for (int k = 0; k < 3; ++k) {
    const float y = origin.y + (height - line) * float(k) / 2.0f;
    draw->AddText(ImVec2(origin.x + axis - style.ItemInnerSpacing.x - ImGui::CalcTextSize(labels[k].c_str()).x, y),
                  text, labels[k].c_str());
  }
  const float width = std::max(40.0f, ImGui::GetContentRegionAvail().x - axis);
  const ImVec2 top_left(origin.x + axis, origin.y), bottom_right(origin.x + axis + width, origin.y + height);
  draw->AddRectFilled(top_left, bottom_right, ImGui::GetColorU32(ImGuiCol_FrameBg), style.FrameRounding);
  end = std::max(end, 1e-9);
  auto at = [&](const plot_point& p) {
    const float t = float(std::clamp(p.seconds / end, 0.0, 1.0));
    const float v = std::clamp(float(std::log10(std::max(p.value, 1e-30))), lo, hi);
    return ImVec2(top_left.x + 2.0f + t * (width - 4.0f),
                  bottom_right.y - 2.0f - (v - lo) / (hi - lo) * (height - 4.0f));
  };
  std::vector<ImVec2> run;  // the segment being drawn, one point per pixel column
  bool marked = false;
  auto flush = [&] {
    if (run.size() > 1) draw->AddPolyline(run.data(), int(run.size()), curve, ImDrawFlags_None, 1.0f);
    if (run.size() <= 4)  // a short segment (a pass of a few steps) shows as dots
      for (const ImVec2& p : run) draw->AddCircleFilled(p, 2.0f, curve);
    run.clear();
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ImVec2 p = at(points[i]);
    if (i > 0 && points[i].segment != points[i - 1].segment) {
      flush();
      draw->AddLine(ImVec2(p.x, top_left.y + 1.0f), ImVec2(p.x, bottom_right.y - 1.0f), mark);
      marked = true;
    }
    if (!run.empty() && std::floor(run.back().x) == std::floor(p.x))
      run.back() = p;
    else
      run.push_back(p);
  }
  flush();
  ImGui::Dummy(ImVec2(axis + width, height));
  char right[32];
  std::snprintf(right, sizeof right, "%.1f s", end);
  ImGui::SetCursorScreenPos(ImVec2(top_left.x, ImGui::GetCursorScreenPos().y));
  ImGui::TextUnformatted("0 s");
  ImGui::SameLine(top_left.x + width - ImGui::CalcTextSize(right).x - ImGui::GetWindowPos().x);
  ImGui::TextUnformatted(right);
  if (marked && event) ImGui::TextDisabled("%s", event);
}

// A log-scale slider whose value is written on the side away from its
// grab, so that the grab never hides it. Returns whether it moved.
bool log_slider(const char* label, float& exponent, float lo, float hi, const std::string& shown) {
  const bool moved = ImGui::SliderFloat(label, &exponent, lo, hi, "", ImGuiSliderFlags_NoRoundToFormat);
  // The item's rectangle runs on over its label: the frame is the item width.
  const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
  const ImVec2 size = ImGui::CalcTextSize(shown.c_str());
  const float pad = ImGui::GetStyle().FramePadding.x, frame_right = min.x + ImGui::CalcItemWidth();
  const bool grab_right = exponent > 0.5f * (lo + hi);
  const float x = grab_right ? min.x + pad : frame_right - pad - size.x;
  ImGui::GetWindowDrawList()->AddText(ImVec2(x, min.y + 0.5f * (max.y - min.y - size.y)),
                                      ImGui::GetColorU32(ImGuiCol_Text), shown.c_str());
  return moved;
}

}  // namespace

std::string setting_key(const solver_settings& o) {
  char key[200];
  if (o.method == solver_method::hierarchical) {
    std::snprintf(key, sizeof key, "hierarchical, link tolerance %g, edge %g, until %g", o.link_tolerance, o.max_edge,
                  o.stop.remaining);
    return key;
  }
  const bool hemicube = o.form_factors.method == form_factor_method::hemicube;
  std::snprintf(key, sizeof key, "progressive, %s %d, edge %g, patches %g, until %g",
                std::string(name_of(o.form_factors.method)).c_str(),
                hemicube ? o.form_factors.hemicube_resolution : o.form_factors.shadow_rays, o.max_edge, o.patch_edge,
                o.stop.remaining);
  std::string text = key;
  if (o.adaptive.enabled) {
    std::snprintf(key, sizeof key, ", adaptive %g, min edge %g", o.adaptive.tolerance, o.min_edge);
    text += key;
  }
  return text;
}

panel_actions choose_solver(panel_state& state, solver_method method) {
  panel_actions act;
  act.apply_mesh = method != state.solver.method;
  state.solver.method = method;
  return act;
}

solver_settings settings_to_run(const solver_settings& panel_settings) {
  solver_settings run = panel_settings;
  if (run.method == solver_method::hierarchical) run.adaptive.enabled = false;
  return run;
}

void send_to_worker(const panel_actions& act, const panel_state& state, solver_worker& worker) {
  if (act.open_scene) worker.load_file(state.scene_path, settings_to_run(state.solver));
  if (act.apply_mesh) worker.reload(settings_to_run(state.solver));
  if (act.set_stop) worker.set_criterion(state.solver.stop);
  if (act.set_view) worker.set_view(state.solver.view);
  if (act.pause) worker.pause();
  if (act.resume) worker.resume();
  if (act.step) worker.step();
  if (act.restart) {
    worker.restart();
    worker.resume();
  }
}

panel_actions escape(panel_state& state, bool working) {
  panel_actions act;
  if (state.confirm_quit)
    state.confirm_quit = false;
  else if (state.show_help)
    state.show_help = false;
  else if (state.show_still)
    state.show_still = false;
  else if (working)
    state.confirm_quit = true;
  else
    act.quit = true;
  return act;
}

std::string camera_command_line(const camera& v) {
  char text[512];
  // %.17g: the numbers read back exactly.
  std::snprintf(text, sizeof text,
                "--eye %.17g,%.17g,%.17g --target %.17g,%.17g,%.17g --up %.17g,%.17g,%.17g --fov %.17g --size %dx%d",
                v.eye.x, v.eye.y, v.eye.z, v.target.x, v.target.y, v.target.z, v.up.x, v.up.y, v.up.z, v.fov_y_degrees,
                v.width, v.height);
  return text;
}

std::string format_percent(double fraction) {
  char text[32];
  const double percent = 100.0 * fraction;
  std::snprintf(text, sizeof text, percent >= 1e-3 || percent == 0.0 ? "%.3g%%" : "%.1e%%", percent);
  std::string s = text;
  if (const std::size_t e = s.find("e-0"); e != std::string::npos) s.erase(e + 2, 1);
  return s;
}

std::string format_tolerance(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", value);
  std::string s = text;
  // "1e-05" -> "1e-5"
  if (const std::size_t e = s.find("e-0"); e != std::string::npos) s.erase(e + 2, 1);
  if (const std::size_t e = s.find("e+0"); e != std::string::npos) s.erase(e + 2, 1);
  return s;
}

std::string run_state(const worker_view& view) {
  if (view.converged) return "converged";
  if (!view.running) return "paused";
  // Under the stopping point but links not final: the solver is refining
  // its links towards the tolerance asked for, not iterating.
  if (view.solution && view.settings.method == solver_method::hierarchical &&
      view.solution->stats.remaining <= view.settings.stop.remaining && !view.solution->stats.remaining_final)
    return "refining links";
  return "solving";
}

std::vector<std::string> statistics_lines(const worker_view& view, double frame_ms) {
  std::vector<std::string> lines;
  if (!view.solution || !view.mesh) return lines;
  auto line = [&lines](const char* format, auto... values) {
    char text[256];
    std::snprintf(text, sizeof text, format, values...);
    lines.emplace_back(text);
  };
  const solver_stats& st = view.solution->stats;
  const bool hierarchical = view.settings.method == solver_method::hierarchical;
  line("%s: %s", std::string(name_of(view.settings.method)).c_str(), run_state(view).c_str());
  const double seconds = std::max(st.seconds, 1e-9);
  if (hierarchical) {
    line("elements %zu, vertices %zu", view.mesh->element_count(), view.mesh->vertex_count());
    line("steps %llu, residual %.4f%%", static_cast<unsigned long long>(st.steps), 100.0 * st.remaining);
    if (st.steps == 0) {
      line("links: none yet (the first step makes them)");
    } else {
      // 16 bytes a link (hierarchy_link).
      line("links %llu (%.1f MiB)", static_cast<unsigned long long>(st.links),
           double(st.links) * 16.0 / (1024.0 * 1024.0));
      const std::string now = format_tolerance(st.link_tolerance);
      if (st.remaining_final)
        line("link tolerance %s, final", now.c_str());
      else
        line("link tolerance %s, refining to %s", now.c_str(), format_tolerance(view.settings.link_tolerance).c_str());
    }
    line(view.settings.view ? "led by the view" : "view-independent");
    line("%.2f s, %.2f Mrays/s", st.seconds, double(st.rays) / seconds * 1e-6);
  } else {
    line("elements %zu, vertices %zu, patches %zu", view.mesh->element_count(), view.mesh->vertex_count(),
         view.mesh->patch_count());
    if (view.meshed_elements != view.mesh->element_count())
      line("adaptive: %zu elements as meshed, %llu refinement passes since", view.meshed_elements,
           static_cast<unsigned long long>(st.refinements));
    line("shots %llu, unshot %.4f%%", static_cast<unsigned long long>(st.steps), 100.0 * st.remaining);
    line("%.0f shots/s, %.2f Mrays/s, %.2f s", double(st.steps) / seconds, double(st.rays) / seconds * 1e-6,
         st.seconds);
  }
  line("frame %.1f ms", frame_ms);
  return lines;
}

namespace {

// The panel's window, docked at the right edge. Widgets leave room on
// their right for the longest label, so that no label is cut off however
// narrow the panel is made.
void begin_panel_window(const panel_state& state) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float width = docked_width(state.layout, display.x);
  ImGui::SetNextWindowPos(ImVec2(display.x - width, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(width, display.y), ImGuiCond_Always);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
  ImGui::Begin("Bounce", nullptr,
               ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoBringToFrontOnFocus |
                   ImGuiWindowFlags_NoSavedSettings);
  ImGui::PopStyleVar();
  float label_room = 0.0f;
  for (const char* label :
       {"stop at residual", "samples per pixel", "element size", "exposure (stops)", "link tolerance"})
    label_room = std::max(label_room, ImGui::CalcTextSize(label).x);
  ImGui::PushItemWidth(-(label_room + ImGui::GetStyle().ItemInnerSpacing.x));
}

// The panel's left edge: a grip 12 pixels wide that resizes it, so that a
// drag meant for it never orbits the camera.
void draw_panel_edge(panel_state& state, panel_actions& act) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float width = docked_width(state.layout, display.x), grip = 12.0f;
  ImGui::SetNextWindowPos(ImVec2(display.x - width - 0.5f * grip, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(grip, display.y), ImGuiCond_Always);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0.0f, 0.0f));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowMinSize, ImVec2(1.0f, 1.0f));
  ImGui::Begin("##panel edge", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing);
  ImGui::InvisibleButton("##resize", ImVec2(grip, display.y));
  if (ImGui::IsItemHovered() || ImGui::IsItemActive()) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
  if (ImGui::IsItemActive()) {
    state.layout.width = width - ImGui::GetIO().MouseDelta.x;
    state.layout.width = docked_width(state.layout, display.x);
  }
  if (ImGui::IsItemDeactivated()) act.save_layout = true;
  ImGui::End();
  ImGui::PopStyleVar(2);
}

// A combo of scene paths; choosing one opens it.
void scene_combo(const char* label, const std::vector<std::string>& scenes, panel_state& state, panel_actions& act) {
  if (!ImGui::BeginCombo(label, "choose...")) return;
  for (const std::string& s : scenes)
    if (ImGui::Selectable(s.c_str())) {
      state.scene_path = s;
      act.open_scene = true;
    }
  ImGui::EndCombo();
}

void draw_scene_section(panel_state& state, panel_actions& act) {
  if (!ImGui::CollapsingHeader("Scene")) return;
  char path[1024];
  std::snprintf(path, sizeof path, "%s", state.scene_path.c_str());
  if (ImGui::InputText("path", path, sizeof path, ImGuiInputTextFlags_EnterReturnsTrue)) act.open_scene = true;
  state.scene_path = path;
  scene_combo("assets", state.asset_scenes, state, act);
  if (!state.recent_scenes.empty()) scene_combo("recent", state.recent_scenes, state, act);
  if (ImGui::Button("Open")) act.open_scene = true;
  ImGui::SameLine();
  ImGui::TextDisabled("or drop a file on the window");
}

// Errors stay visible whatever is collapsed, wrapped in full; the
// previous scene keeps running. The last action's message follows, at the
// top where it is seen without scrolling.
void draw_problems(const panel_state& state, const worker_view& view) {
  if (!state.message.empty()) ImGui::TextWrapped("%s", state.message.c_str());
  if (!view.error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.35f, 0.3f, 1));
    ImGui::TextWrapped("%s", view.error.c_str());
    ImGui::PopStyleColor();
  }
  if (!state.warning.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.8f, 0.3f, 1));
    ImGui::TextWrapped("%s", state.warning.c_str());
    ImGui::PopStyleColor();
  }
}

// What loading the scene warned of, grouped by kind with counts, in a
// section of its own; its header says "new" until it has been opened.
void draw_import_report(panel_state& state, const worker_view& view) {
  if (!view.warnings || view.warnings->empty()) return;
  if (state.warnings_grouped != view.warnings) {
    state.warning_groups = group_warnings(*view.warnings);
    state.warnings_grouped = view.warnings;
  }
  const bool unread = state.warnings_read != view.warnings;
  char header[160];
  std::snprintf(header, sizeof header, "Import report: %zu warning%s, %zu kind%s%s###import", view.warnings->size(),
                view.warnings->size() == 1 ? "" : "s", state.warning_groups.size(),
                state.warning_groups.size() == 1 ? "" : "s", unread ? " (new)" : "");
  if (unread) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.8f, 0.3f, 1));
  const bool open = ImGui::CollapsingHeader(header);
  if (unread) ImGui::PopStyleColor();
  if (!open) return;
  state.warnings_read = view.warnings;
  for (const warning_group& g : state.warning_groups) ImGui::BulletText("%s", describe(g).c_str());
}

// What the worker is doing before it can solve (loading, meshing,
// preparing the solver), with its running time: over the view's top left,
// where it is seen whether the panel is shown or not, so a large scene
// shows life from its first second.
void draw_stage(const worker_view& view) {
  if (view.stage.empty()) return;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - view.stage_started).count();
  char text[600];
  std::snprintf(text, sizeof text, "%s... %.1f s", view.stage.c_str(), seconds);
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const ImVec2 at(12.0f, 12.0f), size = ImGui::CalcTextSize(text);
  draw->AddRectFilled(ImVec2(at.x - 6.0f, at.y - 4.0f), ImVec2(at.x + size.x + 6.0f, at.y + size.y + 4.0f),
                      IM_COL32(0, 0, 0, 160), 4.0f);
  draw->AddText(at, IM_COL32(255, 255, 255, 255), text);
}

// A new solver restarts at once (the mesh is kept when it meshes the
// same); the other settings wait for Apply.
void draw_solver_choice(panel_state& state, panel_actions& act) {
  if (!ImGui::BeginCombo("solver", std::string(name_of(state.solver.method)).c_str())) return;
  for (const auto& m : solver_method_names())
    if (ImGui::Selectable(std::string(m.name).c_str(), m.method == state.solver.method))
      act.apply_mesh |= choose_solver(state, m.method).apply_mesh;
  ImGui::EndCombo();
}

// The element size in scene units: automatic (shown as the mesher chose
// it) until a size is typed.
void draw_element_size(solver_settings& solver, const worker_view& view) {
  bool automatic = solver.max_edge <= 0.0;
  float max_edge = float(automatic && view.mesh ? view.mesh->max_edge : solver.max_edge);
  if (ImGui::Checkbox("auto", &automatic)) solver.max_edge = automatic ? 0.0 : double(max_edge);
  ImGui::SameLine();
  if (automatic) ImGui::BeginDisabled();
  if (ImGui::InputFloat("element size", &max_edge, 0, 0, "%.4g scene units") && !automatic)
    solver.max_edge = std::max(0.0f, max_edge);
  if (automatic) ImGui::EndDisabled();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(solver.method == solver_method::hierarchical
                          ? "longest edge of the starting elements (split further where the light needs it)"
                          : "longest element edge");
}

// The hierarchical solver's link tolerance, on a log scale from 1e-8 to
// 1e-2 of the emitted power, two digits.
void draw_link_tolerance(solver_settings& solver, panel_actions& act) {
  float exponent = float(std::log10(std::clamp(solver.link_tolerance, 1e-8, 1e-2)));
  if (log_slider("link tolerance", exponent, -8.0f, -2.0f, format_tolerance(solver.link_tolerance)))
    solver.link_tolerance = std::strtod(format_tolerance(std::pow(10.0, double(exponent))).c_str(), nullptr);
  // Restarts when the slider is let go, not at every value passed.
  if (ImGui::IsItemDeactivatedAfterEdit()) act.apply_mesh = true;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("power a link may carry unrefined, a fraction of the emitted power: lower is finer");
}

// The progressive solver's form factors: the method and its resolution.
void draw_form_factors(form_factor_params& ff) {
  if (ImGui::BeginCombo("form factors", std::string(name_of(ff.method)).c_str())) {
    for (const auto& m : form_factor_method_names())
      if (ImGui::Selectable(std::string(m.name).c_str(), m.method == ff.method)) ff.method = m.method;
    ImGui::EndCombo();
  }
  if (ff.method == form_factor_method::raycast)
    ImGui::SliderInt("shadow rays", &ff.shadow_rays, 1, 64);
  else
    ImGui::SliderInt("hemicube", &ff.hemicube_resolution, 16, 512);
}

// The stopping point, on a log scale shown as a percentage of the emitted
// power. Applies at once.
void draw_stopping_point(stop_criterion& stop, bool hierarchical, panel_actions& act) {
  float until = float(std::log10(std::max(stop.remaining, 1e-12)));
  if (log_slider(hierarchical ? "stop at residual" : "stop at unshot", until, -8.0f, 0.0f,
                 format_percent(stop.remaining))) {
    stop.remaining = std::strtod(format_tolerance(std::pow(10.0, double(until))).c_str(), nullptr);
    act.set_stop = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(hierarchical ? "stop when what one more iteration would move is below this share of the power"
                                   : "stop when the power not yet shot is below this share of the emitted power");
}

// Adaptive meshing: refine where the light changes (applies on re-mesh).
// Its minimum edge is the one the hierarchical solver's splitting reads too.
void draw_adaptive_meshing(solver_settings& settings) {
  adaptive_params& adaptive = settings.adaptive;
  ImGui::Checkbox("adaptive meshing", &adaptive.enabled);
  if (!adaptive.enabled) return;
  float tolerance = float(adaptive.tolerance);
  ImGui::SliderFloat("tolerance", &tolerance, 0.02f, 1.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  adaptive.tolerance = double(tolerance);
  float min_edge = float(settings.min_edge);
  ImGui::InputFloat("min edge (0: auto)", &min_edge, 0, 0, "%.4g");
  settings.min_edge = std::max(0.0f, min_edge);
}

// Apply, Pause or Start, Step, Restart.
void draw_solver_buttons(const worker_view& view, panel_actions& act) {
  if (ImGui::Button("Apply")) act.apply_mesh = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("solve again with these settings (re-meshed if they change the mesh)");
  ImGui::SameLine();
  if (view.running) {
    if (ImGui::Button("Pause")) act.pause = true;
  } else if (ImGui::Button("Start")) {
    act.resume = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Step")) act.step = true;
  ImGui::SameLine();
  if (ImGui::Button("Restart")) act.restart = true;
}

void draw_solver_section(panel_state& state, const worker_view& view, panel_actions& act) {
  if (!ImGui::CollapsingHeader("Solver", ImGuiTreeNodeFlags_DefaultOpen)) return;
  draw_solver_choice(state, act);
  solver_settings& solver = state.solver;
  const bool hierarchical = solver.method == solver_method::hierarchical;
  draw_element_size(solver, view);
  if (hierarchical) {
    draw_link_tolerance(solver, act);
    bool led = solver.view.has_value();
    if (ImGui::Checkbox("led by the view", &led)) {
      solver.view = led ? std::optional<camera>(state.current_camera) : std::nullopt;
      act.set_view = true;
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "refine first what the window shows, again whenever the camera rests; off: every part of "
          "the scene alike (what is refined stays either way)");
  } else
    draw_form_factors(solver.form_factors);
  draw_stopping_point(solver.stop, hierarchical, act);
  if (!hierarchical) draw_adaptive_meshing(solver);
  draw_solver_buttons(view, act);
}

// Unshot power and, against a reference, the error of the picture, on
// one time axis.
void draw_convergence_plots(const worker_view& view, const error_status& errors) {
  const bool hierarchical = view.settings.method == solver_method::hierarchical;
  const double end = std::max(view.history.empty() ? 0.0 : view.history.back().seconds,
                              errors.history.empty() ? 0.0 : errors.history.back().seconds);
  std::vector<plot_point> remaining;
  remaining.reserve(view.history.size());
  for (std::size_t i = 0; i < view.history.size(); ++i) {
    const convergence_point& p = view.history[i];
    remaining.push_back({p.seconds, p.remaining, hierarchical ? p.refinements : 0});
  }
  if (!remaining.empty())
    log_plot(hierarchical ? "residual (share of the power, log scale) against time"
                          : "unshot power (share of the emitted, log scale) against time",
             remaining, -8.0f, 0.0f, end, "| links refined: the residual is measured anew");
  std::vector<plot_point> error;
  for (const error_point& p : errors.history) error.push_back({p.seconds, p.error, 0});
  if (!error.empty())
    log_plot("error of the picture (relative RMSE, log scale) against time", error, -3.0f, 0.0f, end, nullptr);
}

// The reference the error plot measures against: its progress with a
// Cancel, or the button that starts it, then the error now and that of the
// last run with the same settings.
void draw_error_reference(const error_status& errors, panel_actions& act) {
  if (errors.computing) {
    const float cancel = ImGui::CalcTextSize("Cancel").x + 2.0f * ImGui::GetStyle().FramePadding.x;
    ImGui::ProgressBar(float(errors.progress), ImVec2(-(cancel + ImGui::GetStyle().ItemSpacing.x), 0));
    ImGui::SameLine();
    if (ImGui::Button("Cancel##reference")) act.cancel_reference = true;
  } else if (ImGui::Button("Reference for the error plot")) {
    act.compute_reference = true;
  }
  ImGui::TextWrapped("%s", errors.summary.c_str());
  if (!errors.history.empty())
    ImGui::TextWrapped("error now %.2f%% (relative RMSE of the picture)", 100.0 * errors.history.back().error);
  if (!errors.last) return;
  if (std::isnan(errors.last->error))
    ImGui::TextWrapped("last run with these settings: %.2f s to %.3g%% unshot", errors.last->seconds,
                       100.0 * errors.last->remaining);
  else
    ImGui::TextWrapped("last run with these settings: %.2f s to %.3g%% unshot, error %.2f%%", errors.last->seconds,
                       100.0 * errors.last->remaining, 100.0 * errors.last->error);
}

void draw_statistics_section(const worker_view& view, double frame_ms, const error_status& errors, panel_actions& act) {
  if (!ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen) || !view.solution || !view.mesh) return;
  for (const std::string& text : statistics_lines(view, frame_ms)) ImGui::TextWrapped("%s", text.c_str());
  draw_convergence_plots(view, errors);
  draw_error_reference(errors, act);
}

// Framing the scene, the scene's camera, and screenshots.
void draw_view_buttons(panel_state& state, panel_actions& act) {
  if (ImGui::Button("Frame scene")) act.frame_scene = true;
  ImGui::SameLine();
  if (ImGui::Button("Scene camera")) act.reset_camera = true;
  if (ImGui::Button("Screenshot")) act.screenshot = true;
  ImGui::SameLine();
  ImGui::Checkbox("with panel", &state.screenshot_with_panel);
  if (ImGui::Button("Bake to file")) act.bake = true;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The light as shown, in vertex colours: a .glb for Blender, three.js or an engine");
}

// gouraud.frag's false-colour scale at t in [0, 1], as the screen shows
// it (through the sRGB curve).
ImU32 heat_colour(float t) {
  auto channel = [t](float centre) {
    const float linear = std::clamp(1.5f - std::abs(4.0f * t - centre), 0.0f, 1.0f);
    const float encoded = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return int(std::lround(255.0f * encoded));
  };
  return IM_COL32(channel(3.0f), channel(2.0f), channel(1.0f), 255);
}

// The false colours' legend: the scale as a bar, its two ends labelled.
void draw_false_colour_legend(gl::false_colour colours, const worker_view& view) {
  const char* what = colours == gl::false_colour::remaining ? "unshot radiance (W/(m^2 sr), R+G+B), log scale"
                                                            : "element size (square root of the area)";
  ImGui::TextWrapped("%s", what);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = std::max(40.0f, ImGui::GetContentRegionAvail().x), height = ImGui::GetFrameHeight() * 0.6f;
  ImDrawList* draw = ImGui::GetWindowDrawList();
  constexpr int steps = 32;
  for (int i = 0; i < steps; ++i) {
    const float x0 = origin.x + width * float(i) / steps, x1 = origin.x + width * float(i + 1) / steps;
    draw->AddRectFilledMultiColor(ImVec2(x0, origin.y), ImVec2(x1, origin.y + height), heat_colour(float(i) / steps),
                                  heat_colour(float(i + 1) / steps), heat_colour(float(i + 1) / steps),
                                  heat_colour(float(i) / steps));
  }
  ImGui::Dummy(ImVec2(width, height));
  char low[32], high[64];
  if (colours == gl::false_colour::remaining) {
    std::snprintf(low, sizeof low, "1e-6 or less");
    std::snprintf(high, sizeof high, "1e2 or more");
  } else {
    std::snprintf(low, sizeof low, "0");
    const float largest = view.mesh_arrays ? view.mesh_arrays->largest_element : 0.0f;
    std::snprintf(high, sizeof high, "%.3g scene units", double(largest));
  }
  const float start = ImGui::GetCursorPosX();
  ImGui::TextUnformatted(low);
  ImGui::SameLine(std::max(start + ImGui::CalcTextSize(low).x + ImGui::GetStyle().ItemSpacing.x,
                           start + width - ImGui::CalcTextSize(high).x));
  ImGui::TextUnformatted(high);
}

// How the solution is shown: exposure, tone curve, wireframe, false
// colours, refinement at rest.
void draw_display_section(panel_state& state, const worker_view& view, panel_actions& act) {
  if (!ImGui::CollapsingHeader("Display")) return;
  gl::display_settings& display = state.display;
  ImGui::Checkbox("auto##exposure", &state.auto_exposure);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "set the exposure from the picture: its brightest 5%% just below white; moving the slider fixes it");
  ImGui::SameLine();
  float stops = float(std::log2(display.exposure));
  if (ImGui::SliderFloat("exposure (stops)", &stops, -16.0f, 16.0f, "%.1f")) {
    display.exposure = std::exp2(double(stops));
    state.auto_exposure = false;  // a value the user sets stays
  }
  int curve = int(display.curve) == 1 ? 1 : 0;
  ImGui::Combo("tone curve", &curve, "sRGB\0filmic\0");
  display.curve = curve ? gl::tone_curve::filmic : gl::tone_curve::srgb;
  ImGui::Checkbox("wireframe", &display.wireframe);
  ImGui::SameLine();
  ImGui::Checkbox("ambient term", &display.ambient);
  int colours = int(display.colours);
  ImGui::Combo("colours", &colours, "radiance\0false colour: unshot power\0false colour: element size\0");
  display.colours = static_cast<gl::false_colour>(colours);
  if (display.colours != gl::false_colour::none) draw_false_colour_legend(display.colours, view);
  ImGui::Checkbox("highlight back faces", &display.highlight_back_faces);
  ImGui::Checkbox("refine at rest", &state.refine_at_rest);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("when the camera rests, trace passes of the still in the background and show their mean");
  if (state.refined_passes > 0) {
    ImGui::SameLine();
    ImGui::TextDisabled("%d passes", state.refined_passes);
  }
  draw_view_buttons(state, act);
}

// The scene's bookmarks: go to one, or delete it (x).
void draw_bookmarks(const panel_state& state, panel_actions& act) {
  for (std::size_t i = 0; i < state.bookmarks.size(); ++i) {
    ImGui::PushID(int(i));
    if (ImGui::SmallButton("x")) act.delete_bookmark = int(i);
    ImGui::SameLine();
    if (ImGui::Selectable(state.bookmarks[i].name.c_str())) act.go_to_bookmark = int(i);
    ImGui::PopID();
  }
}

// The camera for the command line (a view found here renders the same
// with `render` and `trace`), a camera file, and bookmarks.
void draw_camera_section(panel_state& state, panel_actions& act) {
  if (!ImGui::CollapsingHeader("Camera")) return;
  if (ImGui::Button("Copy as options")) {
    ImGui::SetClipboardText(camera_command_line(state.current_camera).c_str());
    state.message = "camera copied as command-line options";
  }
  ImGui::SameLine();
  if (ImGui::Button("Copy as JSON")) {
    ImGui::SetClipboardText(camera_json(state.current_camera).c_str());
    state.message = "camera copied as JSON (a camera file)";
  }
  char path[1024];
  std::snprintf(path, sizeof path, "%s", state.camera_path.c_str());
  ImGui::InputText("camera file", path, sizeof path);
  state.camera_path = path;
  if (ImGui::Button("Save camera file")) act.save_camera = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("then: bounce render SCENE --camera FILE");
  ImGui::SameLine();
  if (ImGui::Button("Bookmark this view")) act.add_bookmark = true;
  draw_bookmarks(state, act);
}

// The ray-traced still's settings, and its progress or the button that
// starts it.
void draw_still_section(panel_state& state, const worker_view& view, const still_status& still, panel_actions& act) {
  if (!ImGui::CollapsingHeader("Ray-traced still", ImGuiTreeNodeFlags_DefaultOpen)) return;
  still_settings& st = state.still;
  ImGui::Combo("integrator", &st.integrator,
               "Whitted over the radiosity\0two-pass: caustics + final gather\0progressive photon mapping\0"
               "path tracer (reference)\0");
  ImGui::SliderInt("samples per pixel", &st.spp, 1, 256, "%d", ImGuiSliderFlags_Logarithmic);
  if (st.integrator == 0) ImGui::Combo("direct light", &st.direct, "shadow rays (sharp)\0from the radiosity\0");
  ImGui::Checkbox("at the window's size", &st.window_size);
  if (!st.window_size) {
    if ((st.size[0] <= 0 || st.size[1] <= 0) && view.source) {  // start from the scene camera's
      st.size[0] = view.source->view.width;
      st.size[1] = view.source->view.height;
    }
    ImGui::InputInt2("size", st.size);
    st.size[0] = std::clamp(st.size[0], 1, 16384);
    st.size[1] = std::clamp(st.size[1], 1, 16384);
  }
  if (still.running) {
    ImGui::ProgressBar(float(still.progress), ImVec2(-80, 0));
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) act.cancel_still = true;
  } else if (ImGui::Button("Ray trace still (T)")) {
    act.trace_still = true;
  }
}

// The help button, under the sections.
void end_panel_window(panel_state& state) {
  if (ImGui::Button("Help (H)")) state.show_help = true;
  ImGui::PopItemWidth();
  ImGui::End();
}

// A path typed into a text field of the still's window.
void path_field(const char* label, std::string& value) {
  char path[1024];
  std::snprintf(path, sizeof path, "%s", value.c_str());
  ImGui::InputTextWithHint(label, "automatic: scene name and time", path, sizeof path);
  value = path;
}

// The finished still in a window of its own over the view, with its PNG
// and PFM saves. It stays inside the view's part of the window: the
// picture is scaled down to fit (saved at full size), and the window is
// put back inside whenever it would leave it.
void draw_still_window(panel_state& state, const still_status& still, panel_actions& act) {
  if (!still.texture || !state.show_still) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float view_width = std::max(1.0f, display.x - docked_width(state.layout, display.x));
  const ImGuiStyle& style = ImGui::GetStyle();
  // Room for the frame, the title and the four lines under the picture.
  const float chrome_x = 2.0f * style.WindowPadding.x + 2.0f;
  const float chrome_y = 2.0f * style.WindowPadding.y + 5.0f * ImGui::GetFrameHeightWithSpacing() + 8.0f;
  const float scale = std::clamp(std::min((view_width - 16.0f - chrome_x) / float(std::max(still.width, 1)),
                                          (display.y - 16.0f - chrome_y) / float(std::max(still.height, 1))),
                                 0.05f, 1.0f);
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Appearing);
  ImGui::Begin("Ray-traced still", &state.show_still, ImGuiWindowFlags_AlwaysAutoResize);
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  const ImVec2 inside(std::clamp(pos.x, 0.0f, std::max(0.0f, view_width - size.x)),
                      std::clamp(pos.y, 0.0f, std::max(0.0f, display.y - size.y)));
  if (inside.x != pos.x || inside.y != pos.y) ImGui::SetWindowPos(inside);
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(still.texture)),
               ImVec2(float(still.width) * scale, float(still.height) * scale));
  ImGui::TextUnformatted(still.summary.c_str());
  path_field("PNG", state.still.png_path);
  ImGui::SameLine();
  if (ImGui::Button("Save##png")) act.save_still_png = true;
  path_field("PFM", state.still.pfm_path);
  ImGui::SameLine();
  if (ImGui::Button("Save##pfm")) act.save_still_pfm = true;
  if (!state.still_message.empty()) {
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + std::max(240.0f, float(still.width) * scale));
    ImGui::TextUnformatted(state.still_message.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
}

void draw_help_window(panel_state& state) {
  if (!state.show_help) return;
  ImGui::Begin("Keyboard and mouse", &state.show_help, ImGuiWindowFlags_AlwaysAutoResize);
  for (const auto& [key, what] : shortcuts()) ImGui::Text("%-30s %s", key.c_str(), what.c_str());
  ImGui::End();
}

// "Quit while working?", opened by escape().
void draw_quit_popup(panel_state& state, const still_status& still, panel_actions& act) {
  if (!state.confirm_quit) return;
  ImGui::OpenPopup("Quit?");
  if (!ImGui::BeginPopupModal("Quit?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::TextUnformatted(still.running ? "A still is being traced. Quit anyway?"
                                       : "The solver is running. Quit anyway?");
  if (ImGui::Button("Quit")) act.quit = true;
  ImGui::SameLine();
  if (ImGui::Button("Cancel")) state.confirm_quit = false;
  if (!state.confirm_quit) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

}  // namespace

panel_actions draw_panel(panel_state& state, const worker_view& view, double frame_ms, const still_status& still,
                         const error_status& errors) {
  panel_actions act;
  if (state.layout.visible) {
    begin_panel_window(state);
    draw_scene_section(state, act);
    draw_problems(state, view);
    draw_import_report(state, view);
    draw_solver_section(state, view, act);
    draw_statistics_section(view, frame_ms, errors, act);
    draw_display_section(state, view, act);
    draw_camera_section(state, act);
    draw_still_section(state, view, still, act);
    end_panel_window(state);
    draw_panel_edge(state, act);
  }
  draw_stage(view);
  draw_still_window(state, still, act);
  draw_help_window(state);
  draw_quit_popup(state, still, act);
  return act;
}

}  // namespace bounce
