// The layers of algorithms/: dependencies point down only.
//   core < mesh < camera < surface < pipeline < visibility < contours, and
//   export includes nothing above pipeline and is included by no other layer;
//   reference (the dense ground truth) includes core..pipeline and, from
//   contours/, only the consistent mesh's charts (to read a method's
//   preimages), never visibility/ or a method, and is included by no other
//   layer;
//   inside contours/consistent/: mesh < predicates < numerics < edits <
//   phases < extensions < the method's own files (consistent/*.cpp);
//   algorithms/ includes nothing from widgets/ or app/, and no Qt or VTK header.
// Every .h/.cpp under algorithms/ is read and each #include line checked.
#include <QtTest>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kLayers = {"core",     "mesh",       "camera",  "surface",
                                          "pipeline", "visibility", "contours"};
const std::vector<std::string> kConsistentLayers = {"mesh",  "predicates", "numerics",
                                                    "edits", "phases",     "extensions"};

int indexOf(const std::vector<std::string>& v, const std::string& x) {
    for (size_t i = 0; i < v.size(); ++i)
        if (v[i] == x)
            return static_cast<int>(i);
    return -1;
}

std::vector<std::string> components(const std::string& path) {
    std::vector<std::string> out;
    for (const fs::path& p : fs::path(path))
        out.push_back(p.string());
    return out;
}

// The rank of a path relative to algorithms/ in the consistent sub-layers:
// 0.. for mesh..extensions, kConsistentLayers.size() for the method's own
// files in consistent/, nothing outside consistent/.
std::optional<int> consistentRank(const std::string& path) {
    const std::vector<std::string> c = components(path);
    if (c.size() < 3 || c[0] != "contours" || c[1] != "consistent")
        return std::nullopt;
    if (c.size() == 3)
        return static_cast<int>(kConsistentLayers.size());
    const int i = indexOf(kConsistentLayers, c[2]);
    return i >= 0 ? std::optional<int>(i) : std::nullopt;
}

// Why `from` (a file relative to algorithms/) may not include `to` (a
// header relative to algorithms/), or an empty string when it may.
std::string layerViolation(const std::string& from, const std::string& to) {
    const std::vector<std::string> a = components(from), b = components(to);
    if (a.empty() || b.empty())
        return "empty path";
    if (b[0] == "widgets" || b[0] == "app")
        return "algorithms/ includes " + b[0] + "/";
    const std::string& la = a[0];
    const std::string& lb = b[0];
    if (lb == "export" && la != "export")
        return "only export/ includes export/ (" + la + " includes " + to + ")";
    if (lb == "reference" && la != "reference")
        return "only reference/ includes reference/ (" + la + " includes " + to + ")";
    if (la == "reference") {
        // The oracle shares no contour code with the methods.
        const bool charts =
            lb == "contours" && b.size() > 3 && b[1] == "consistent" && b[2] == "mesh";
        if (lb == "contours" && !charts)
            return "reference/ includes a contour method's code (" + to + ")";
        if (lb == "visibility" || lb == "export")
            return "reference/ includes " + lb + "/ (" + to + ")";
        if (lb != "reference" && lb != "contours" && indexOf(kLayers, lb) < 0)
            return "unknown layer " + lb;
        return {};
    }
    const int ra = la == "export" ? indexOf(kLayers, "pipeline") : indexOf(kLayers, la);
    const int rb = lb == "export" ? ra : indexOf(kLayers, lb);
    if (ra < 0)
        return "unknown layer " + la;
    if (rb < 0)
        return "unknown layer " + lb;
    if (rb > ra)
        return la + " includes the higher layer " + lb;
    const std::optional<int> ca = consistentRank(from), cb = consistentRank(to);
    if (ca && cb && *cb > *ca)
        return "consistent/" + (a.size() == 3 ? std::string("(method)") : a[2]) +
               " includes the higher sub-layer " +
               (b.size() == 3 ? std::string("consistent/ (the method)") : "consistent/" + b[2]);
    for (const auto& [path, c] : {std::pair{&a, ca}, std::pair{&b, cb}})
        if (!c && path->size() > 3 && (*path)[0] == "contours" && (*path)[1] == "consistent")
            return "unknown sub-layer consistent/" + (*path)[2];
    if (!ca && cb && la == "contours" && a.size() > 2)
        return "contours/" + a[1] + " includes the consistent method's internals";
    return {};
}

struct Violation {
    std::string file;
    int line;
    std::string text, why;
};

const std::regex kQuoted("^\\s*#\\s*include\\s*\"([^\"]+)\"");
const std::regex kAngled("^\\s*#\\s*include\\s*<([^>]+)>");
const std::regex kQtOrVtk("^(Q[A-Za-z0-9_]*(/.*)?|qt[a-z0-9_]*\\.h|vtk.*)$");

