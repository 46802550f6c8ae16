#include "solver_worker.h"

#include <chrono>

#include "scene/scene_io.h"

namespace bounce {

struct solver_worker::command {
  enum class kind { load, load_file, pause, resume, step, restart, criterion } what;
  scene s;
  std::string path;
  solver_settings settings;
  stop_criterion criterion;
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

void solver_worker::load(scene s, const solver_settings& settings) {
  auto c = std::make_unique<command>();
  c->what = command::kind::load;
  c->s = std::move(s);
  c->settings = settings;
  enqueue(std::move(c));
}

void solver_worker::load_file(const std::string& path, const solver_settings& settings) {
  auto c = std::make_unique<command>();
  c->what = command::kind::load_file;
  c->path = path;
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

void solver_worker::wait_idle() const {
  while (!idle_.load()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
}

void solver_worker::handle(command& c) {
  using kind = command::kind;
  switch (c.what) {
    case kind::load_file: {
      load_report report;
      scene s;
      if (!load_scene(c.path, s, report)) {
        error_ = report.error;  // the previous scene stays
        return;
      }
      c.s = std::move(s);
      [[fallthrough]];
    }
    case kind::load: {
      auto s = std::make_shared<const scene>(std::move(c.s));
      auto mesh = std::make_shared<patch_mesh>();
      std::string error;
      if (!make_patch_mesh(*s, mesher_params_for(c.settings, *s), *mesh, error)) {
        error_ = s->source + ": " + error;
        return;
      }
      // The old state refers to the old mesh: replace both together.
      state_.reset();
      scene_ = s;
      mesh_ = mesh;
      state_ = make_radiosity_state(*scene_, *mesh_, radiosity_params_for(c.settings));
      criterion_ = c.settings.stop;
      ++mesh_version_;
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
      if (state_) {
        restart_radiosity(*state_);
        ++run_;
        history_.clear();
        single_step_ = false;
        exhausted_ = false;
      }
      break;
    case kind::criterion:
      criterion_ = c.criterion;
      break;
  }
}

void solver_worker::publish() {
  auto v = std::make_shared<worker_view>();
  v->mesh_version = mesh_version_;
  v->run = run_;
  v->source = scene_;
  v->mesh = state_ && state_->refined_mesh ? state_->refined_mesh : mesh_;  // adaptive meshing refines it
  v->meshed_elements = mesh_ ? mesh_->element_count() : 0;
  if (state_) v->solution = make_snapshot(*state_);
  v->history = history_;
  unpublished_ = false;
  v->error = error_;
  if (state_) {
    v->converged = exhausted_ || stop_reached(*state_, criterion_);
    v->running = !paused_ && !v->converged;
  }
  std::atomic_store(&view_, std::shared_ptr<const worker_view>(std::move(v)));
}

void solver_worker::run() {
  publish();
  for (;;) {
    std::unique_ptr<command> next;
    // Worker-thread state only: no lock needed to decide.
    const bool work = state_ && (!paused_ || single_step_) && !(exhausted_ || stop_reached(*state_, criterion_));
    if (!work) {
      single_step_ = false;         // a step asked for when nothing was left
      if (unpublished_) publish();  // the last step's state, before going idle (outside the lock)
    }
    {
      std::unique_lock lock(mutex_);
      if (queue_.empty() && !work) {
        idle_ = true;
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
    // One shot, then publish if the last view was taken: the view shows
    // the newest iteration at every frame, and no snapshot is built that no
    // frame takes. The shot runs on all cores but one, which stays free for
    // drawing (Mesa's llvmpipe renders on the CPU): the UI must not stall.
    bool stepped = false;
    arena_.execute([&] { stepped = step_radiosity(*state_); });
    exhausted_ = !stepped;  // nothing left: done
    single_step_ = false;
    if (!stepped) continue;
    history_.push_back({state_->stats.seconds, state_->stats.unshot_fraction});
    unpublished_ = true;
    if (wanted_.exchange(false)) publish();
  }
}

}  // namespace bounce
