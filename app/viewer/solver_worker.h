// The solver on its own thread. The UI sends commands (one queue, owned by
// the worker) and takes the newest published view of the work; it never
// touches solver internals, and no lock is held while stepping or drawing.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <tbb/task_arena.h>

#include "mesh/patch_mesh.h"
#include "radiosity/solver.h"
#include "radiosity/solver_settings.h"
#include "render/mesh_arrays.h"
#include "scene/scene.h"

namespace bounce {

struct convergence_point {
  double seconds;                 // solver time
  double remaining;               // solver_stats::remaining
  std::uint64_t refinements = 0;  // solver_stats::refinements: a new count starts a new curve (links refined)
};

// The convergence history, appended to by the worker after every step and
// published without copying the points: blocks are shared between the
// worker and every view published, and a view sees the first size() points
// (the worker only writes past them). Copying a log copies a few pointers.
class convergence_log {
 public:
  static constexpr std::size_t block_size = 1024;
  void push_back(const convergence_point& p);
  void clear();  // the published views keep their blocks
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const convergence_point& operator[](std::size_t i) const { return (*blocks_[i / block_size])[i % block_size]; }
  const convergence_point& front() const { return (*this)[0]; }
  const convergence_point& back() const { return (*this)[size_ - 1]; }

 private:
  using block = std::array<convergence_point, block_size>;
  std::vector<std::shared_ptr<block>> blocks_;
  std::size_t size_ = 0;
};

// What the UI sees, immutable once published.
struct worker_view {
  std::uint64_t mesh_version = 0;  // changes when a new scene or mesh density is loaded
  std::uint64_t run = 0;           // a new run: changes with every load and restart
  std::shared_ptr<const scene> source;
  // The mesh being solved, which the solution belongs to: a new one with
  // each refinement pass (adaptive meshing). The view uploads it when it
  // changes: the one signal that a mesh is new.
  std::shared_ptr<const patch_mesh> mesh;
  std::size_t meshed_elements = 0;  // elements as the mesher built them
  solver_settings settings;         // the run's: which solver, its parameters, the stopping point
  std::shared_ptr<const radiosity_snapshot> solution;
  // The mesh and the solution as the renderer's buffers take them, built
  // here on the worker: the UI thread only copies them into GL.
  std::shared_ptr<const gl::mesh_arrays> mesh_arrays;     // of `mesh`
  std::shared_ptr<const std::vector<glm::vec3>> colours;  // of `solution`
  convergence_log history;                                // remaining fraction against time since the (re)start
  bool running = false;                                   // stepping now
  bool converged = false;                                 // the stopping criterion holds (or nothing is left)
  std::string error;  // last failure (bad scene, mesh too large); the previous scene stays
  // What loading `source` warned of, one by one (warning_groups.h groups them).
  std::shared_ptr<const std::vector<std::string>> warnings;
  // What the worker does before it can solve, and since when: "loading
  // room.obj", "meshing room.obj", "preparing the solver"; empty while it
  // solves or waits. The window shows it with a running time.
  std::string stage;
  std::chrono::steady_clock::time_point stage_started{};
};

class solver_worker {
 public:
  solver_worker();
  ~solver_worker();  // stops and joins the thread
  solver_worker(const solver_worker&) = delete;
  solver_worker& operator=(const solver_worker&) = delete;

  // Meshes the scene with these settings and starts solving at once;
  // `warnings` are what loading it said, published with it.
  void load(scene s, const solver_settings& settings, std::vector<std::string> warnings = {});
  // Loads a scene file (path) on the worker; errors arrive in the view.
  void load_file(const std::string& path, const solver_settings& settings);
  // Solves the current scene again with other settings (another solver,
  // tolerance or mesh density): re-meshed on the worker, or the same mesh
  // kept when the settings mesh it the same way.
  void reload(const solver_settings& settings);
  void pause();
  void resume();
  void step();     // one step, then paused
  void restart();  // back to B = E; running or paused as before
  void set_criterion(const stop_criterion& criterion);
  // Leads the hierarchical solver's refinement by this camera from now on
  // (none: every part alike), keeping what is refined; later reloads keep it.
  void set_view(const std::optional<camera>& view);

  // The newest published view. Taking it asks for the next: the worker
  // builds a snapshot after a step only when the last one was taken (at
  // most one per frame of the window), and always before it goes idle.
  std::shared_ptr<const worker_view> latest() const {
    wanted_ = true;
    return std::atomic_load(&view_);
  }

  // Blocks until the worker is idle (paused, converged or failed): nothing
  // queued and nothing being worked on. For tests and the scripted window
  // run.
  void wait_idle() const;
  // Whether it is idle now, without waiting.
  bool idle() const;

 private:
  struct command;
  void enqueue(std::unique_ptr<command> c);
  void send(int what);  // a command without arguments
  void run();
  void publish();
  void handle(command& c);
  // Names what the worker starts doing now and publishes it (empty: done).
  void enter_stage(std::string what);

  std::thread thread_;
  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;  // the worker's: a command or quit
  std::deque<std::unique_ptr<command>> queue_;
  bool quit_ = false;
  // Set by the worker when it goes to wait with nothing queued and nothing
  // to do, cleared by every command queued; under mutex_.
  bool idle_ = true;
  mutable std::condition_variable went_idle_;  // wait_idle's

  // Worker-thread state.
  std::shared_ptr<const scene> scene_;
  std::shared_ptr<const std::vector<std::string>> warnings_;  // scene_'s
  std::shared_ptr<const patch_mesh> mesh_;
  // A new scene's surfaces as they come (mesh/preview_mesh.h), shown while
  // its patch mesh is built; null otherwise.
  std::shared_ptr<const patch_mesh> preview_;
  std::shared_ptr<const scene> preview_source_;
  std::unique_ptr<radiosity_solver> solver_;
  solver_settings settings_;
  stop_criterion criterion_;
  bool paused_ = false;
  bool single_step_ = false;
  bool exhausted_ = false;
  std::uint64_t mesh_version_ = 0;
  std::uint64_t run_ = 0;
  convergence_log history_;
  bool unpublished_ = false;  // steps made since the last publish
  mutable std::atomic<bool> wanted_{true};
  std::string error_;
  std::string stage_;
  std::chrono::steady_clock::time_point stage_started_{};

  std::shared_ptr<const worker_view> view_;
  std::shared_ptr<const patch_mesh> arrays_mesh_;  // the mesh mesh_arrays_ were built from
  std::shared_ptr<const gl::mesh_arrays> mesh_arrays_;
  tbb::task_arena arena_{int(std::max(1u, std::thread::hardware_concurrency() - 1))};
};

}  // namespace bounce
