#include "apex_rviz_plugin/recovery_bar.hpp"

#include <QHBoxLayout>
#include <QLabel>
#include <QLocale>
#include <QPushButton>

namespace apex_rviz_plugin {

RecoveryBar::RecoveryBar(QWidget* parent)
    : QFrame(parent), label_(new QLabel), restore_(new QPushButton("Restore")), discard_(new QPushButton("Discard")) {
  setObjectName("recovery");
  setFrameShape(QFrame::StyledPanel);
  setStyleSheet("#recovery { background: #fff3cd; }");  // a notice, as a browser's "restore pages?" bar
  restore_->setObjectName("recovery_restore");
  discard_->setObjectName("recovery_discard");
  restore_->setToolTip("Load the unsaved graph into the runtime, in place of the graph it has now");
  discard_->setToolTip("Delete the unsaved graph");
  // a narrow dock keeps its width: the text gives way (cut, whole in the tooltip), not the panel
  label_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
  label_->setMinimumWidth(60);
  auto* row = new QHBoxLayout(this);
  row->setContentsMargins(6, 2, 6, 2);
  row->addWidget(label_, 1);
  row->addWidget(restore_);
  row->addWidget(discard_);
  connect(restore_, &QPushButton::clicked, this, &RecoveryBar::restoreRequested);
  connect(discard_, &QPushButton::clicked, this, &RecoveryBar::discardRequested);
  hide();
}

void RecoveryBar::offer(const QDateTime& when, int nodes) {
  label_->setText(QString("Unsaved graph from %1 (%2 %3) found")
                      .arg(QLocale().toString(when, QLocale::ShortFormat))
                      .arg(nodes)
                      .arg(nodes == 1 ? "node" : "nodes"));
  label_->setToolTip(label_->text() + ": the runtime's copy of a graph that was never saved (a crash or a kill)");
  setBusy(false);
  show();
}

void RecoveryBar::withdraw() { hide(); }

void RecoveryBar::setBusy(bool busy) {
  restore_->setEnabled(!busy);
  discard_->setEnabled(!busy);
}

QString RecoveryBar::text() const { return label_->text(); }

}  // namespace apex_rviz_plugin
