#include "apex_rviz_plugin/type_search.hpp"

#include <algorithm>

namespace apex_rviz_plugin {

TypeQuery::TypeQuery(const QString& typed)
    : phrase_(typed.simplified().toLower()), words_(phrase_.split(' ', Qt::SkipEmptyParts)) {}

bool TypeQuery::matches(const QString& searched) const {
  return std::all_of(words_.begin(), words_.end(), [&](const QString& w) { return searched.contains(w); });
}

int TypeQuery::rank(const QString& type_id) const {
  if (isEmpty()) return 4;
  const QString id = type_id.toLower(), name = shortName(type_id).toLower();
  if (name == phrase_ || id == phrase_) return 0;
  if (name.startsWith(phrase_)) return 1;
  return id.contains(phrase_) ? 2 : 3;
}

QString TypeQuery::searched(const apex::NodeTypeInfo& type) {
  return QString::fromStdString(type.id + '\n' + type.category + '\n' + type.description).toLower();
}

QString TypeQuery::shortName(const QString& id) {
  const int slash = id.indexOf('/');
  return slash > 0 ? id.mid(slash + 1) : id;
}

}  // namespace apex_rviz_plugin
