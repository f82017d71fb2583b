#include "pipeline/Runner.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace contour {

Runner::Runner(const Method& method, Snapshot input, Camera camera, ParameterSet parameters)
    : method_(&method), camera_(std::move(camera)), parameters_(std::move(parameters)) {
    if (const std::string problem = camera_.validate(); !problem.empty())
        throw std::invalid_argument("camera: " + problem);
    const auto problems = validateParameters(method.parameters, parameters_);
    if (!problems.empty()) {
        std::string all;
        for (const std::string& p : problems)
            all += (all.empty() ? "" : "; ") + p;
        throw std::invalid_argument(all);
    }
    if (!input.mesh)
        throw std::invalid_argument("the input snapshot has no mesh");
    for (const BranchRule& rule : method.branches) {
        const Range r{method.phaseIndex(rule.rerunFrom), method.phaseIndex(rule.decideAfter)};
        if (r.from < 0 || r.to < r.from || !rule.plan || !rule.figure || !rule.report)
            throw std::invalid_argument("branch \"" + rule.name +
                                        "\": needs phases rerunFrom <= decideAfter, a plan, a "
                                        "figure and a report");
        for (const Range& other : ranges_)
            if (r.from <= other.to && other.from <= r.to)
                throw std::invalid_argument("branch \"" + rule.name +
                                            "\" overlaps another branch's phases");
        ranges_.push_back(r);
    }
    snapshots_.push_back(std::move(input));
}

std::vector<std::shared_ptr<const BranchSummary>> Runner::branchSummaries() const {
    std::vector<std::shared_ptr<const BranchSummary>> out;
    for (const Decision& d : decisions_)
        out.push_back(d.summary);
    return out;
}

Snapshot Runner::runPhase(int index, const PhaseContext& context, const Snapshot& previous) const {
    const Phase& phase = method_->phases[static_cast<size_t>(index)];
    Snapshot next = previous;
    next.phaseIndex = index;
    next.phaseName = phase.name;
    next.invariants.clear();
    next.notes.clear();
    next.run = {};
    const auto start = std::chrono::steady_clock::now();
    try {
        phase.run(context, next);
    } catch (const PhaseCancelled&) {
        throw;
    } catch (const PhaseError&) {
        throw;
    } catch (const std::exception& e) {
        throw PhaseError(phase.name, e.what());
    }
    next.phaseSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (phase.postconditions)
        next.invariants = phase.postconditions(context, next);
#ifdef CONTOUR_CHECK_INVARIANTS
    for (const InvariantCheck& check : next.invariants)
        if (check.violations > 0)
            throw PhaseError(phase.name, "post-condition \"" + check.name + "\" violated " +
                                             std::to_string(check.violations) +
                                             " times (first: " + check.firstExample + ")");
#endif
    return next;
}

std::function<void(double)> Runner::progressOf(int index) {
    return [this, index](double fraction) {
        if (progress_)
            progress_(index, fraction);
    };
}

const Runner::Decision* Runner::decisionContaining(int index) const {
    for (const Decision& d : decisions_)
        if (ranges_[d.rule].from <= index && index <= ranges_[d.rule].to)
            return &d;
    return nullptr;
}

