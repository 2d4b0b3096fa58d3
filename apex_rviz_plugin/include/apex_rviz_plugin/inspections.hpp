// The ports the runtime publishes for the panel (inspections.cpp): those the person asked to
// inspect (shown in rviz, or as values on their boxes) and each Optimizer's progress (evaluations,
// best fitness), which its box draws while it tunes. It owns both lists; a load, group or ungroup
// ends every inspection in the runtime, and again() asks for them anew.
#pragma once

#include <set>
#include <string>
#include <utility>

#include <QObject>

#include "apex_rviz_plugin/panel_context.hpp"

namespace apex_rviz_plugin {

class Inspections : public QObject {
  Q_OBJECT
 public:
  explicit Inspections(const PanelContext& context, QObject* parent = nullptr) : QObject(parent), ctx_(context) {}

  /** @brief Inspects node/port for the person: an rviz display of it (displayRequested) if rviz
   *  has one for its type, else its values on its box; the message line says where it is published. */
  void inspect(const QString& node, const QString& port);
  /** @brief Inspects each Optimizer of the graph shown not watched yet, once, for its box to draw its progress. */
  void watchOptimizers();
  /** @brief Node `from` is about to be `to` (a rename, a group, an ungroup): the ports inspected
   *  in it follow it. */
  void follow(const std::string& from, const std::string& to);
  /** @brief The runtime ended every inspection: the Optimizers watched again, the ports the
   *  person asked for inspected again if the graph has them. */
  void again();
  /** @brief The runtime is gone or another one came: no Optimizer is watched (the ports asked
   *  for are kept: the displays showing them are there still). */
  void reset() { watched_.clear(); }
  /** @brief Another namespace: the ports asked for are forgotten too. */
  void forgetPorts() { inspected_.clear(); }

 signals:
  /** The runtime publishes node/port on `topic` as `message_type`, which rviz has a display for. */
  void displayRequested(const QString& node, const QString& port, const QString& topic, const QString& message_type);

 private:
  PanelContext ctx_;
  std::set<std::string> watched_;  // Optimizers whose progress is inspected
  std::set<std::pair<std::string, std::string>> inspected_;  // (node, port) asked for by the person
};

}  // namespace apex_rviz_plugin
