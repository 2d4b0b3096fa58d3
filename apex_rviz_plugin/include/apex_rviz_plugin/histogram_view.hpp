// A node's histograms in a window of their own (its menu: "Latency histogram..."): firing time
// and latency from its frames' stamps over the last 5-10 s, as bars on a log scale, with the
// median and 95th percentile marked, asked for again every second (~node_profile).
#pragma once

#include <apex/GetNodeProfile.h>

#include <QDialog>
#include <QWidget>

class QLabel;
class QTimer;

namespace apex_rviz_plugin {

/** @brief Bars of one histogram ([lower, upper) ms, count), drawn on a log scale. */
struct Bars {
  std::vector<double> lower_ms, upper_ms;
  std::vector<std::uint64_t> counts;
  std::uint64_t total() const;
  /** The q-quantile, ms (the middle of its bar); -1 if empty. */
  double quantileMs(double q) const;
  /** "412 over 7.3 s · p50 0.12 ms · p95 0.25 ms · max < 0.31 ms", or `none`. */
  QString summary(double window_s, const QString& none) const;
};

class HistogramChart : public QWidget {
 public:
  explicit HistogramChart(QWidget* parent = nullptr);
  void setBars(Bars bars) { bars_ = std::move(bars), update(); }
  const Bars& bars() const { return bars_; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  Bars bars_;
};

class HistogramView : public QDialog {
  Q_OBJECT
 public:
  HistogramView(const QString& node, QWidget* parent = nullptr);
  const QString& node() const { return node_; }
  /** @brief Shows an answer of ~node_profile (failed: its message). */
  void showProfile(bool ok, const std::string& message, const apex::GetNodeProfile::Response& res);
  const HistogramChart* timeChart() const { return time_; }
  const HistogramChart* latencyChart() const { return latency_; }
  QString timeText() const;
  QString latencyText() const;

 signals:
  /** Every second while shown: the panel asks the runtime and calls showProfile. */
  void refreshRequested(const QString& node);

 protected:
  void showEvent(QShowEvent* e) override;
  void hideEvent(QHideEvent* e) override;

 private:
  QString node_;
  HistogramChart *time_, *latency_;
  QLabel *time_text_, *latency_text_;
  QTimer* timer_;
};

}  // namespace apex_rviz_plugin
