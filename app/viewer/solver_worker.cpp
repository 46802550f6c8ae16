#include "viewer/solver_worker.h"

#include "mesh/preview_mesh.h"
#include "radiosity/solve.h"
#include "scene/scene_io.h"

namespace bounce {
namespace {

// Whether two sets of mesher parameters build the same mesh.
bool same_meshing(const mesher_params& a, const mesher_params& b) {
  return a.max_edge == b.max_edge && a.crease_angle_degrees == b.crease_angle_degrees && a.patch_edge == b.patch_edge &&
         a.a_priori_min_edge == b.a_priori_min_edge && a.shadow_outlines == b.shadow_outlines;
}

}  // namespace

struct solver_worker::command {
  enum class kind { load, load_file, reload, pause, resume, step, restart, criterion, view } what;
  scene s;
  std::string path;
  solver_settings settings;
  stop_criterion criterion;
  std::optional<camera> view;
  std::vector<std::string> warnings;  // load, load_file: what loading the scene said
};

void convergence_log::push_back(const convergence_point& p) {
  if (size_ % block_size == 0) blocks_.push_back(std::make_shared<block>());
  (*blocks_.back())[size_ % block_size] = p;
  ++size_;
}

void convergence_log::clear() {
  blocks_.clear();
  size_ = 0;
}

solver_worker::solver_worker() : view_(std::make_shared<worker_view>()) {
  thread_ = std::thread([this] { run(); });
}

solver_worker::~solver_worker() {
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void solver_worker::enqueue(std::unique_ptr<command> c) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(c));
    idle_ = false;
  }
  wake_.notify_all();
}

void solver_worker::load(scene s, const solver_settings& settings, std::vector<std::string> warnings) {
  auto c = std::make_unique<command>();
  c->what = command::kind::load;
  c->s = std::move(s);
  c->settings = settings;
  c->warnings = std::move(warnings);
  enqueue(std::move(c));
}

void solver_worker::load_file(const std::string& path, const solver_settings& settings) {
  auto c = std::make_unique<command>();
  c->what = command::kind::load_file;
  c->path = path;
  c->settings = settings;
  enqueue(std::move(c));
}

void solver_worker::reload(const solver_settings& settings) {
  auto c = std::make_unique<command>();
  c->what = command::kind::reload;
  c->settings = settings;
  enqueue(std::move(c));
}

void solver_worker::send(int what) {
  auto c = std::make_unique<command>();
  c->what = static_cast<command::kind>(what);
  enqueue(std::move(c));
}

void solver_worker::pause() {
  send(int(command::kind::pause));
}
void solver_worker::resume() {
  send(int(command::kind::resume));
}
void solver_worker::step() {
  send(int(command::kind::step));
}
void solver_worker::restart() {
  send(int(command::kind::restart));
}

void solver_worker::set_criterion(const stop_criterion& criterion) {
  auto c = std::make_unique<command>();
  c->what = command::kind::criterion;
  c->criterion = criterion;
  enqueue(std::move(c));
}

void solver_worker::set_view(const std::optional<camera>& view) {
  auto c = std::make_unique<command>();
  c->what = command::kind::view;
  c->view = view;
  enqueue(std::move(c));
}

void solver_worker::wait_idle() const {
  std::unique_lock lock(mutex_);
  went_idle_.wait(lock, [this] { return idle_; });
}

bool solver_worker::idle() const {
  std::lock_guard lock(mutex_);
  return idle_;
}

