// The parameter schema of every method: each parameter belongs to a group
// (the phase declared after it, or a method-wide group), its help text is
// short and cites the paper without figures or history, every method offers
// the "default" preset, and the consistent method's "paper" preset turns
// every extension off (Bénard 2014 as written), and what a set of values
// changed from a preset. Also contour-batch's --preset flag and the preset its
// JSON report records, end to end.
#include "ContourTestSupport.h"
#include "contours/Methods.h"
#include "mesh/ProceduralShapes.h"

#include <QFile>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

using namespace contour;

namespace {

const char* const kProgram = CONTOUR_BINARY_DIR "/app/batch/contour-batch";

// Groups that are not a phase: parameters every phase reads (the surface,
// the traced method's tolerances), and the cusp retry, which reruns phases
// instead of being one.
const std::set<std::string> kMethodWideGroups = {"surface", "tolerances", "cusp-retry"};

constexpr size_t kMaxHelp = 300;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

bool saysNotInThePaper(const ParameterSpec& spec) {
    return contains(lower(spec.help), "not in the paper");
}

// What a text shown to the user must not hold: history, files outside the
// repository, measurement logs ("12 -> 10").
QString forbiddenIn(const std::string& text) {
    for (const char* word : {"session", "notes §", "DESIGN.md", "->", "issue"})
        if (contains(lower(text), lower(word)))
            return QString::fromUtf8(word);
    return {};
}

// The value that switches an extension off: false, or the bottom of its
// range (0 for counts and distances, 1 round for the crossing search).
bool isOffValue(const ParameterSpec& spec, const ParameterValue& value) {
    switch (spec.type) {
    case ParameterType::Bool:
        return !std::get<bool>(value);
    case ParameterType::Int:
        return std::get<int>(value) == static_cast<int>(spec.minimum);
    case ParameterType::Double:
        return std::get<double>(value) == spec.minimum;
    case ParameterType::Choice:
        return false;
    }
    return false;
}

} // namespace

class TestParameterSchema : public QObject {
    Q_OBJECT

    static void methodRows() {
        QTest::addColumn<QString>("method");
        for (const Method& m : contourMethods())
            QTest::newRow(m.name.c_str()) << QString::fromStdString(m.name);
    }

    static const Method& fetchMethod() {
        QFETCH(QString, method);
        return *findMethod(method.toStdString());
    }

    struct Run {
        int exitCode = -1;
        QString out, err;
    };

    Run run(const QStringList& args) {
        QProcess process;
        process.start(kProgram, args);
        Run r;
        if (!process.waitForStarted() || !process.waitForFinished(300000)) {
            process.kill();
            process.waitForFinished();
            r.err = "did not run";
            return r;
        }
        r.out = QString::fromUtf8(process.readAllStandardOutput());
        r.err = QString::fromUtf8(process.readAllStandardError());
        r.exitCode = process.exitStatus() == QProcess::NormalExit ? process.exitCode() : -2;
        return r;
    }

    QTemporaryDir dir_;

private slots:
    void everyParameterHasAGroupOfItsMethod_data() { methodRows(); }
    void everyParameterHasAGroupOfItsMethod() {
        const Method& m = fetchMethod();
        const std::vector<std::string> groups = m.parameterGroups();
        QVERIFY(!groups.empty());
        for (const ParameterSpec& spec : m.parameters) {
            QVERIFY2(!spec.group.empty(), spec.name.c_str());
            QVERIFY2(m.phaseIndex(spec.group) >= 0 || kMethodWideGroups.count(spec.group) > 0,
                     (spec.name + ": " + spec.group).c_str());
        }
        // A group's parameters are declared together, and phase groups come
        // in phase order: the form and --help list them as declared.
        int lastPhase = -1;
        for (size_t i = 0; i < groups.size(); ++i) {
            size_t first = m.parameters.size(), last = 0;
            for (size_t p = 0; p < m.parameters.size(); ++p)
                if (m.parameters[p].group == groups[i]) {
                    first = std::min(first, p);
                    last = std::max(last, p);
                }
            for (size_t p = first; p <= last; ++p)
                QVERIFY2(m.parameters[p].group == groups[i], m.parameters[p].name.c_str());
            const int phase = m.phaseIndex(groups[i]);
            if (phase >= 0) {
                QVERIFY2(phase > lastPhase, groups[i].c_str());
                lastPhase = phase;
            }
        }
    }

