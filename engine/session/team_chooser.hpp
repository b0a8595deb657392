#pragma once
// How many OpenMP threads the next steps get, when the user asked for N > 1 on a machine that
// others may share. Two threads whose partner is descheduled wait at every barrier of the step,
// and on a busy machine two threads have run at 0.6x one thread (app/bench/README.md, "Threads
// on a shared machine"). The results are the same bits for any thread count, so a run may
// change its team between steps: this chooser times windows of steps, runs with the team that
// was faster, and now and then times one window with the other team to follow the machine.
//
// The teams are N and 1, timed in windows of kWindowSteps steps. The first two windows time each;
// after that the faster team runs `probe_every` windows, then the other team runs one, and the team
// whose latest time per step is lower (by more than `margin`, against flip-flopping on noise) runs
// next. Each probe the other team loses doubles the windows before the next one, up to
// kMaxBackoff x probe_every (a steadily busy machine then pays one slow window in 81, not in 21);
// a change of team starts again from probe_every.
#include <algorithm>
#include <cstdint>
#include <string>

namespace drumlab {

class TeamChooser {
 public:
  static constexpr std::uint64_t kWindowSteps = 100;
  static constexpr int kProbeEvery = 20;
  static constexpr double kMargin = 0.05;
  static constexpr int kMaxBackoff = 4;

  /// threads: the team the user asked for (with 1 the chooser always answers 1).
  explicit TeamChooser(int threads, int probe_every = kProbeEvery, double margin = kMargin)
      : full_(threads < 1 ? 1 : threads),
        probe_every_(probe_every),
        interval_(probe_every),
        margin_(margin) {}

  /// The team for the next steps.
  int team() const { return full_ == 1 ? 1 : (probing_ ? other(current_) : current_); }

  /// Records `steps` steps just run with team() in `seconds`. A window closes once it holds
  /// kWindowSteps steps (several calls if the caller stops more often, for frames).
  void record(double seconds, std::uint64_t steps) {
    if (full_ == 1) return;
    window_seconds_ += seconds;
    window_steps_ += steps;
    if (window_steps_ < kWindowSteps) return;
    close_window(window_seconds_ / static_cast<double>(window_steps_));
    window_seconds_ = 0.0;
    window_steps_ = 0;
  }

  /// Windows run so far with the full team and with one thread.
  std::uint64_t full_windows() const { return full_windows_; }
  std::uint64_t single_windows() const { return one_windows_; }
  int threads() const { return full_; }
  /// Windows of the current team between two probes now.
  int probe_interval() const { return interval_; }

 private:
  int other(int team) const { return team == full_ ? 1 : full_; }

  // The current team's time per step is the mean of its latest windows (halving the weight of
  // each older one: a window's Verlet rebuilds make single windows noisy); a probe's is its one
  // window's.
  void close_window(double per_step) {
    const int ran = team();
    (ran == full_ ? full_windows_ : one_windows_) += 1;
    double& time = ran == full_ ? full_time_ : one_time_;
    const bool first_time = time < 0.0;
    time = probing_ || first_time ? per_step : 0.5 * (time + per_step);
    if (probing_) {
      probing_ = false;
      since_probe_ = 0;
      const double theirs = current_ == full_ ? one_time_ : full_time_;
      const double mine = current_ == full_ ? full_time_ : one_time_;
      if (theirs < (1.0 - margin_) * mine) {
        current_ = other(current_);
        (current_ == full_ ? full_time_ : one_time_) = theirs;
        interval_ = probe_every_;
      } else if (!first_time) {
        interval_ = std::min(2 * interval_, kMaxBackoff * probe_every_);
      }
    } else if (++since_probe_ >= (full_time_ < 0.0 || one_time_ < 0.0 ? 1 : interval_)) {
      probing_ = true;
    }
  }

  int full_;
  int probe_every_;
  int interval_;  ///< windows between probes now: probe_every_ to kMaxBackoff x probe_every_
  double margin_;
  int current_ = full_;
  bool probing_ = false;
  int since_probe_ = 0;
  double window_seconds_ = 0.0;
  std::uint64_t window_steps_ = 0;
  double full_time_ = -1.0;  ///< time per step with the full team (< 0: none yet)
  double one_time_ = -1.0;
  std::uint64_t full_windows_ = 0;
  std::uint64_t one_windows_ = 0;
};

/// "adaptive: N thread(s) in F of W windows of 100 steps, 1 in S": what a run says of its team.
std::string team_report(const TeamChooser& t);

}  // namespace drumlab
