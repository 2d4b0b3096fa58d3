#include "apex_rviz_plugin/param_editor.hpp"

#include "apex_rviz_plugin/file_dialog.hpp"

#include <yaml-cpp/yaml.h>

#include <QAbstractSlider>
#include <QCheckBox>
#include <QColorDialog>
#include <QPointer>
#include <QComboBox>
#include <QDial>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QFileInfo>
#include <QLineEdit>
#include <QPushButton>
#include <QSlider>
#include <QSpinBox>
#include <QVBoxLayout>

#include <algorithm>

#include <cmath>

namespace apex_rviz_plugin {
namespace {

YAML::Node parse(const std::string& text) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception&) {
    return YAML::Node();
  }
}

template <class T>
T as(const YAML::Node& n, T fallback) {
  try {
    return n ? n.as<T>() : fallback;
  } catch (const YAML::Exception&) {
    return fallback;
  }
}

QString number(double v) { return QString::number(v, 'g', 10); }

/** Whether two YAML texts say the same value: 'x' and x, 25 and 25.0, [a, b] and [ a,b ]
 *  (but not '1' and "1.0": strings). */
bool same(const YAML::Node& a, const YAML::Node& b) {
  if (a.Type() != b.Type()) return false;
  if (a.IsScalar()) {  // numbers by value where both are plain; a quoted "1.0" is a string
    double x, y;
    if (a.Tag() == "?" && b.Tag() == "?" && YAML::convert<double>::decode(a, x) && YAML::convert<double>::decode(b, y))
      return x == y;
    return a.Scalar() == b.Scalar();
  }
  if (a.IsSequence()) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!same(a[i], b[i])) return false;
    return true;
  }
  if (a.IsMap()) {
    if (a.size() != b.size()) return false;
    for (const auto& kv : a)
      if (!b[kv.first.Scalar()] || !same(kv.second, b[kv.first.Scalar()])) return false;
    return true;
  }
  return true;  // both null
}

/** Whether the text was typed into since it was last sent or shown; forgets it (Qt emits
 *  editingFinished on Return and again when the focus leaves). */
bool typedInto(QLineEdit* line) {
  const bool typed = line->isModified();
  line->setModified(false);
  return typed;
}

bool sameText(const std::string& a, const std::string& b) {
  if (a == b) return true;
  try {
    return same(YAML::Load(a), YAML::Load(b));
  } catch (const YAML::Exception&) {
    return false;  // not YAML: only the very same text is the same
  }
}

/** A YAML single-quoted string: reads back as exactly `s`. */
QString quoted(const QString& s) { return "'" + QString(s).replace("'", "''") + "'"; }

/** A slider over [min, max] in at most 1000 steps, for a double value; logarithmic for a
 *  positive range over more than two decades (0.01 to 1000: each decade as wide as the next). */
struct SliderScale {
  double min, max, step;
  bool log() const { return min > 0 && max / min > 100; }
  int steps() const { return log() ? 1000 : std::max(1, std::min(1000, static_cast<int>(std::lround((max - min) / step)))); }
  int toSlider(double v) const {
    const double f = log() ? std::log(std::max(v, min) / min) / std::log(max / min) : (v - min) / (max - min);
    return static_cast<int>(std::lround(f * steps()));
  }
  double fromSlider(int i) const {
    const double f = static_cast<double>(i) / steps();
    if (!log()) return min + (max - min) * f;
    const double v = min * std::pow(max / min, f);
    return std::clamp(min + std::round((v - min) / step) * step, min, max);  // on the parameter's steps
  }
};

QSlider* makeSlider(const SliderScale& s) {
  auto* slider = new QSlider(Qt::Horizontal);
  slider->setRange(0, s.steps());
  slider->setMinimumWidth(60);
  if (s.log()) slider->setToolTip("logarithmic: each decade takes the same width");
  return slider;
}

/** What the parameter is: its kind, range, default and description. */
QString tip(const apex::ParamInfo& p) {
  QString t = QString::fromStdString(p.name + " (" + p.kind + ")");
  if (p.kind.find("range") != std::string::npos || p.kind == "interval")
    t += QString(": %1 to %2").arg(number(p.min), number(p.max)) + (p.step > 0 ? ", step " + number(p.step) : "");
  if (!p.options.empty()) {
    QStringList o;
    for (const auto& x : p.options) o << QString::fromStdString(x);
    t += p.kind == "path" ? ": files " + o.join(" ") : ": one of " + o.join(", ");
  }
  t += "\ndefault " + QString::fromStdString(p.default_value);
  if (!p.description.empty()) t += "\n" + QString::fromStdString(p.description);
  return t + "\n(right-click: reset to default)";
}