    void groupsFollowTheDeclaringPhase() {
        const Method& consistent = *findMethod("consistent");
        const std::vector<std::pair<const char*, const char*>> expected = {
            {"surface", "surface"},
            {"embedding-tolerance", "surface"},
            {"crossing-samples", "initialization"},
            {"cusp-contour-samples", "cusp-detection"},
            {"cusp-refinement-levels", "cusp-refinement"},
            {"snap-fraction", "contour-insertion"},
            {"radial-cusp-both-sides", "radial-edge-insertion"},
            {"radial-fan-sequences", "radial-flips"},
            {"patch-grow", "patch-search"},
            {"cusp-retry-pixels", "cusp-retry"},
            {"include-boundaries", "chaining"},
            {"near-face-epsilon", "visibility"},
            {"simplify-threshold", "simplification"},
        };
        for (const auto& [name, group] : expected) {
            const ParameterSpec* spec = consistent.parameter(name);
            QVERIFY2(spec, name);
            QCOMPARE(QString::fromStdString(spec->group), QString::fromUtf8(group));
        }
        const Method& mesh = *findMethod("mesh");
        QCOMPARE(QString::fromStdString(mesh.parameter("tessellation-level")->group),
                 QStringLiteral("surface"));
        QCOMPARE(QString::fromStdString(mesh.parameter("drop-concave")->group),
                 QStringLiteral("chaining"));
        const Method& interpolated = *findMethod("interpolated");
        QCOMPARE(QString::fromStdString(interpolated.parameter("normal-weighting")->group),
                 QStringLiteral("surface"));
    }

    void addPhaseGroupsTheParametersBeforeIt() {
        Method m;
        m.name = "test";
        m.parameters.push_back({"a", "A", "", ParameterType::Bool, true, 0, 0, {}});
        m.addPhase({"first", "", {}, {}});
        m.parameters.push_back({"b", "B", "", ParameterType::Bool, true, 0, 0, {}, "shared"});
        m.parameters.push_back({"c", "C", "", ParameterType::Bool, true, 0, 0, {}});
        m.addPhase({"second", "", {}, {}});
        m.addPhase({"third", "", {}, {}});
        QCOMPARE(QString::fromStdString(m.parameter("a")->group), QStringLiteral("first"));
        QCOMPARE(QString::fromStdString(m.parameter("b")->group), QStringLiteral("shared"));
        QCOMPARE(QString::fromStdString(m.parameter("c")->group), QStringLiteral("second"));
        QCOMPARE(m.parameterGroups(), (std::vector<std::string>{"first", "shared", "second"}));
        // A phase appended past addPhase while a parameter waits for its group.
        m.parameters.push_back({"d", "D", "", ParameterType::Bool, true, 0, 0, {}});
        m.phases.push_back({"fourth", "", {}, {}});
        QVERIFY_THROWS_EXCEPTION(std::logic_error, m.addPhase({"fifth", "", {}, {}}));
    }

    void helpTextsAreShortAndCiteNoHistory_data() { methodRows(); }
    void helpTextsAreShortAndCiteNoHistory() {
        const Method& m = fetchMethod();
        for (const ParameterSpec& spec : m.parameters) {
            QVERIFY2(!spec.help.empty(), spec.name.c_str());
            // Characters, not bytes: "§" and "κ" are one each.
            const qsizetype length = QString::fromStdString(spec.help).size();
            QVERIFY2(static_cast<size_t>(length) <= kMaxHelp,
                     qPrintable(QStringLiteral("%1: %2 characters")
                                    .arg(QString::fromStdString(spec.name))
                                    .arg(length)));
            const QString word = forbiddenIn(spec.help);
            QVERIFY2(word.isEmpty(), qPrintable(QString::fromStdString(spec.name) + ": " + word));
        }
        for (const Phase& phase : m.phases) {
            const QString word = forbiddenIn(phase.description);
            QVERIFY2(word.isEmpty(), qPrintable(QString::fromStdString(phase.name) + ": " + word));
        }
        QVERIFY2(forbiddenIn(m.description).isEmpty(), m.name.c_str());
        QVERIFY2(QString::fromStdString(m.description).size() <= 600, m.name.c_str());
    }

