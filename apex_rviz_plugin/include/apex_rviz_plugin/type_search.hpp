// How a person finds a node type by typing: every word typed must be in the type's id, category
// or description; the best match is the one whose name is the phrase, then whose name starts with
// it, then whose id holds it. One rule for the palette and the quick-add box at the cursor.
#pragma once

#include <QString>
#include <QStringList>

#include <apex/NodeTypeInfo.h>

namespace apex_rviz_plugin {

class TypeQuery {
 public:
  /** @brief What was typed (case and extra spaces do not matter). */
  explicit TypeQuery(const QString& typed);
  /** @brief Nothing typed: every type matches and none is best. */
  bool isEmpty() const { return words_.isEmpty(); }
  /** @brief Whether every word typed is in `searched` (a type's searched(); true when nothing is typed). */
  bool matches(const QString& searched) const;
  /** @brief How well a type that matches fits, lower is better: 0 its short name or id is what was
   *  typed, 1 its name starts with it, 2 its id holds it, 3 the words are found elsewhere; 4 when
   *  nothing is typed. */
  int rank(const QString& id) const;

  /** @brief What is searched of a type: its id, category and description, in lower case. */
  static QString searched(const apex::NodeTypeInfo& type);
  /** @brief A type's name without its package: "GaussianBlur" for "apex_nodes/GaussianBlur". */
  static QString shortName(const QString& id);

 private:
  QString phrase_;  ///< what was typed, simplified, in lower case
  QStringList words_;
};

}  // namespace apex_rviz_plugin
