// The panel's side of the runtime's recovery copy (issue #35): on connecting, it asks the
// runtime whether a previous run left an unsaved graph, and offers it in the RecoveryBar.
#include <QDateTime>

#include "apex_rviz_plugin/panel_widget.hpp"
#include "apex_rviz_plugin/recovery_bar.hpp"

namespace apex_rviz_plugin {

void PanelWidget::askRecovery() {
  // An older runtime has no ~recovery: no answer, no bar.
  link_.recovery("keep", [this](bool ok, const std::string&, const apex::Recovery::Response& res) {
    if (!ok || !res.offered) return recovery_->withdraw();
    recovery_->offer(QDateTime::fromMSecsSinceEpoch(static_cast<qint64>(res.written.toNSec() / 1000000)),
                     static_cast<int>(res.nodes));
  });
}

void PanelWidget::onRecoveryRestore() {
  recovery_->setBusy(true);
  const auto done = replacingGraph("restored the unsaved graph");  // as a Load: a fresh history
  link_.recovery("restore", [this, done](bool ok, const std::string& m, const apex::Recovery::Response& res) {
    done(ok, m);
    if (res.offered || !ok) recovery_->setBusy(false);  // refused, or no answer: still offered, to try again
    else recovery_->withdraw();
  });
}

void PanelWidget::onRecoveryDiscard() {
  recovery_->setBusy(true);
  link_.recovery("discard", [this](bool ok, const std::string& m, const apex::Recovery::Response& res) {
    report(ok, m, "discarded the unsaved graph");
    if (res.offered || !ok) recovery_->setBusy(false);
    else recovery_->withdraw();
  });
}

}  // namespace apex_rviz_plugin
