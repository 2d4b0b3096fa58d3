#include "apex_rviz_plugin/help_view.hpp"

#include <QTextBrowser>
#include <QVBoxLayout>

#include "apex/core/param.hpp"  // toText: numbers written as the runtime (and docs/nodes.md) writes them
#include "apex_rviz_plugin/graph_model.hpp"  // isBuiltinEvent

namespace apex_rviz_plugin {
namespace {

QString esc(const std::string& text) { return QString::fromStdString(text).toHtmlEscaped(); }

QString code(const std::string& text) { return text.empty() ? QString() : "<code>" + esc(text) + "</code>"; }

QString row(const QStringList& cells) { return "<tr><td>" + cells.join("</td><td>") + "</td></tr>"; }

/** A titled table of `rows` under `head`; nothing without rows. */
QString table(const QString& title, const QStringList& head, const QStringList& rows) {
  if (rows.isEmpty()) return QString();
  return "<p><b>" + title + "</b></p><table border='1' cellspacing='0' cellpadding='3'><tr><th>" + head.join("</th><th>") +
         "</th></tr>" + rows.join("") + "</table>";
}

/** The inputs, outputs, slots and triggers, as docs/nodes.md has them (without the events every node has). */
QString portTables(const apex::NodeTypeInfo& type) {
  QStringList inputs, outputs, slot_rows, triggers;
  for (const auto& p : type.ports) {
    if (p.kind == "input") inputs << row({code(p.name), code(p.type), p.optional ? "yes" : "", esc(p.description)});
    if (p.kind == "output") outputs << row({code(p.name), code(p.type), esc(p.description)});
    if (p.kind == "slot" && !isBuiltinEvent(p.name)) slot_rows << row({code(p.name), esc(p.description)});
    if (p.kind == "trigger" && !isBuiltinEvent(p.name)) triggers << row({code(p.name), esc(p.description)});
  }
  return table("Inputs", {"name", "type", "optional", "description"}, inputs) +
         table("Outputs", {"name", "type", "description"}, outputs) + table("Slots", {"name", "description"}, slot_rows) +
         table("Triggers", {"name", "description"}, triggers);
}

QString parameterTable(const apex::NodeTypeInfo& type) {
  QStringList rows;
  bool shapes = false;
  for (const auto& p : type.parameters) {
    QStringList notes;
    if (p.interactive) notes << "has ports by default";
    if (p.shapes_ports) notes << "changes the ports";
    if (p.legacy) notes << "kept so older graphs load";
    shapes = shapes || p.shapes_ports;
    QString about = esc(p.description);
    if (!notes.isEmpty()) about += (about.isEmpty() ? "<i>(" : " <i>(") + notes.join("; ") + ")</i>";
    rows << row({code(p.name), esc(p.kind), HelpView::limits(p).toHtmlEscaped(), code(p.default_value), about});
  }
  QString out = table("Parameters", {"name", "kind", "range / options", "default", "description"}, rows);
  if (shapes)
    out +=
        "<p>The ports listed are those of the default parameters: the parameters marked <i>changes the ports</i> add or "
        "remove some.</p>";
  return out;
}

}  // namespace

HelpView::HelpView(QWidget* parent) : QDialog(parent), text_(new QTextBrowser) {
  setObjectName("help");
  setWindowTitle("Node type help");
  setModal(false);
  text_->setObjectName("help_text");
  text_->setOpenLinks(false);
  auto* column = new QVBoxLayout(this);
  column->setContentsMargins(4, 4, 4, 4);
  column->addWidget(text_);
  resize(620, 560);  // the parameters' table readable without scrolling sideways
}

void HelpView::showType(const apex::NodeTypeInfo& type, const QString& node) {
  type_ = QString::fromStdString(type.id);
  setWindowTitle("Help: " + (node.isEmpty() ? type_ : node + " (" + type_ + ")"));
  text_->setHtml(html(type));
  show();
  raise();
}

QString HelpView::text() const { return text_->toPlainText(); }

QString HelpView::limits(const apex::ParamInfo& p) {
  if (p.kind == "int range" || p.kind == "double range" || p.kind == "interval" || p.kind == "angle") {
    const bool whole = p.kind == "int range";
    auto bound = [whole](double v) {
      return QString::fromStdString(whole ? apex::toText(apex::ParamValue(static_cast<int>(v)))
                                          : apex::toText(apex::ParamValue(v)));
    };
    QString text = "[" + bound(p.min) + ", " + bound(p.max) + "]";
    if (p.step > 0 && !(whole && p.step == 1)) text += " step " + bound(p.step);
    return p.kind == "angle" ? text + " (radians)" : text;
  }
  if (p.kind == "set") {
    QStringList options;
    for (const auto& o : p.options) options << QString::fromStdString(o);
    return options.join(", ");
  }
  if (p.kind != "path") return QString();
  QStringList files;
  for (const auto& o : p.options) files << QString::fromStdString(o);
  return "mode: " + QString::fromStdString(p.path_mode) + (files.isEmpty() ? "" : ", files " + files.join(" "));
}

QString HelpView::html(const apex::NodeTypeInfo& type) {
  QString out = "<h3>" + esc(type.id) + "</h3>";
  out += "<p><i>category:</i> " + esc(type.category.empty() ? "other" : type.category) + "</p>";
  out += "<p>" + (type.description.empty() ? QString("(no description)") : esc(type.description)) + "</p>";
  out += portTables(type) + parameterTable(type);
  return out +
         "<p>Besides these, every node has the slots <code>enable</code> and <code>disable</code> and the trigger "
         "<code>processed</code>. Parameter values are written as in a graph file (YAML); angles in radians.</p>";
}

}  // namespace apex_rviz_plugin
