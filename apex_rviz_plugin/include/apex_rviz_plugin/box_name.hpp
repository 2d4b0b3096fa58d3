// A box's name as drawn zoomed out (the detail gone): as large as the box holds it, never
// smaller on screen than kLeastPixels, wrapped where the name has a break (after "_" or "/")
// over as many lines as the box is tall (a word with no break, anywhere); a box too small for it
// even so shows one line, its end elided. A map viewer's labels do the same: they keep their
// size on screen as the map shrinks. Qt's fonts only: no scene, no ROS.
#pragma once

#include <QFont>
#include <QRectF>
#include <QString>

namespace apex_rviz_plugin {

struct BoxName {
  /** The least height of the name's letters on screen (the font's pixel size), in pixels. */
  static constexpr double kLeastPixels = 13;
  /** The largest, in scene units: a name alone in a box, read from across the canvas. */
  static constexpr double kMostPixels = 30;

  QFont font;  ///< in scene units (pixel size)
  QString text;  ///< the name with its break chances marked
  int flags = 0;  ///< Qt::AlignmentFlag | Qt::TextFlag, for QPainter::drawText
  bool whole = true;  ///< every letter fits in the area; false: one line, its end elided

  /** @brief How `name` is drawn in `area` (scene units) at view scale `zoom`, from `base` (bold). */
  static BoxName fit(const QString& name, const QRectF& area, double zoom, QFont base);
  /** @brief The letters' height on screen, in pixels, at view scale `zoom`. */
  double pixels(double zoom) const { return font.pixelSize() * zoom; }
};

}  // namespace apex_rviz_plugin
