// Where the panel puts boxes and where nodes run (placement.cpp): new nodes on free places, a
// loaded graph laid out (graphviz), boxes that grew pushed off the ones below; positions sent as
// set_ui outside the history and reserved until the graph shows them. Tidy and Balance are the
// person's: each is one edit, asked for with editRequested. It owns the places reserved, the box
// sizes last shown and when to lay a graph out.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <QObject>
#include <QPointF>

#include "apex_rviz_plugin/layout.hpp"
#include "apex_rviz_plugin/panel_context.hpp"

namespace apex_rviz_plugin {

class Placement : public QObject {
  Q_OBJECT
 public:
  explicit Placement(const PanelContext& context, QObject* parent = nullptr) : QObject(parent), ctx_(context) {}

  /** @brief Tidy: the nodes shown in layers, where their top-left corner was; one edit. */
  void tidy();
  /** @brief Balance: the runtime proposes thread groups from the nodes' times (~balance), applied
   *  as one edit; the status line says what to expect (and which links would need a Relay). */
  void balance();

  /** @brief A path for a new node of `type` in the subgraph shown, and a free place for a box of
   *  `size` with its top-left corner near `at` (its top-right one if `left_of`); reserved until
   *  the graph shows it. */
  std::pair<std::string, Box> placeNew(const std::string& type, const Box& size, QPointF at, bool left_of = false);
  /** @brief The boxes a new one must not lie on: those shown, and those sent a place not shown there yet. */
  std::vector<Box> takenPlaces() const;
  /** @brief The places the set_ui calls among `calls` send nodes to, taken until the graph shows them there. */
  void reserve(const std::vector<Call>& calls);
  /** @brief The places of a refused edit's set_ui calls: free again. */
  void release(const std::vector<Call>& calls);

  /** @brief A graph is shown: a loaded one at `revision` or later is laid out if its boxes lie on
   *  each other; else nodes without a position get one, or boxes that grew push the ones below. */
  void graphShown(std::uint64_t revision);
  /** @brief A Load answered with the loaded graph's revision: laid out once shown (now, if it is). */
  void loaded(std::uint64_t revision);
  /** @brief The next graph shown is laid out if its boxes lie on each other (a runtime met). */
  void untangleNext() { untangle_ = true; }
  /** @brief Another subgraph shown: its nodes without a position get one once shown. */
  void levelChanged();
  /** @brief The boxes grew (previews on): none lies on another. */
  void pushApart();
  /** @brief Another graph (a Load, a New, another runtime): nothing reserved, no sizes, no Load waited for. */
  void reset();

 signals:
  /** Tidy or Balance as an edit to make (nothing: not possible). */
  void editRequested(const std::optional<Edit>& edit);

 private:
  /** Gives nodes shown without a position one (a graph written by hand, a node added by a
   *  script): laid out in layers beside the others, never on top of one. Not an edit of the
   *  person's: not in the history. */
  void placeUnplaced();
  /** Laid out in layers if the boxes lie on each other (untangle_, cleared); true if so. */
  bool untangle(const std::map<std::string, Box>& boxes);
  /** Sends positions for nodes (set_ui), outside the history. */
  void place(const std::map<std::string, std::pair<double, double>>& positions);
  /** Lays a loaded graph out if its boxes lie on each other (placeUnplaced with untangle_). */
  void untangleLoaded();
  /** Places nodes shown without a position, else pushes boxes that grew apart. */
  void arrangeShown();
  /** Boxes below a box that grew onto them move down (a box is sized to its content). */
  void pushDownUnderGrown();
  void rememberSizes();

  PanelContext ctx_;
  std::map<std::string, Box> placing_;  // where nodes were sent, until the graph shows them there
  std::map<std::string, Box> sizes_;  // the boxes when the graph was shown last
  std::uint64_t untangle_from_ = 0;  // a loaded graph's revision: lay it out when it is shown
  bool untangle_ = true;  // next graph shown: boxes on top of each other are laid out (a Load, a new level)
  int placements_sent_ = 0;  // counts place() calls
};

}  // namespace apex_rviz_plugin
