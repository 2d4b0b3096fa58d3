#include "apex_rviz_plugin/palette.hpp"

#include <QKeyEvent>
#include <QLineEdit>
#include <QMenu>
#include <QToolButton>
#include <QTreeWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <map>
#include <tuple>

#include "apex/core/categories.hpp"
#include "apex_rviz_plugin/type_search.hpp"

namespace apex_rviz_plugin {
namespace {

constexpr int kId = Qt::UserRole;  // a type's id; none on a heading
constexpr int kSearched = Qt::UserRole + 1;  // a type's id, category and description, in lower case

/** The package of a type's id ("apex_nodes" for "apex_nodes/Clock"); "" for an id without one. */
QString package(const QString& id) {
  const int slash = id.indexOf('/');
  return slash > 0 ? id.left(slash) : QString();
}

bool isOwn(const QString& id) { return package(id).isEmpty() || package(id) == "apex_nodes"; }

/** Where a heading goes: APEX's categories in their order, then any other category
 *  alphabetically, then "other", then other packages' headings alphabetically. */
std::tuple<int, int, QString> place(const apex::NodeTypeInfo& type) {
  const QString heading = Palette::heading(type);
  if (!isOwn(QString::fromStdString(type.id))) return {3, 0, heading};
  const auto& known = apex::nodeCategories();
  const auto at = std::find(known.begin(), known.end(), type.category);
  if (at != known.end()) return {0, static_cast<int>(at - known.begin()), heading};
  return {heading == QString::fromStdString(apex::kOtherCategory) ? 2 : 1, 0, heading};
}

}  // namespace

Palette::Palette(QWidget* parent) : QWidget(parent), search_(new QLineEdit), tree_(new QTreeWidget) {
  search_->setObjectName("search");
  search_->setPlaceholderText("Search node types (Enter adds)");
  search_->setToolTip(
      "the types whose name, category or description hold every word typed; Enter adds the best match, "
      "Down goes to the list (Enter there adds the type picked); F1 explains the type");
  search_->setClearButtonEnabled(true);
  tree_->setObjectName("palette");
  tree_->setHeaderHidden(true);
  tree_->setUniformRowHeights(true);
  tree_->setIndentation(12);
  tree_->setSelectionMode(QAbstractItemView::SingleSelection);
  tree_->setContextMenuPolicy(Qt::CustomContextMenu);  // Add, Help
  auto* refresh = new QToolButton;
  refresh->setObjectName("refresh_types");
  refresh->setText("Reload types");
  refresh->setToolTip("ask the runtime for its node types again");
  auto* column = new QVBoxLayout(this);
  column->setContentsMargins(0, 0, 0, 0);
  column->addWidget(search_);
  column->addWidget(tree_, 1);
  column->addWidget(refresh);
  setMaximumWidth(240);
  connect(search_, &QLineEdit::textChanged, this, &Palette::filter);
  connect(search_, &QLineEdit::returnPressed, this, &Palette::addCurrent);
  connect(tree_, &QTreeWidget::itemActivated, this, [this](QTreeWidgetItem* item) {
    const QString id = item->data(0, kId).toString();
    if (!id.isEmpty()) emit addRequested(id);  // a heading: Enter opens it (eventFilter), a double-click too
  });
  connect(tree_, &QTreeWidget::itemExpanded, this, [this](QTreeWidgetItem* item) {
    if (!searching()) open_.insert(item->text(0));
  });
  connect(tree_, &QTreeWidget::itemCollapsed, this, [this](QTreeWidgetItem* item) {
    if (!searching()) open_.remove(item->text(0));
  });
  connect(refresh, &QToolButton::clicked, this, &Palette::reloadRequested);
  connect(tree_, &QTreeWidget::customContextMenuRequested, this, &Palette::showMenu);
  search_->installEventFilter(this);
  tree_->installEventFilter(this);
}

QString Palette::heading(const apex::NodeTypeInfo& type) {
  const QString id = QString::fromStdString(type.id);
  if (!isOwn(id)) return package(id);
  return QString::fromStdString(type.category.empty() ? apex::kOtherCategory : type.category);
}

QString Palette::tooltip(const apex::NodeTypeInfo& type) {
  auto html = [](const std::string& text) { return QString::fromStdString(text).toHtmlEscaped(); };
  QString out = "<p><b>" + html(type.id) + "</b>";
  if (!type.category.empty()) out += " <i>(" + html(type.category) + ")</i>";
  out += "<br>" + html(type.description) + "</p>";
  const std::pair<const char*, std::vector<std::string>> sections[] = {
      {"inputs", {"input", "param_in"}}, {"outputs", {"output", "param_out"}}, {"slots", {"slot"}}, {"triggers", {"trigger"}}};
  for (const auto& [title, kinds] : sections) {
    QString lines;
    for (const auto& p : type.ports)
      if (std::find(kinds.begin(), kinds.end(), p.kind) != kinds.end())
        lines += "<br>&nbsp;&nbsp;" + html(p.name) + (p.type.empty() ? QString() : ": " + html(p.type)) +
                 (p.optional ? " (optional)" : "");
    if (!lines.isEmpty()) out += QString("<p><b>%1</b>").arg(title) + lines + "</p>";
  }
  if (type.parameters.empty()) return out;
  out += "<p><b>parameters</b>";
  for (const auto& p : type.parameters) {
    QString value = QString::fromStdString(p.default_value);
    if (value.size() > 40) value = value.left(39) + QChar(0x2026);  // a long list or text: its start
    out += "<br>&nbsp;&nbsp;" + html(p.name) + " (" + html(p.kind) + ") = " + value.toHtmlEscaped();
  }
  return out + "</p>";
}

std::vector<apex::NodeTypeInfo> Palette::inOrder(std::vector<apex::NodeTypeInfo> types) {
  std::stable_sort(types.begin(), types.end(),
                   [](const apex::NodeTypeInfo& a, const apex::NodeTypeInfo& b) { return place(a) < place(b); });
  return types;
}

void Palette::showTypes(const std::vector<apex::NodeTypeInfo>& types) {
  const QString picked = current();
  tree_->clear();
  std::map<std::tuple<int, int, QString>, QTreeWidgetItem*> headings;
  for (const auto& t : types) {
    const auto key = place(t);
    QTreeWidgetItem*& heading = headings[key];
    if (!heading) {
      heading = new QTreeWidgetItem({std::get<2>(key)});
      heading->setFlags(Qt::ItemIsEnabled);
      QFont bold = heading->font(0);
      bold.setBold(true);
      heading->setFont(0, bold);
    }
    const QString id = QString::fromStdString(t.id);
    auto* item = new QTreeWidgetItem(heading, {TypeQuery::shortName(id)});
    item->setData(0, kId, id);
    item->setData(0, kSearched, TypeQuery::searched(t));
    item->setToolTip(0, tooltip(t));
  }
  for (const auto& [key, heading] : headings) {
    heading->setToolTip(0, QString("%1 node type%2").arg(heading->childCount()).arg(heading->childCount() == 1 ? "" : "s"));
    tree_->addTopLevelItem(heading);
  }
  filter();
  if (searching() || picked.isEmpty()) return;
  for (int i = 0; i < tree_->topLevelItemCount(); ++i)  // the type picked before, picked again
    for (int j = 0; j < tree_->topLevelItem(i)->childCount(); ++j)
      if (tree_->topLevelItem(i)->child(j)->data(0, kId).toString() == picked)
        tree_->setCurrentItem(tree_->topLevelItem(i)->child(j));
}

bool Palette::searching() const { return !search_->text().trimmed().isEmpty(); }

void Palette::filter() {
  const TypeQuery query(search_->text());
  QTreeWidgetItem* best = nullptr;
  int best_rank = 4;
  for (int i = 0; i < tree_->topLevelItemCount(); ++i) {
    QTreeWidgetItem* heading = tree_->topLevelItem(i);
    int shown = 0;
    for (int j = 0; j < heading->childCount(); ++j) {
      QTreeWidgetItem* type = heading->child(j);
      const bool match = query.matches(type->data(0, kSearched).toString());
      type->setHidden(!match);
      if (!match) continue;
      ++shown;
      const int r = query.rank(type->data(0, kId).toString());
      if (r < best_rank) best = type, best_rank = r;
    }
    heading->setHidden(shown == 0);
    heading->setExpanded(query.isEmpty() ? open_.contains(heading->text(0)) : true);
  }
  if (query.isEmpty()) return;  // the type picked stays picked
  tree_->setCurrentItem(best);
  if (best) tree_->scrollToItem(best);
}

QString Palette::current() const {
  const QTreeWidgetItem* item = tree_->currentItem();
  return item && !item->isHidden() ? item->data(0, kId).toString() : QString();
}

void Palette::addCurrent() {
  const QString text = search_->text().simplified();
  if (text.isEmpty()) return emit refused("type a node type's name (or a word of its description), then Enter");
  const QString id = current();
  if (id.isEmpty()) return emit refused("no node type matches '" + text + "'");
  emit addRequested(id);
}

void Palette::helpCurrent() {
  const QString id = current();
  if (id.isEmpty()) return emit refused("pick a node type in the list (or search for one), then F1 explains it");
  emit helpRequested(id);
}

void Palette::fillMenu(QMenu& menu, const QString& type) {
  menu.addAction("Add " + TypeQuery::shortName(type), this, [this, type] { emit addRequested(type); });
  menu.addAction("Help (F1)", this, [this, type] { emit helpRequested(type); });
}

void Palette::showMenu(const QPoint& at) {
  const QTreeWidgetItem* item = tree_->itemAt(at);
  const QString id = item ? item->data(0, kId).toString() : QString();
  if (id.isEmpty()) return;  // a heading
  QMenu menu;
  fillMenu(menu, id);
  menu.exec(tree_->viewport()->mapToGlobal(at));
}

bool Palette::eventFilter(QObject* watched, QEvent* event) {
  if (event->type() != QEvent::KeyPress) return QWidget::eventFilter(watched, event);
  const int key = static_cast<QKeyEvent*>(event)->key();
  if (key == Qt::Key_F1) return helpCurrent(), true;
  QTreeWidgetItem* item = tree_->currentItem();
  if (watched == search_ && key == Qt::Key_Down) {  // to the list: at the best match, or the first heading
    if (item && item->parent() && !item->parent()->isExpanded()) item = item->parent();
    for (int i = 0; (!item || item->isHidden()) && i < tree_->topLevelItemCount(); ++i)
      if (!tree_->topLevelItem(i)->isHidden()) item = tree_->topLevelItem(i);
    if (item && !item->isHidden()) tree_->setCurrentItem(item);
    tree_->setFocus();
    return true;
  }
  if (watched == tree_ && key == Qt::Key_Up && (!item || !tree_->itemAbove(item))) {  // the top: back to the search
    search_->setFocus();
    return true;
  }
  if (watched == tree_ && (key == Qt::Key_Return || key == Qt::Key_Enter) && item && item->data(0, kId).isNull()) {
    item->setExpanded(!item->isExpanded());  // a heading: opened or closed
    return true;
  }
  return QWidget::eventFilter(watched, event);
}

}  // namespace apex_rviz_plugin
