// The previews on the nodes in view.
#include "apex_rviz_plugin/previews.hpp"

#include <QGraphicsView>

namespace apex_rviz_plugin {
namespace {

std::pair<std::string, std::string> nodeAndPort(const std::string& key) {
  const auto slash = key.rfind('/');
  return {key.substr(0, slash), key.substr(slash + 1)};
}

}  // namespace

Previews::Previews(const PanelContext& context, QObject* parent) : QObject(parent), ctx_(context) {
  connect(&timer_, &QTimer::timeout, this, &Previews::update);
}

void Previews::setOn(bool on) {
  on_ = on;
  if (on) timer_.start(300);
  else timer_.stop();
  update();
}

void Previews::update() {
  QGraphicsView* view = ctx_.editor.view();
  const QRectF seen = view->mapToScene(view->viewport()->rect()).boundingRect();
  std::set<std::string> wanted;
  for (const auto& [name, item] : ctx_.editor.scene()->nodes()) {
    item->setPreviews(on_);
    if (!on_ || !seen.intersects(item->sceneBoundingRect())) continue;  // out of view: not previewed
    for (const auto& port : item->previewPorts()) wanted.insert(name + "/" + port);
  }
  for (auto it = previewing_.begin(); it != previewing_.end();) {  // no longer wanted: unsubscribed
    if (wanted.count(*it)) {
      ++it;
      continue;
    }
    const auto [node, port] = nodeAndPort(*it);
    ctx_.link.unwatchPreview(node, port);
    it = previewing_.erase(it);
  }
  for (const auto& key : wanted)
    if (previewing_.insert(key).second) start(key);
}

void Previews::start(const std::string& key) {
  const auto [node, port] = nodeAndPort(key);
  ctx_.link.inspect(
      node, port,
      [this, node = node, port = port, key](bool ok, const std::string&, const std::string& topic, const std::string& type) {
        if (ok) ctx_.editor.showMessageType(QString::fromStdString(node), QString::fromStdString(port), type);
        if (!ok || !previewing_.count(key) || !on_) return previewing_.erase(key), void();
        ctx_.link.watchPreview(node, port, topic, type);
      },
      true);
}

void Previews::again() {
  for (const auto& key : previewing_) {
    const auto [node, port] = nodeAndPort(key);
    ctx_.link.unwatchPreview(node, port);
  }
  previewing_.clear();  // a load ends the runtime's previews: asked for again by the next update
}

}  // namespace apex_rviz_plugin