    void presetsAreCompleteValueSets_data() { methodRows(); }
    void presetsAreCompleteValueSets() {
        const Method& m = fetchMethod();
        QVERIFY(!m.presets.empty());
        QCOMPARE(QString::fromStdString(m.presets.front().name), QStringLiteral("default"));
        const ParameterPreset* byName = m.preset("default");
        QVERIFY(byName);
        QVERIFY(presetValues(m.parameters, *byName).values() ==
                ParameterSet::defaults(m.parameters).values());
        std::set<std::string> names;
        for (const ParameterPreset& preset : m.presets) {
            QVERIFY2(names.insert(preset.name).second, preset.name.c_str());
            QVERIFY(!preset.description.empty());
            for (const auto& [name, value] : preset.values) {
                const ParameterSpec* spec = m.parameter(name);
                QVERIFY2(spec, (preset.name + ": " + name).c_str());
                QVERIFY2(value.index() == spec->defaultValue.index(),
                         (preset.name + ": " + name + " has another type").c_str());
            }
            const std::vector<std::string> problems =
                validateParameters(m.parameters, presetValues(m.parameters, preset));
            QVERIFY2(problems.empty(), problems.empty() ? "" : problems.front().c_str());
        }
        QVERIFY(!m.preset("no-such-preset"));
    }

    void aMethodWithoutPresetsOffersTheDefaults() {
        Method m;
        m.name = "bare";
        m.parameters = {{"level", "Level", "A level.", ParameterType::Int, 2, 0, 5, {}}};
        QVERIFY(m.presets.empty());
        const ParameterPreset* defaults = m.preset("default");
        QVERIFY(defaults);
        QCOMPARE(defaults->name, std::string("default"));
        QVERIFY(defaults->values.empty());
        QVERIFY(!m.preset("paper"));
        ParameterSet values = ParameterSet::defaults(m.parameters);
        QVERIFY(changedFromPreset(m.parameters, *defaults, values).values().empty());
        values.set("level", 4);
        QCOMPARE(changedFromPreset(m.parameters, *defaults, values).getInt("level"), 4);
    }

    void changedFromPresetListsWhatDiffers_data() { methodRows(); }
    void changedFromPresetListsWhatDiffers() {
        const Method& m = fetchMethod();
        for (const ParameterPreset& preset : m.presets) {
            const ParameterSet start = presetValues(m.parameters, preset);
            QVERIFY2(changedFromPreset(m.parameters, preset, start).values().empty(),
                     preset.name.c_str());
            // One value changed (a choice to another choice, a number, a
            // switch): that value alone.
            for (const ParameterSpec& spec : m.parameters) {
                ParameterSet values = start;
                ParameterValue other;
                if (spec.type == ParameterType::Bool)
                    other = !start.getBool(spec.name);
                else if (spec.type == ParameterType::Int)
                    other = start.getInt(spec.name) == static_cast<int>(spec.minimum)
                                ? static_cast<int>(spec.minimum) + 1
                                : static_cast<int>(spec.minimum);
                else if (spec.type == ParameterType::Double) {
                    const double x = start.getDouble(spec.name);
                    other = x != spec.minimum             ? spec.minimum
                            : spec.maximum > spec.minimum ? spec.maximum
                                                          : x + 1.0;
                } else if (spec.choices.size() > 1)
                    other = start.getChoice(spec.name) == spec.choices[0] ? spec.choices[1]
                                                                          : spec.choices[0];
                else
                    continue;
                values.set(spec.name, other);
                const ParameterSet changed = changedFromPreset(m.parameters, preset, values);
                QCOMPARE(changed.values().size(), size_t(1));
                QVERIFY2(changed.has(spec.name) && changed.value(spec.name) == other,
                         (preset.name + ": " + spec.name).c_str());
            }
        }
        // Names outside the schema are not changes.
        ParameterSet values = ParameterSet::defaults(m.parameters);
        values.set("no-such-parameter", 1);
        QVERIFY(changedFromPreset(m.parameters, m.presets.front(), values).values().empty());
    }

