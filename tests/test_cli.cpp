// contour-batch end to end: runs the program with QProcess on procedural
// meshes written to a temporary folder, and checks its SVG, its JSON report,
// its summary, its exit codes and error messages, and that no output file is
// left behind when it fails.
#include "ContourTestSupport.h"
#include "contours/Methods.h"
#include "export/JsonReport.h"
#include "export/SessionFile.h"
#include "export/SvgWriter.h"
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshReader.h"
#include "pipeline/FieldNames.h"

#include <QDir>
#include <QFile>
#include <QImage>
#include <QProcess>
#include <QSet>
#include <QTemporaryDir>
#include <QXmlStreamReader>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

using namespace contour;

namespace {

const char* const kProgram = CONTOUR_BINARY_DIR "/app/batch/contour-batch";

struct RunResult {
    int exitCode = -1;
    QString out;
    QString err;
};

void writeText(const QString& path, const QByteArray& text) {
    QFile file(path);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write(text);
}

nlohmann::json readJson(const QString& path) {
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly))
        return nullptr;
    return nlohmann::json::parse(file.readAll().toStdString(), nullptr, false);
}

struct SvgPolyline {
    QString group; // the innermost <g>'s id
    QString layer; // the outermost <g>'s id (visible, hidden, ... with a view graph)
    QString type;
    bool closed = false;
    int index = -1;
    int chain = -1, qi = -2; // view graph: data-chain, data-qi
    QString rule;
    std::vector<Vec2> points;
};

// A view-graph node marker: any element with data-node.
struct SvgMarker {
    QString group;
    QString type;
    QString nodeClass;
    int node = -1;
};

struct SvgFile {
    bool ok = false;
    QString error;
    int width = 0, height = 0;
    QString viewBox;
    QStringList groups;
    std::map<QString, QString> groupDisplay; // id -> display attribute
    std::vector<SvgPolyline> polylines;
    std::vector<SvgMarker> markers;

    int count(const QString& group) const {
        int n = 0;
        for (const SvgPolyline& p : polylines)
            n += p.group == group;
        return n;
    }
};

SvgFile readSvg(const QString& path) {
    SvgFile svg;
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) {
        svg.error = "cannot open " + path;
        return svg;
    }
    QXmlStreamReader xml(&file);
    QStringList stack; // enclosing <g> ids
    while (!xml.atEnd()) {
        xml.readNext();
        if (xml.isStartElement()) {
            const auto a = xml.attributes();
            const QString group = stack.isEmpty() ? QString() : stack.back();
            if (xml.name() == QLatin1String("svg")) {
                svg.width = a.value("width").toInt();
                svg.height = a.value("height").toInt();
                svg.viewBox = a.value("viewBox").toString();
            } else if (xml.name() == QLatin1String("g")) {
                stack << a.value("id").toString();
                svg.groups << stack.back();
                svg.groupDisplay[stack.back()] = a.value("display").toString();
            } else if (a.hasAttribute("data-node")) {
                svg.markers.push_back({group, a.value("data-type").toString(),
                                       a.value("data-class").toString(),
                                       a.value("data-node").toInt()});
            } else if (xml.name() == QLatin1String("polyline")) {
                SvgPolyline p;
                p.group = group;
                p.layer = stack.isEmpty() ? QString() : stack.front();
                p.type = a.value("data-type").toString();
                p.closed = a.value("data-closed") == QLatin1String("true");
                p.index = a.value("data-index").toInt();
                if (a.hasAttribute("data-chain")) {
                    p.chain = a.value("data-chain").toInt();
                    p.qi = a.value("data-qi").toInt();
                    p.rule = a.value("data-rule").toString();
                }
                const QStringList pairs =
                    a.value("points").toString().split(' ', Qt::SkipEmptyParts);
                for (const QString& pair : pairs) {
                    const QStringList xy = pair.split(',');
                    bool okX = false, okY = false;
                    if (xy.size() == 2)
                        p.points.emplace_back(xy[0].toDouble(&okX), xy[1].toDouble(&okY));
                    if (!okX || !okY) {
                        svg.error = "bad point \"" + pair + "\"";
                        return svg;
                    }
                }
                svg.polylines.push_back(std::move(p));
            }
        } else if (xml.isEndElement() && xml.name() == QLatin1String("g") && !stack.isEmpty()) {
            stack.removeLast();
        }
    }
    if (xml.hasError()) {
        svg.error = xml.errorString();
        return svg;
    }
    svg.ok = true;
    return svg;
}

double polylineLength(const std::vector<Vec2>& points) {
    double length = 0.0;
    for (size_t i = 1; i < points.size(); ++i)
        length += (points[i] - points[i - 1]).norm();
    return length;
}

QStringList filesIn(const QString& dir) {
    return QDir(dir).entryList(QDir::Files | QDir::Hidden | QDir::NoDotAndDotDot);
}

// The methods the generic view-graph tests below cover (the Powell-Sabin
// method has its own test: its contours pass through cone points, which
// those tests do not expect).
bool drawsContours(const Method& m) {
    return m.name != "powell-sabin";
}

} // namespace

class TestCli : public QObject {
    Q_OBJECT

private:
    QTemporaryDir dir_;
    QString sphere_; // closed: one contour loop from any outside view
    QString saddle_; // open: one boundary loop
    QString torus_;  // T-junctions and curtain folds from a grazing view
    QString bumpyTorus_;
    PolygonMesh sphereMesh_;

    QString path(const QString& name) const { return dir_.filePath(name); }
    // An empty folder for one run's outputs.
    QString freshOutputDir(const QString& name) {
        QDir d(path(name));
        d.removeRecursively();
        QDir().mkpath(d.path());
        return d.path();
    }

    // `withoutDisplay` runs the program with DISPLAY and WAYLAND_DISPLAY
    // removed from its environment.
    RunResult run(const QStringList& args, int timeoutMs = 120000, bool withoutDisplay = false) {
        QProcess process;
        if (withoutDisplay) {
            QProcessEnvironment environment = QProcessEnvironment::systemEnvironment();
            environment.remove("DISPLAY");
            environment.remove("WAYLAND_DISPLAY");
            process.setProcessEnvironment(environment);
        }
        process.start(kProgram, args);
        RunResult r;
        if (!process.waitForStarted()) {
            r.err = "cannot start " + QString(kProgram);
            return r;
        }
        if (!process.waitForFinished(timeoutMs)) {
            process.kill();
            process.waitForFinished();
            r.err = "timed out";
            return r;
        }
        r.out = QString::fromUtf8(process.readAllStandardOutput());
        r.err = QString::fromUtf8(process.readAllStandardError());
        r.exitCode = process.exitStatus() == QProcess::NormalExit ? process.exitCode() : -2;
        return r;
    }

private slots:
    void initTestCase() {
        QVERIFY2(QFile::exists(kProgram), kProgram);
        QVERIFY(dir_.isValid());
        sphereMesh_ = makeSphere(1.0, 32);
        sphere_ = path("sphere.obj");
        QVERIFY(testing::writeObjFile(sphereMesh_, sphere_.toStdString()));
        saddle_ = path("saddle.obj");
        QVERIFY(testing::writeObjFile(makeSaddlePatch(16), saddle_.toStdString()));
        torus_ = path("torus.obj");
        QVERIFY(testing::writeObjFile(makeProceduralShape("torus", 48), torus_.toStdString()));
        bumpyTorus_ = path("bumpy-torus.obj");
        QVERIFY(testing::writeObjFile(makeProceduralShape("bumpy-torus", 64),
                                      bumpyTorus_.toStdString()));
    }

