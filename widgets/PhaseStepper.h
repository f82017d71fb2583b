#pragma once
// Lists a method's phases with their state (done / current / pending, or
// running), and for each phase that has run its time, the counters it set or
// changed, the other counters of its snapshot (unchanged, in a collapsed
// group), its post-condition violations and its notes; within a branch's
// range (pipeline/Branch.h) which run it shows ("run 2 of 3, adopted") and
// every run the branch judged. Buttons ask to reset,
// step back, step, or run to the end; the owner runs the phases.
#include "pipeline/Method.h"
#include "pipeline/Snapshot.h"

#include <QString>
#include <QStringList>
#include <QWidget>
#include <utility>
#include <vector>

class QPushButton;
class QTreeWidget;
class QTreeWidgetItem;

namespace contour {

class PhaseStepper : public QWidget {
    Q_OBJECT

public:
    enum class PhaseState { Pending, Running, Current, Done };

    explicit PhaseStepper(QWidget* parent = nullptr);

    // Lists the method's phases, all pending; null clears the list.
    void setMethod(const Method* method);
    // snapshots[0] is the input, snapshots[i] the state after phase i - 1.
    void setSnapshots(const std::vector<Snapshot>& snapshots);
    // While busy the buttons are disabled; runningPhase (or -1) is marked.
    void setBusy(bool busy, int runningPhase = -1);
    bool isBusy() const { return busy_; }

    int phaseCount() const;
    int completedPhases() const { return completed_; }
    PhaseState phaseState(int phase) const;
    static QString toString(PhaseState state);
    // What the list shows for a phase: the counters it set or changed (name,
    // value), or with `includeUnchanged` every counter of its snapshot, and
    // its time and notes.
    std::vector<std::pair<QString, double>> displayedCounters(int phase,
                                                              bool includeUnchanged = false) const;
    QStringList displayedNotes(int phase) const;
    QString displayedTime(int phase) const;
    // Within a branch's range: the run row ("cusp-retry: run 2 of 3,
    // adopted (…)"), and one line per run judged; empty elsewhere.
    QString displayedRun(int phase) const;
    QStringList displayedBranchRuns(int phase) const;

    QPushButton* resetButton() const { return reset_; }
    QPushButton* backButton() const { return back_; }
    QPushButton* stepButton() const { return step_; }
    QPushButton* runButton() const { return run_; }

signals:
    void resetRequested();
    void backRequested();
    void stepRequested();
    void runToEndRequested();

private:
    void refresh();
    QTreeWidgetItem* phaseItem(int phase) const;

    QTreeWidget* tree_;
    QPushButton* reset_;
    QPushButton* back_;
    QPushButton* step_;
    QPushButton* run_;
    const Method* method_ = nullptr;
    std::vector<Snapshot> snapshots_;
    int completed_ = 0;
    bool busy_ = false;
    int runningPhase_ = -1;
};

} // namespace contour
