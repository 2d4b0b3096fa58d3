// A widget for one parameter, fitting its kind: slider with spin box for
// ranges, check box, combo box for sets, interval sliders, colour picker, file
// chooser, angle dial. It emits the value a person sets as YAML text (throttled
// while a slider is dragged) and shows the value the runtime applied. No ROS.
#pragma once

#include <QPointer>
#include <QTimer>
#include <QWidget>

#include <apex/ParamInfo.h>

#include <functional>

class QCheckBox;
class QFileDialog;
class QHBoxLayout;

namespace apex_rviz_plugin {

class ParamEditor : public QWidget {
  Q_OBJECT
 public:
  /** Milliseconds between values sent while a slider is dragged. */
  static constexpr int kThrottleMs = 100;

  explicit ParamEditor(const apex::ParamInfo& param, QWidget* parent = nullptr);
  const apex::ParamInfo& param() const { return param_; }
  /** @brief Shows the applied value (from ~graph) without emitting it back; kept while being edited. */
  void showApplied(const apex::ParamInfo& param);

 signals:
  /** `dragging`: one of the values sent while a slider is held; its release sends the last one. */
  void edited(const QString& name, const QString& yaml, bool dragging = false);
  void interactiveToggled(const QString& name, bool interactive);
  /** A right-click on the parameter (to reset it, or optimise a number), at a screen position. */
  void menuRequested(const QString& name, QPoint screen_pos);

 private:
  void build();
  void buildNumber(bool integer);
  void buildInterval();
  void buildSet();
  void buildAngle();
  void buildPath();
  void buildColor();
  void buildText();
  /** Sends now, or after the throttle interval while a slider is held. */
  void send(const QString& yaml, bool dragging);

  apex::ParamInfo param_;
  std::function<void(const std::string&)> show_;  ///< puts a YAML value into the widgets
  bool updating_ = false;  ///< true while show_ runs: no signals out
  QTimer throttle_;
  QString pending_;
  bool drag_sent_ = false;  ///< values went out during the drag: its release must end it
  QCheckBox* interactive_ = nullptr;
  QHBoxLayout* row_ = nullptr;  ///< the name, the value's widgets, the ports check box
  QPointer<QFileDialog> dialog_;  ///< a path's file chooser while open: one at a time
};

/** @brief An editor of node `node`'s parameter `param` whose signals come out of `owner` as its
 *  own parameterEdited, interactiveToggled and paramMenuRequested, with the node's name (a box, the
 *  properties view: both are the same edits). */
template <class Owner>
ParamEditor* editorFor(const apex::ParamInfo& param, const QString& node, Owner* owner) {
  auto* e = new ParamEditor(param);
  QObject::connect(e, &ParamEditor::edited, owner, [owner, node](const QString& n, const QString& v, bool dragging) {
    emit owner->parameterEdited(node, n, v, dragging);
  });
  QObject::connect(e, &ParamEditor::interactiveToggled, owner,
                   [owner, node](const QString& n, bool on) { emit owner->interactiveToggled(node, n, on); });
  QObject::connect(e, &ParamEditor::menuRequested, owner,
                   [owner, node](const QString& n, QPoint at) { emit owner->paramMenuRequested(node, n, at); });
  return e;
}

}  // namespace apex_rviz_plugin
