// The panel's side of starting a Tracker on a box drawn on its frame (TrackerStartView): the
// output feeding its image input is inspected, and the frame it holds (the one the Tracker last
// saw: the runtime sends it again to a new subscriber) opens the window; the box drawn becomes the
// Tracker's x, y, width and height in one edit, and setting them restarts it on that box. The
// window is the panel's while it is open (tracker_start_); one at a time.
#include <QTimer>

#include <algorithm>

#include "apex_rviz_plugin/label_view.hpp"
#include "apex_rviz_plugin/panel_widget.hpp"
#include "apex_rviz_plugin/tracker_start.hpp"

namespace apex_rviz_plugin {
namespace {

constexpr int kFrameWaitMs = 3000;  // a held frame comes within a round trip; none by then: none was sent

/** The output whose messages reach `node`'s `port`: through the exports of the subgraphs around
 *  it, to the data link outside; nothing if none is linked. */
std::optional<std::pair<std::string, std::string>> outputFeeding(const apex::GraphState& g, std::string node, std::string port) {
  for (std::size_t hops = 0; hops <= g.connections.size(); ++hops) {
    const auto in = std::find_if(g.connections.begin(), g.connections.end(), [&](const apex::Connection& c) {
      return c.to_node == node && c.to_port == port && (c.kind == "data" || c.kind == "export");
    });
    if (in == g.connections.end()) return std::nullopt;
    if (in->kind == "data") return std::make_pair(in->from_node, in->from_port);
    node = in->from_node, port = in->from_port;  // a subgraph's input, exported to the node inside it
  }
  return std::nullopt;
}

}  // namespace

void PanelWidget::startTrackerOnDrawnBox(const QString& tracker) {
  const auto source = outputFeeding(model_.graph(), tracker.toStdString(), "image");
  if (!source)
    return editor_->showMessage("nothing feeds " + tracker + "'s image input: link a camera or a player to it first", true);
  if (TrackerStartView* old = tracker_start_.data()) {  // one window at a time: the last asked for
    if (!old->hasFrame()) stopTrackerFrames(old->source().section('/', 0, -2), old->source().section('/', -1));
    old->close();
  }
  const QString from = QString::fromStdString(source->first), port = QString::fromStdString(source->second);
  auto* view = new TrackerStartView(tracker, from + "/" + port, this);
  tracker_start_ = view;
  connect(view, &TrackerStartView::boxChosen, this, &PanelWidget::startTrackerOn);
  editor_->showMessage("fetching the frame " + tracker + " last saw, from " + from + "/" + port, false);
  const QPointer<TrackerStartView> alive(view);
  link_.inspect(source->first, source->second,
                [this, alive, tracker, from, port](bool ok, const std::string& m, const std::string& topic, const std::string&) {
                  if (!alive || alive.data() != tracker_start_.data()) return;  // another window asked for since
                  if (!ok) {
                    alive->close();
                    return report(false, m, "show the frame of " + from + "/" + port);
                  }
                  link_.watchFrames(from.toStdString(), port.toStdString(), topic);
                  QTimer::singleShot(kFrameWaitMs, alive.data(), [this, alive, tracker, from, port] {
                    if (alive->hasFrame() || alive.data() != tracker_start_.data()) return;
                    stopTrackerFrames(from, port);
                    editor_->showMessage("no frame has reached " + tracker + " yet (" + from + "/" + port +
                                             " has sent none): play or step its source, then draw its box",
                                         true);
                    alive->close();
                  });
                });
}

TrackerStartView* PanelWidget::trackerStartView() const { return tracker_start_.data(); }

void PanelWidget::onTrackerFrame(const QString& node, const QString& port, const QImage& image, quint64,
                                 const QString& encoding) {
  TrackerStartView* view = tracker_start_.data();
  if (!view || view->hasFrame() || view->source() != node + "/" + port) return;
  stopTrackerFrames(node, port);  // one frame is drawn on
  if (image.isNull()) {
    editor_->showMessage(node + "/" + port + " sends " + encoding +
                             " images, which cannot be shown here (bgr8, rgb8 and mono8 can, as the Tracker takes)",
                         true);
    view->close();
    return;
  }
  view->showFrame(image);
  editor_->showMessage("drag a box around the object on the frame " + view->tracker() + " saw", false);
}

void PanelWidget::stopTrackerFrames(const QString& node, const QString& port) {
  // The subscription is one per port: a labelling window on it keeps it.
  if (LabelView* labelling = labelView(node, port); !labelling || !labelling->isVisible())
    link_.unwatchFrames(node.toStdString(), port.toStdString());
}

void PanelWidget::startTrackerOn(const QString& tracker, const QRect& box) {
  const std::string name = tracker.toStdString();
  const std::vector<std::pair<std::string, std::string>> values{{"x", std::to_string(box.x())},
                                                                {"y", std::to_string(box.y())},
                                                                {"width", std::to_string(box.width())},
                                                                {"height", std::to_string(box.height())}};
  const bool same = std::all_of(values.begin(), values.end(), [&](const auto& v) {
    const apex::ParamInfo* p = model_.parameter(name, v.first);
    return p && p->value == v.second;
  });
  if (same) return onFireSlotRequested(tracker, "restart");  // a parameter set to its value restarts nothing
  const std::string where = std::to_string(box.x()) + ", " + std::to_string(box.y()) + ", " + std::to_string(box.width()) + "×" +
                            std::to_string(box.height());
  perform(model_.setParameters(name, values, "Start " + name + " on " + where));
}

}  // namespace apex_rviz_plugin
