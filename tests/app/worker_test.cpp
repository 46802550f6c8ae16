// The solver thread: commands through one queue, an immutable view
// published after every step, errors that keep the previous scene.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "mesh_builders.h"
#include "scene/scene_io.h"
#include "test_files.h"
#include "viewer/error_tracker.h"
#include "viewer/solver_worker.h"
#include "viewer/still_job.h"

namespace bounce {
namespace {

// The progressive solver: one shot per step, unshot falling.
solver_settings coarse(double until) {
  solver_settings o;
  o.method = solver_method::progressive;
  o.max_edge = 120;
  o.stop.remaining = until;
  return o;
}

TEST(SolverWorker, SolvesToTheCriterionAndPublishesEveryStep) {
  solver_worker worker;
  worker.load(test_support::default_cornell_box(), coarse(0.01));
  worker.wait_idle();
  auto view = worker.latest();
  ASSERT_TRUE(view->mesh);
  ASSERT_TRUE(view->solution);
  EXPECT_TRUE(view->converged);
  EXPECT_FALSE(view->running);
  EXPECT_LE(view->solution->stats.remaining, 0.01);
  // One history point per shot, unshot falling (a shot may add up to a
  // few tenths of a percent: vertex-sampled form factors at the blocks'
  // feet, Radiosity.UnshotFractionFallsBarVertexSampling).
  EXPECT_EQ(view->history.size(), view->solution->stats.steps);
  for (std::size_t i = 1; i < view->history.size(); ++i)
    EXPECT_LE(view->history[i].remaining, view->history[i - 1].remaining * (1.0 + 1e-2));
  EXPECT_EQ(view->solution->radiosity.size(), view->mesh->vertex_count());
}

TEST(SolverWorker, HierarchicalPublishesEveryStepAndConverges) {
  solver_worker worker;
  solver_settings settings;  // the default solver
  settings.max_edge = 60;
  settings.stop.remaining = 0.01;
  ASSERT_EQ(settings.method, solver_method::hierarchical);
  worker.load(test_support::default_cornell_box(), settings);
  worker.wait_idle();
  auto view = worker.latest();
  ASSERT_TRUE(view->solution);
  EXPECT_TRUE(view->converged);
  EXPECT_TRUE(view->solution->stats.remaining_final);
  EXPECT_GT(view->solution->stats.links, 0u);
  EXPECT_LE(view->solution->stats.remaining, 0.01);
  EXPECT_EQ(view->history.size(), view->solution->stats.steps);  // one point per step
  EXPECT_EQ(view->solution->radiosity.size(), view->mesh->vertex_count());
}

// The window re-targets its solver as the camera comes to rest: a close-up
// of one corner is refined further where it looks, and nothing refined
// before is undone; no view at all refines what the close-up left coarse.
TEST(SolverWorker, ReTargetsAtANewViewAndKeepsWhatIsRefined) {
  solver_worker worker;
  const scene box = test_support::default_cornell_box();
  solver_settings settings;  // the default solver
  settings.max_edge = 60;
  settings.link_tolerance = 1e-4;  // coarse: the test is of re-targeting, not of the light
  settings.stop.remaining = 0.01;
  settings.view = box.view;
  worker.load(box, settings);
  worker.wait_idle();
  const auto led = worker.latest();
  ASSERT_TRUE(led->converged);
  ASSERT_TRUE(led->settings.view);
  const std::uint64_t links_led = led->solution->stats.links;

  camera close_up = box.view;  // the floor's front left corner, seen from above
  close_up.eye = vec3(60, 200, 60);
  close_up.target = vec3(0, 0, 0);
  close_up.fov_y_degrees = 20;
  worker.set_view(close_up);
  worker.wait_idle();
  const auto retargeted = worker.latest();
  EXPECT_TRUE(retargeted->converged);
  EXPECT_EQ(retargeted->run, led->run) << "a new view is not a new run";
  ASSERT_TRUE(retargeted->settings.view);
  EXPECT_EQ(retargeted->settings.view->eye, close_up.eye);
  EXPECT_GT(retargeted->solution->stats.links, links_led);

  worker.set_view(std::nullopt);
  worker.wait_idle();
  const auto independent = worker.latest();
  EXPECT_TRUE(independent->converged);
  EXPECT_FALSE(independent->settings.view);
  EXPECT_GT(independent->solution->stats.links, retargeted->solution->stats.links);
}

TEST(SolverWorker, PauseStepAndRestart) {
  solver_worker worker;
  worker.load(test_support::default_cornell_box(), coarse(1e-9));
  worker.pause();
  worker.wait_idle();
  const std::uint64_t paused_at = worker.latest()->solution->stats.steps;
  EXPECT_FALSE(worker.latest()->running);
  worker.step();
  worker.wait_idle();
  EXPECT_EQ(worker.latest()->solution->stats.steps, paused_at + 1);
  worker.step();
  worker.wait_idle();
  EXPECT_EQ(worker.latest()->solution->stats.steps, paused_at + 2);
  // A restart while paused goes back to B = E and stays paused: no shot
  // made, the history empty, every vertex at its emission, a new run.
  const std::uint64_t run_before = worker.latest()->run;
  worker.restart();
  worker.wait_idle();
  const auto restarted = worker.latest();
  EXPECT_EQ(restarted->run, run_before + 1);
  EXPECT_EQ(restarted->solution->stats.steps, 0u);
  EXPECT_TRUE(restarted->history.empty());
  EXPECT_FALSE(restarted->running);
  for (std::size_t v = 0; v < restarted->mesh->vertex_count(); ++v) {
    EXPECT_EQ(restarted->solution->radiosity[v], restarted->mesh->vertex_emission[v]) << "vertex " << v;
  }
  // Running again from there makes the same first shots as the first run.
  worker.step();
  worker.wait_idle();
  EXPECT_EQ(worker.latest()->solution->stats.steps, 1u);
  EXPECT_EQ(worker.latest()->mesh_version, 1u);
}

// A run that runs out of power to shoot (nothing reflects) ends converged,
// with one history point per shot made and none for the step that found
// nothing left.
TEST(SolverWorker, ARunThatRunsOutRecordsOnlyTheShotsMade) {
  scene s = test_support::default_cornell_box();
  for (material& m : s.materials) m.rho = rgb(0.0);
  solver_settings settings = coarse(0.0);
  solver_worker worker;
  worker.load(std::move(s), settings);
  worker.wait_idle();
  const auto view = worker.latest();
  ASSERT_TRUE(view->solution);
  EXPECT_TRUE(view->converged);
  EXPECT_GT(view->solution->stats.steps, 0u);
  EXPECT_EQ(view->history.size(), view->solution->stats.steps);
}

// With adaptive meshing the published mesh is the refined one, and the
// solution published with it belongs to it.
TEST(SolverWorker, PublishesTheRefinedMeshWithItsSolution) {
  solver_worker worker;
  solver_settings settings = coarse(0.05);
  settings.max_edge = 150;
  settings.adaptive.enabled = true;
  settings.adaptive.tolerance = 0.15;
  worker.load(test_support::default_cornell_box(), settings);
  worker.wait_idle();
  const auto view = worker.latest();
  ASSERT_TRUE(view->mesh && view->solution);
  EXPECT_GT(view->solution->stats.refinements, 0u);
  EXPECT_GT(view->mesh->element_count(), view->meshed_elements);
  EXPECT_EQ(view->solution->radiosity.size(), view->mesh->vertex_count());
}

// The mesh and the solution come converted for the renderer, off the UI
// thread: the arrays once per mesh, the colours with every solution.
TEST(SolverWorker, PublishesTheMeshAndSolutionAsTheRendererTakesThem) {
  solver_worker worker;
  worker.load(test_support::default_cornell_box(), coarse(0.05));
  worker.wait_idle();
  const auto view = worker.latest();
  ASSERT_TRUE(view->mesh && view->solution && view->mesh_arrays && view->colours);
  const patch_mesh& mesh = *view->mesh;
  EXPECT_EQ(view->mesh_arrays->vertex_count, mesh.vertex_count());
  constexpr std::size_t stride = gl::mesh_arrays::floats_per_vertex;
  ASSERT_EQ(view->mesh_arrays->vertices.size(), stride * mesh.vertex_count());
  EXPECT_EQ(view->mesh_arrays->source, view->source);  // for its textures and background
  // The triangles, then the elements' outline (2 indices an edge) for the wireframe.
  ASSERT_EQ(view->mesh_arrays->plain_count, 3 * mesh.element_count());
  ASSERT_EQ(view->mesh_arrays->indices.size(), 9 * mesh.element_count());
  // Every element once, in chunks along a Morton curve rather than in the mesh's order.
  std::vector<std::array<unsigned, 3>> drawn, elements;
  for (std::size_t i = 0; i < view->mesh_arrays->plain_count; i += 3)
    drawn.push_back(
        {view->mesh_arrays->indices[i], view->mesh_arrays->indices[i + 1], view->mesh_arrays->indices[i + 2]});
  for (const glm::ivec3& t : mesh.elements) elements.push_back({unsigned(t[0]), unsigned(t[1]), unsigned(t[2])});
  std::sort(drawn.begin(), drawn.end());
  std::sort(elements.begin(), elements.end());
  EXPECT_EQ(drawn, elements);
  std::size_t chunked = 0;
  for (const gl::draw_chunk& c : view->mesh_arrays->plain_chunks) {
    EXPECT_EQ(c.first, chunked);
    chunked += c.count;
  }
  EXPECT_EQ(chunked, view->mesh_arrays->plain_count);
  EXPECT_EQ(view->mesh_arrays->vertices[stride * 7 + 1], float(mesh.positions[7].y));
  ASSERT_EQ(view->colours->size(), 2 * mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    ASSERT_EQ((*view->colours)[v], glm::vec3(view->solution->radiosity[v])) << v;
    ASSERT_EQ((*view->colours)[mesh.vertex_count() + v], glm::vec3(view->solution->remaining[v])) << v;
  }
  // A restart publishes a new solution with the same mesh: the arrays are kept.
  worker.restart();
  worker.wait_idle();
  const auto restarted = worker.latest();
  EXPECT_EQ(restarted->mesh_arrays, view->mesh_arrays);
  EXPECT_NE(restarted->colours, view->colours);
}

// The history is shared between published views, not copied: a view keeps
// the points it was published with while the worker appends.
TEST(ConvergenceLog, AppendsAcrossBlocksAndSharesThem) {
  convergence_log log;
  for (int i = 0; i < 2500; ++i) log.push_back({double(i), 1.0 / (i + 1)});
  const convergence_log published = log;
  for (int i = 2500; i < 3000; ++i) log.push_back({double(i), 0.0});
  ASSERT_EQ(published.size(), 2500u);
  ASSERT_EQ(log.size(), 3000u);
  for (std::size_t i = 0; i < published.size(); ++i) ASSERT_EQ(published[i].seconds, double(i));
  EXPECT_EQ(published.back().remaining, 1.0 / 2500);
  EXPECT_EQ(log.back().seconds, 2999.0);
  log.clear();
  EXPECT_TRUE(log.empty());
  EXPECT_EQ(published.size(), 2500u);  // the published view keeps its points
  EXPECT_EQ(published.front().seconds, 0.0);
}

TEST(SolverWorker, ABadSceneKeepsThePreviousOne) {
  test_support::scratch_dir dir;
  solver_worker worker;
  worker.load(test_support::default_cornell_box(), coarse(0.05));
  worker.wait_idle();
  const auto before = worker.latest();
  worker.load_file(dir.write("bad.json", "{ not json"), coarse(0.05));
  worker.wait_idle();
  const auto after = worker.latest();
  EXPECT_NE(after->error.find("bad.json:1:"), std::string::npos) << after->error;
  EXPECT_EQ(after->mesh, before->mesh);
  EXPECT_EQ(after->mesh_version, before->mesh_version);
  // A good scene file replaces it and clears the error.
  worker.load_file(test_support::source_path("assets/furnace/furnace.json"), coarse(0.05));
  worker.wait_idle();
  EXPECT_TRUE(worker.latest()->error.empty());
  EXPECT_EQ(worker.latest()->mesh_version, before->mesh_version + 1);
}

// The window's error plot: a path-traced reference of the camera, then the
// error of the published solutions against it, falling as the solver
// converges; the finished run is remembered under its setting.
TEST(ErrorTracker, MeasuresPublishedSolutionsAgainstAPathTracedReference) {
  solver_worker worker;
  error_tracker tracker;
  worker.load(test_support::default_cornell_box(), coarse(1e-3));
  worker.wait_idle();
  const auto first = worker.latest();
  EXPECT_FALSE(tracker.status("s").ready);
  tracker.compute_reference(first->source, first->source->view, 32, 256);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!tracker.status("s").ready && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(tracker.status("s").ready);
  EXPECT_NE(tracker.status("s").summary.find("32x32 path traced, 256 spp"), std::string::npos);

  // A run measured from its start: three single steps, each measured, then
  // on to the criterion.
  worker.restart();
  worker.pause();
  worker.wait_idle();
  error_status status;
  for (int i = 0; i < 3; ++i) {
    const std::size_t before = tracker.status("s").history.size();
    worker.step();
    worker.wait_idle();
    tracker.observe(*worker.latest(), "s");
    while (tracker.status("s").history.size() == before && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(tracker.status("s").history.size(), 3u);
  worker.resume();
  while (std::chrono::steady_clock::now() < deadline) {
    tracker.observe(*worker.latest(), "s");
    status = tracker.status("s");
    if (status.last && std::isfinite(status.last->error)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(status.last.has_value());
  ASSERT_GE(status.history.size(), 2u);
  for (std::size_t i = 1; i < status.history.size(); ++i)
    EXPECT_GE(status.history[i].seconds, status.history[i - 1].seconds);
  EXPECT_LT(status.history.back().error, status.history.front().error);
  EXPECT_LT(status.history.back().error, 0.3);  // 120 mm elements against 32x32 pixels: coarse, but close
  EXPECT_EQ(status.last->error, status.history.back().error);
  EXPECT_EQ(status.last->seconds, worker.latest()->solution->stats.seconds);
  EXPECT_LE(status.last->remaining, 1e-3);
  EXPECT_FALSE(tracker.status("another setting").last.has_value());
}

// Before it solves, the worker says what it is doing (loading, meshing,
// preparing the solver), so the window can show life on a large scene;
// once it solves, it says nothing.
TEST(SolverWorker, SaysWhatItDoesBeforeItSolves) {
  solver_worker worker;
  worker.load_file("generated:interior-10k", coarse(0.5));
  std::vector<std::string> seen;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    const auto view = worker.latest();
    if (!view->stage.empty() && (seen.empty() || seen.back() != view->stage)) seen.push_back(view->stage);
    if (view->mesh && view->stage.empty()) break;
  }
  worker.wait_idle();
  std::string all;
  for (const std::string& s : seen) all += s + "; ";
  EXPECT_NE(all.find("meshing generated:interior-10k"), std::string::npos) << all;
  EXPECT_TRUE(worker.latest()->stage.empty());
  EXPECT_TRUE(worker.latest()->mesh);
}

// While a new scene is meshed, its surfaces as they come are shown (no
// solution with them); then the patch mesh takes their place.
TEST(SolverWorker, ShowsTheSurfacesWhileItMeshes) {
  solver_worker worker;
  worker.load_file("generated:interior-100k", coarse(0.5));
  std::shared_ptr<const patch_mesh> preview;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  while (std::chrono::steady_clock::now() < deadline) {
    const auto view = worker.latest();
    if (view->mesh && view->stage.rfind("meshing", 0) == 0) {
      preview = view->mesh;
      EXPECT_FALSE(view->solution);
      EXPECT_EQ(view->meshed_elements, 0u);
      ASSERT_TRUE(view->source);
      EXPECT_EQ(view->source->source, "generated:interior-100k");
      break;
    }
    if (view->mesh && view->stage.empty()) break;  // meshed already: missed
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(preview) << "no preview while meshing";
  worker.wait_idle();
  const auto done = worker.latest();
  ASSERT_TRUE(done->mesh);
  EXPECT_NE(done->mesh, preview);
  // The mesher cuts away hidden ground and overlaps: never more area than the preview.
  EXPECT_LE(total_area(*done->mesh), total_area(*preview) * (1.0 + 1e-9));
  EXPECT_GT(total_area(*done->mesh), 0.8 * total_area(*preview));
}

// A reference being traced says so, and Cancel stops it: nothing is
// measured, and the panel is told it was cancelled.
TEST(ErrorTracker, AReferenceSaysItIsBeingTracedAndCanBeCancelled) {
  solver_worker worker;
  error_tracker tracker;
  worker.load(test_support::default_cornell_box(), coarse(1e-3));
  worker.wait_idle();
  const auto view = worker.latest();
  tracker.compute_reference(view->source, view->source->view, 64, 1 << 16);  // minutes: it must be cancelled
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!tracker.status("s").computing && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_TRUE(tracker.status("s").computing);
  EXPECT_NE(tracker.status("s").summary.find("path tracing the reference: 64x64"), std::string::npos)
      << tracker.status("s").summary;
  tracker.cancel_reference();
  while (tracker.status("s").computing && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const error_status status = tracker.status("s");
  EXPECT_FALSE(status.computing);
  EXPECT_FALSE(status.ready);
  EXPECT_NE(status.summary.find("cancelled"), std::string::npos) << status.summary;
}

// The window's still with progressive photon mapping shows each photon
// pass as it comes: results with rising versions before the last, each
// saying how many passes it holds, then the finished still.
TEST(StillJob, ProgressivePhotonMappingShowsItsPasses) {
  solver_worker worker;
  solver_settings settings = coarse(1e-2);
  settings.max_edge = 0.3;  // metres
  worker.load_file(test_support::source_path("assets/glass_on_table/glass_on_table.json"), settings);
  worker.wait_idle();
  const auto view = worker.latest();
  ASSERT_TRUE(view->mesh && view->solution);
  camera cam = view->source->view;
  cam.width = cam.height = 24;
  trace_params params;
  params.method = integrator::ppm;
  params.spp = 1;
  params.passes = 4;
  params.photons = 20000;
  params.gather_rays = 16;
  still_job job;
  job.start(view->source, cam, view->mesh, view->solution, params);
  std::vector<std::string> summaries;
  std::uint64_t seen = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    const bool running = job.running();
    if (const auto r = job.result(); r && r->version != seen) {
      seen = r->version;
      summaries.push_back(r->summary);
      EXPECT_EQ(r->picture.width, 24);
    }
    if (!running && job.result() && job.result()->version == seen) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_FALSE(summaries.empty());
  EXPECT_NE(summaries.back().find("4 of 4 photon passes"), std::string::npos) << summaries.back();
  // The passes before the last were published too (the polling may miss some).
  EXPECT_GE(summaries.size(), 2u);
  EXPECT_NE(summaries.front().find(" of 4 photon passes"), std::string::npos) << summaries.front();
}

}  // namespace
}  // namespace bounce
