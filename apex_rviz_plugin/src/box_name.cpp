#include "apex_rviz_plugin/box_name.hpp"

#include <QFontMetricsF>

#include <algorithm>
#include <cmath>

namespace apex_rviz_plugin {

BoxName BoxName::fit(const QString& name, const QRectF& area, double zoom, QFont base) {
  BoxName out;
  out.text = name;
  for (const QString mark : {"_", "/"}) out.text.replace(mark, mark + QChar(0x200B));  // may break after
  out.flags = Qt::AlignCenter | Qt::TextWordWrap;
  const int least = static_cast<int>(std::ceil(kLeastPixels / std::max(zoom, 1e-3)));
  for (int px = std::max(least, static_cast<int>(kMostPixels));; px = std::max(least, static_cast<int>(px * 0.85))) {
    base.setPixelSize(std::max(px, 1));
    const QRectF need = QFontMetricsF(base).boundingRect(area, out.flags, out.text);
    out.font = base;
    out.whole = need.width() <= area.width() + 0.5 && need.height() <= area.height() + 0.5;
    if (out.whole) return out;
    if (px <= least) break;
  }
  // At the least size and still too wide: a word broken anywhere ("passthro|ugh") if the lines fit
  // the box's height; else one line, its end elided ("preset_cl…"; the properties and Find show it
  // whole), never lines past the box's edges.
  const QFontMetricsF metrics(out.font);
  const int anywhere = Qt::AlignCenter | Qt::TextWrapAnywhere;
  if (metrics.boundingRect(area, anywhere, out.text).height() <= area.height() + 0.5) {
    out.flags = anywhere;
    out.whole = true;
    return out;
  }
  out.text = metrics.elidedText(name, Qt::ElideRight, area.width());
  out.flags = Qt::AlignCenter | Qt::TextSingleLine;
  out.whole = false;
  return out;
}

}  // namespace apex_rviz_plugin
