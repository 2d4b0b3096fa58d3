#include "apex_rviz_plugin/file_dialog.hpp"

#include <QDir>
#include <QFileInfo>
#include <QGraphicsProxyWidget>
#include <QGraphicsScene>
#include <QGraphicsView>

namespace apex_rviz_plugin {

QString apexFolder() {
  const QByteArray ros_home = qgetenv("ROS_HOME");
  return (ros_home.isEmpty() ? QString::fromLocal8Bit(qgetenv("HOME")) + "/.ros" : QString::fromLocal8Bit(ros_home)) + "/apex/";
}

QString& lastChosenFolder() {
  static QString folder = apexFolder();
  return folder;
}

QWidget* dialogParent(QWidget* w) {
  QGraphicsProxyWidget* proxy = w ? w->window()->graphicsProxyWidget() : nullptr;
  if (!proxy || !proxy->scene() || proxy->scene()->views().isEmpty()) return w;
  return proxy->scene()->views().front();
}

QFileDialog* openFileDialog(QPointer<QFileDialog>& open_one, QWidget* parent, const FileDialogSpec& spec,
                            std::function<void(const QString&)> chosen) {
  if (open_one) {  // a second click while one is open: that one, in front
    open_one->raise();
    open_one->activateWindow();
    return nullptr;
  }
  auto* dialog = new QFileDialog(dialogParent(parent), spec.caption);
  dialog->setObjectName(spec.name);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  // The desktop's dialog (GTK, a portal) inside rviz's OpenGL window drew black and ignored the
  // default suffix: Qt's own behaves the same everywhere.
  dialog->setOption(QFileDialog::DontUseNativeDialog);
  dialog->setWindowModality(Qt::WindowModal);
  if (!spec.filter.isEmpty()) dialog->setNameFilter(spec.filter);
  if (spec.mode == FileDialogSpec::Mode::Save) dialog->setAcceptMode(QFileDialog::AcceptSave);
  dialog->setFileMode(spec.mode == FileDialogSpec::Mode::Directory ? QFileDialog::Directory
                      : spec.mode == FileDialogSpec::Mode::Save    ? QFileDialog::AnyFile
                                                                   : QFileDialog::ExistingFile);
  if (!spec.suffix.isEmpty()) dialog->setDefaultSuffix(spec.suffix);
  const QFileInfo start(spec.start);
  if (spec.start.isEmpty()) {
    dialog->setDirectory(QDir::home());
  } else if (start.isDir()) {
    dialog->setDirectory(start.absoluteFilePath());
  } else {  // a file, or one to be written: its folder, with it selected
    dialog->setDirectory(start.absolutePath());
    dialog->selectFile(start.fileName());
  }
  // The dialog belongs to the view, the requester may not outlive it (a node's box is rebuilt when
  // its parameters change shape): its going closes the dialog and cuts the answer.
  QObject* requester = parent ? static_cast<QObject*>(parent) : dialog;
  QObject::connect(dialog, &QFileDialog::fileSelected, requester, [chosen = std::move(chosen)](const QString& path) {
    if (!path.isEmpty()) chosen(path);
  });
  if (parent) QObject::connect(parent, &QObject::destroyed, dialog, &QWidget::close);
  open_one = dialog;
  dialog->open();
  return dialog;
}

}  // namespace apex_rviz_plugin