// Every include of the file that breaks a rule.
std::vector<Violation> checkFile(const fs::path& root, const fs::path& file) {
    std::vector<Violation> out;
    const std::string from = fs::relative(file, root).generic_string();
    std::ifstream in(file);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        std::smatch m;
        if (std::regex_search(line, m, kQuoted)) {
            const std::string to = m[1].str();
            std::string why;
            if (!fs::exists(root / to) && !fs::exists(root.parent_path() / to))
                why = "the header is not under algorithms/";
            else if (!fs::exists(root / to))
                why = "algorithms/ includes " + to + " outside algorithms/";
            else
                why = layerViolation(from, to);
            if (!why.empty())
                out.push_back({from, n, line, why});
        } else if (std::regex_search(line, m, kAngled) && std::regex_match(m[1].str(), kQtOrVtk)) {
            out.push_back({from, n, line, "algorithms/ includes a Qt or VTK header"});
        }
    }
    return out;
}

} // namespace

class TestLayers : public QObject {
    Q_OBJECT
private slots:
    // The rule itself, on paths that break it and paths that keep it.
    void ruleRejectsUpwardIncludes() {
        QVERIFY(layerViolation("mesh/TriangleMesh.h", "core/Types.h").empty());
        QVERIFY(!layerViolation("mesh/TriangleMesh.h", "camera/Camera.h").empty());
        QVERIFY(!layerViolation("pipeline/Method.h", "visibility/RayCaster.h").empty());
        QVERIFY(layerViolation("export/JsonReport.h", "pipeline/Snapshot.h").empty());
        QVERIFY(!layerViolation("export/JsonReport.h", "visibility/RayCaster.h").empty());
        QVERIFY(!layerViolation("contours/Methods.cpp", "export/JsonReport.h").empty());
        QVERIFY(layerViolation("reference/X.cpp", "surface/SurfaceFields.h").empty());
        QVERIFY(layerViolation("reference/X.cpp", "pipeline/Snapshot.h").empty());
        QVERIFY(
            layerViolation("reference/X.cpp", "contours/consistent/mesh/DomainCharts.h").empty());
        QVERIFY(!layerViolation("reference/X.cpp", "contours/common/ContourChaining.h").empty());
        QVERIFY(!layerViolation("reference/X.cpp", "contours/consistent/phases/X.h").empty());
        QVERIFY(!layerViolation("reference/X.cpp", "visibility/ViewGraphBuilder.h").empty());
        QVERIFY(!layerViolation("contours/Methods.cpp", "reference/DenseGroundTruth.h").empty());
        QVERIFY(!layerViolation("surface/X.cpp", "reference/DenseGroundTruth.h").empty());
        QVERIFY(!layerViolation("core/Types.h", "widgets/SceneView3D.h").empty());
        QVERIFY(layerViolation("contours/consistent/phases/X.cpp",
                               "contours/consistent/numerics/Bisection.h")
                    .empty());
        QVERIFY(!layerViolation("contours/consistent/edits/X.cpp",
                                "contours/consistent/phases/SnapshotRoundTrip.h")
                     .empty());
        QVERIFY(!layerViolation("contours/consistent/mesh/X.cpp",
                                "contours/consistent/predicates/FoldTest.h")
                     .empty());
        QVERIFY(!layerViolation("contours/consistent/extensions/X.cpp",
                                "contours/consistent/ConsistentMethod.h")
                     .empty());
        QVERIFY(layerViolation("contours/consistent/ConsistentContourMethod.cpp",
                               "contours/consistent/extensions/ExtensionPhases.h")
                    .empty());
        QVERIFY(!layerViolation("contours/common/X.cpp", "contours/consistent/mesh/X.h").empty());
        QVERIFY(!layerViolation("contours/consistent/misc/X.cpp", "contours/consistent/mesh/X.h")
                     .empty());
        QVERIFY(std::regex_match(std::string("QString"), kQtOrVtk));
        QVERIFY(std::regex_match(std::string("QtCore/QObject"), kQtOrVtk));
        QVERIFY(std::regex_match(std::string("vtkPolyData.h"), kQtOrVtk));
        QVERIFY(!std::regex_match(std::string("queue"), kQtOrVtk));
    }

    void algorithmsIncludeOnlyLowerLayers() {
        const fs::path root = fs::path(CONTOUR_SOURCE_DIR) / "algorithms";
        QVERIFY(fs::is_directory(root));
        int files = 0;
        std::vector<Violation> all;
        for (const fs::directory_entry& e : fs::recursive_directory_iterator(root)) {
            const std::string ext = e.path().extension().string();
            if (!e.is_regular_file() || (ext != ".h" && ext != ".cpp"))
                continue;
            ++files;
            for (Violation& v : checkFile(root, e.path()))
                all.push_back(std::move(v));
        }
        // The tree is there (not an empty or wrong directory).
        QVERIFY2(files > 100, qPrintable(QString("only %1 files under algorithms/").arg(files)));
        QString report;
        for (const Violation& v : all)
            report += QString("\nalgorithms/%1:%2: %3 (%4)")
                          .arg(QString::fromStdString(v.file))
                          .arg(v.line)
                          .arg(QString::fromStdString(v.text))
                          .arg(QString::fromStdString(v.why));
        QVERIFY2(all.empty(), qPrintable(report));
    }
};

QTEST_GUILESS_MAIN(TestLayers)
#include "test_layers.moc"
