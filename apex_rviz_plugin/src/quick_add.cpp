#include "apex_rviz_plugin/quick_add.hpp"

#include <QGuiApplication>
#include <QKeyEvent>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QScreen>
#include <QVBoxLayout>

#include <algorithm>

#include "apex_rviz_plugin/palette.hpp"
#include "apex_rviz_plugin/type_search.hpp"

namespace apex_rviz_plugin {
namespace {

constexpr int kOffer = Qt::UserRole;  // an item's index in offers_

/** `at` moved so that a `size` box at it stays inside `window` (rviz's, global coordinates) where
 *  it fits there, else on the screen it is on. */
QPoint inside(QPoint at, QSize size, const QRect& window) {
  const QScreen* screen = QGuiApplication::screenAt(at);
  if (!screen) screen = QGuiApplication::primaryScreen();
  QRect room = screen ? screen->availableGeometry() : window;
  if (const QRect both = room & window; both.width() >= size.width() && both.height() >= size.height()) room = both;
  if (room.isEmpty()) return at;
  at.setX(std::max(room.left(), std::min(at.x(), room.right() - size.width())));
  at.setY(std::max(room.top(), std::min(at.y(), room.bottom() - size.height())));
  return at;
}

}  // namespace

QuickAdd::QuickAdd(QWidget* parent)
    : QFrame(parent, Qt::Popup), title_(new QLabel), search_(new QLineEdit), list_(new QListWidget), about_(new QLabel) {
  setObjectName("quick_add");
  setFrameShape(QFrame::StyledPanel);
  search_->setObjectName("quick_add_search");
  search_->setPlaceholderText("Search node types");
  search_->setToolTip(
      "every word typed is in the type's name, category or description; Enter adds the first, "
      "Up and Down pick another, F1 explains it, Esc closes");
  list_->setObjectName("quick_add_list");
  list_->setUniformItemSizes(true);
  list_->setFocusPolicy(Qt::NoFocus);  // the keyboard stays in the search field; Up and Down reach the list
  about_->setObjectName("quick_add_about");
  about_->setWordWrap(true);
  QFont small = about_->font();
  small.setPointSizeF(small.pointSizeF() * 0.9);
  about_->setFont(small);
  about_->setMaximumHeight(QFontMetrics(small).lineSpacing() * 3 + 4);  // three lines of the description
  QFont bold = title_->font();
  bold.setBold(true);
  title_->setFont(bold);
  auto* column = new QVBoxLayout(this);
  column->setContentsMargins(4, 4, 4, 4);
  column->setSpacing(3);
  for (QWidget* w : {static_cast<QWidget*>(title_), static_cast<QWidget*>(search_)}) column->addWidget(w);
  column->addWidget(list_, 1);
  column->addWidget(about_);
  resize(290, 320);
  connect(search_, &QLineEdit::textChanged, this, &QuickAdd::filter);
  connect(search_, &QLineEdit::returnPressed, this, &QuickAdd::choose);
  connect(list_, &QListWidget::itemClicked, this, &QuickAdd::choose);
  connect(list_, &QListWidget::currentRowChanged, this, &QuickAdd::describeCurrent);
  search_->installEventFilter(this);
}

void QuickAdd::open(std::vector<Offer> offers, QPoint global, const QString& title) {
  offers_ = std::move(offers);
  title_->setText(title);
  search_->blockSignals(true);  // one filter() below, not one for the old text's removal too
  search_->clear();
  search_->blockSignals(false);
  filter();
  const QWidget* owner = parentWidget() ? parentWidget()->window() : nullptr;
  const QRect room = owner ? owner->geometry() : QRect();
  move(inside(global, size(), room));
  show();
  move(inside(global, frameGeometry().size(), room));  // as shown: its frame and margins too
  raise();
  activateWindow();
  search_->setFocus(Qt::PopupFocusReason);
}

void QuickAdd::filter() {
  const TypeQuery query(search_->text());
  std::vector<std::pair<int, std::size_t>> hits;  // (rank, offer)
  for (std::size_t i = 0; i < offers_.size(); ++i)
    if (query.matches(TypeQuery::searched(offers_[i].type)))
      hits.emplace_back(query.rank(QString::fromStdString(offers_[i].type.id)), i);
  std::stable_sort(hits.begin(), hits.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  list_->clear();
  for (const auto& [rank, i] : hits) {
    const Offer& o = offers_[i];
    const QString name = TypeQuery::shortName(QString::fromStdString(o.type.id));
    auto* item = new QListWidgetItem(o.port.isEmpty() ? name : name + QString::fromUtf8(" \u00b7 ") + o.port, list_);
    item->setData(kOffer, static_cast<int>(i));
    item->setToolTip(Palette::tooltip(o.type));
  }
  list_->setCurrentRow(hits.empty() ? -1 : 0);
  describeCurrent();
}

void QuickAdd::describeCurrent() {
  const QListWidgetItem* item = list_->currentItem();
  if (!item) return about_->setText(offers_.empty() ? "no node type fits here" : "no node type matches");
  const Offer& o = offers_[static_cast<std::size_t>(item->data(kOffer).toInt())];
  QString text =
      QString::fromStdString(o.type.category.empty() ? "" : o.type.category + ": ") + QString::fromStdString(o.type.description);
  if (!o.port.isEmpty()) text = "the link goes to its '" + o.port + "'. " + text;
  about_->setText(text);
}

QString QuickAdd::current() const {
  const QListWidgetItem* item = list_->currentItem();
  return item ? QString::fromStdString(offers_[static_cast<std::size_t>(item->data(kOffer).toInt())].type.id) : QString();
}

QStringList QuickAdd::shown() const {
  QStringList out;
  for (int i = 0; i < list_->count(); ++i)
    out << QString::fromStdString(offers_[static_cast<std::size_t>(list_->item(i)->data(kOffer).toInt())].type.id);
  return out;
}

void QuickAdd::choose() {
  const QListWidgetItem* item = list_->currentItem();
  if (!item) return;  // nothing matches: the box stays, to type something else
  const Offer o = offers_[static_cast<std::size_t>(item->data(kOffer).toInt())];
  hide();
  emit chosen(QString::fromStdString(o.type.id), o.port);
}

bool QuickAdd::eventFilter(QObject* watched, QEvent* event) {
  if (watched != search_ || event->type() != QEvent::KeyPress) return QFrame::eventFilter(watched, event);
  const int key = static_cast<QKeyEvent*>(event)->key();
  if (key == Qt::Key_Escape) return hide(), true;
  if (key == Qt::Key_F1) {
    if (!current().isEmpty()) emit helpRequested(current());
    return true;
  }
  if (key != Qt::Key_Up && key != Qt::Key_Down && key != Qt::Key_PageUp && key != Qt::Key_PageDown) return false;
  QKeyEvent copy(QEvent::KeyPress, key, Qt::NoModifier);
  QCoreApplication::sendEvent(list_, &copy);  // moves the current row
  return true;
}

}  // namespace apex_rviz_plugin