/** A line edit that asks for the width of its text (a file path, a topic list), up to a
 *  limit: the node's box is sized from its editors' size hints, so values are shown whole. */
class FittingLineEdit : public QLineEdit {
 public:
  FittingLineEdit() {
    connect(this, &QLineEdit::textChanged, this, [this] { updateGeometry(); });  // a new text, a new hint
  }
  QSize sizeHint() const override {
    QSize s = QLineEdit::sizeHint();
    const int wide = fontMetrics().horizontalAdvance(text()) + 16;  // frame and margins
    s.setWidth(std::clamp(wide, 60, 340));  // with its label and buttons, within the widest box
    return s;
  }
};

}  // namespace

ParamEditor::ParamEditor(const apex::ParamInfo& param, QWidget* parent) : QWidget(parent), param_(param) {
  setObjectName(QString::fromStdString("param_" + param.name));
  setToolTip(tip(param));
  throttle_.setSingleShot(true);
  connect(&throttle_, &QTimer::timeout, this, [this] {
    if (!pending_.isEmpty()) emit edited(QString::fromStdString(param_.name), pending_, true);
    drag_sent_ = drag_sent_ || !pending_.isEmpty();
    pending_.clear();
  });
  auto* column = new QVBoxLayout(this);  // the name and value on one line; a slider below, full width
  column->setContentsMargins(0, 0, 0, 0);
  column->setSpacing(0);
  auto* row = row_ = new QHBoxLayout;
  row->setContentsMargins(0, 0, 0, 0);
  row->setSpacing(4);
  column->addLayout(row);
  auto* label = new QLabel(QString::fromStdString(param.name));
  label->setMinimumWidth(50);
  row->addWidget(label, 1);
  for (QWidget* w : std::initializer_list<QWidget*>{this, label}) {  // reset to default; a number can be tuned too
    w->setContextMenuPolicy(Qt::CustomContextMenu);  // the name too, not only the value's widgets
    connect(w, &QWidget::customContextMenuRequested, this,
            [this, w](const QPoint& at) { emit menuRequested(QString::fromStdString(param_.name), w->mapToGlobal(at)); });
  }
  build();
  if (!param.type.empty()) {  // a parameter with a port type can be linked: show its ports
    interactive_ = new QCheckBox;
    interactive_->setObjectName("interactive");
    interactive_->setToolTip("interactive: give this parameter an input and an output port");
    interactive_->setChecked(param.interactive);
    connect(interactive_, &QCheckBox::toggled, this, [this](bool on) {
      if (!updating_) emit interactiveToggled(QString::fromStdString(param_.name), on);
    });
    row->addWidget(interactive_);
  }
  showApplied(param);
}

void ParamEditor::showApplied(const apex::ParamInfo& param) {
  param_ = param;
  if (throttle_.isActive()) return;  // a value is on its way: the next graph shows it
  for (auto* s : findChildren<QAbstractSlider*>())
    if (s->isSliderDown()) return;  // being dragged: not moved under the mouse
  updating_ = true;
  show_(param.value);
  if (interactive_) interactive_->setChecked(param.interactive);
  updating_ = false;
}

void ParamEditor::send(const QString& yaml, bool dragging) {
  if (updating_) return;
  if (!dragging) {
    const bool ends_drag = drag_sent_ || throttle_.isActive();
    if (sameText(yaml.toStdString(), param_.value) && !ends_drag) return;  // unchanged (e.g. focus left): no edit
    throttle_.stop();
    pending_.clear();
    drag_sent_ = false;
    emit edited(QString::fromStdString(param_.name), yaml);
    return;
  }
  pending_ = yaml;
  if (!throttle_.isActive()) throttle_.start(kThrottleMs);
}

void ParamEditor::build() {
  const std::string& k = param_.kind;
  if (k == "bool") {
    auto* box = new QCheckBox;
    row_->addWidget(box);
    connect(box, &QCheckBox::toggled, this, [this](bool on) { send(on ? "true" : "false", false); });
    show_ = [box](const std::string& v) { box->setChecked(as<bool>(parse(v), false)); };
  } else if (k == "int" || k == "int range") {
    buildNumber(true);
  } else if (k == "double" || k == "double range") {
    buildNumber(false);
  } else if (k == "interval") {
    buildInterval();
  } else if (k == "set") {
    buildSet();
  } else if (k == "angle") {
    buildAngle();
  } else if (k == "path") {
    buildPath();
  } else if (k == "color") {
    buildColor();
  } else {
    buildText();
  }
}

