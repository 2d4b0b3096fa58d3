#include "apex_rviz_plugin/label_view.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QHideEvent>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QShortcut>
#include <QToolButton>
#include <QVBoxLayout>

#include "apex_rviz_plugin/file_dialog.hpp"
#include "apex_rviz_plugin/label_canvas.hpp"

namespace apex_rviz_plugin {
namespace {

/** A stamp as ROS prints it: seconds, a point, nine decimals. */
QString stampText(quint64 ns) { return QString("%1.%2").arg(ns / 1000000000ULL).arg(ns % 1000000000ULL, 9, 10, QChar('0')); }

/** "1 box", "2 boxes". */
QString count(std::size_t n, const QString& one, const QString& many) { return QString("%1 %2").arg(n).arg(n == 1 ? one : many); }

QPushButton* button(const QString& text, const QString& name, const QString& tip) {
  auto* b = new QPushButton(text);
  b->setObjectName(name);
  b->setToolTip(tip);
  b->setAutoDefault(false);  // Return in the class field must not press a button
  return b;
}

}  // namespace

LabelView::LabelView(const QString& node, const QString& port, QWidget* parent)
    : QDialog(parent), node_(node), port_(port), canvas_(new LabelCanvas) {
  setObjectName("label_view");
  setWindowTitle("Label frames: " + node + "/" + port);
  setModal(false);
  auto* column = new QVBoxLayout(this);
  column->addWidget(buildTools());
  column->addWidget(canvas_, 1);
  column->addWidget(buildSaveRow());
  status_ = new QLabel;
  status_->setObjectName("label_status");
  status_->setWordWrap(true);
  column->addWidget(status_);
  connect(canvas_, &LabelCanvas::boxDrawn, this, &LabelView::onBoxDrawn);
  connect(canvas_, &LabelCanvas::boxClicked, this, &LabelView::onBoxClicked);
  connect(canvas_, &LabelCanvas::textTyped, this, [this](const QString& text) {  // a class name begun on the frame
    class_->setFocus();
    class_->setEditText(text);
  });
  // Keys (the class field keeps those it edits with while it has the focus): the arrows step,
  // Delete removes the selected box, Ctrl+S saves.
  for (const auto& key : {QKeySequence(Qt::Key_Delete), QKeySequence(Qt::Key_Backspace)})
    connect(new QShortcut(key, this), &QShortcut::activated, this, &LabelView::deleteSelected);
  for (const auto& key : {QKeySequence(Qt::Key_Right), QKeySequence(Qt::Key_PageDown)})
    connect(new QShortcut(key, this), &QShortcut::activated, this, [this] { step("next"); });
  for (const auto& key : {QKeySequence(Qt::Key_Left), QKeySequence(Qt::Key_PageUp)})
    connect(new QShortcut(key, this), &QShortcut::activated, this, [this] { step("previous"); });
  connect(new QShortcut(QKeySequence::Save, this), &QShortcut::activated, this, [this] { save(); });
  setPlayer("");
  refresh(-1);
  showStatus("drag a box around each object, with its class in the class field; then Next", false);
}

QWidget* LabelView::buildTools() {
  auto* tools = new QWidget;
  auto* row = new QHBoxLayout(tools);
  row->setContentsMargins(0, 0, 0, 0);
  row->addWidget(new QLabel("Class:"));
  class_ = new QComboBox;
  class_->setObjectName("label_class");
  class_->setEditable(true);
  class_->setInsertPolicy(QComboBox::NoInsert);  // the classes listed are those of the boxes
  class_->setMinimumContentsLength(12);
  class_->setToolTip(
      "the class of the next box drawn (type one, or pick one used before); "
      "with a box selected, its class");
  class_->setEditText("object");
  connect(class_, &QComboBox::currentTextChanged, this, &LabelView::onClassEdited);
  row->addWidget(class_);
  delete_ = button("Delete box", "delete_box", "removes the selected box (Delete)");
  connect(delete_, &QPushButton::clicked, this, &LabelView::deleteSelected);
  row->addWidget(delete_);
  labelled_ = new QCheckBox("Frame labelled");
  labelled_->setObjectName("frame_labelled");
  labelled_->setToolTip(
      "the frame is in the file: checked by its first box; check it for a frame with nothing "
      "to find, uncheck it to leave the frame out (its boxes go)");
  connect(labelled_, &QCheckBox::clicked, this, &LabelView::setFrameLabelled);
  row->addWidget(labelled_);
  row->addStretch(1);
  previous_ = button("◀ Previous", "previous_frame", "");
  next_ = button("Next ▶", "next_frame", "");
  connect(previous_, &QPushButton::clicked, this, [this] { step("previous"); });
  connect(next_, &QPushButton::clicked, this, [this] { step("next"); });
  row->addWidget(previous_);
  row->addWidget(next_);
  return tools;
}

QWidget* LabelView::buildSaveRow() {
  auto* bottom = new QWidget;
  auto* row = new QHBoxLayout(bottom);
  row->setContentsMargins(0, 0, 0, 0);
  info_ = new QLabel;
  info_->setObjectName("frame_info");
  row->addWidget(info_, 1);
  path_ = new QLineEdit(apexFolder() + "labels.json");
  path_->setObjectName("labels_path");
  path_->setToolTip("the COCO file (.json) the labels are saved to: set it as a RegionScore's truth");
  path_->setMinimumWidth(260);
  row->addWidget(path_, 1);
  auto* choose = new QToolButton;
  choose->setText("...");
  choose->setToolTip("choose the file");
  connect(choose, &QToolButton::clicked, this, &LabelView::chooseFile);
  row->addWidget(choose);
  auto* save_button = button("Save", "save_labels", "writes the frames labelled as a COCO file (Ctrl+S)");
  connect(save_button, &QPushButton::clicked, this, [this] { save(); });
  row->addWidget(save_button);
  return bottom;
}

void LabelView::setPlayer(const QString& player) {
  player_ = player;
  const QString why = "no player (BagReader) feeds " + node_ + ": step its source yourself";
  previous_->setEnabled(!player.isEmpty());
  next_->setEnabled(!player.isEmpty());
  previous_->setToolTip(player.isEmpty() ? why : "the previous frame of " + player + " (←)");
  next_->setToolTip(player.isEmpty() ? why : "the next frame of " + player + " (→)");
}

void LabelView::showFrame(const QImage& image, quint64 stamp, const QString& encoding) {
  if (canvas_->dragging()) {  // a drag is on this frame: the next waits for its end
    pending_ = image, pending_stamp_ = stamp, pending_encoding_ = encoding, has_pending_ = true;
    return;
  }
  if (image.isNull())
    return showStatus(node_ + "/" + port_ + " sends " + encoding +
                          " images, which cannot be shown here (bgr8, rgb8, mono8 and bgra8 can): label an output "
                          "of those, e.g. before a conversion",
                      true);
  const bool same = stamp == stamp_ && !canvas_->image().isNull();
  stamp_ = stamp;
  canvas_->setImage(image);
  if (const LabelledFrame* f = labels_.frame(stamp); f && (f->width != image.width() || f->height != image.height()))
    showStatus("this frame was labelled at " + QString("%1×%2").arg(f->width).arg(f->height) + ", it is now " +
                   QString("%1×%2").arg(image.width()).arg(image.height()) + ": its boxes may be off",
               true);
  refresh(same ? canvas_->selected() : -1);
}

void LabelView::onBoxDrawn(const QRect& box) {
  if (canvas_->image().isNull())
    return showStatus("no frame from " + node_ + "/" + port_ + " yet: play or step its source", true);
  const QImage& image = canvas_->image();
  const apex::Status st = labels_.add(stamp_, image.width(), image.height(),
                                      {box.x(), box.y(), box.width(), box.height(), currentClass().toStdString()});
  if (!st) showStatus(QString::fromStdString(st.message()), true);
  else {
    if (class_->findText(currentClass()) < 0) {
      const QSignalBlocker quiet(class_);  // listed for the next boxes; no box's class changes
      class_->addItem(currentClass());
    }
    const LabelBox& b = labels_.frame(stamp_)->boxes.back();
    showStatus(QString("box %1: %2 at %3, %4, %5×%6")
                   .arg(labels_.frame(stamp_)->boxes.size())
                   .arg(QString::fromStdString(b.label))
                   .arg(b.x)
                   .arg(b.y)
                   .arg(b.width)
                   .arg(b.height),
               false);
  }
  refresh(-1);
  if (has_pending_) {  // the frame that came during the drag
    has_pending_ = false;
    showFrame(pending_, pending_stamp_, pending_encoding_);
  }
}

void LabelView::onBoxClicked(int index) {
  refresh(index);
  if (index < 0) return;
  const LabelBox& b = labels_.frame(stamp_)->boxes[static_cast<std::size_t>(index)];
  const QSignalBlocker quiet(class_);  // showing its class does not change it
  class_->setEditText(QString::fromStdString(b.label));
  showStatus("selected " + QString::fromStdString(b.label) + ": type a class to change it, Delete to remove it", false);
}

void LabelView::onClassEdited(const QString& text) {
  const int selected = canvas_->selected();
  if (selected < 0 || !labels_.relabel(stamp_, static_cast<std::size_t>(selected), text.toStdString())) return;
  refresh(selected);
  showStatus("the selected box's class is " + text.trimmed(), false);
}

void LabelView::deleteSelected() {
  const int selected = canvas_->selected();
  if (selected < 0) return showStatus("no box selected: click one to select it", true);
  labels_.remove(stamp_, static_cast<std::size_t>(selected));
  showStatus("box removed", false);
  refresh(-1);
}

void LabelView::step(const QString& slot) {
  if (player_.isEmpty()) return showStatus("no player (BagReader) feeds " + node_ + ": step its source yourself", true);
  emit stepRequested(player_, slot);
}

void LabelView::setFrameLabelled(bool labelled) {
  if (canvas_->image().isNull()) {
    showStatus("no frame from " + node_ + "/" + port_ + " yet: play or step its source", true);
    return refresh(-1);
  }
  if (!labelled) {
    const std::size_t boxes = labels_.frame(stamp_) ? labels_.frame(stamp_)->boxes.size() : 0;
    labels_.unmark(stamp_);
    showStatus(QString("frame left out of the file (its %1 boxes removed)").arg(boxes), false);
  } else if (const apex::Status st = labels_.mark(stamp_, canvas_->image().width(), canvas_->image().height()); !st) {
    showStatus(QString::fromStdString(st.message()), true);
  } else {
    showStatus("frame labelled with nothing to find on it", false);
  }
  refresh(-1);
}

bool LabelView::save(const QString& path) {
  const QString to = path.isEmpty() ? path_->text().trimmed() : path;
  if (!path.isEmpty()) path_->setText(path);
  if (to.startsWith(apexFolder())) QDir().mkpath(apexFolder());  // the default place, made on first use
  const apex::Status st = saveCoco(labels_, to.toStdString());
  if (!st) {
    showStatus(QString::fromStdString(st.message()), true);
    return false;
  }
  showStatus("saved " + count(labels_.frames().size(), "frame", "frames") + ", " + count(labels_.boxCount(), "box", "boxes") +
                 " to " + to + ": set it as a RegionScore's truth",
             false);
  return true;
}

void LabelView::chooseFile() {
  FileDialogSpec spec;
  spec.name = "labels_file_dialog";
  spec.caption = "Save the labels as";
  spec.start = path_->text();
  spec.mode = FileDialogSpec::Mode::Save;
  spec.filter = "COCO labels (*.json)";
  spec.suffix = "json";
  openFileDialog(file_dialog_, this, spec, [this](const QString& chosen) { save(chosen); });
}

void LabelView::showStatus(const QString& text, bool error) {
  status_->setText(text);
  status_->setStyleSheet(error ? "color: #c00000" : "");
}

QString LabelView::status() const { return status_->text(); }

void LabelView::hideEvent(QHideEvent* event) {
  QDialog::hideEvent(event);
  if (!event->spontaneous()) emit closed();  // closed, not minimised
}

void LabelView::refresh(int selected) {
  const LabelledFrame* f = labels_.frame(stamp_);
  canvas_->setBoxes(f ? f->boxes : std::vector<LabelBox>{}, selected);
  labelled_->setChecked(f != nullptr);
  delete_->setEnabled(canvas_->selected() >= 0);
  const QString frame = canvas_->image().isNull() ? QString("no frame yet")
                                                  : QString("frame %1 s · %2×%3 · %4")
                                                        .arg(stampText(stamp_))
                                                        .arg(canvas_->image().width())
                                                        .arg(canvas_->image().height())
                                                        .arg(count(f ? f->boxes.size() : 0, "box", "boxes"));
  info_->setText(frame + " — " + count(labels_.frames().size(), "frame", "frames") + " labelled, " +
                 count(labels_.boxCount(), "box", "boxes"));
}

QString LabelView::currentClass() const {
  const QString c = class_->currentText().trimmed();
  return c.isEmpty() ? QString("object") : c;
}

}  // namespace apex_rviz_plugin
