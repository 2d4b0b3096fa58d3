// Starting a Tracker on a box drawn on its frame (TrackerStartView). The window is the starter's
// while it is open (view_); one at a time: a window asked for later closes the one before, and an
// answer for a window no longer the current one is dropped.
#include "apex_rviz_plugin/tracker_starter.hpp"

#include <QTimer>

#include <algorithm>

#include "apex_rviz_plugin/label_windows.hpp"
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

TrackerStarter::TrackerStarter(const PanelContext& context, const LabelWindows& labels, QWidget* owner)
    : ctx_(context), labels_(labels), owner_(owner) {
  connect(&ctx_.link, &RuntimeLink::frameReceived, this, &TrackerStarter::onFrame);
}

void TrackerStarter::start(const QString& tracker) {
  const auto source = outputFeeding(ctx_.model.graph(), tracker.toStdString(), "image");
  if (!source)
    return ctx_.editor.showMessage("nothing feeds " + tracker + "'s image input: link a camera or a player to it first", true);
  if (TrackerStartView* old = view_.data()) {  // one window at a time: the last asked for
    if (!old->hasFrame()) stopFrames(old->source().section('/', 0, -2), old->source().section('/', -1));
    old->close();
  }
  const QString from = QString::fromStdString(source->first), port = QString::fromStdString(source->second);
  auto* view = new TrackerStartView(tracker, from + "/" + port, owner_);
  view_ = view;
  connect(view, &TrackerStartView::boxChosen, this, &TrackerStarter::startOn);
  ctx_.editor.showMessage("fetching the frame " + tracker + " last saw, from " + from + "/" + port, false);
  const QPointer<TrackerStartView> alive(view);
  ctx_.link.inspect(
      source->first, source->second,
      [this, alive, tracker, from, port](bool ok, const std::string& m, const std::string& topic, const std::string&) {
        if (!alive || alive.data() != view_.data()) return;  // another window asked for since
        if (!ok) {
          alive->close();
          return ctx_.report(false, m, "show the frame of " + from + "/" + port);
        }
        watchSource(alive, tracker, from, port, topic);
      });
}

TrackerStartView* TrackerStarter::view() const { return view_.data(); }

void TrackerStarter::watchSource(const QPointer<TrackerStartView>& alive, const QString& tracker, const QString& from,
                                 const QString& port, const std::string& topic) {
  ctx_.link.watchFrames(from.toStdString(), port.toStdString(), topic);
  QTimer::singleShot(kFrameWaitMs, alive.data(), [this, alive, tracker, from, port] {
    if (alive->hasFrame() || alive.data() != view_.data()) return;
    stopFrames(from, port);
    ctx_.editor.showMessage("no frame has reached " + tracker + " yet (" + from + "/" + port +
                                " has sent none): play or step its source, then draw its box",
                            true);
    alive->close();
  });
}

void TrackerStarter::onFrame(const QString& node, const QString& port, const QImage& image, quint64, const QString& encoding) {
  TrackerStartView* view = view_.data();
  if (!view || view->hasFrame() || view->source() != node + "/" + port) return;
  stopFrames(node, port);  // one frame is drawn on
  if (image.isNull()) {
    ctx_.editor.showMessage(node + "/" + port + " sends " + encoding +
                                " images, which cannot be shown here (bgr8, rgb8 and mono8 can, as the Tracker takes)",
                            true);
    view->close();
    return;
  }
  view->showFrame(image);
  ctx_.editor.showMessage("drag a box around the object on the frame " + view->tracker() + " saw", false);
}

void TrackerStarter::stopFrames(const QString& node, const QString& port) {
  // The subscription is one per port: a labelling window on it keeps it.
  if (!labels_.showing(node, port)) ctx_.link.unwatchFrames(node.toStdString(), port.toStdString());
}

void TrackerStarter::startOn(const QString& tracker, const QRect& box) {
  const std::string name = tracker.toStdString();
  const std::vector<std::pair<std::string, std::string>> values{{"x", std::to_string(box.x())},
                                                                {"y", std::to_string(box.y())},
                                                                {"width", std::to_string(box.width())},
                                                                {"height", std::to_string(box.height())}};
  const bool same = std::all_of(values.begin(), values.end(), [&](const auto& v) {
    const apex::ParamInfo* p = ctx_.model.parameter(name, v.first);
    return p && p->value == v.second;
  });
  if (same) {  // a parameter set to its value restarts nothing
    emit fireSlotRequested(tracker, "restart");
    return;
  }
  const std::string where = std::to_string(box.x()) + ", " + std::to_string(box.y()) + ", " + std::to_string(box.width()) + "×" +
                            std::to_string(box.height());
  emit editRequested(ctx_.model.setParameters(name, values, "Start " + name + " on " + where));
}

}  // namespace apex_rviz_plugin