    void paperChangesFromTheDefaultsAreItsValues() {
        const Method& m = *findMethod("consistent");
        const ParameterPreset& paper = *m.preset("paper");
        const ParameterSet changed = changedFromPreset(m.parameters, *m.preset("default"),
                                                       presetValues(m.parameters, paper));
        QVERIFY(!changed.values().empty());
        for (const auto& [name, value] : changed.values()) {
            QVERIFY2(paper.values.count(name), name.c_str());
            QVERIFY(paper.values.at(name) == value);
        }
        // A number equal by value is no change: 10.0 for the integer 10.
        ParameterSet values = presetValues(m.parameters, paper);
        values.set("snap-fraction", 0); // an int for the double 0.2: a change
        values.set("cusp-area-threshold", 1e-20);
        const ParameterSet edited = changedFromPreset(m.parameters, paper, values);
        QCOMPARE(edited.values().size(), size_t(1));
        QVERIFY(edited.has("snap-fraction"));
        ParameterSet sameByValue = presetValues(m.parameters, paper);
        sameByValue.set("snap-fraction", 0.2);
        sameByValue.set("crossing-samples", 10.0);
        QVERIFY(changedFromPreset(m.parameters, paper, sameByValue).values().empty());
    }

    void cliReportRecordsThePresetAndItsChanges() {
        QVERIFY2(QFile::exists(kProgram), kProgram);
        QVERIFY(dir_.isValid());
        const QString mesh = dir_.filePath("preset-sphere.obj");
        QVERIFY(testing::writeObjFile(makeSphere(1.0, 16), mesh.toStdString()));
        const auto report = [&](const QStringList& args) {
            const QString json = dir_.filePath("preset-report.json");
            QFile::remove(json);
            const Run r = run(QStringList{"--mesh", mesh, "--json", json} + args);
            if (r.exitCode != 0)
                qWarning("%s", qPrintable(r.err));
            QFile file(json);
            if (!file.open(QIODevice::ReadOnly))
                return nlohmann::json();
            return nlohmann::json::parse(file.readAll().toStdString()).at("method").at("preset");
        };
        // The paper preset with one flag on top: the flag is the one change.
        const nlohmann::json paper = report({"--method", "consistent", "--preset", "paper",
                                             "--snap-fraction", "0.3", "--phase", "1"});
        QVERIFY(paper.is_object());
        QCOMPARE(paper.at("name").get<std::string>(), std::string("paper"));
        QCOMPARE(paper.at("changed").size(), size_t(1));
        QCOMPARE(paper.at("changed").at("snap-fraction").get<double>(), 0.3);
        // Without --preset: the defaults, and a flag set to its default is no change.
        const Method& meshMethod = *findMethod("mesh");
        const std::string levelDefault =
            toString(meshMethod.parameter("tessellation-level")->defaultValue);
        const nlohmann::json plain = report(
            {"--method", "mesh", "--tessellation-level", QString::fromStdString(levelDefault)});
        QVERIFY(plain.is_object());
        QCOMPARE(plain.at("name").get<std::string>(), std::string("default"));
        QVERIFY(plain.at("changed").empty());
        const nlohmann::json smooth = report({"--method", "mesh", "--surface", "catmull-clark"});
        QVERIFY(smooth.is_object());
        QCOMPARE(smooth.at("changed").at("surface").get<std::string>(),
                 std::string("catmull-clark"));
    }