void ParamEditor::buildNumber(bool integer) {
  const bool ranged = param_.kind.find("range") != std::string::npos;
  const double lo = ranged ? param_.min : -1e9, hi = ranged ? param_.max : 1e9;
  const double step = param_.step > 0 ? param_.step : (integer ? 1 : 0.01);
  auto* spin = new QDoubleSpinBox;
  spin->setObjectName("spin");
  spin->setDecimals(integer ? 0 : 4);
  spin->setRange(lo, hi);
  spin->setSingleStep(step);
  spin->setKeyboardTracking(false);  // typed digits go out on Enter or focus loss
  spin->setMinimumWidth(76);
  auto text = [integer](double v) { return integer ? QString::number(std::lround(v)) : number(v); };
  QSlider* slider = nullptr;
  const SliderScale scale{lo, hi, step};
  if (ranged && hi > lo) {
    slider = makeSlider(scale);
    static_cast<QBoxLayout*>(layout())->addWidget(slider);  // below the line
    connect(slider, &QSlider::valueChanged, this, [this, spin, slider, scale, text](int i) {
      const double v = scale.fromSlider(i);
      QSignalBlocker block(spin);
      spin->setValue(v);
      send(text(v), slider->isSliderDown());
    });
    connect(slider, &QSlider::sliderReleased, this,
            [this, slider, scale, text] { send(text(scale.fromSlider(slider->value())), false); });
  }
  row_->addWidget(spin);
  connect(spin, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this, slider, scale, text](double v) {
    if (slider) {
      QSignalBlocker block(slider);
      slider->setValue(scale.toSlider(v));
    }
    send(text(v), false);
  });
  show_ = [spin, slider, scale](const std::string& v) {
    const auto* typing = spin->findChild<QLineEdit*>();
    if (spin->hasFocus() && typing && typing->isModified()) return;  // digits typed, not sent yet: kept
    const double d = as<double>(parse(v), 0.0);
    QSignalBlocker b1(spin);
    spin->setValue(d);
    if (slider) {
      QSignalBlocker b2(slider);
      slider->setValue(scale.toSlider(d));
    }
  };
}

void ParamEditor::buildInterval() {
  const SliderScale scale{param_.min, param_.max, param_.step > 0 ? param_.step : 0.01};
  QSlider* low = makeSlider(scale);
  QSlider* high = makeSlider(scale);
  low->setObjectName("low"), high->setObjectName("high");
  auto* values = new QLabel;
  row_->addWidget(values);
  for (QSlider* s : {low, high}) static_cast<QBoxLayout*>(layout())->addWidget(s);
  auto value = [scale, low, high] {
    return "[" + number(scale.fromSlider(low->value())) + ", " + number(scale.fromSlider(high->value())) + "]";
  };
  for (QSlider* s : {low, high}) {
    connect(s, &QSlider::valueChanged, this, [this, low, high, s, values, value] {
      if (low->value() > high->value()) (s == low ? high : low)->setValue(s->value());  // keep low <= high
      values->setText(value());
      send(value(), s->isSliderDown());
    });
    connect(s, &QSlider::sliderReleased, this, [this, value] { send(value(), false); });
  }
  show_ = [scale, low, high, values](const std::string& v) {
    const YAML::Node n = parse(v);
    QSignalBlocker b1(low), b2(high);
    low->setValue(scale.toSlider(as<double>(n.IsSequence() ? n[0] : n["low"], scale.min)));
    high->setValue(scale.toSlider(as<double>(n.IsSequence() ? n[1] : n["high"], scale.max)));
    values->setText(QString::fromStdString(v));
  };
}

void ParamEditor::buildSet() {
  auto* combo = new QComboBox;
  for (const auto& o : param_.options) combo->addItem(QString::fromStdString(o));
  row_->addWidget(combo);
  connect(combo, QOverload<int>::of(&QComboBox::activated), this,
          [this, combo](int) { send(quoted(combo->currentText()), false); });
  show_ = [combo](const std::string& v) {
    QSignalBlocker block(combo);
    combo->setCurrentText(QString::fromStdString(as<std::string>(parse(v), v)));
  };
}

