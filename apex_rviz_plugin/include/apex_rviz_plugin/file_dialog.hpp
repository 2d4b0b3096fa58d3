// The panel's file choosers (Save, Load, a path parameter's "..."): Qt's own dialog, owned by the
// panel's window, one at a time, never blocking the GUI thread.
#pragma once

#include <QFileDialog>
#include <QPointer>
#include <QString>

#include <functional>

class QWidget;

namespace apex_rviz_plugin {

struct FileDialogSpec {
  enum class Mode { Open, Save, Directory };
  QString name;  ///< the dialog's objectName (tests find it by it)
  QString caption;
  QString start;  ///< a file (its folder is shown, the file selected) or a folder; "" the home folder
  Mode mode = Mode::Open;
  QString filter;  ///< e.g. "APEX graphs (*.yaml)"; "" every file
  QString suffix;  ///< Save: added to a name typed without one ("blur" -> "blur.yaml"); "" none
};

/** @brief $ROS_HOME/apex/ (~/.ros/apex/): where graphs and presets go by default, a folder the
 *  runtime reads (~file_roots). */
QString apexFolder();
/** @brief The folder a path parameter's chooser picked from last (in any box): where the next one
 *  opens for a parameter that has no file yet; at first apexFolder(). */
QString& lastChosenFolder();

/** @brief The widget a dialog opened from `w` belongs to. A widget in a node's box lives in the
 *  graph's scene (a QGraphicsProxyWidget): a window parented there is embedded in the scene too,
 *  drawn into the canvas (a black window), so the view that shows the scene is taken instead. */
QWidget* dialogParent(QWidget* w);

/** @brief Opens Qt's own file dialog (not the desktop's), window-modal to `parent`'s window and
 *  without a nested event loop (rviz goes on drawing); `chosen` gets the path picked (nothing on
 *  Cancel). While the dialog in `open_one` is still open, that one is raised instead and nullptr
 *  returned: one at a time. Returns the dialog opened. */
QFileDialog* openFileDialog(QPointer<QFileDialog>& open_one, QWidget* parent, const FileDialogSpec& spec,
                            std::function<void(const QString&)> chosen);

}  // namespace apex_rviz_plugin
