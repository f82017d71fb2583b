#include "PhaseStepper.h"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QPushButton>
#include <QTreeWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

namespace contour {

namespace {

// Item data: what a child row is, and a counter's value.
constexpr int kKindRole = Qt::UserRole + 1;
constexpr int kValueRole = Qt::UserRole + 2;
enum RowKind {
    kCounterRow = 1,
    kInvariantRow = 2,
    kNoteRow = 3,
    kUnchangedGroupRow = 4,
    kUnchangedCounterRow = 5,
    kRunRow = 6,
    kBranchRunRow = 7
};

QString formatValue(double value) {
    if (std::isfinite(value) && value == std::floor(value) && std::abs(value) < 1e15)
        return QString::number(static_cast<long long>(value));
    return QString::number(value, 'g', 6);
}

QString formatSeconds(double seconds) {
    if (seconds < 1.0)
        return QStringLiteral("%1 ms").arg(seconds * 1000.0, 0, 'f', 1);
    return QStringLiteral("%1 s").arg(seconds, 0, 'f', 2);
}

// Counters that `after` set or changed relative to `before`, and the others.
struct CounterSplit {
    std::vector<Counter> changed, unchanged;
};
CounterSplit splitCounters(const Snapshot* before, const Snapshot& after) {
    CounterSplit split;
    for (const Counter& c : after.counters) {
        const double old = before ? before->counter(c.name, std::nan("")) : std::nan("");
        if (std::isnan(old) || old != c.value)
            split.changed.push_back(c);
        else
            split.unchanged.push_back(c);
    }
    return split;
}

QTreeWidgetItem* addCounterRow(QTreeWidgetItem* parent, const Counter& c, RowKind kind) {
    auto* row = new QTreeWidgetItem(parent);
    row->setText(0, QString::fromStdString(c.name));
    row->setText(1, formatValue(c.value));
    row->setTextAlignment(1, Qt::AlignRight | Qt::AlignVCenter);
    row->setData(0, kKindRole, kind);
    row->setData(0, kValueRole, c.value);
    return row;
}

// "run 2: rings 0, levels 1 — 3, post-conditions kept, adopted".
QString describeBranchRun(const BranchSummary& b, size_t k) {
    const BranchRunSummary& r = b.runs[k];
    QString text = QStringLiteral("run %1").arg(k + 1);
    if (!r.label.empty())
        text += QStringLiteral(": %1").arg(QString::fromStdString(r.label));
    text += QStringLiteral(" — %1").arg(r.figure ? formatValue(*r.figure) : QStringLiteral("?"));
    text += r.postconditionsKept ? QStringLiteral(", post-conditions kept")
                                 : QStringLiteral(", a post-condition broken");
    text += r.adopted ? QStringLiteral(", adopted") : QStringLiteral(", rejected");
    return text;
}

// Within a branch's range: which run the snapshot is, and every run the
// branch judged (a child row each, also in the tooltip).
void addRunRows(QTreeWidgetItem* item, const RunInfo& run) {
    const BranchSummary& b = *run.branch;
    auto* row = new QTreeWidgetItem(item);
    row->setText(0, QStringLiteral("%1: %2").arg(QString::fromStdString(b.rule),
                                                 QString::fromStdString(run.describe())));
    row->setData(0, kKindRole, kRunRow);
    row->setForeground(0, QColor(30, 90, 180));
    row->setFirstColumnSpanned(true);
    QStringList lines{QStringLiteral("Branch %1: phases %2 to %3 re-run; first run %4")
                          .arg(QString::fromStdString(b.rule), QString::fromStdString(b.rerunFrom),
                               QString::fromStdString(b.decideAfter), formatValue(b.firstFigure))};
    for (size_t k = 0; k < b.runs.size(); ++k) {
        auto* child = new QTreeWidgetItem(row);
        child->setText(0, describeBranchRun(b, k));
        child->setData(0, kKindRole, kBranchRunRow);
        child->setFirstColumnSpanned(true);
        if (!b.runs[k].adopted)
            child->setForeground(0, QColor(120, 120, 120));
        lines << child->text(0);
    }
    row->setToolTip(0, lines.join('\n'));
}

void fillDetails(QTreeWidgetItem* shown, const CounterSplit& counters, const Snapshot& snapshot) {
    qDeleteAll(shown->takeChildren());
    // The rows are built under an item outside the tree and moved in at
    // once: inserted one by one, each row would make the tree re-measure
    // its columns (a spline method carries about a hundred counters per
    // phase, so a run to the end rebuilt over a thousand rows row by row).
    QTreeWidgetItem staging;
    QTreeWidgetItem* item = &staging;
    if (snapshot.run.inBranch())
        addRunRows(item, snapshot.run);
    for (const Counter& c : counters.changed)
        addCounterRow(item, c, kCounterRow);
    // The state the phase left unchanged (e.g. the consistent method's
    // "inconsistent faces" staying 0) is still there to look at.
    if (!counters.unchanged.empty()) {
        auto* group = new QTreeWidgetItem(item);
        group->setText(0, QStringLiteral("unchanged counters (%1)").arg(counters.unchanged.size()));
        group->setToolTip(0, QStringLiteral("Counters of this snapshot that the phase did not "
                                            "change"));
        group->setForeground(0, QColor(120, 120, 120));
        group->setData(0, kKindRole, kUnchangedGroupRow);
        for (const Counter& c : counters.unchanged) {
            QTreeWidgetItem* row = addCounterRow(group, c, kUnchangedCounterRow);
            row->setForeground(0, QColor(120, 120, 120));
            row->setForeground(1, QColor(120, 120, 120));
        }
    }
    long long failed = 0;
    for (const InvariantCheck& check : snapshot.invariants) {
        if (check.violations == 0)
            continue;
        ++failed;
        auto* row = new QTreeWidgetItem(item);
        row->setText(0, QStringLiteral("✗ %1").arg(QString::fromStdString(check.name)));
        row->setText(1, QString::number(check.violations));
        row->setTextAlignment(1, Qt::AlignRight | Qt::AlignVCenter);
        row->setForeground(0, QColor(200, 30, 30));
        row->setForeground(1, QColor(200, 30, 30));
        row->setToolTip(
            0, QStringLiteral("first: %1").arg(QString::fromStdString(check.firstExample)));
        row->setData(0, kKindRole, kInvariantRow);
    }
    if (!snapshot.invariants.empty() && failed == 0) {
        auto* row = new QTreeWidgetItem(item);
        row->setText(0,
                     QStringLiteral("✓ %1 post-conditions hold").arg(snapshot.invariants.size()));
        row->setForeground(0, QColor(30, 140, 60));
        row->setData(0, kKindRole, kInvariantRow);
        QStringList names;
        for (const InvariantCheck& check : snapshot.invariants)
            names << QString::fromStdString(check.name);
        row->setToolTip(0, names.join('\n'));
    }
    for (const std::string& note : snapshot.notes) {
        auto* row = new QTreeWidgetItem(item);
        row->setText(0, QString::fromStdString(note));
        row->setToolTip(0, QString::fromStdString(note));
        QFont font = row->font(0);
        font.setItalic(true);
        row->setFont(0, font);
        row->setData(0, kKindRole, kNoteRow);
    }
    shown->addChildren(staging.takeChildren());
    // Spanning is a property of the tree's row: set once the row is in it.
    for (int i = 0; i < shown->childCount(); ++i)
        if (shown->child(i)->data(0, kKindRole).toInt() == kNoteRow)
            shown->child(i)->setFirstColumnSpanned(true);
}

} // namespace

PhaseStepper::PhaseStepper(QWidget* parent) : QWidget(parent) {
    tree_ = new QTreeWidget(this);
    tree_->setColumnCount(3);
    tree_->setHeaderLabels({tr("Phase"), tr("State"), tr("Time")});
    tree_->setRootIsDecorated(true);
    tree_->setUniformRowHeights(true);
    tree_->setSelectionMode(QAbstractItemView::NoSelection);
    tree_->header()->setStretchLastSection(false);
    tree_->header()->setSectionResizeMode(0, QHeaderView::Stretch);
    tree_->header()->setSectionResizeMode(1, QHeaderView::ResizeToContents);
    tree_->header()->setSectionResizeMode(2, QHeaderView::ResizeToContents);

    reset_ = new QPushButton(tr("Reset"), this);
    back_ = new QPushButton(tr("Back"), this);
    step_ = new QPushButton(tr("Step"), this);
    run_ = new QPushButton(tr("Run to end"), this);
    reset_->setToolTip(tr("Drop every phase result and return to the input"));
    back_->setToolTip(tr("Drop the last phase result"));
    step_->setToolTip(tr("Run the next phase"));
    run_->setToolTip(tr("Run every remaining phase"));
    connect(reset_, &QPushButton::clicked, this, &PhaseStepper::resetRequested);
    connect(back_, &QPushButton::clicked, this, &PhaseStepper::backRequested);
    connect(step_, &QPushButton::clicked, this, &PhaseStepper::stepRequested);
    connect(run_, &QPushButton::clicked, this, &PhaseStepper::runToEndRequested);

    auto* buttons = new QHBoxLayout;
    buttons->addWidget(reset_);
    buttons->addWidget(back_);
    buttons->addWidget(step_);
    buttons->addWidget(run_);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(tree_, 1);
    layout->addLayout(buttons);
    refresh();
}

void PhaseStepper::setMethod(const Method* method) {
    method_ = method;
    snapshots_.clear();
    completed_ = 0;
    runningPhase_ = -1;
    tree_->clear();
    if (method_) {
        auto* input = new QTreeWidgetItem(tree_);
        input->setText(0, tr("input"));
        input->setToolTip(0, tr("The mesh as loaded and its triangulation"));
        for (const Phase& phase : method_->phases) {
            auto* item = new QTreeWidgetItem(tree_);
            item->setText(0, QString::fromStdString(phase.name));
            item->setToolTip(0, QString::fromStdString(phase.description));
        }
    }
    refresh();
}

void PhaseStepper::setSnapshots(const std::vector<Snapshot>& snapshots) {
    snapshots_ = snapshots;
    completed_ =
        snapshots_.empty() ? 0 : std::min(static_cast<int>(snapshots_.size()) - 1, phaseCount());
    refresh();
}

void PhaseStepper::setBusy(bool busy, int runningPhase) {
    busy_ = busy;
    runningPhase_ = busy ? runningPhase : -1;
    refresh();
}

int PhaseStepper::phaseCount() const {
    return method_ ? static_cast<int>(method_->phases.size()) : 0;
}

PhaseStepper::PhaseState PhaseStepper::phaseState(int phase) const {
    if (busy_ && phase == runningPhase_)
        return PhaseState::Running;
    if (phase < completed_ - 1)
        return PhaseState::Done;
    if (phase == completed_ - 1)
        return PhaseState::Current;
    return PhaseState::Pending;
}

QString PhaseStepper::toString(PhaseState state) {
    switch (state) {
    case PhaseState::Pending:
        return tr("pending");
    case PhaseState::Running:
        return tr("running…");
    case PhaseState::Current:
        return tr("current");
    case PhaseState::Done:
        return tr("done");
    }
    return {};
}

QTreeWidgetItem* PhaseStepper::phaseItem(int phase) const {
    return tree_->topLevelItem(phase + 1); // item 0 is the input
}

std::vector<std::pair<QString, double>>
PhaseStepper::displayedCounters(int phase, bool includeUnchanged) const {
    std::vector<std::pair<QString, double>> counters;
    const QTreeWidgetItem* item = phase < 0 ? tree_->topLevelItem(0) : phaseItem(phase);
    if (!item)
        return counters;
    for (int i = 0; i < item->childCount(); ++i) {
        const QTreeWidgetItem* row = item->child(i);
        const int kind = row->data(0, kKindRole).toInt();
        if (kind == kCounterRow)
            counters.emplace_back(row->text(0), row->data(0, kValueRole).toDouble());
        if (kind == kUnchangedGroupRow && includeUnchanged)
            for (int j = 0; j < row->childCount(); ++j)
                counters.emplace_back(row->child(j)->text(0),
                                      row->child(j)->data(0, kValueRole).toDouble());
    }
    return counters;
}

QStringList PhaseStepper::displayedNotes(int phase) const {
    QStringList notes;
    const QTreeWidgetItem* item = phase < 0 ? tree_->topLevelItem(0) : phaseItem(phase);
    for (int i = 0; item && i < item->childCount(); ++i)
        if (item->child(i)->data(0, kKindRole).toInt() == kNoteRow)
            notes << item->child(i)->text(0);
    return notes;
}

QString PhaseStepper::displayedRun(int phase) const {
    const QTreeWidgetItem* item = phaseItem(phase);
    for (int i = 0; item && i < item->childCount(); ++i)
        if (item->child(i)->data(0, kKindRole).toInt() == kRunRow)
            return item->child(i)->text(0);
    return {};
}

QStringList PhaseStepper::displayedBranchRuns(int phase) const {
    QStringList runs;
    const QTreeWidgetItem* item = phaseItem(phase);
    for (int i = 0; item && i < item->childCount(); ++i)
        if (item->child(i)->data(0, kKindRole).toInt() == kRunRow)
            for (int j = 0; j < item->child(i)->childCount(); ++j)
                runs << item->child(i)->child(j)->text(0);
    return runs;
}

QString PhaseStepper::displayedTime(int phase) const {
    const QTreeWidgetItem* item = phaseItem(phase);
    return item ? item->text(2) : QString();
}

void PhaseStepper::refresh() {
    const bool haveMethod = method_ != nullptr && !snapshots_.empty();
    reset_->setEnabled(haveMethod && !busy_ && completed_ > 0);
    back_->setEnabled(haveMethod && !busy_ && completed_ > 0);
    step_->setEnabled(haveMethod && !busy_ && completed_ < phaseCount());
    run_->setEnabled(haveMethod && !busy_ && completed_ < phaseCount());
    if (!method_)
        return;

    QTreeWidgetItem* input = tree_->topLevelItem(0);
    const bool atInput = completed_ == 0;
    input->setText(1, snapshots_.empty() ? QString()
                      : atInput          ? toString(PhaseState::Current)
                                         : toString(PhaseState::Done));
    if (!snapshots_.empty())
        fillDetails(input, splitCounters(nullptr, snapshots_[0]), snapshots_[0]);
    else
        qDeleteAll(input->takeChildren());

    for (int phase = 0; phase < phaseCount(); ++phase) {
        QTreeWidgetItem* item = phaseItem(phase);
        const PhaseState state = phaseState(phase);
        item->setText(1, toString(state));
        QFont font = item->font(0);
        font.setBold(state == PhaseState::Current || state == PhaseState::Running);
        for (int column = 0; column < 3; ++column) {
            item->setFont(column, font);
            item->setForeground(column, state == PhaseState::Pending
                                            ? QColor(140, 140, 140)
                                            : palette().color(QPalette::Text));
        }
        const bool ran = phase < completed_ && phase + 1 < static_cast<int>(snapshots_.size());
        if (ran) {
            const Snapshot& after = snapshots_[phase + 1];
            item->setText(2, formatSeconds(after.phaseSeconds));
            fillDetails(item, splitCounters(&snapshots_[phase], after), after);
            if (after.invariantViolations() > 0)
                item->setForeground(1, QColor(200, 30, 30));
            // A phase of a branch's range: its run in the state column.
            if (after.run.inBranch())
                item->setText(
                    1, QStringLiteral("%1 · %2").arg(toString(state),
                                                     QString::fromStdString(after.run.describe())));
        } else {
            item->setText(2, QString());
            qDeleteAll(item->takeChildren());
        }
        item->setExpanded(state == PhaseState::Current);
    }
    input->setExpanded(atInput);
}

} // namespace contour