    void paperPresetTurnsEveryExtensionOff() {
        const Method& m = *findMethod("consistent");
        const ParameterPreset* paper = m.preset("paper");
        QVERIFY(paper);
        const ParameterSet values = presetValues(m.parameters, *paper);
        int extensions = 0;
        for (const ParameterSpec& spec : m.parameters) {
            if (!saysNotInThePaper(spec))
                continue;
            ++extensions;
            if (paper->values.count(spec.name) && isOffValue(spec, values.value(spec.name)))
                continue;
            // Otherwise a setting of an extension: its help names the
            // switch, which the preset turns off.
            bool switchedOff = false;
            for (const ParameterSpec& other : m.parameters)
                if (&other != &spec && contains(spec.help, other.name) &&
                    saysNotInThePaper(other) && paper->values.count(other.name) &&
                    isOffValue(other, values.value(other.name)))
                    switchedOff = true;
            QVERIFY2(switchedOff, (spec.name + " is not turned off by the paper preset").c_str());
        }
        QVERIFY(extensions >= 30);
        // The paper's numbers (§6.1, §6.2 d-e, §6.4, footnote 3).
        QCOMPARE(values.getInt("crossing-samples"), 10);
        QCOMPARE(values.getInt("crossing-search-rounds"), 1);
        QCOMPARE(values.getDouble("cusp-area-threshold"), 1e-20);
        QCOMPARE(values.getDouble("snap-fraction"), 0.2);
        QCOMPARE(values.getInt("wiggle-samples"), 100);
        QCOMPARE(values.getInt("split-samples"), 10);
        QCOMPARE(values.getInt("normal-wiggle-samples"), 100);
        QCOMPARE(values.getDouble("normal-wiggle-max-offset"), 1.0);
        QCOMPARE(values.getDouble("near-face-epsilon"), 1.0);
        // Appendix B's charts are a vertex's one-ring.
        QVERIFY(values.getBool("chart-vertex-rings"));
        // Today's defaults are not the paper's.
        QVERIFY(values.getBool("patch-search") !=
                ParameterSet::defaults(m.parameters).getBool("patch-search"));
    }

    void cliPresetStartsFromThePaperValues() {
        QVERIFY2(QFile::exists(kProgram), kProgram);
        QVERIFY(dir_.isValid());
        const QString mesh = dir_.filePath("sphere.obj");
        QVERIFY(testing::writeObjFile(makeSphere(1.0, 16), mesh.toStdString()));
        const QString json = dir_.filePath("paper.json");
        // Two phases are enough: the report records every parameter.
        const Run r = run({"--mesh", mesh, "--method", "consistent", "--preset", "paper",
                           "--cusp-retry", "true", "--phase", "2", "--json", json});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QFile file(json);
        QVERIFY(file.open(QIODevice::ReadOnly));
        const nlohmann::json report = nlohmann::json::parse(file.readAll().toStdString());
        const nlohmann::json& parameters = report.at("method").at("parameters");
        QCOMPARE(parameters.at("patch-search").get<bool>(), false);
        QCOMPARE(parameters.at("cusp-contour-samples").get<int>(), 0);
        QCOMPARE(parameters.at("crossing-search-rounds").get<int>(), 1);
        // A flag overrides the preset.
        QCOMPARE(parameters.at("cusp-retry").get<bool>(), true);

        const Run bad = run({"--mesh", mesh, "--method", "mesh", "--preset", "paper"});
        QCOMPARE(bad.exitCode, 2);
        QVERIFY2(bad.err.contains("--preset") && bad.err.contains("default"), qPrintable(bad.err));
    }

    void cliListsParametersByGroupAndPresets() {
        const Run list = run({"--list-methods"});
        QCOMPARE(list.exitCode, 0);
        const Method& m = *findMethod("consistent");
        const qsizetype start = list.out.indexOf("consistent - ");
        QVERIFY(start >= 0);
        qsizetype at = start;
        for (const std::string& group : m.parameterGroups()) {
            const qsizetype heading =
                list.out.indexOf(QString::fromStdString("[" + group + "]"), at);
            QVERIFY2(heading > at, group.c_str());
            at = heading;
            for (const ParameterSpec& spec : m.parameters)
                if (spec.group == group)
                    QVERIFY2(list.out.indexOf(QString::fromStdString("--" + spec.name), at) > at,
                             spec.name.c_str());
        }
        QVERIFY(list.out.indexOf("presets (--preset):", start) > start);
        QVERIFY(list.out.indexOf("    paper: ", start) > start);

        const Run help = run({"--help"});
        QCOMPARE(help.exitCode, 0);
        QVERIFY(help.out.contains("--preset"));
        QVERIFY(help.out.contains("consistent: default, paper"));
        for (const std::string& group : m.parameterGroups())
            QVERIFY2(help.out.contains(QString::fromStdString("Parameters: " + group)),
                     group.c_str());
    }
};

QTEST_GUILESS_MAIN(TestParameterSchema)
#include "test_parameter_schema.moc"
