#pragma once
// The teaching mode: one particle's search walked cell by cell with each cell-grid method
// (m1..m5), played, stepped or cycled through the methods in its panel. It turns the shown
// snapshot into the one drawn (a prefix of the focus particle's search by the chosen method).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/gui/gui_options.hpp"
#include "app/gui/teach_steps.hpp"
#include "engine/session/frame_snapshot.hpp"

namespace drumlab::gui {

class GuiWindow;

class Teaching {
 public:
  /// --teach, --teach-method, --teach-cells; throws InputError for a method it does not walk.
  explicit Teaching(const GuiOptions& options);

  bool on() const { return on_; }
  /// The methods each snapshot must replay for the panel: all it walks while on with a focus.
  std::vector<std::string> compare_methods(bool focus) const;
  /// A new focus: show its whole search until one steps.
  void show_whole_search() { step_ = kWhole; }
  /// The method and the cells shown (the view draws anew when they change).
  std::pair<int, int> key() const { return {method_, step_}; }
  /// The snapshot as drawn: while on, a prefix of the focus particle's search by the chosen
  /// method (`generation` names `s`); otherwise `s`.
  FrameSnapshot display_snapshot(const FrameSnapshot& s, std::uint64_t generation);
  /// The panel (collapsed when off; opening it turns the mode on); true when on() changed (the
  /// snapshot's wish changes). `now`: s, for playing.
  bool panel(const GuiWindow& window, const FrameSnapshot* s, std::uint64_t generation,
             std::optional<Index> focus_id, double now);
  /// One line about the walk shown in `s` (headless runs), e.g. "teach m2: cells 1 / 9, ...";
  /// empty when nothing is walked.
  std::string report(const FrameSnapshot& s, std::uint64_t generation);

 private:
  static constexpr int kWhole = 1 << 30;  ///< cells shown: the whole search (clamped)
  /// The method chooser and the walk's buttons (playing advances the walk).
  void walk_controls(const FrameSnapshot& s, std::uint64_t generation, double now);
  void method_table(const FrameSnapshot& s, std::optional<Index> focus_id) const;

  bool on_ = false;
  int method_ = 0;     ///< index into methods_
  int step_ = kWhole;  ///< cells shown (clamped: the whole search until one steps)
  bool play_ = false;
  bool cycle_ = false;  ///< m1..m5 one after another
  double last_advance_ = 0.0;
  std::vector<std::string> methods_;
  std::optional<TeachWalk> walk_;
  std::uint64_t walk_generation_ = 0;
  int walk_method_ = -1;
};

}  // namespace drumlab::gui
