// What an Optimizer's box draws of its run: evaluations of the budget and the best fitness on a
// line, the best fitness's curve over the evaluations and, with two objectives, the Pareto front:
// each point its cost (ms per frame, across) against its fitness (up), joined cheapest to dearest.
#pragma once

#include <QColor>
#include <QPainter>
#include <QRectF>

#include <vector>

#include "apex_rviz_plugin/graph_model.hpp"

namespace apex_rviz_plugin {

/** @brief The colour of the front's points (tests look for it). */
inline const QColor kFrontColor(240, 170, 60);

/** @brief Draws the run into `area`: the line on top, then the curve, and the front beside it if any. */
void paintOptimizerRun(QPainter* p, const QRectF& area, int evaluations, int budget, const std::vector<double>& fitness,
                       const std::vector<FrontPoint>& front);

}  // namespace apex_rviz_plugin