void solver_worker::handle(command& c) {
  using kind = command::kind;
  switch (c.what) {
    case kind::load_file: {
      load_report report;
      scene s;
      enter_stage("loading " + c.path);
      if (!load_scene(c.path, s, report)) {
        error_ = report.error;  // the previous scene stays
        enter_stage("");
        return;
      }
      if (c.settings.view) c.settings.view = s.view;  // a scene opened is first led by its own camera
      c.s = std::move(s);
      c.warnings = std::move(report.warnings);
      [[fallthrough]];
    }
    case kind::reload:
    case kind::load: {
      if (c.what == kind::reload && !scene_) return;  // nothing loaded yet
      // A reload keeps the scene (no copy) and, when the new settings mesh
      // it as before, the mesh: a new solver or tolerance only restarts.
      auto s = c.what == kind::reload ? scene_ : std::make_shared<const scene>(std::move(c.s));
      const mesher_params meshing = mesher_params_for(c.settings, *s);
      const bool same_mesh = c.what == kind::reload && mesh_ && same_meshing(meshing, mesher_params_for(settings_, *s));
      std::shared_ptr<const patch_mesh> mesh = mesh_;
      if (!same_mesh) {
        // The old run (its links may take hundreds of MiB) goes before the
        // new mesh is built.
        if (c.what == kind::reload) solver_.reset();
        solve_setup fresh;
        std::string error;
        if (c.what != kind::reload) {  // a new scene: its shape at once (a reload shows the old mesh meanwhile)
          enter_stage("tessellating " + s->source);
          preview_ = std::make_shared<const patch_mesh>(make_preview_mesh(*s));
          preview_source_ = s;
        }
        enter_stage("meshing " + s->source);
        const bool meshed = mesh_for_solve(*s, c.settings, fresh, error);
        preview_.reset();
        preview_source_.reset();
        if (!meshed) {
          error_ = s->source + ": " + error;
          enter_stage("");
          if (!solver_ && mesh_) {  // the previous run starts again
            solver_ = make_solver_for(*scene_, *mesh_, settings_);
            ++run_;
            history_.clear();
            exhausted_ = false;
          }
          return;
        }
        mesh = fresh.mesh;
      }
      solver_.reset();
      if (s != scene_) warnings_ = std::make_shared<const std::vector<std::string>>(std::move(c.warnings));
      scene_ = s;
      mesh_ = mesh;
      settings_ = c.settings;
      enter_stage("preparing the solver");
      solver_ = make_solver_for(*scene_, *mesh_, c.settings);
      stage_.clear();  // published with the new run below
      criterion_ = c.settings.stop;
      if (!same_mesh) ++mesh_version_;
      ++run_;
      history_.clear();
      error_.clear();
      paused_ = false;
      single_step_ = false;
      exhausted_ = false;
      break;
    }
    case kind::pause:
      paused_ = true;
      break;
    case kind::resume:
      paused_ = false;
      break;
    case kind::step:
      paused_ = true;
      single_step_ = true;
      break;
    case kind::restart:
      if (solver_) {
        restart_solver(*solver_);
        ++run_;
        history_.clear();
        single_step_ = false;
        exhausted_ = false;
      }
      break;
    case kind::criterion:
      criterion_ = c.criterion;
      break;
    case kind::view:
      settings_.view = c.view;
      if (solver_) {
        set_solver_view(*solver_, c.view);
        exhausted_ = false;  // the links are refined again for the new view
      }
      break;
  }
}

void solver_worker::enter_stage(std::string what) {
  stage_ = std::move(what);
  stage_started_ = std::chrono::steady_clock::now();
  publish();
}

void solver_worker::publish() {
  auto v = std::make_shared<worker_view>();
  v->mesh_version = mesh_version_;
  v->run = run_;
  v->source = preview_ ? preview_source_ : scene_;
  v->warnings = warnings_;
  v->mesh = preview_                            ? preview_
            : solver_ && refined_mesh(*solver_) ? refined_mesh(*solver_)
                                                : mesh_;  // the solver may refine it
  v->meshed_elements = mesh_ && !preview_ ? mesh_->element_count() : 0;
  v->settings = settings_;
  v->settings.stop = criterion_;
  if (v->mesh != arrays_mesh_) {  // once per mesh: a large one takes a while
    mesh_arrays_.reset();
    if (v->mesh) mesh_arrays_ = std::make_shared<const gl::mesh_arrays>(gl::make_mesh_arrays(*v->mesh, v->source));
    arrays_mesh_ = v->mesh;
  }
  v->mesh_arrays = mesh_arrays_;
  if (solver_ && !preview_) {  // an old scene's solver, while a new one is meshed, is not shown
    v->solution = make_snapshot(*solver_);
    v->colours = std::make_shared<const std::vector<glm::vec3>>(gl::solution_colours(*v->solution));
  }
  v->history = history_;
  unpublished_ = false;
  v->error = error_;
  v->stage = stage_;
  v->stage_started = stage_started_;
  if (solver_ && !preview_) {
    v->converged = exhausted_ || stop_reached(*solver_, criterion_);
    v->running = !paused_ && !v->converged;
  }
  std::atomic_store(&view_, std::shared_ptr<const worker_view>(std::move(v)));
}

void solver_worker::run() {
  publish();
  for (;;) {
    std::unique_ptr<command> next;
    // Worker-thread state only: no lock needed to decide.
    const bool work = solver_ && (!paused_ || single_step_) && !(exhausted_ || stop_reached(*solver_, criterion_));
    if (!work) {
      single_step_ = false;         // a step asked for when nothing was left
      if (unpublished_) publish();  // the last step's state, before going idle (outside the lock)
    }
    {
      std::unique_lock lock(mutex_);
      if (queue_.empty() && !work) {
        idle_ = true;
        went_idle_.notify_all();
        wake_.wait(lock, [this] { return quit_ || !queue_.empty(); });
      }
      if (quit_) return;
      if (!queue_.empty()) {
        next = std::move(queue_.front());
        queue_.pop_front();
      }
    }
    if (next) {
      handle(*next);
      publish();
      continue;
    }
    // One step, then publish if the last view was taken: the view shows
    // the newest iteration at every frame, and no snapshot is built that no
    // frame takes. The step runs on all cores but one, which stays free for
    // drawing (Mesa's llvmpipe renders on the CPU): the UI must not stall.
    bool stepped = false;
    arena_.execute([&] { stepped = step_solver(*solver_); });
    exhausted_ = !stepped;  // nothing left: done
    single_step_ = false;
    if (!stepped) continue;
    history_.push_back({solver_->stats.seconds, solver_->stats.remaining, solver_->stats.refinements});
    unpublished_ = true;
    if (wanted_.exchange(false)) publish();
  }
}

}  // namespace bounce
