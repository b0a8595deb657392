#include "app/gui/sim_thread.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <utility>

#include <fmt/format.h>

#include "engine/threads.hpp"

namespace drumlab::gui {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

SimThread::SimThread(SceneConfig scene, SessionOptions options, SnapshotWish wish, int threads,
                     std::optional<ScheduledSwitch> scheduled, std::uint64_t step_limit)
    : options_(std::move(options)),
      session_(std::make_unique<RunSession>(std::move(scene), options_)),
      scheduled_(std::move(scheduled)),
      step_limit_(step_limit),
      threads_(threads),
      scene_(session_->scene()),
      wish_(std::move(wish)) {
  if (wish_.view.focus_id) {  // an unknown id is bad input: one line, before any window opens
    render::index_of_id(session_->simulation().particles(), *wish_.view.focus_id);
  }
  thread_ = std::thread([this] { loop(); });
}

SimThread::~SimThread() {
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

std::shared_ptr<const FrameSnapshot> SimThread::latest() const {
  std::lock_guard lock(mutex_);
  taken_generation_ = generation_;
  return latest_;
}

std::uint64_t SimThread::generation() const {
  std::lock_guard lock(mutex_);
  return generation_;
}

void SimThread::set_running(bool running) {
  {
    std::lock_guard lock(mutex_);
    running_ = running;
  }
  cv_.notify_all();
}

bool SimThread::running() const {
  std::lock_guard lock(mutex_);
  return running_;
}

void SimThread::single_step() {
  {
    std::lock_guard lock(mutex_);
    if (!running_) step_once_ = true;
  }
  cv_.notify_all();
}

void SimThread::set_chunk(std::uint64_t steps) {
  std::lock_guard lock(mutex_);
  chunk_ = std::max<std::uint64_t>(1, steps);
}

void SimThread::switch_method(const std::string& name) {
  {
    std::lock_guard lock(mutex_);
    pending_method_ = name;
  }
  cv_.notify_all();
}

void SimThread::restart(SceneConfig scene) {
  {
    std::lock_guard lock(mutex_);
    pending_restart_ = std::move(scene);
  }
  cv_.notify_all();
}

void SimThread::set_wish(SnapshotWish wish) {
  {
    std::lock_guard lock(mutex_);
    wish_ = std::move(wish);
    snapshot_due_ = true;
  }
  cv_.notify_all();
}

void SimThread::with_simulation(const std::function<void(const Simulation&)>& job) {
  std::unique_lock lock(mutex_);
  std::exception_ptr failure;
  bool done = false;
  pending_job_ = [&](const Simulation& sim) {
    try {
      job(sim);
    } catch (...) {
      failure = std::current_exception();
    }
    done = true;
  };
  cv_.notify_all();
  cv_.wait(lock, [&] { return done || quit_; });
  if (failure) std::rethrow_exception(failure);
}

SceneConfig SimThread::scene() const {
  std::lock_guard lock(mutex_);
  return scene_;
}

std::string SimThread::state_text() const {
  std::lock_guard lock(mutex_);
  if (!error_.empty()) return error_;
  if (settling_) {
    return fmt::format("settling (drum at rest) {} / {} steps{}", settle_done_, settle_total_,
                       running_ ? "" : ", paused");
  }
  if (finished_) return "done";
  return running_ ? "running" : "paused";
}

bool SimThread::finished() const {
  std::lock_guard lock(mutex_);
  return finished_;
}

double SimThread::particle_steps_per_second() const {
  std::lock_guard lock(mutex_);
  return step_seconds_ > 0.0 ? particle_steps_ / step_seconds_ : 0.0;
}

std::pair<double, double> SimThread::stepping_totals() const {
  std::lock_guard lock(mutex_);
  return {particle_steps_, step_seconds_};
}

std::optional<TeamChooser> SimThread::team() const {
  std::lock_guard lock(mutex_);
  return team_;
}

void SimThread::note_team() {
  if (const TeamChooser* chooser = session_->team_chooser()) team_ = *chooser;
}

bool SimThread::settled() const {
  std::lock_guard lock(mutex_);
  return settled_;
}

void SimThread::wait_finished() const {
  std::unique_lock lock(mutex_);
  cv_.wait(lock, [&] { return finished_ || quit_; });
}

SnapshotWish SimThread::current_wish() const {
  std::lock_guard lock(mutex_);
  return wish_;
}

void SimThread::publish(const SnapshotWish& wish) {
  SnapshotRequest request;
  request.compare_methods = wish.compare_methods;
  auto snap = std::make_shared<FrameSnapshot>(
      render::view_snapshot(session_->simulation(), wish.view, request));
  std::lock_guard lock(mutex_);
  latest_ = std::move(snap);
  ++generation_;
}

void SimThread::run_pending_job() {
  auto job = std::move(pending_job_);
  pending_job_ = nullptr;
  job(session_->simulation());  // under the lock: the UI thread waits for it anyway
  cv_.notify_all();
}

bool SimThread::settle_progress() {
  {
    std::lock_guard lock(mutex_);
    settle_done_ = session_->simulation().steps();
  }
  publish(current_wish());
  std::unique_lock lock(mutex_);
  for (;;) {  // paused inside the settling: wait here, serving exports and new wishes
    cv_.wait(lock, [&] {
      return quit_ || pending_restart_ || pending_job_ || snapshot_due_ || running_ || step_once_;
    });
    if (pending_job_) run_pending_job();
    if (quit_ || pending_restart_) return false;
    if (running_ || step_once_) {
      step_once_ = false;
      return true;
    }
    if (snapshot_due_) {
      snapshot_due_ = false;
      const SnapshotWish wish = wish_;
      lock.unlock();
      publish(wish);
      lock.lock();
    }
  }
}

SimThread::Command SimThread::take_command(std::unique_lock<std::mutex>& lock) {
  using Kind = Command::Kind;
  for (;;) {
    cv_.wait(lock, [&] {
      return quit_ || pending_restart_ || pending_job_ || pending_method_ || snapshot_due_ ||
             (!finished_ && (running_ || step_once_));
    });
    Command c;
    if (quit_) return c;
    if (pending_restart_) {
      c.kind = Kind::restart;
      c.scene = std::move(*pending_restart_);
      pending_restart_.reset();
      return c;
    }
    if (pending_job_) run_pending_job();
    if (pending_method_) {
      c.kind = Kind::switch_method;
      c.method = std::move(*pending_method_);
      pending_method_.reset();
      return c;
    }
    if (snapshot_due_) {
      snapshot_due_ = false;
      c.kind = Kind::snapshot;
      c.wish = wish_;
      return c;
    }
    if (finished_ || !(running_ || step_once_)) continue;  // a job only
    c.particles = static_cast<double>(session_->simulation().particles().size());
    if (!settled_) {
      c.kind = Kind::settle;
      settling_ = true;
      settle_done_ = 0;
      settle_total_ = session_->settle_steps();
      return c;
    }
    const std::uint64_t done = session_->simulation().steps() - turn_start_;
    c.kind = Kind::advance;
    c.steps = chunk_;
    if (scheduled_ && done < scheduled_->step) c.steps = std::min(c.steps, scheduled_->step - done);
    if (step_limit_ > 0) c.steps = std::min(c.steps, step_limit_ - std::min(step_limit_, done));
    step_once_ = false;
    return c;
  }
}

void SimThread::restart_session(SceneConfig scene) {
  std::unique_ptr<RunSession> fresh;
  std::string error;
  try {
    fresh = std::make_unique<RunSession>(std::move(scene), options_);
  } catch (const std::exception& e) {
    error = fmt::format("restart refused: {}", e.what());
  }
  if (fresh) session_ = std::move(fresh);  // the UI thread never reads session_
  std::lock_guard lock(mutex_);
  if (error.empty()) {
    scene_ = session_->scene();
    settled_ = false;
  }
  error_ = error;
  running_ = false;
  finished_ = false;
  snapshot_due_ = true;
}

void SimThread::switch_search(const std::string& name) {
  std::string error;
  try {
    session_->set_search_method(name);
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::lock_guard lock(mutex_);
  scene_ = session_->scene();
  error_ = error;
  snapshot_due_ = true;
}

void SimThread::settle(double particles) {
  const auto t0 = std::chrono::steady_clock::now();
  session_->settle([this](std::uint64_t, std::uint64_t) { return settle_progress(); });
  const double dt = seconds_since(t0);
  SnapshotWish wish;
  {
    std::lock_guard lock(mutex_);
    settling_ = false;
    if (pending_restart_ || quit_) return;  // stopped inside the settling
    step_seconds_ += dt;
    particle_steps_ += particles * static_cast<double>(settle_total_);
    note_team();
    settled_ = true;
    turn_start_ = session_->simulation().steps();
    wish = wish_;
  }
  publish(wish);
}

void SimThread::advance(std::uint64_t steps, double particles) {
  const auto t0 = std::chrono::steady_clock::now();
  if (steps > 0) session_->advance(steps);
  const double dt = seconds_since(t0);
  const std::uint64_t done = session_->simulation().steps() - turn_start_;
  const bool switched = scheduled_ && done == scheduled_->step;
  if (switched) {
    session_->set_search_method(scheduled_->method);
    scheduled_.reset();
  }
  const bool last = step_limit_ > 0 && done >= step_limit_;
  std::optional<SnapshotWish> wish;
  {
    std::lock_guard lock(mutex_);
    if (switched) scene_ = session_->scene();
    step_seconds_ += dt;
    particle_steps_ += particles * static_cast<double>(steps);
    note_team();
    // A snapshot when the UI has taken the last one (it draws no faster than that), when not
    // running on, and at the end.
    if (taken_generation_ == generation_ || !running_ || last) wish = wish_;
  }
  if (wish) publish(*wish);
  if (!last) return;
  std::lock_guard lock(mutex_);  // finished only once the last snapshot is there
  finished_ = true;
  running_ = false;
  cv_.notify_all();
}

void SimThread::stop(const std::exception& e) {
  std::lock_guard lock(mutex_);
  settling_ = false;
  error_ = fmt::format("stopped: {}", e.what());
  finished_ = true;
  running_ = false;
  cv_.notify_all();
}

void SimThread::loop() {
  using Kind = Command::Kind;
  set_thread_count(threads_);  // OpenMP's count is this thread's own
  for (;;) {
    Command c;
    {
      std::unique_lock lock(mutex_);
      c = take_command(lock);
    }
    try {
      switch (c.kind) {
        case Kind::quit:
          cv_.notify_all();
          return;
        case Kind::restart:
          restart_session(std::move(c.scene));
          break;
        case Kind::switch_method:
          switch_search(c.method);
          break;
        case Kind::snapshot:
          publish(c.wish);
          break;
        case Kind::settle:
          settle(c.particles);
          break;
        case Kind::advance:
          advance(c.steps, c.particles);
          break;
      }
    } catch (const std::exception& e) {
      stop(e);
    }
  }
}

}  // namespace drumlab::gui
