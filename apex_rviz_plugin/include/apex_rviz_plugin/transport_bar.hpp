// The transport bar of a player node (BagReader, or any node with the same
// parameters and slots): restart, previous, play/pause, next, and which frame
// it is on. The frame slider is the `frame` parameter's own editor below it.
#pragma once

#include <apex/NodeInfo.h>

#include <QWidget>

class QLabel;
class QToolButton;

namespace apex_rviz_plugin {

class TransportBar : public QWidget {
  Q_OBJECT
 public:
  /** @brief Parameters playing and frame, slots restart, previous and next. */
  static bool isPlayer(const apex::NodeInfo& node);
  explicit TransportBar(const apex::NodeInfo& node, QWidget* parent = nullptr);
  /** @brief Shows the node's current values: playing or held, frame k of n. */
  void show(const apex::NodeInfo& node);
  QString text() const;

 signals:
  void parameterEdited(const QString& param, const QString& yaml);
  void slotFired(const QString& slot);

 private:
  QToolButton* play_;
  bool ended_ = false;  // on the last frame of a pass that does not loop: play starts again
  QLabel* label_;
  bool playing_ = false;
};

}  // namespace apex_rviz_plugin
