// The quick-add box: a small search field and list that opens at the cursor (Tab or Space in the
// view, a double-click on empty canvas, a link let go on empty canvas), offers node types as the
// palette finds them (TypeQuery: names, categories, descriptions) and says which one was chosen.
// It is a popup: Esc or a click elsewhere closes it. Where the node goes is the editor's business.
#pragma once

#include <QFrame>
#include <QString>

#include <apex/NodeTypeInfo.h>

#include <vector>

class QLabel;
class QLineEdit;
class QListWidget;

namespace apex_rviz_plugin {

class QuickAdd : public QFrame {
  Q_OBJECT
 public:
  /** @brief A type offered, and the port of it a dragged link goes to ("" when adding alone). */
  struct Offer {
    apex::NodeTypeInfo type;
    QString port;
  };

  explicit QuickAdd(QWidget* parent = nullptr);
  /** @brief Opens with its top-left corner at `global` (kept on the screen), offering `offers` in
   *  their order (the best matches first once something is typed), under `title`. */
  void open(std::vector<Offer> offers, QPoint global, const QString& title);
  /** @brief The type Enter adds (the best match, or the one picked); "" if none. */
  QString current() const;
  /** @brief The ids of the types shown, in their order. */
  QStringList shown() const;
  QLineEdit* search() const { return search_; }
  QListWidget* list() const { return list_; }

 signals:
  /** A type chosen (Enter, a click): `port` is its port a dragged link goes to, or "". */
  void chosen(const QString& type, const QString& port);
  /** F1 on a type. */
  void helpRequested(const QString& type);

 protected:
  /** Up and Down in the search field move in the list; F1 asks for the current type's help. */
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  /** The offers that hold every word typed, best first. */
  void filter();
  /** What the current type is: its category and description, and the port a link goes to. */
  void describeCurrent();
  void choose();

  QLabel* title_;
  QLineEdit* search_;
  QListWidget* list_;
  QLabel* about_;
  std::vector<Offer> offers_;
};

}  // namespace apex_rviz_plugin