    // The view graph in the SVG, the JSON report and the summary agree, for
    // every method, on a torus seen from a grazing view (T-junctions and
    // curtain folds). Exact mesh visibility has no conflict (--strict passes).
    void viewGraphOutputs_data() {
        QTest::addColumn<QString>("method");
        for (const Method& m : contourMethods())
            if (drawsContours(m))
                QTest::newRow(m.name.c_str()) << QString::fromStdString(m.name);
    }
    void viewGraphOutputs() {
        QFETCH(QString, method);
        const QString out = freshOutputDir("view-graph-" + method);
        const RunResult r = run({"--mesh", torus_, "--method", method, "--eye", "3,0.4,0.9",
                                 "--svg", out + "/t.svg", "--json", out + "/t.json", "--strict"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const SvgFile svg = readSvg(out + "/t.svg");
        QVERIFY2(svg.ok, qPrintable(svg.error));
        for (const char* group : {"visible", "hidden", "simplified", "nodes"})
            QVERIFY2(svg.groups.contains(group), group);
        QCOMPARE(svg.groupDisplay.at("simplified"), QString("none"));
        QVERIFY(svg.groupDisplay.at("hidden").isEmpty()); // drawn, dashed

        const nlohmann::json j = readJson(out + "/t.json");
        const nlohmann::json& graph = j["views"][0]["view_graph"];
        QVERIFY(graph.is_object());
        const nlohmann::json& chains = graph["chains"];
        const nlohmann::json& nodes = graph["nodes"];
        QVERIFY(chains.size() > 1);
        // Something passes in front of a contour in 2D on the mesh and
        // interpolated contours. The dense ground truth's contour has no
        // crossing from such views (test_ground_truth), and neither have the
        // consistent mesh (no image intersection and no mesh fold left
        // crossing a drawn curve) nor the contour traced on the limit surface.
        const nlohmann::json& byType = graph["totals"]["nodes_by_type"];
        qInfo("%s: nodes by type %s", qPrintable(method), byType.dump().c_str());
        if (method == "consistent" || method == "traced")
            QCOMPARE(byType.value("image-intersection", 0), 0);
        else
            QVERIFY(byType.value("image-intersection", 0) > 0);
        // The interpolated contours have no fold test; the traced ones use
        // the interpolated visibility (their cusps are counted, not nodes).
        if (method != "interpolated" && method != "traced")
            QVERIFY(graph["totals"]["nodes_by_type"].value("curtain-fold", 0) > 0);
        if (method == "mesh")
            QCOMPARE(graph["totals"]["conflicts"].get<int>(), 0);

        // Every chain is drawn once (the torus is in front of the eye), in its
        // layer and type group, with the report's QI and rule.
        std::vector<int> drawn(chains.size(), 0);
        long long visible = 0;
        for (const SvgPolyline& p : svg.polylines) {
            QVERIFY(p.chain >= 0 && p.chain < int(chains.size()));
            const nlohmann::json& c = chains[size_t(p.chain)];
            ++drawn[size_t(p.chain)];
            const QString layer = c["simplified_away"].get<bool>() ? "simplified"
                                  : c["qi"].get<int>() == 0        ? "visible"
                                                                   : "hidden";
            QCOMPARE(p.layer, layer);
            QCOMPARE(p.group, layer + "-" + p.type);
            QCOMPARE(p.type, QString::fromStdString(c["type"].get<std::string>()));
            QCOMPARE(p.qi, c["qi"].get<int>());
            QCOMPARE(p.rule, QString::fromStdString(c["rule"].get<std::string>()));
            QVERIFY(p.rule != "unknown");
            QCOMPARE(p.points.size(), c["points"].size());
            visible += layer == "visible";
        }
        for (size_t c = 0; c < chains.size(); ++c)
            QVERIFY2(drawn[c] == 1, qPrintable(QString("chain %1 drawn %2x").arg(c).arg(drawn[c])));
        QCOMPARE(visible, graph["totals"]["visible_chains"].get<long long>());

        // One marker per node, with the report's type and class.
        QCOMPARE(svg.markers.size(), nodes.size());
        for (const SvgMarker& m : svg.markers) {
            const nlohmann::json& n = nodes[size_t(m.node)];
            QCOMPARE(m.type, QString::fromStdString(n["type"].get<std::string>()));
            QCOMPARE(m.group, "nodes-" + m.type);
            QCOMPARE(m.nodeClass, QString::fromStdString(n["class"].get<std::string>()));
        }

        // The summary's line.
        const nlohmann::json& totals = graph["totals"];
        const QString line = QString("graph   %1 chains: %2 visible, %3 hidden")
                                 .arg(totals["chains"].get<int>())
                                 .arg(totals["visible_chains"].get<int>())
                                 .arg(totals["hidden_chains"].get<int>());
        QVERIFY2(r.out.contains(line), qPrintable(line + "\n" + r.out));
        const QString tail =
            QString("%1 T-junction").arg(totals["nodes_by_type"].value("image-intersection", 0));
        QVERIFY2(r.out.contains(tail), qPrintable(tail));
        QVERIFY(r.out.contains(QString("%1 ray test").arg(totals["ray_tests"].get<long long>())));
    }

    // --visibility false: no view graph, the raw-curve SVG and report.
    void visibilityOff() {
        const QString out = freshOutputDir("visibility-off");
        const RunResult r =
            run({"--mesh", torus_, "--method", "mesh", "--eye", "3,0.4,0.9", "--visibility",
                 "false", "--svg", out + "/t.svg", "--json", out + "/t.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const nlohmann::json j = readJson(out + "/t.json");
        QCOMPARE(j["method"]["parameters"]["visibility"].get<bool>(), false);
        QVERIFY(!j["views"][0].contains("view_graph"));
        const SvgFile svg = readSvg(out + "/t.svg");
        QVERIFY2(svg.ok, qPrintable(svg.error));
        QVERIFY(svg.groups.contains("contour") && !svg.groups.contains("visible"));
        QVERIFY(svg.markers.empty());
        QCOMPARE(int(svg.polylines.size()), j["views"][0]["totals"]["curves"].get<int>());
        QVERIFY(!r.out.contains("graph   "));
    }

    // --illustration-svg writes the clean drawing beside the diagnostic
    // SVG: Inkscape layers, no node markers; --illustration-hidden adds the
    // hidden layer; the two paths must differ.
    void illustrationSvg() {
        const QString out = freshOutputDir("illustration");
        for (const bool hidden : {false, true}) {
            QStringList args{
                "--mesh",    torus_,  "--method",     "consistent",         "--eye",
                "3,0.4,0.9", "--svg", out + "/d.svg", "--illustration-svg", out + "/i.svg"};
            if (hidden)
                args << "--illustration-hidden";
            const RunResult r = run(args);
            QVERIFY2(r.exitCode == 0, qPrintable(r.err));
            QVERIFY(r.out.contains(out + "/i.svg"));
            const SvgFile svg = readSvg(out + "/i.svg");
            QVERIFY2(svg.ok, qPrintable(svg.error));
            QVERIFY(svg.groups.contains("visible") && svg.groups.contains("visible-contour"));
            QCOMPARE(svg.groups.contains("hidden"), hidden);
            QVERIFY(!svg.groups.contains("nodes"));
            QVERIFY(svg.markers.empty());
            QVERIFY(readSvg(out + "/d.svg").groups.contains("nodes"));
        }
        const RunResult same =
            run({"--mesh", torus_, "--svg", out + "/x.svg", "--illustration-svg", out + "/x.svg"});
        QCOMPARE(same.exitCode, 2);
    }

    // --simplify true hides short visible chains (Bénard 2014 §9) without
    // removing any: the same chains, the hidden ones in the "simplified"
    // layer, none longer than the threshold.
    void simplifyHidesShortChains() {
        const QString out = freshOutputDir("simplify");
        const QStringList base{"--mesh", bumpyTorus_, "--method", "mesh", "--eye", "3,0.3,1.2"};
        const RunResult off = run(QStringList(base) << "--json" << out + "/off.json");
        QVERIFY2(off.exitCode == 0, qPrintable(off.err));
        const RunResult on = run(QStringList(base) << "--simplify"
                                                   << "true"
                                                   << "--json" << out + "/on.json"
                                                   << "--svg" << out + "/on.svg");
        QVERIFY2(on.exitCode == 0, qPrintable(on.err));
        const nlohmann::json a = readJson(out + "/off.json")["views"][0]["view_graph"];
        const nlohmann::json b = readJson(out + "/on.json")["views"][0]["view_graph"];
        QCOMPARE(a["totals"]["simplified_chains"].get<int>(), 0);
        QCOMPARE(b["totals"]["chains"], a["totals"]["chains"]);
        const int hidden = b["totals"]["simplified_chains"].get<int>();
        qInfo("bumpy torus, mesh contours: %d of %d visible chains simplified away", hidden,
              a["totals"]["visible_chains"].get<int>());
        QVERIFY(hidden > 0);
        QCOMPARE(b["totals"]["visible_chains"].get<int>() + hidden,
                 a["totals"]["visible_chains"].get<int>());
        for (const nlohmann::json& c : b["chains"])
            if (c["simplified_away"].get<bool>()) {
                QVERIFY(c["length_px"].get<double>() <= 15.0);
                QCOMPARE(a["chains"][c["index"].get<size_t>()]["visible"].get<bool>(), true);
            }
        const SvgFile svg = readSvg(out + "/on.svg");
        QVERIFY2(svg.ok, qPrintable(svg.error));
        QCOMPARE(svg.groupDisplay.at("simplified"), QString("none"));
        int drawnSimplified = 0;
        for (const SvgPolyline& p : svg.polylines)
            drawnSimplified += p.layer == "simplified";
        QCOMPARE(drawnSimplified, hidden);
        QVERIFY(on.out.contains(QString("%1 simplified away").arg(hidden)));
    }

    // --strict ignores the conflicts the heuristic votes are bound to produce
    // (interpolated contours, tutorial §6.2.4): they are reported only.
    void strictIgnoresVoteConflicts() {
        const QString out = freshOutputDir("strict-votes");
        const RunResult r = run({"--mesh", bumpyTorus_, "--method", "interpolated", "--eye",
                                 "3,0.3,1.2", "--strict", "--json", out + "/r.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const nlohmann::json graph = readJson(out + "/r.json")["views"][0]["view_graph"];
        qInfo("interpolated bumpy torus: %d conflicts (expected)",
              graph["totals"]["conflicts"].get<int>());
        QVERIFY(graph["totals"]["conflicts"].get<int>() > 0);
        QVERIFY(r.err.isEmpty());
    }

    void helpAndMethodList() {
        const RunResult help = run({"--help"});
        QCOMPARE(help.exitCode, 0);
        for (const Method& method : contourMethods())
            for (const ParameterSpec& spec : method.parameters)
                QVERIFY2(help.out.contains(QString::fromStdString("--" + spec.name)),
                         spec.name.c_str());
        QVERIFY(help.out.contains("--views26"));

        const RunResult list = run({"--list-methods"});
        QCOMPARE(list.exitCode, 0);
        for (const Method& method : contourMethods()) {
            QVERIFY(list.out.contains(QString::fromStdString(method.name)));
            for (const Phase& phase : method.phases)
                QVERIFY(list.out.contains(QString::fromStdString(phase.name)));
        }
        for (const PlannedMethod& planned : plannedMethods())
            QVERIFY(list.out.contains(QString::fromStdString(planned.reason)));
    }

    void sphereGivesOneLoop_data() {
        QTest::addColumn<QString>("method");
        for (const Method& m : contourMethods())
            if (drawsContours(m))
                QTest::newRow(m.name.c_str()) << QString::fromStdString(m.name);
    }

    void sphereGivesOneLoop() {
        QFETCH(QString, method);
        const Method& m = *findMethod(method.toStdString());
        const QString out = freshOutputDir("sphere-" + method);
        const QString svgPath = out + "/sphere.svg", jsonPath = out + "/sphere.json";
        const RunResult r =
            run({"--mesh", sphere_, "--method", method, "--svg", svgPath, "--json", jsonPath});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY(r.err.isEmpty());
        for (const Phase& phase : m.phases)
            QVERIFY2(r.out.contains(QString::fromStdString(phase.name)), qPrintable(r.out));
        QCOMPARE(filesIn(out), QStringList({"sphere.json", "sphere.svg"}));

        // SVG: the viewport's size, the view graph's layers (the visibility
        // phase is on by default), one closed visible contour chain, QI 0.
        const SvgFile svg = readSvg(svgPath);
        QVERIFY2(svg.ok, qPrintable(svg.error));
        QCOMPARE(svg.width, 800);
        QCOMPARE(svg.height, 600);
        QCOMPARE(svg.viewBox, QString("0 0 800 600"));
        for (const char* group : {"visible", "hidden", "simplified", "nodes"})
            QVERIFY2(svg.groups.contains(group), group);
        QVERIFY(!svg.groups.contains("contour")); // the raw-curve layout is replaced
        QCOMPARE(int(svg.polylines.size()), 1);
        QVERIFY(svg.markers.empty()); // a sphere: no cusp, no T-junction
        const SvgPolyline& loop = svg.polylines.front();
        QCOMPARE(loop.chain, 0);
        QCOMPARE(loop.type, QString("contour"));
        // Every method sees the loop: the interpolated contours' heuristic
        // vote (tutorial §6.2.4) ignores the faces sharing a vertex with the
        // contour's face by default (visibility-ignored-faces), which keeps
        // a sphere's outline visible although its segments lie partly on
        // back faces, whose rays leave through front faces.
        const bool exact = method != "interpolated";
        QCOMPARE(svg.count("visible-contour"), 1);
        QCOMPARE(loop.layer, QString("visible"));
        QCOMPARE(loop.qi, 0);
        QCOMPARE(loop.type, QString("contour"));
        QVERIFY(loop.closed);
        QVERIFY(loop.points.size() >= 8);
        QVERIFY((loop.points.front() - loop.points.back()).norm() < 1e-9);
        for (const Vec2& p : loop.points) {
            QVERIFY2(p.x() >= 0 && p.x() <= 800 && p.y() >= 0 && p.y() <= 600,
                     qPrintable(QString("point %1, %2").arg(p.x()).arg(p.y())));
        }

        // JSON: mesh, method, parameters, camera, phases, totals, curves.
        const nlohmann::json j = readJson(jsonPath);
        QVERIFY(j.is_object());
        QCOMPARE(j["tool"]["name"].get<std::string>(), std::string("contour-batch"));
        QVERIFY(!j["tool"]["version"].get<std::string>().empty());
        QCOMPARE(j["mesh"]["path"].get<std::string>(), sphere_.toStdString());
        QCOMPARE(j["mesh"]["vertices"].get<int>(), sphereMesh_.vertexCount());
        QCOMPARE(j["mesh"]["faces"].get<int>(), sphereMesh_.faceCount());
        QCOMPARE(j["mesh"]["boundary_edges"].get<int>(), 0);
        QVERIFY(j["mesh"]["polygon_faces"].get<int>() > 0); // quads between the poles
        QCOMPARE(j["method"]["name"].get<std::string>(), m.name);
        for (const ParameterSpec& spec : m.parameters)
            QVERIFY2(j["method"]["parameters"].contains(spec.name), spec.name.c_str());
        QCOMPARE(j["method"]["parameters"].size(), m.parameters.size());
        QCOMPARE(j["views"].size(), size_t(1));
        const nlohmann::json& view = j["views"][0];
        QCOMPARE(view["camera"]["viewport"]["width"].get<int>(), 800);
        QCOMPARE(view["phases"].size(), m.phases.size());
        QCOMPARE(view["completed_phases"].get<size_t>(), m.phases.size());
        for (size_t i = 0; i < m.phases.size(); ++i) {
            const nlohmann::json& phase = view["phases"][i];
            QCOMPARE(phase["name"].get<std::string>(), m.phases[i].name);
            QVERIFY(phase["seconds"].is_number());
            QVERIFY(phase["seconds"].get<double>() >= 0.0);
            QVERIFY(phase["counters"].is_object());
            QVERIFY(phase["invariants"].is_array());
            QCOMPARE(phase["violations"].get<long long>(), 0LL);
        }
        const nlohmann::json& totals = view["totals"];
        QCOMPARE(totals["contour_chains"].get<int>(), 1);
        QCOMPARE(totals["closed_loops"].get<int>(), 1);
        QCOMPARE(totals["open_chains"].get<int>(), 0);
        QCOMPARE(totals["boundary_curves"].get<int>(), 0);
        QCOMPARE(totals["counters"]["closed loops"].get<int>(), 1);
        QCOMPARE(view["curves"].size(), size_t(1));
        const nlohmann::json& curve = view["curves"][0];
        QCOMPARE(curve["type"].get<std::string>(), std::string("contour"));
        QVERIFY(curve["closed"].get<bool>());
        QCOMPARE(curve["points"].get<size_t>() + 1, loop.points.size());
        // The report measures the curve the SVG draws.
        const double length = curve["length_px"].get<double>();
        QVERIFY(length > 100.0);
        QVERIFY(std::abs(length - polylineLength(loop.points)) < 1e-3 * length);
        // The view graph: one visible closed chain, no node, no conflict
        // (interpolated: the check ray, which ignores the contour's face
        // only, may be hidden by the neighbours the vote ignores; such a
        // conflict is expected, README "--strict").
        const nlohmann::json& graph = view["view_graph"];
        QVERIFY(graph.is_object());
        QCOMPARE(graph["chains"].size(), size_t(1));
        QCOMPARE(graph["nodes"].size(), size_t(0));
        QVERIFY(graph["totals"]["conflicts"].get<int>() <= (exact ? 0 : 1));
        QVERIFY(graph["chains"][0]["closed"].get<bool>());
        QCOMPARE(graph["chains"][0]["qi"].get<int>(), loop.qi);
        QCOMPARE(graph["chains"][0]["points"].size(), loop.points.size());
        if (exact) {
            QCOMPARE(graph["totals"]["visible_chains"].get<int>(), 1);
            QVERIFY(std::abs(graph["totals"]["visible_length_px"].get<double>() - length) <
                    1e-3 * length);
            QVERIFY2(r.out.contains("graph   1 chain: 1 visible, 0 hidden; 0 T-junctions, 0 "
                                    "curtain folds;"),
                     qPrintable(r.out));
        }
    }

    void cameraFlagsAreReported() {
        const QString out = freshOutputDir("flags");
        const RunResult r = run({"--mesh",         sphere_,
                                 "--method",       "interpolated",
                                 "--eye",          "0.5,1,6",
                                 "--target",       "0,0.1,0",
                                 "--up",           "0,1,0",
                                 "--fov",          "40",
                                 "--width",        "640",
                                 "--height",       "480",
                                 "--json",         out + "/r.json",
                                 "--svg",          out + "/r.svg",
                                 "--write-camera", out + "/cam.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const nlohmann::json j = readJson(out + "/r.json");
        const nlohmann::json& camera = j["views"][0]["camera"];
        QCOMPARE(camera["projection"].get<std::string>(), std::string("perspective"));
        QCOMPARE(camera["eye"], nlohmann::json({0.5, 1.0, 6.0}));
        QCOMPARE(camera["target"], nlohmann::json({0.0, 0.1, 0.0}));
        QCOMPARE(camera["up"], nlohmann::json({0.0, 1.0, 0.0}));
        QCOMPARE(camera["fov_y_degrees"].get<double>(), 40.0);
        QCOMPARE(camera["viewport"]["width"].get<int>(), 640);
        QCOMPARE(camera["viewport"]["height"].get<int>(), 480);
        // --write-camera writes the same camera, and it reads back.
        QCOMPARE(readJson(out + "/cam.json"), camera);
        QCOMPARE(Camera::readJson((out + "/cam.json").toStdString()).toJson(), camera);
        const SvgFile svg = readSvg(out + "/r.svg");
        QVERIFY(svg.ok);
        QCOMPARE(svg.width, 640);
        QCOMPARE(svg.height, 480);
        QCOMPARE(svg.count("visible-contour"), 1);
    }

    void cameraFile() {
        Camera camera;
        camera.projection = Projection::Orthographic;
        camera.eye = Vec3(1, 2, 5);
        camera.target = Vec3(0, 0, 0);
        camera.up = Vec3(0, 1, 0);
        camera.orthoHeight = 3.0;
        camera.viewport = {500, 400};
        const QString cameraPath = path("ortho-camera.json");
        camera.writeJson(cameraPath.toStdString());
        for (const char* method : {"mesh", "interpolated"}) {
            const QString out = freshOutputDir(QString("camera-file-") + method);
            const RunResult r = run({"--mesh", sphere_, "--method", method, "--camera", cameraPath,
                                     "--json", out + "/r.json", "--svg", out + "/r.svg"});
            QVERIFY2(r.exitCode == 0, qPrintable(r.err));
            const nlohmann::json j = readJson(out + "/r.json");
            QCOMPARE(j["views"][0]["camera"], camera.toJson());
            QCOMPARE(j["views"][0]["totals"]["closed_loops"].get<int>(), 1);
            const SvgFile svg = readSvg(out + "/r.svg");
            QCOMPARE(svg.width, 500);
            QCOMPARE(svg.height, 400);
            QCOMPARE(svg.count("visible-contour"), 1);
            // Orthographic: the unit sphere's outline is a circle of
            // radius 1/3 of the view height (the view is 3 units high).
            for (const Vec2& p : svg.polylines.front().points)
                QVERIFY(std::abs((p - Vec2(250, 200)).norm() - 400.0 / 3.0) < 4.0);
        }
        // --width overrides the file's viewport.
        const QString out = freshOutputDir("camera-file-width");
        const RunResult r = run(
            {"--mesh", sphere_, "--camera", cameraPath, "--width", "300", "--svg", out + "/r.svg"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const SvgFile svg = readSvg(out + "/r.svg");
        QCOMPARE(svg.width, 300);
        QCOMPARE(svg.height, 400);
    }

    // The Powell-Sabin method runs its phases, reports them and writes its
    // view graph.
    void powellSabinFitsTheSurface() {
        const QString out = freshOutputDir("powell-sabin");
        const RunResult r = run({"--mesh", sphere_, "--method", "powell-sabin", "--svg",
                                 out + "/s.svg", "--json", out + "/s.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        for (const char* phase : {"cones", "conformal-map", "layout", "patches", "factorization",
                                  "fit", "patch-contours", "chaining", "cusps", "visibility"})
            QVERIFY2(r.out.contains(QString::fromLatin1(phase)), phase);
        QVERIFY(!r.out.contains(QStringLiteral("INVARIANT VIOLATED")));
        const nlohmann::json report = readJson(out + "/s.json");
        const auto& phases = report["views"][0]["phases"];
        QCOMPARE(static_cast<int>(phases.size()), 10);
        QVERIFY(report["views"][0].contains("view_graph"));
        QVERIFY(QFileInfo::exists(out + "/s.svg"));
        // --phase stops after the layout.
        const RunResult early = run({"--mesh", sphere_, "--method", "powell-sabin", "--phase", "3",
                                     "--json", out + "/e.json"});
        QVERIFY2(early.exitCode == 0, qPrintable(early.err));
        QCOMPARE(static_cast<int>(readJson(out + "/e.json")["views"][0]["phases"].size()), 3);
        QVERIFY(!early.out.contains(QStringLiteral(" patches ")));
        // A sphere without cones has no flat metric: the CLI names the reason.
        const RunResult bad = run({"--mesh", sphere_, "--method", "powell-sabin",
                                   "--cones-per-component", "0", "--json", out + "/b.json"});
        QVERIFY(bad.exitCode != 0);
        QVERIFY2(bad.err.contains(QStringLiteral("conformal map failed")), qPrintable(bad.err));
    }

    // --ply on powell-sabin writes the spline's tessellation with each
    // triangle's quadratic patch and macro-patch as face properties.
    void powellSabinPlyHasPatchIds() {
        const QString out = freshOutputDir("powell-sabin-ply");
        const RunResult r = run({"--mesh", sphere_, "--method", "powell-sabin", "--ply",
                                 out + "/s.ply", "--json", out + "/s.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const nlohmann::json counters = readJson(out + "/s.json")["views"][0]["totals"]["counters"];
        PlyLabels labels;
        const PolygonMesh mesh = readMesh((out + "/s.ply").toStdString(), &labels);
        QCOMPARE(mesh.faceCount(), counters["tessellation faces"].get<int>());
        QVERIFY(labels.faceLabels.count(fields::kPatch) &&
                labels.faceLabels.count(fields::kMacroPatch));
        const std::vector<int>& patch = labels.faceLabels[fields::kPatch];
        const std::vector<int>& macro = labels.faceLabels[fields::kMacroPatch];
        const int patches = counters["quadratic patches"].get<int>();
        std::vector<int> faces(static_cast<size_t>(patches), 0);
        for (size_t f = 0; f < patch.size(); ++f) {
            QVERIFY(patch[f] >= 0 && patch[f] < patches);
            QCOMPARE(macro[f], patch[f] / 12); // patch 12 f + l of the 12-split
            ++faces[static_cast<size_t>(patch[f])];
        }
        // Every patch is there, each with the same number of triangles.
        QCOMPARE(std::count(faces.begin(), faces.end(), faces.front()), std::ptrdiff_t(patches));
        QCOMPARE(faces.front() * patches, mesh.faceCount());
    }

    void phaseStopsEarly_data() {
        QTest::addColumn<QString>("method");
        QTest::addColumn<int>("phases");
        for (const Method& m : contourMethods())
            for (int n = 0; drawsContours(m) && n < static_cast<int>(m.phases.size()); ++n)
                QTest::addRow("%s-%d", m.name.c_str(), n) << QString::fromStdString(m.name) << n;
    }

    void phaseStopsEarly() {
        QFETCH(QString, method);
        QFETCH(int, phases);
        const Method& m = *findMethod(method.toStdString());
        const QString out = freshOutputDir("phase");
        const RunResult r =
            run({"--mesh", sphere_, "--method", method, "--phase", QString::number(phases),
                 "--json", out + "/r.json", "--svg", out + "/r.svg"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const nlohmann::json j = readJson(out + "/r.json");
        const nlohmann::json& view = j["views"][0];
        QCOMPARE(view["phases"].size(), size_t(phases));
        QCOMPARE(view["completed_phases"].get<int>(), phases);
        QCOMPARE(view["phase_count"].get<size_t>(), m.phases.size());
        for (int i = 0; i < phases; ++i)
            QCOMPARE(view["phases"][size_t(i)]["name"].get<std::string>(),
                     m.phases[size_t(i)].name);
        // The phase after the last one run did not run.
        QVERIFY(!r.out.contains(QString::fromStdString(" " + m.phases[size_t(phases)].name + " ")));
        // Before chaining (traced contours: tracing) there are no curves;
        // after it, the sphere's loop (raw, then as a view-graph chain once
        // visibility has run).
        const int chaining =
            m.phaseIndex("chaining") >= 0 ? m.phaseIndex("chaining") : m.phaseIndex("tracing");
        QVERIFY(chaining >= 0);
        const SvgFile svg = readSvg(out + "/r.svg");
        QVERIFY(svg.ok);
        QCOMPARE(int(svg.polylines.size()), phases > chaining ? 1 : 0);
        if (phases > chaining) {
            const QStringList expected = view.contains("view_graph")
                                             ? QStringList{"visible-contour", "hidden-contour"}
                                             : QStringList{"contour"};
            QVERIFY2(expected.contains(svg.polylines.front().group),
                     qPrintable(svg.polylines.front().group));
        }
    }

    void parametersReachTheMethod_data() {
        QTest::addColumn<QString>("method");
        QTest::addColumn<QString>("includeBoundaries");
        QTest::addColumn<int>("boundaryCurves");
        for (const char* m : {"mesh", "interpolated"}) {
            QTest::addRow("%s-default", m) << QString(m) << QString() << 1;
            QTest::addRow("%s-true", m) << QString(m) << QString("true") << 1;
            QTest::addRow("%s-false", m) << QString(m) << QString("false") << 0;
        }
    }

    void parametersReachTheMethod() {
        QFETCH(QString, method);
        QFETCH(QString, includeBoundaries);
        QFETCH(int, boundaryCurves);
        const QString out = freshOutputDir("parameters");
        // Without the view graph: the raw-curve SVG, one polyline per curve.
        QStringList args{"--mesh",        saddle_, "--method",     method,         "--json",
                         out + "/r.json", "--svg", out + "/r.svg", "--visibility", "false"};
        if (!includeBoundaries.isEmpty())
            args << "--include-boundaries" << includeBoundaries;
        if (method == "interpolated")
            args << "--normal-weighting"
                 << "angle";
        const RunResult r = run(args);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const nlohmann::json j = readJson(out + "/r.json");
        QCOMPARE(j["method"]["parameters"]["include-boundaries"].get<bool>(), boundaryCurves == 1);
        if (method == "interpolated")
            QCOMPARE(j["method"]["parameters"]["normal-weighting"].get<std::string>(),
                     std::string("angle"));
        QCOMPARE(j["mesh"]["boundary_edges"].get<int>(), 4 * 16);
        QCOMPARE(j["views"][0]["totals"]["boundary_curves"].get<int>(), boundaryCurves);
        const SvgFile svg = readSvg(out + "/r.svg");
        QVERIFY(svg.ok);
        QCOMPARE(svg.count("boundary"), boundaryCurves);
        for (const SvgPolyline& p : svg.polylines)
            QCOMPARE(p.type, p.group);
    }

    void views26() {
        const QString out = freshOutputDir("views26");
        const RunResult r =
            run({"--mesh", sphere_, "--method", "interpolated", "--views26", "--svg",
                 out + "/s.svg", "--json", out + "/r.json", "--write-camera", out + "/cam.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(filesIn(out).size(), 2 * 26 + 1);
        const nlohmann::json j = readJson(out + "/r.json");
        QCOMPARE(j["views"].size(), size_t(26));
        const std::vector<Camera> expected =
            Camera::views26(sphereMesh_.triangulate().boundingBox(), Viewport{800, 600});
        for (int v = 0; v < 26; ++v) {
            const QString suffix = QString("_view%1").arg(v, 2, 10, QChar('0'));
            const SvgFile svg = readSvg(out + "/s" + suffix + ".svg");
            QVERIFY2(svg.ok, qPrintable(suffix + ": " + svg.error));
            // One chain, visible or not (interpolated: a heuristic vote).
            QCOMPARE(svg.count("visible-contour") + svg.count("hidden-contour"), 1);
            const nlohmann::json& view = j["views"][size_t(v)];
            QCOMPARE(view["index"].get<int>(), v);
            QCOMPARE(view["totals"]["closed_loops"].get<int>(), 1);
            QCOMPARE(view["totals"]["contour_chains"].get<int>(), 1);
            QCOMPARE(view["camera"], expected[size_t(v)].toJson());
            QCOMPARE(readJson(out + "/cam" + suffix + ".json"), view["camera"]);
        }
    }

    // --ply writes the last snapshot's mesh with its int and double vertex
    // and face fields; it reads back with the snapshot's counts, and the
    // labels agree with the counters of the JSON report.
    void plyOutput() {
        const QString out = freshOutputDir("ply");
        const QString spot = CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj";
        const RunResult r = run({"--mesh", spot, "--method", "consistent", "--ply",
                                 out + "/spot.ply", "--json", out + "/r.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(filesIn(out), QStringList({"r.json", "spot.ply"}));
        const nlohmann::json counters = readJson(out + "/r.json")["views"][0]["totals"]["counters"];
        PlyLabels labels;
        const PolygonMesh mesh = readMesh((out + "/spot.ply").toStdString(), &labels);
        QCOMPARE(mesh.faceCount(), counters["faces"].get<int>());
        QCOMPARE(mesh.vertexCount(), counters["vertices"].get<int>());
        for (Index f = 0; f < mesh.faceCount(); ++f)
            QCOMPARE(mesh.face(f).size(), size_t(3));
        using namespace fields;
        for (const char* name : {kLabel, kCusp, kProvenance, kVertexChangedByPhase, kPreimageFace})
            QVERIFY2(labels.vertexLabels.count(name), name);
        for (const char* name : {kG, kRadialCurvature, kNormalOffset})
            QVERIFY2(labels.vertexScalars.count(name), name);
        for (const char* name : {kFacing, kVbo, kConsistent, kRadial, kStandardRadial,
                                 kChangedByPhase, kFolded, kDomainFace})
            QVERIFY2(labels.faceLabels.count(name), name);
        // Vector and edge fields have no PLY property.
        QVERIFY(!labels.vertexScalars.count(kVertexNormal));
        QVERIFY(!labels.faceLabels.count(kContourEdge));
        const auto count = [](const std::vector<int>& column, int value) {
            return static_cast<int>(std::count(column.begin(), column.end(), value));
        };
        QCOMPARE(count(labels.faceLabels[kConsistent], 0),
                 counters["inconsistent faces"].get<int>());
        QCOMPARE(count(labels.vertexLabels[kLabel], 0), counters["contour vertices"].get<int>());
        QCOMPARE(count(labels.vertexLabels[kCusp], 1), counters["cusps"].get<int>());
        QVERIFY(count(labels.vertexLabels[kLabel], 0) > 0);
        QCOMPARE(count(labels.faceLabels[kVbo], 1) + count(labels.faceLabels[kVbo], -1) +
                     count(labels.faceLabels[kVbo], 0),
                 mesh.faceCount());
    }

    // With --views26, one PLY per view; with --phase, the mesh after it.
    void plyPerViewAndPhase() {
        const QString out = freshOutputDir("ply-views26");
        RunResult r =
            run({"--mesh", sphere_, "--method", "mesh", "--views26", "--ply", out + "/s.ply"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(filesIn(out).size(), 26);
        const int triangles = sphereMesh_.triangulate().faceCount();
        for (int v = 0; v < 26; ++v) {
            const QString suffix = QString("_view%1").arg(v, 2, 10, QChar('0'));
            PlyLabels labels;
            const PolygonMesh mesh =
                readMesh((out + "/s" + suffix + ".ply").toStdString(), &labels);
            QCOMPARE(mesh.faceCount(), triangles);
            QVERIFY(labels.faceLabels.count(fields::kFacing));
        }
        const QString phase = freshOutputDir("ply-phase");
        r = run(
            {"--mesh", sphere_, "--method", "mesh", "--phase", "0", "--ply", phase + "/input.ply"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        PlyLabels labels;
        const PolygonMesh mesh = readMesh((phase + "/input.ply").toStdString(), &labels);
        QCOMPARE(mesh.faceCount(), triangles);
        QVERIFY(!labels.faceLabels.count(fields::kFacing)); // facing has not run
    }

    // A --ply that cannot be written fails the run and leaves no file: a
    // missing folder is found before the run; a folder in the file's place
    // fails the write, which takes the other outputs along.
    void plyUnwritable() {
        const QString out = freshOutputDir("ply-unwritable");
        RunResult r = run(
            {"--mesh", sphere_, "--json", out + "/r.json", "--ply", out + "/missing-folder/m.ply"});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("missing-folder/m.ply: cannot write"), qPrintable(r.err));
        QVERIFY2(filesIn(out).isEmpty(), qPrintable(filesIn(out).join(", ")));

        QVERIFY(QDir(out).mkdir("a-folder.ply"));
        r = run({"--mesh", sphere_, "--json", out + "/r.json", "--svg", out + "/r.svg", "--ply",
                 out + "/a-folder.ply"});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("a-folder.ply"), qPrintable(r.err));
        QVERIFY2(filesIn(out).isEmpty(), qPrintable(filesIn(out).join(", ")));
        QVERIFY(QDir(out + "/a-folder.ply").isEmpty());

        r = run({"--mesh", sphere_, "--json", out + "/same.out", "--ply", out + "/same.out"});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("--json and --ply name the same file"), qPrintable(r.err));
    }

    // Batch parity with the workbench's diagnostic snapshot:
    // --snapshot-dir writes the report, SVG, PLY and session of the run,
    // and (GUI build, with a display: the suites run under xvfb-run) the two
    // PNGs drawn by the workbench's views; they agree with each other and
    // with --json.
    void snapshotDir() {
        const QString out = freshOutputDir("snapshot");
        const QString spot = CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj";
        const RunResult r = run({"--mesh", spot, "--method", "consistent", "--snapshot-dir",
                                 out + "/snap/", "--json", out + "/r.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(filesIn(out), QStringList({"r.json"}));
        QStringList files = filesIn(out + "/snap");
        files.sort();
        QStringList expected({"mesh.ply", "report.json", "session.cwsession", "view-2d.svg"});
#ifdef CONTOUR_BATCH_HAS_WIDGETS
        const bool pictures = qEnvironmentVariableIsSet("DISPLAY");
#else
        const bool pictures = false;
#endif
        if (pictures) {
            expected << "view-2d.png"
                     << "view-3d.png";
            expected.sort();
            // Decoded at the camera's viewport size; not blank: the 3D view
            // shows the mesh's front colour, the 2D view black curves.
            for (const QString& name : {QString("view-3d.png"), QString("view-2d.png")}) {
                const QImage image(out + "/snap/" + name);
                QVERIFY2(!image.isNull(), qPrintable(name));
                QCOMPARE(image.size(), QSize(800, 600));
                QSet<QRgb> colours;
                for (int y = 0; y < image.height(); y += 4)
                    for (int x = 0; x < image.width(); x += 4)
                        colours.insert(image.pixel(x, y));
                QVERIFY2(colours.size() > 20, qPrintable(name));
            }
        } else {
            QVERIFY2(r.out.contains("view-3d.png and view-2d.png not written"), qPrintable(r.out));
        }
        QCOMPARE(files, expected);
        const nlohmann::json report = readJson(out + "/snap/report.json");
        QCOMPARE(static_cast<qsizetype>(report["snapshot"]["files"].size()), expected.size());
        const nlohmann::json& view = report["views"][0];
        QCOMPARE(view["camera"], readJson(out + "/r.json")["views"][0]["camera"]);
        QCOMPARE(report["method"], readJson(out + "/r.json")["method"]);
        const nlohmann::json& counters = view["totals"]["counters"];
        QCOMPARE(view["inconsistent_faces"].size(), counters["inconsistent faces"].get<size_t>());
        for (const nlohmann::json& face : view["inconsistent_faces"])
            for (const char* key : {"face", "vertices", "reason", "vbo", "facing", "vertex_labels",
                                    "g", "neighbours", "changed_by_phase_name"})
                QVERIFY2(face.contains(key), key);
        QCOMPARE(report["snapshot"]["phase_reached"].get<int>(),
                 view["completed_phases"].get<int>());
        const SvgFile svg = readSvg(out + "/snap/view-2d.svg");
        QVERIFY2(svg.ok, qPrintable(svg.error));
        QVERIFY(!svg.polylines.empty());
        PlyLabels labels;
        const PolygonMesh mesh = readMesh((out + "/snap/mesh.ply").toStdString(), &labels);
        QCOMPARE(mesh.faceCount(), counters["faces"].get<int>());
        const std::vector<int>& consistent = labels.faceLabels[fields::kConsistent];
        QCOMPARE(static_cast<int>(std::count(consistent.begin(), consistent.end(), 0)),
                 counters["inconsistent faces"].get<int>());
        const Session session = readSession((out + "/snap/session.cwsession").toStdString());
        QCOMPARE(session.method, std::string("consistent"));
        QCOMPARE(session.phaseReached, view["completed_phases"].get<int>());
        QCOMPARE(QFileInfo(QString::fromStdString(session.meshPath)).canonicalFilePath(),
                 QFileInfo(spot).canonicalFilePath());

        // --views26: one sub-folder per view.
        const QString views = freshOutputDir("snapshot-views26");
        const RunResult r26 =
            run({"--mesh", sphere_, "--views26", "--snapshot-dir", views + "/snap"});
        QVERIFY2(r26.exitCode == 0, qPrintable(r26.err));
        QCOMPARE(QDir(views + "/snap").entryList(QDir::Dirs | QDir::NoDotAndDotDot).size(), 26);
        QCOMPARE(filesIn(views + "/snap/view25").size(), pictures ? 6 : 4);

        // Without a display the pictures are left out, and the run says so.
        const QString headless = freshOutputDir("snapshot-headless");
        const RunResult rh =
            run({"--mesh", sphere_, "--snapshot-dir", headless + "/snap"}, 120000, true);
        QVERIFY2(rh.exitCode == 0, qPrintable(rh.err));
        QVERIFY2(rh.out.contains("view-3d.png and view-2d.png not written"), qPrintable(rh.out));
        QCOMPARE(filesIn(headless + "/snap").size(), 4);
    }

    // --session runs what a session holds (here the snapshot's own session):
    // the same camera, parameters, phase and result; flags override
    // parameters; the mesh, method and camera cannot be given twice.
    void sessionRun() {
        const QString out = freshOutputDir("session");
        RunResult r = run({"--mesh", sphere_, "--method", "interpolated", "--phase", "3",
                           "--normal-weighting", "angle", "--snapshot-dir", out + "/snap"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QString session = out + "/snap/session.cwsession";
        r = run({"--session", session, "--json", out + "/again.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const nlohmann::json first = readJson(out + "/snap/report.json");
        const nlohmann::json again = readJson(out + "/again.json");
        QCOMPARE(again["method"], first["method"]);
        QCOMPARE(again["views"][0]["camera"], first["views"][0]["camera"]);
        QCOMPARE(again["views"][0]["completed_phases"].get<int>(), 3);
        QCOMPARE(again["views"][0]["totals"]["counters"], first["views"][0]["totals"]["counters"]);

        r = run({"--session", session, "--normal-weighting", "max", "--phase", "1", "--json",
                 out + "/override.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const nlohmann::json overridden = readJson(out + "/override.json");
        QCOMPARE(overridden["method"]["parameters"]["normal-weighting"].get<std::string>(),
                 std::string("max"));
        QCOMPARE(overridden["views"][0]["completed_phases"].get<int>(), 1);

        r = run({"--session", session, "--mesh", sphere_});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("--session cannot be combined with --mesh"), qPrintable(r.err));
        writeText(path("broken.cwsession"), "{\"format\": \"contour-workbench-session\"}");
        r = run({"--session", path("broken.cwsession")});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("broken.cwsession") && r.err.contains("\"version\" is missing"),
                 qPrintable(r.err));
    }

    // A sphere whose faces are all oriented inward: by default it is flipped
    // (one line says so, the report's mesh notes it) and its contour is
    // visible; --keep-orientation keeps it as in the file, which hides every
    // contour (the front faces point away from the eye). A session records
    // the choice and a run of it keeps the file's orientation again.
    void inwardMeshIsFlipped() {
        const QString out = freshOutputDir("inward");
        const QString mesh = out + "/inward.obj";
        QVERIFY(testing::writeObjFile(testing::reversedFaces(sphereMesh_), mesh.toStdString()));
        const QString prefix = mesh + ": 1 of 1 closed components ";

        RunResult r = run({"--mesh", mesh, "--method", "mesh", "--json", out + "/flipped.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QString flippedLine = prefix + "had inward normals (signed volume -";
        QVERIFY2(r.out.startsWith(flippedLine), qPrintable(r.out));
        const QString firstLine = r.out.section('\n', 0, 0);
        QVERIFY2(firstLine.endsWith("); flipped (--keep-orientation keeps them)"),
                 qPrintable(firstLine));
        const nlohmann::json flipped = readJson(out + "/flipped.json");
        QCOMPARE(flipped["mesh"]["notes"], nlohmann::json::array({firstLine.toStdString()}));
        const nlohmann::json& graph = flipped["views"][0]["view_graph"]["totals"];
        QVERIFY(graph["visible_chains"].get<int>() > 0);
        QVERIFY(graph["visible_length_px"].get<double>() > 0.0);

        // The same run as on the sphere written outward, but for the note.
        r = run({"--mesh", sphere_, "--method", "mesh", "--json", out + "/outward.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(!r.out.contains("inward normals"), qPrintable(r.out));
        const nlohmann::json outward = readJson(out + "/outward.json");
        QVERIFY(outward["mesh"]["notes"].empty());
        QCOMPARE(flipped["views"][0]["view_graph"]["chains"],
                 outward["views"][0]["view_graph"]["chains"]);

        r = run({"--mesh", mesh, "--method", "mesh", "--keep-orientation", "--json",
                 out + "/kept.json", "--snapshot-dir", out + "/snap"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QString keptLine = r.out.section('\n', 0, 0);
        QVERIFY2(keptLine.startsWith(prefix + "has inward normals (signed volume -") &&
                     keptLine.endsWith("; kept as in the file (--keep-orientation): its "
                                       "contours will read as hidden"),
                 qPrintable(r.out));
        const nlohmann::json kept = readJson(out + "/kept.json");
        QCOMPARE(kept["mesh"]["notes"], nlohmann::json::array({keptLine.toStdString()}));
        const nlohmann::json& hidden = kept["views"][0]["view_graph"]["totals"];
        QVERIFY(hidden["chains"].get<int>() > 0);
        QCOMPARE(hidden["visible_chains"].get<int>(), 0);
        QCOMPARE(hidden["visible_length_px"].get<double>(), 0.0);

        const QString session = out + "/snap/session.cwsession";
        QCOMPARE(readJson(session)["keep_file_orientation"].get<bool>(), true);
        r = run({"--session", session, "--json", out + "/again.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(r.out.contains("kept as in the file"), qPrintable(r.out));
        QCOMPARE(readJson(out + "/again.json")["views"][0]["view_graph"]["totals"]["visible_chains"]
                     .get<int>(),
                 0);

        // The open saddle's orientation cannot be decided: said, and untouched.
        r = run({"--mesh", saddle_, "--method", "mesh", "--phase", "0"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(r.out.startsWith(saddle_ + ": 1 open component left as in the file: its "
                                            "orientation cannot be decided by volume\n"),
                 qPrintable(r.out));
    }

    // The preset a run started from and the parameters changed from it go
    // into the snapshot's session and report; a run of that session starts
    // from the same preset; a session naming a preset the method lacks runs
    // from the defaults, saying so.
    void sessionRecordsThePreset() {
        const QString out = freshOutputDir("preset-session");
        RunResult r =
            run({"--mesh", sphere_, "--method", "consistent", "--preset", "paper",
                 "--snap-fraction", "0.3", "--phase", "1", "--snapshot-dir", out + "/snap"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QString sessionPath = out + "/snap/session.cwsession";
        nlohmann::json session = readJson(sessionPath);
        const nlohmann::json expected = {{"name", "paper"}, {"changed", {{"snap-fraction", 0.3}}}};
        QCOMPARE(session["preset"], expected);
        QCOMPARE(readJson(out + "/snap/report.json")["method"]["preset"], expected);
        const Session read = readSession(sessionPath.toStdString());
        QCOMPARE(read.preset, std::string("paper"));
        QCOMPARE(read.presetChanges.getDouble("snap-fraction"), 0.3);

        r = run({"--session", sessionPath, "--json", out + "/again.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(readJson(out + "/again.json")["method"]["preset"], expected);
        // --preset replaces the session's parameters and its preset.
        r = run({"--session", sessionPath, "--preset", "default", "--json", out + "/plain.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const nlohmann::json plain = readJson(out + "/plain.json")["method"]["preset"];
        QCOMPARE(plain["name"].get<std::string>(), std::string("default"));
        QVERIFY(plain["changed"].empty());

        session["preset"]["name"] = "no-such-preset";
        writeText(path("unknown-preset.cwsession"), QByteArray::fromStdString(session.dump()));
        r = run({"--session", path("unknown-preset.cwsession"), "--json", out + "/unknown.json"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2((r.out + r.err).contains("has no preset \"no-such-preset\""),
                 qPrintable(r.out + r.err));
        const nlohmann::json fallback = readJson(out + "/unknown.json")["method"]["preset"];
        QCOMPARE(fallback["name"].get<std::string>(), std::string("default"));
        // Every value the paper preset sets away from the defaults, and the flag.
        QVERIFY(fallback["changed"].size() > 1);
        QCOMPARE(fallback["changed"]["snap-fraction"].get<double>(), 0.3);
    }

    // A snapshot file that cannot be written fails the run and takes every
    // other output along; the folder it made is removed again.
    void snapshotDirUnwritable() {
        const QString out = freshOutputDir("snapshot-unwritable");
        QVERIFY(QDir().mkpath(out + "/snap/view-2d.svg/inside"));
        RunResult r =
            run({"--mesh", sphere_, "--json", out + "/r.json", "--snapshot-dir", out + "/snap"});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("snap/view-2d.svg: cannot write"), qPrintable(r.err));
        QCOMPARE(filesIn(out), QStringList());
        QCOMPARE(
            QDir(out + "/snap").entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot),
            QStringList({"view-2d.svg"}));
        r = run({"--mesh", sphere_, "--views26", "--snapshot-dir", out + "/new/snap"});
        QCOMPARE(r.exitCode, 1); // the parent folder does not exist
        QVERIFY2(r.err.contains("new/snap: cannot write"), qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(out + "/new"));
    }

    // --strict turns counted post-condition violations into exit code 3 (a
    // Debug build fails the phase itself: exit code 1). Two bisection steps
    // cannot bring |g| at the C vertices below 1e-16, so the contour
    // insertion's root post-condition is violated on purpose.
    void strictExitCode() {
        const QString out = freshOutputDir("strict");
        const QStringList args{"--mesh",
                               sphere_,
                               "--method",
                               "consistent",
                               "--root-tolerance",
                               "1e-16",
                               "--root-max-iterations",
                               "2",
                               "--json",
                               out + "/r.json"};
        RunResult r = run(args);
#ifdef CONTOUR_CHECK_INVARIANTS
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("|g|"), qPrintable(r.err));
#else
        QCOMPARE(r.exitCode, 0); // counted, reported, not fatal
        QVERIFY(QFile::exists(out + "/r.json"));
        r = run(QStringList(args) << "--strict");
        QCOMPARE(r.exitCode, 3);
        QVERIFY2(r.err.contains("--strict") && r.err.contains("|g|"), qPrintable(r.err));
        QVERIFY(QFile::exists(out + "/r.json")); // the outputs are still written
        // Without violations --strict changes nothing.
        QCOMPARE(run({"--mesh", sphere_, "--strict", "--json", out + "/m.json"}).exitCode, 0);
#endif
    }

    void cliErrors_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<int>("exitCode");
        QTest::addColumn<QString>("message");

        const QString s = sphere_;
        QTest::newRow("missing --mesh")
            << QStringList{"--method", "mesh"} << 2 << "--mesh is required";
        QTest::newRow("unknown method")
            << QStringList{"--mesh", s, "--method", "bogus"} << 2 << "unknown method \"bogus\"";
        for (const PlannedMethod& planned : plannedMethods())
            QTest::addRow("planned %s", planned.name.c_str())
                << QStringList{"--mesh", s, "--method", QString::fromStdString(planned.name)} << 2
                << QString::fromStdString(planned.reason);
        QTest::newRow("unknown option")
            << QStringList{"--mesh", s, "--frobnicate"} << 2 << "--frobnicate";
        QTest::newRow("bad --eye: two numbers")
            << QStringList{"--mesh", s, "--eye", "1,2"} << 2 << "--eye: \"1,2\" is not three";
        QTest::newRow("bad --eye: text")
            << QStringList{"--mesh", s, "--eye", "1,x,3"} << 2 << "--eye: \"1,x,3\"";
        QTest::newRow("bad --target")
            << QStringList{"--mesh", s, "--target", "0,0,nan"} << 2 << "--target";
        QTest::newRow("eye at target")
            << QStringList{"--mesh", s, "--eye", "0,0,0", "--target", "0,0,0"} << 2
            << "eye and target coincide";
        QTest::newRow("bad --fov") << QStringList{"--mesh", s, "--fov", "200"} << 2 << "--fov";
        QTest::newRow("bad --width text")
            << QStringList{"--mesh", s, "--width", "wide"} << 2 << "--width";
        QTest::newRow("bad --width value")
            << QStringList{"--mesh", s, "--width", "0"} << 2 << "--width";
        // The mesh method's phase count comes from the registry, not a literal.
        const int phases = static_cast<int>(contour::findMethod("mesh")->phases.size());
        const QString range = QString("[0, %1]").arg(phases);
        QTest::newRow("--phase too large")
            << QStringList{"--mesh", s, "--phase", QString::number(phases + 1)} << 2
            << QString("--phase: %1 is not in %2").arg(phases + 1).arg(range);
        QTest::newRow("--phase negative") << QStringList{"--mesh", s, "--phase", "-1"} << 2
                                          << QString("--phase: -1 is not in %1").arg(range);
        QTest::newRow("bad --height value")
            << QStringList{"--mesh", s, "--height", "-5"} << 2 << "--height: -5 pixels";
        QTest::newRow("--camera with --eye")
            << QStringList{"--mesh", s, "--camera", path("ortho-camera.json"), "--eye", "1,2,3"}
            << 2 << "cannot be combined with --eye";
        QTest::newRow("--views26 with --eye")
            << QStringList{"--mesh", s, "--views26", "--eye", "1,2,3"} << 2
            << "cannot be combined with --eye";
        QTest::newRow("parameter of the other method")
            << QStringList{"--mesh", s, "--method", "mesh", "--normal-weighting", "angle"} << 2
            << "--normal-weighting is a parameter of method interpolated, not of method mesh";
        QTest::newRow("choice out of range")
            << QStringList{"--mesh", s, "--method", "interpolated", "--normal-weighting", "median"}
            << 2 << "must be one of: area, angle, max";
        QTest::newRow("bad boolean") << QStringList{"--mesh", s, "--include-boundaries", "maybe"}
                                     << 2 << "\"maybe\" is not a boolean";

        QTest::newRow("missing mesh file")
            << QStringList{"--mesh", path("nowhere.obj")} << 1 << "nowhere.obj";
        writeText(path("bad-index.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
        QTest::newRow("bad mesh: index out of range")
            << QStringList{"--mesh", path("bad-index.obj")} << 1 << "bad-index.obj";
        writeText(path("empty.obj"), "# nothing\n");
        QTest::newRow("bad mesh: empty")
            << QStringList{"--mesh", path("empty.obj")} << 1 << "empty.obj";
        const QDir bad(CONTOUR_SOURCE_DIR "/tests/data/bad");
        for (const QString& name : bad.entryList({"*.obj", "*.off", "*.ply"}, QDir::Files))
            QTest::addRow("tests/data/bad/%s", qPrintable(name))
                << QStringList{"--mesh", bad.filePath(name)} << 1 << name;

        writeText(path("broken-camera.json"), "{\"eye\": [0, 0, 5], \"target\": ");
        QTest::newRow("camera file: bad JSON")
            << QStringList{"--mesh", s, "--camera", path("broken-camera.json")} << 1
            << "broken-camera.json: not valid JSON";
        writeText(path("no-eye-camera.json"), "{\"target\": [0, 0, 0]}");
        QTest::newRow("camera file: no eye")
            << QStringList{"--mesh", s, "--camera", path("no-eye-camera.json")} << 1
            << "missing \"eye\"";
        QTest::newRow("camera file: missing")
            << QStringList{"--mesh", s, "--camera", path("no-camera.json")} << 1
            << "no-camera.json: cannot open";
    }

    void cliErrors() {
        QFETCH(QStringList, args);
        QFETCH(int, exitCode);
        QFETCH(QString, message);
        const QString out = freshOutputDir("errors");
        args << "--svg" << out + "/r.svg"
             << "--json" << out + "/r.json"
             << "--write-camera" << out + "/cam.json";
        const RunResult r = run(args);
        QVERIFY2(r.exitCode == exitCode,
                 qPrintable(QString("exit code %1, stderr: %2").arg(r.exitCode).arg(r.err)));
        QVERIFY2(r.err.contains(message), qPrintable("stderr: " + r.err));
        QVERIFY2(filesIn(out).isEmpty(), qPrintable(filesIn(out).join(", ")));
    }

    // The exporters behind the CLI draw and measure only what lies in front
    // of a perspective eye: a closed square around the eye keeps one piece.
    void curvesBehindTheEyeAreClipped() {
        Camera camera;
        camera.eye = Vec3(0, 0, 0.5);
        camera.target = Vec3(1, 0, 0.5);
        camera.up = Vec3(0, 0, 1);
        camera.viewport = {400, 300};
        Polyline square;
        square.closed = true;
        for (const Vec3& p : {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)})
            square.points.push_back({p});
        Snapshot snapshot;
        snapshot.curves = std::make_shared<const std::vector<Polyline>>(1, square);
        const QString svgPath = path("clipped.svg");
        writeSvg(svgPath.toStdString(), snapshot, camera);
        const SvgFile svg = readSvg(svgPath);
        QVERIFY2(svg.ok, qPrintable(svg.error));
        QCOMPARE(svg.count("contour"), 1);
        const std::vector<Vec2>& drawn = svg.polylines.front().points;
        QCOMPARE(drawn.size(), size_t(2));
        const Vec2 a = camera.project(Vec3(1, -1, 0)).pixel,
                   b = camera.project(Vec3(1, 1, 0)).pixel;
        QVERIFY((drawn[0] - a).norm() < 1e-3 && (drawn[1] - b).norm() < 1e-3);
        QVERIFY(svg.polylines.front().closed); // the curve's own flag

        const nlohmann::json curves = curvesJson(snapshot, camera);
        QCOMPARE(curves.size(), size_t(1));
        QCOMPARE(curves[0]["hidden_points"].get<int>(), 2);
        QCOMPARE(curves[0]["pieces"].get<int>(), 1);
        QVERIFY(std::abs(curves[0]["length_px"].get<double>() - (b - a).norm()) < 1e-9);

        camera.projection = Projection::Orthographic; // sees everything
        const nlohmann::json ortho = curvesJson(snapshot, camera);
        QCOMPARE(ortho[0]["hidden_points"].get<int>(), 0);
        QCOMPARE(ortho[0]["pieces"].get<int>(), 1);
    }

    // An output that cannot be written fails the run and leaves nothing
    // behind: a missing folder is found before the run, a failed write
    // takes the outputs already written by the run along.
    void unwritableOutput() {
        const QString out = freshOutputDir("unwritable");
        RunResult r = run(
            {"--mesh", sphere_, "--svg", out + "/r.svg", "--json", out + "/missing-folder/r.json"});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("missing-folder/r.json: cannot write"), qPrintable(r.err));
        QVERIFY2(!r.out.contains("facing"), qPrintable(r.out)); // nothing ran
        QVERIFY2(filesIn(out).isEmpty(), qPrintable(filesIn(out).join(", ")));

        QVERIFY(QDir(out).mkdir("a-folder.json"));
        r = run({"--mesh", sphere_, "--svg", out + "/r.svg", "--write-camera", out + "/c.json",
                 "--json", out + "/a-folder.json"});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("a-folder.json"), qPrintable(r.err));
        QVERIFY2(filesIn(out).isEmpty(), qPrintable(filesIn(out).join(", ")));
    }
};

QTEST_GUILESS_MAIN(TestCli)
#include "test_cli.moc"
