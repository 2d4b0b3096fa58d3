// The ports inspected for the person and the Optimizers' progress.
#include "apex_rviz_plugin/inspections.hpp"

#include "apex_rviz_plugin/rviz_displays.hpp"

namespace apex_rviz_plugin {

void Inspections::inspect(const QString& node, const QString& port) {
  inspected_.insert({node.toStdString(), port.toStdString()});
  ctx_.link.inspect(
      node.toStdString(), port.toStdString(),
      [this, node, port](bool ok, const std::string& m, const std::string& topic, const std::string& type) {
        if (!ok) return ctx_.report(false, m, "inspect " + node + "/" + port);
        const QString t = QString::fromStdString(topic), name = node + "/" + port;
        ctx_.editor.showMessageType(node, port, type);  // for the port menu's "Show in rviz"
        if (rvizDisplayFor(type)) emit displayRequested(node, port, t, QString::fromStdString(type));
        else if (type.empty())  // a port of any type: its first message decides
          return ctx_.report(
              true, "",
              node + "/" + port + " is published on " + t + " from its first message on; inspect it again then to see it here");
        else ctx_.link.watchScalar(node.toStdString(), port.toStdString(), topic, type);
        ctx_.report(true, "",
                    "inspecting " + name + " on " + t + (type.empty() ? "" : " (" + QString::fromStdString(type) + ")"));
      });
}

void Inspections::watchOptimizers() {
  for (const auto& name : ctx_.model.optimizers()) {
    if (!watched_.insert(name).second) continue;
    for (const char* port : {"evaluations", "best_fitness"})  // the node's box draws its progress from them
      ctx_.link.inspect(name, port,
                        [this, name, port](bool ok, const std::string& m, const std::string& topic, const std::string& type) {
                          if (!ok) return ctx_.report(false, m, QString::fromStdString("watch " + name + "/" + port));
                          ctx_.link.watchScalar(name, port, topic, type);
                        });
  }
}

void Inspections::follow(const std::string& from, const std::string& to) {
  std::set<std::pair<std::string, std::string>> followed;  // the ports inspected, under the names they will have
  for (const auto& [node, port] : inspected_) {
    const bool inside = node.size() > from.size() && node.compare(0, from.size() + 1, from + "/") == 0;
    followed.insert({node == from || inside ? to + node.substr(from.size()) : node, port});
  }
  inspected_ = std::move(followed);
}

void Inspections::again() {
  watched_.clear();  // a load, group or ungroup ends every inspection: the Optimizers' progress and the displays
  watchOptimizers();  // the loaded graph may be shown already: no other ~graph may follow
  for (const auto& [node, port] : inspected_)  // displays showing a port go on if the new graph has it
    ctx_.link.inspect(node, port, [](bool, const std::string&, const std::string&, const std::string&) {});
}

}  // namespace apex_rviz_plugin
