// Presets as files: one YAML file per name, written whole or not at all (QSaveFile).
#include "apex_rviz_plugin/preset_files.hpp"

#include <QDir>
#include <QFileInfo>
#include <QSaveFile>

namespace apex_rviz_plugin {

QString PresetFiles::folder() { return GraphEditor::defaultGraphFolder() + "presets"; }

void PresetFiles::list() {
  QStringList names;
  for (const QFileInfo& f : QDir(folder()).entryInfoList({"*.yaml"}, QDir::Files, QDir::Name)) names << f.completeBaseName();
  ctx_.editor.showPresets(names);
}

void PresetFiles::save(const QString& name, const QStringList& nodes) {
  if (name.contains('/') || name.startsWith('.'))
    return ctx_.editor.showMessage("a preset's name cannot hold '/' or start with '.': " + name, true);
  std::vector<std::string> names;
  for (const auto& n : nodes) names.push_back(n.toStdString());
  QDir().mkpath(folder());
  QSaveFile file(folder() + "/" + name + ".yaml");  // whole or not at all
  const std::string text = ctx_.model.preset(names) + "\n";
  if (!file.open(QIODevice::WriteOnly) || file.write(text.data(), static_cast<qint64>(text.size())) < 0 || !file.commit())
    return ctx_.editor.showMessage("cannot save preset " + name + ": " + file.errorString(), true);
  list();
  ctx_.editor.showMessage("saved preset " + name + " in " + folder(), false);
}

std::string PresetFiles::read(const QString& name) {
  QFile file(folder() + "/" + name + ".yaml");
  if (!file.open(QIODevice::ReadOnly)) {
    ctx_.editor.showMessage("cannot read preset " + name + ": " + file.errorString(), true);
    return "";
  }
  return file.readAll().toStdString();
}

void PresetFiles::restore(const QString& name) {
  const std::string text = read(name);
  if (text.empty()) return;
  std::string error;
  auto edit = ctx_.model.restore(text, name.toStdString(), &error);
  if (!edit)
    return ctx_.editor.showMessage(
        error.empty() ? "the parameters are as preset " + name + " has them already" : QString::fromStdString(error),
        !error.empty());
  emit editRequested(edit);
}

void PresetFiles::compare(const QString& name) {
  const std::string text = read(name);
  if (text.empty()) return;
  std::string error;
  const auto changes = ctx_.model.compare(text, &error);
  if (!error.empty()) return ctx_.editor.showMessage(QString::fromStdString(error), true);
  QString out = changes.empty() ? "Every parameter is as the preset has it." : "now -> preset " + name + ":\n";
  for (const auto& c : changes)
    out += QString::fromStdString("\n" + c.node + "/" + c.param + ": " + (c.now.empty() ? "(not in the graph)" : c.now) + " -> " +
                                  c.then);
  ctx_.editor.showPresetDiff(name, out);
}

}  // namespace apex_rviz_plugin
