#include "apex_rviz_plugin/transport_bar.hpp"

#include "apex_rviz_plugin/box_view.hpp"

#include <QHBoxLayout>
#include <QLabel>
#include <QToolButton>
#include <QVBoxLayout>

#include <algorithm>
#include <cstdlib>

namespace apex_rviz_plugin {
namespace {

const apex::ParamInfo* param(const apex::NodeInfo& n, const std::string& name) {
  for (const auto& p : n.parameters)
    if (p.name == name) return &p;
  return nullptr;
}

bool hasSlot(const apex::NodeInfo& n, const std::string& name) {
  return std::any_of(n.ports.begin(), n.ports.end(), [&](const apex::PortInfo& p) { return p.kind == "slot" && p.name == name; });
}

}  // namespace

bool TransportBar::isPlayer(const apex::NodeInfo& n) {
  return param(n, "playing") && param(n, "frame") && hasSlot(n, "restart") && hasSlot(n, "previous") && hasSlot(n, "next");
}

TransportBar::TransportBar(const apex::NodeInfo& node, QWidget* parent) : QWidget(parent) {
  setObjectName(QString::fromStdString("transport_" + node.name));
  auto* column = new QVBoxLayout(this);
  column->setContentsMargins(0, 0, 0, 0);
  column->setSpacing(0);
  auto* row = new QHBoxLayout;
  row->setSpacing(2);
  column->addLayout(row);
  auto button = [&](const QString& text, const QString& tip) {
    auto* b = new QToolButton;
    b->setText(text);
    b->setToolTip(tip);
    b->setAutoRaise(true);
    row->addWidget(b);
    return b;
  };
  connect(button("|◀", "back to the first frame"), &QToolButton::clicked, this, [this] { emit slotFired("restart"); });
  connect(button("◀", "previous frame"), &QToolButton::clicked, this, [this] { emit slotFired("previous"); });
  play_ = button("▶", "play");
  play_->setObjectName("play");
  connect(play_, &QToolButton::clicked, this, [this] {
    if (ended_ && playing_) return emit slotFired("restart");  // from the first frame, again
    emit parameterEdited("playing", playing_ ? "false" : "true");
  });
  connect(button("▶|", "next frame"), &QToolButton::clicked, this, [this] { emit slotFired("next"); });
  row->addStretch(1);
  label_ = new QLabel;
  label_->setObjectName("where");
  column->addWidget(label_);
  show(node);
}

void TransportBar::show(const apex::NodeInfo& node) {
  const apex::ParamInfo* playing = param(node, "playing");
  const apex::ParamInfo* frame = param(node, "frame");
  if (!playing || !frame) return;
  playing_ = playing->value == "true";
  const apex::ParamInfo* time = param(node, "time");
  const apex::ParamInfo* loop = param(node, "loop");
  const std::string where = playerPlace(std::atol(frame->value.c_str()), static_cast<long>(frame->max), frame->max < 1e7,
                                        time ? std::atof(time->value.c_str()) : 0.0, playing_, loop && loop->value == "true");
  ended_ = where.rfind("ended", 0) == 0;
  play_->setText(playing_ && !ended_ ? "❚❚" : "▶");
  play_->setToolTip(ended_     ? "the bag's end: play it again from the first frame"
                    : playing_ ? "pause: hold this frame; every change downstream runs it again"
                               : "play");
  label_->setText(QString::fromStdString(where));
}

QString TransportBar::text() const { return play_->text() + " " + label_->text(); }

}  // namespace apex_rviz_plugin
