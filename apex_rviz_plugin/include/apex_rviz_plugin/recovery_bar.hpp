// The bar at the top of the panel that offers the graph a runtime's previous run left unsaved
// (it crashed or was killed: the runtime kept a recovery copy, issue #35). Not modal: the
// person goes on editing and answers when they like. Emits signals only; PanelWidget makes
// the calls (panel_recovery.cpp).
#pragma once

#include <QDateTime>
#include <QFrame>

class QLabel;
class QPushButton;

namespace apex_rviz_plugin {

class RecoveryBar : public QFrame {
  Q_OBJECT
 public:
  explicit RecoveryBar(QWidget* parent = nullptr);
  /** @brief Shows "Unsaved graph from <when> (<nodes> nodes) found", with Restore and Discard. */
  void offer(const QDateTime& when, int nodes);
  /** @brief Hides the bar: nothing is offered (any more). */
  void withdraw();
  /** @brief While an answer is asked for: the buttons wait for it. */
  void setBusy(bool busy);
  QString text() const;

 signals:
  void restoreRequested();
  void discardRequested();

 private:
  QLabel* label_;
  QPushButton *restore_, *discard_;
};

}  // namespace apex_rviz_plugin