void ParamEditor::buildAngle() {
  auto* dial = new QDial;
  dial->setRange(-180, 180);
  dial->setWrapping(true);
  dial->setFixedSize(40, 40);
  auto* spin = new QDoubleSpinBox;
  spin->setObjectName("spin");
  spin->setSuffix(QString::fromUtf8("\u00b0"));
  spin->setRange(param_.max > param_.min ? param_.min * 180 / M_PI : -360,
                 param_.max > param_.min ? param_.max * 180 / M_PI : 360);
  spin->setKeyboardTracking(false);
  row_->addWidget(dial), row_->addWidget(spin);
  auto radians = [](double deg) { return number(deg * M_PI / 180); };
  connect(dial, &QDial::valueChanged, this, [this, dial, spin, radians](int deg) {
    QSignalBlocker block(spin);
    spin->setValue(deg);
    send(radians(deg), dial->isSliderDown());
  });
  connect(dial, &QDial::sliderReleased, this, [this, dial, radians] { send(radians(dial->value()), false); });
  connect(spin, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this, dial, radians](double deg) {
    QSignalBlocker block(dial);
    dial->setValue(static_cast<int>(std::lround(deg)));
    send(radians(deg), false);
  });
  show_ = [dial, spin](const std::string& v) {
    const double deg = as<double>(parse(v), 0.0) * 180 / M_PI;
    QSignalBlocker b1(dial), b2(spin);
    dial->setValue(static_cast<int>(std::lround(deg)));
    spin->setValue(deg);
  };
}

void ParamEditor::buildPath() {
  auto* line = new FittingLineEdit;
  auto* browse = new QPushButton("...");
  browse->setFixedWidth(28);
  row_->addWidget(line), row_->addWidget(browse);
  connect(line, &QLineEdit::editingFinished, this, [this, line] {
    if (!typedInto(line)) return;  // Return, then focus away: one edit
    send(quoted(line->text()), false);
  });
  connect(browse, &QPushButton::clicked, this, [this, line] {  // in the current file's folder
    const std::string& mode = param_.path_mode;
    QStringList files;  // the kinds of file the node takes first, then any
    for (const auto& o : param_.options) files << QString::fromStdString(o);
    const QString filter =
        files.isEmpty() ? "" : QString::fromStdString(param_.name) + " (" + files.join(" ") + ");;All files (*)";
    const FileDialogSpec spec{"path_dialog",
                              QString::fromStdString(param_.name),
                              line->text().isEmpty() ? lastChosenFolder() : line->text(),
                              mode == "directory" ? FileDialogSpec::Mode::Directory
                              : mode == "write"   ? FileDialogSpec::Mode::Save
                                                  : FileDialogSpec::Mode::Open,
                              filter,
                              ""};
    openFileDialog(dialog_, this, spec, [this, line](const QString& path) {
      lastChosenFolder() = QFileInfo(path).absolutePath();
      line->setText(path);
      send(quoted(path), false);
    });
  });
  show_ = [line](const std::string& v) { line->setText(QString::fromStdString(as<std::string>(parse(v), v))); };
}

void ParamEditor::buildColor() {
  auto* button = new QPushButton;
  button->setFixedWidth(48);
  row_->addWidget(button);
  auto paint = [button](const QColor& c) { button->setStyleSheet("background-color: " + c.name()); };
  auto current = std::make_shared<QColor>();
  connect(button, &QPushButton::clicked, this, [this, current, paint] {
    const QPointer<ParamEditor> self(this);  // the dialog's own event loop: the box may be rebuilt meanwhile
    const QColor c = QColorDialog::getColor(*current, dialogParent(this), QString::fromStdString(param_.name));
    if (!self || !c.isValid()) return;
    *current = c;
    paint(c);
    send(QString("[%1, %2, %3]").arg(c.red()).arg(c.green()).arg(c.blue()), false);
  });
  show_ = [current, paint](const std::string& v) {
    const YAML::Node n = parse(v);
    if (n.IsSequence() && n.size() == 3) *current = QColor(as<int>(n[0], 0), as<int>(n[1], 0), as<int>(n[2], 0));
    else if (n.IsMap()) *current = QColor(as<int>(n["r"], 0), as<int>(n["g"], 0), as<int>(n["b"], 0));
    paint(*current);
  };
}

void ParamEditor::buildText() {  // strings as text; pairs and lists as their YAML
  const bool is_string = param_.kind == "string";
  auto* line = new FittingLineEdit;
  row_->addWidget(line);
  connect(line, &QLineEdit::editingFinished, this, [this, line, is_string] {
    if (!typedInto(line)) return;  // Return, then focus away: one edit
    send(is_string ? quoted(line->text()) : line->text(), false);
  });
  show_ = [line, is_string](const std::string& v) {
    if (line->hasFocus()) return;  // being typed into
    line->setText(QString::fromStdString(is_string ? as<std::string>(parse(v), v) : v));
  };
}

}  // namespace apex_rviz_plugin
