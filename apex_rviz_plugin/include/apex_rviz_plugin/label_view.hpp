// Labelling a graph's frames in the panel: one window per image output (a node's port), beside the
// editor, not modal. It shows the output's current frame (LabelCanvas); the person drags boxes on
// it, names their class (the class field: what new boxes get, and a clicked box's class), deletes
// a box, steps to the next or previous frame of the player upstream, and saves the frames labelled
// as a COCO file RegionScore reads (FrameLabels, saveCoco). It makes no calls itself: the panel
// gives it frames (showFrame) and fires the player's slots it asks for (stepRequested).
// Its labels live as long as the window: closing it hides it, and it shows them again when opened.
#pragma once

#include <QDialog>
#include <QImage>
#include <QPointer>

#include "apex_rviz_plugin/frame_labels.hpp"

class QCheckBox;
class QComboBox;
class QFileDialog;
class QLabel;
class QLineEdit;
class QPushButton;

namespace apex_rviz_plugin {

class LabelCanvas;

class LabelView : public QDialog {
  Q_OBJECT
 public:
  LabelView(const QString& node, const QString& port, QWidget* parent = nullptr);
  const QString& node() const { return node_; }
  const QString& port() const { return port_; }
  /** @brief The player whose `next` and `previous` slots the frame buttons fire; "" for none (the
   *  buttons are then off, their tooltip says why). */
  void setPlayer(const QString& player);
  /** @brief A frame of the output: shown, with the boxes drawn on it before if it has a label (a
   *  frame sent again keeps its selection). A null `image` (an encoding not drawn here) is said,
   *  naming `encoding`. During a drag it waits for the drag's end. */
  void showFrame(const QImage& image, quint64 stamp, const QString& encoding);
  /** @brief Saves the frames labelled as COCO at `path` (the file field's path if empty); says
   *  what was saved, or why not. */
  bool save(const QString& path = QString());
  /** @brief The status line: what was done last, or what was wrong (red). */
  void showStatus(const QString& text, bool error);
  QString status() const;
  const FrameLabels& labels() const { return labels_; }
  /** @brief The stamp of the frame shown (ns), 0 before one came. */
  quint64 stamp() const { return stamp_; }
  LabelCanvas* canvas() const { return canvas_; }

 signals:
  /** Fire `slot` ("next" or "previous") of `player`. */
  void stepRequested(const QString& player, const QString& slot);
  /** The window was hidden: no frames are needed until it shows again. */
  void closed();

 protected:
  void hideEvent(QHideEvent* event) override;

 private:
  QWidget* buildTools();
  QWidget* buildSaveRow();
  void onBoxDrawn(const QRect& box);
  void onBoxClicked(int index);
  void onClassEdited(const QString& text);
  void deleteSelected();
  void step(const QString& slot);
  void setFrameLabelled(bool labelled);
  void chooseFile();
  /** The canvas, the frame's check box and the counts, as labels_ has them now. */
  void refresh(int selected);
  /** The class for a new box: the class field's text, "object" if it is empty. */
  QString currentClass() const;

  QString node_, port_, player_;
  FrameLabels labels_;
  quint64 stamp_ = 0;
  QImage pending_;  // a frame that came during a drag
  quint64 pending_stamp_ = 0;
  QString pending_encoding_;
  bool has_pending_ = false;
  LabelCanvas* canvas_;
  QComboBox* class_ = nullptr;
  QCheckBox* labelled_ = nullptr;
  QPushButton *previous_ = nullptr, *next_ = nullptr, *delete_ = nullptr;
  QLabel* info_ = nullptr;
  QLabel* status_ = nullptr;
  QLineEdit* path_ = nullptr;
  QPointer<QFileDialog> file_dialog_;
};

}  // namespace apex_rviz_plugin
