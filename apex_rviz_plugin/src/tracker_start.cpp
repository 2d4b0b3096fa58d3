#include "apex_rviz_plugin/tracker_start.hpp"

#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

#include "apex_rviz_plugin/label_canvas.hpp"

namespace apex_rviz_plugin {

std::optional<QRect> boxInImage(const QRect& drawn, const QSize& size) {
  const QRect box = drawn & QRect(QPoint(0, 0), size);  // a drag that ends outside the image ends at its edge
  if (box.isEmpty()) return std::nullopt;
  return box;
}

TrackerStartView::TrackerStartView(const QString& tracker, const QString& source, QWidget* parent)
    : QDialog(parent), tracker_(tracker), source_(source), canvas_(new LabelCanvas), status_(new QLabel) {
  setObjectName("tracker_start_view");
  setAttribute(Qt::WA_DeleteOnClose);
  setWindowTitle("Start " + tracker + " on a box");
  setModal(false);
  auto* column = new QVBoxLayout(this);
  column->addWidget(canvas_, 1);
  auto* row = new QHBoxLayout;
  status_->setObjectName("tracker_start_status");
  status_->setWordWrap(true);
  row->addWidget(status_, 1);
  auto* cancel = new QPushButton("Cancel");
  cancel->setObjectName("tracker_start_cancel");
  cancel->setAutoDefault(false);
  connect(cancel, &QPushButton::clicked, this, &QDialog::reject);
  row->addWidget(cancel);
  column->addLayout(row);
  connect(canvas_, &LabelCanvas::boxDrawn, this, &TrackerStartView::onBoxDrawn);
  connect(canvas_, &LabelCanvas::boxClicked, this,
          [this](int) { showStatus("a click is no box: drag from one corner of the object to the opposite one", true); });
}

void TrackerStartView::showFrame(const QImage& image) {
  if (hasFrame() || image.isNull()) return;
  canvas_->setImage(image);
  showStatus(QString("drag a box around the object on this frame of %1 (%2×%3): %4 starts on it with the next frame it "
                     "gets (pause its source to start on this one)")
                 .arg(source_)
                 .arg(image.width())
                 .arg(image.height())
                 .arg(tracker_),
             false);
  resize(720, 760);  // a camera's frame, upright or turned, scaled to fit
  show();
  raise();
  activateWindow();
}

bool TrackerStartView::hasFrame() const { return !canvas_->image().isNull(); }

QString TrackerStartView::status() const { return status_->text(); }

void TrackerStartView::onBoxDrawn(const QRect& drawn) {
  const auto box = boxInImage(drawn, canvas_->image().size());
  if (!box) return showStatus("that box has no pixel in the image: drag from one corner of the object to the opposite one", true);
  emit boxChosen(tracker_, *box);
  accept();  // closed: deleted
}

void TrackerStartView::showStatus(const QString& text, bool error) {
  status_->setText(text);
  status_->setStyleSheet(error ? "color: #c00000" : "");
}

}  // namespace apex_rviz_plugin
