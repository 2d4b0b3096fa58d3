#include "apex_rviz_plugin/transport_bar.hpp"

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
  connect(play_, &QToolButton::clicked, this, [this] { emit parameterEdited("playing", playing_ ? "false" : "true"); });
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
  play_->setText(playing_ ? "❚❚" : "▶");
  play_->setToolTip(playing_ ? "pause: hold this frame; every change downstream runs it again" : "play");
  QString where = "frame " + QString::fromStdString(frame->value);
  if (frame->max < 1e7) where += " / " + QString::number(static_cast<long>(frame->max) + 1);
  if (const apex::ParamInfo* time = param(node, "time"))
    where += " · " + QString::number(std::atof(time->value.c_str()), 'f', 2) + " s";
  label_->setText(playing_ ? where : "held · " + where);
}

QString TransportBar::text() const { return play_->text() + " " + label_->text(); }

}  // namespace apex_rviz_plugin
