// The palette of node types: a search field over a tree of the types the runtime lists
// (ListNodeTypes), one collapsible heading per category, each type by its short name with its
// description, ports and parameters as its tooltip. It says which type the person wants added
// (or explained: F1, or Help in an entry's menu), as a signal; where the node goes is the editor's
// business. What matches a search is TypeQuery's rule (type_search.hpp), shared with quick add.
#pragma once

#include <QSet>
#include <QString>
#include <QWidget>

#include <apex/NodeTypeInfo.h>

#include <vector>

class QLineEdit;
class QMenu;
class QTreeWidget;
class QTreeWidgetItem;

namespace apex_rviz_plugin {

class Palette : public QWidget {
  Q_OBJECT
 public:
  explicit Palette(QWidget* parent = nullptr);
  /** @brief The types under their headings, in the order of headings(); the search and the
   *  headings opened stay as they were. */
  void showTypes(const std::vector<apex::NodeTypeInfo>& types);
  /** @brief The heading a type is listed under: the package of another package's type
   *  ("apex_example/Gain": "apex_example"), else its category, or "other" without one. */
  static QString heading(const apex::NodeTypeInfo& type);
  /** @brief The tooltip of a type: its id and description, its ports with their types, its
   *  parameters with their kinds and defaults (rich text). */
  static QString tooltip(const apex::NodeTypeInfo& type);
  /** @brief The types in the order the palette lists them: by heading (see heading()), in the
   *  order given under each. */
  static std::vector<apex::NodeTypeInfo> inOrder(std::vector<apex::NodeTypeInfo> types);
  /** @brief The id of the type Enter adds: the best match of the search, or the type picked;
   *  "" if none. */
  QString current() const;
  /** @brief The menu of a right-click on a type: Add, Help. Filled for tests to read. */
  void fillMenu(QMenu& menu, const QString& type);

 signals:
  void addRequested(const QString& type);
  /** F1 on a type (in the list or the search field), or Help in its menu. */
  void helpRequested(const QString& type);
  /** Enter with nothing to add: why. */
  void refused(const QString& why);
  void reloadRequested();

 protected:
  /** Down in the search field: to the list, at the best match; Up at the list's top: back.
   *  Enter on a heading opens or closes it. */
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  bool searching() const;
  /** Shows the types whose id, category and description hold every word searched (all when
   *  none), the headings with one shown, opened while searching; the best match current. */
  void filter();
  /** Adds the current type (Enter in the search field). */
  void addCurrent();
  /** Asks for the current type's help (F1). */
  void helpCurrent();
  void showMenu(const QPoint& at);

  QLineEdit* search_;
  QTreeWidget* tree_;
  QSet<QString> open_;  ///< the headings the person opened, when not searching
};

}  // namespace apex_rviz_plugin