Runner::Decision Runner::decide(size_t ruleIndex, const PhaseContext& baseContext,
                                Snapshot& decided, std::vector<Snapshot>& replaced) {
    const BranchRule& rule = method_->branches[ruleIndex];
    const Range range = ranges_[ruleIndex];
    const BranchPlan plan = rule.plan(baseContext, decided);
    auto summary = std::make_shared<BranchSummary>();
    summary->rule = rule.name;
    summary->rerunFrom = rule.rerunFrom;
    summary->decideAfter = rule.decideAfter;
    summary->data = plan.data;
    const std::optional<double> firstFigure = rule.figure(decided);
    summary->firstFigure = firstFigure ? *firstFigure : std::numeric_limits<double>::infinity();

    // Each variant's parameters, checked against the schema.
    std::vector<ParameterSet> parameters(plan.variants.size(), parameters_);
    for (size_t v = 0; v < plan.variants.size(); ++v) {
        for (const auto& [name, value] : plan.variants[v].overrides)
            parameters[v].set(name, value);
        const auto problems = validateParameters(method_->parameters, parameters[v]);
        if (!problems.empty())
            throw PhaseError(rule.decideAfter, "branch \"" + rule.name + "\", variant \"" +
                                                   plan.variants[v].label + "\": " + problems[0]);
    }
    struct Run {
        std::vector<Snapshot> snapshots; // phases from..to
        bool kept = true;
    };
    const auto runVariant = [&](size_t v) {
        const PhaseContext context(camera_, parameters[v], &cancel_, {}, plan.variants[v].data);
        Run run;
        const Snapshot* previous = &snapshots_[static_cast<size_t>(range.from)];
        for (int i = range.from; i <= range.to; ++i) {
            run.snapshots.push_back(runPhase(i, context, *previous));
            previous = &run.snapshots.back();
            for (const InvariantCheck& c : previous->invariants)
                run.kept = run.kept && c.violations == 0;
        }
        return run;
    };
    // The variants run in waves of as many as the machine has cores (they
    // are independent and mostly serial) and are then judged in order, as
    // if run one by one: a wave starts only while no run is perfect, and the
    // runs of a wave after a perfect one are not judged.
    const size_t wave =
        std::max<size_t>(1, static_cast<size_t>(tbb::this_task_arena::max_concurrency()));
    double best = summary->firstFigure;
    std::optional<Run> adopted;
    for (size_t first = 0; first < plan.variants.size() && best > rule.perfect; first += wave) {
        const size_t count = std::min(wave, plan.variants.size() - first);
        std::vector<Run> runs(count);
        tbb::parallel_for(size_t(0), count, [&](size_t k) { runs[k] = runVariant(first + k); });
        for (size_t k = 0; k < count && best > rule.perfect; ++k) {
            BranchRunSummary r;
            r.label = plan.variants[first + k].label;
            r.figure = rule.figure(runs[k].snapshots.back());
            r.better = r.figure && *r.figure < best;
            r.postconditionsKept = runs[k].kept;
            r.adopted = r.better && r.postconditionsKept;
            if (r.adopted) {
                // A later adoption supersedes this one.
                if (summary->adopted > 0)
                    summary->runs[static_cast<size_t>(summary->adopted - 1)].adopted = false;
                best = *r.figure;
                adopted = std::move(runs[k]);
                summary->adopted = static_cast<int>(summary->runs.size()) + 1;
            }
            summary->runs.push_back(std::move(r));
        }
        if (progress_)
            progress_(range.to, static_cast<double>(first + count) /
                                    static_cast<double>(plan.variants.size()));
    }

    Decision d;
    d.rule = ruleIndex;
    d.parameters = parameters_;
    if (adopted) {
        // The judged runs are the first variants, in order.
        const size_t v = static_cast<size_t>(summary->adopted - 1);
        d.adopted = plan.variants[v];
        d.parameters = parameters[v];
        decided = std::move(adopted->snapshots.back());
        adopted->snapshots.pop_back();
        replaced = std::move(adopted->snapshots);
    }
    summary->note = rule.report(baseContext, *summary, decided);
    d.summary = summary;
    return d;
}

bool Runner::step() {
    if (atEnd())
        return false;
    cancel_ = false;
    const int index = completedPhases();
    const Decision* within = decisionContaining(index);
    const bool overridden = within && within->adopted;
    const PhaseContext context(camera_, overridden ? within->parameters : parameters_, &cancel_,
                               progressOf(index), overridden ? within->adopted->data : nullptr);
    Snapshot next = runPhase(index, context, snapshots_.back());
    std::optional<Decision> decision;
    std::vector<Snapshot> replaced;
    for (size_t rule = 0; rule < ranges_.size(); ++rule) {
        if (ranges_[rule].to != index)
            continue;
        const PhaseContext base(camera_, parameters_, &cancel_, progressOf(index));
        if (within) {
            // Stepping through a decided range again: the same report.
            const std::string note = method_->branches[rule].report(base, *within->summary, next);
            if (!note.empty())
                next.notes.push_back(note);
        } else {
            decision = decide(rule, base, next, replaced);
            if (!decision->summary->note.empty())
                next.notes.push_back(decision->summary->note);
        }
    }
    // Commit (nothing above changed the state, so a failure leaves it as it was).
    if (within && !within->summary->runs.empty())
        next.run = {within->summary, within->summary->adopted};
    if (decision) {
        const std::shared_ptr<const BranchSummary>& summary = decision->summary;
        const int from = ranges_[decision->rule].from;
        if (!summary->runs.empty()) {
            for (size_t k = 0; k < replaced.size(); ++k)
                snapshots_[static_cast<size_t>(from) + 1 + k] = std::move(replaced[k]);
            for (int i = from + 1; i <= index; ++i)
                snapshots_[static_cast<size_t>(i)].run = {summary, summary->adopted};
            next.run = {summary, summary->adopted};
        }
        decisions_.push_back(std::move(*decision));
    }
    snapshots_.push_back(std::move(next));
    return true;
}

bool Runner::back() {
    if (snapshots_.size() <= 1)
        return false;
    snapshots_.pop_back();
    // Before rerunFrom the decision no longer holds.
    const int completed = completedPhases();
    std::erase_if(decisions_, [&](const Decision& d) { return completed <= ranges_[d.rule].from; });
    return true;
}

void Runner::reset() {
    snapshots_.resize(1);
    decisions_.clear();
}

void Runner::runTo(int completed) {
    if (completed < 0 || completed > phaseCount())
        throw std::out_of_range("no phase " + std::to_string(completed));
    while (completedPhases() > completed)
        back();
    while (completedPhases() < completed)
        step();
}

} // namespace contour
