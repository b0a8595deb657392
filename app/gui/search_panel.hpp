#pragma once
// The Search panel: the method chooser (it switches the simulation's search), the last step's
// counters, per size class, the step time's split and the history plots.
#include <string>
#include <vector>

#include "app/gui/search_history.hpp"
#include "app/gui/sim_thread.hpp"

namespace drumlab::gui {

class GuiWindow;

class SearchPanel {
 public:
  /// Every method the GUI offers (the search methods, each Verlet list, auto); `active` chosen.
  explicit SearchPanel(const std::string& active);
  /// A new snapshot for the plots.
  void add(const FrameSnapshot& s) { history_.add(s); }
  void panel(const GuiWindow& window, SimThread& sim, const FrameSnapshot* s);

 private:
  void counters(const FrameSnapshot& s) const;
  void plots(const FrameSnapshot& s) const;

  std::vector<std::string> methods_;
  int method_index_ = 0;
  SearchHistory history_;
};

}  // namespace drumlab::gui
