// The workbench on the consistent method: the overlay data
// of SnapshotToVtk on hand-made fields (exact counts and geometry), then the
// real window stepping the method through every phase on the spot sample:
// after each step the stepper shows every counter of the snapshot, its time
// and notes, and the 3D view's overlays are there exactly when the snapshot
// has their fields, with as many elements as the fields say; after contour
// insertion the grabbed 3D view has magenta outline pixels in proportion to
// the inconsistent faces' projected edges (none with the overlay off), C
// vertex dots and cusp squares, and the VBO colouring. Phases are looked up
// by name: others are being added. Needs a display: run under
// `xvfb-run -a -s "-screen 0 1600x1200x24"` (Mesa llvmpipe).
#include "MainWindow.h"
#include "MethodPanel.h"
#include "PhaseStepper.h"
#include "SceneColors.h"
#include "SceneView3D.h"
#include "SnapshotToVtk.h"
#include "SurfaceFormat.h"
#include "mesh/ProceduralShapes.h"
#include "pipeline/FieldNames.h"

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QPainter>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <map>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

using namespace contour;

namespace {

constexpr int kIdleTimeoutMs = 600000;

QString grabPath(const QString& name) {
    return QDir::temp().filePath(QStringLiteral("test_consistent_view_%1.png").arg(name));
}

double hueDistance(double a, double b) {
    const double d = std::fmod(std::abs(a - b), 360.0);
    return std::min(d, 360.0 - d);
}

// Unlit overlay colours come out exactly (no lighting, no multisampling).
bool isMagenta(QRgb p) {
    return qRed(p) >= 200 && qBlue(p) >= 200 && qGreen(p) <= 40;
}
bool isWhiteDot(QRgb p) {
    return qRed(p) >= 250 && qGreen(p) >= 250 && qBlue(p) >= 250;
}
bool isCyanSquare(QRgb p) {
    return qRed(p) <= 40 && qGreen(p) >= 200 && qBlue(p) >= 240;
}
// Shaded faces: lighting scales a colour, so hue and saturation identify it.
bool matchesHue(QRgb rgb, const SceneColor& reference) {
    const QColor pixel = QColor::fromRgb(rgb);
    const QColor ref = reference.toQColor();
    if (pixel.hsvSaturationF() < 0.6 * ref.hsvSaturationF() || pixel.valueF() < 0.15)
        return false;
    return hueDistance(pixel.hsvHueF() * 360.0, ref.hsvHueF() * 360.0) < 12.0;
}

struct Pixels {
    long long total = 0, magenta = 0, white = 0, cyan = 0, front = 0, back = 0, undefined = 0;
    QString describe() const {
        return QStringLiteral("magenta %1, white %2, cyan %3, front %4, back %5, undefined-VBO "
                              "green %6 of %7")
            .arg(magenta)
            .arg(white)
            .arg(cyan)
            .arg(front)
            .arg(back)
            .arg(undefined)
            .arg(total);
    }
};

Pixels countPixels(const QImage& image) {
    Pixels n;
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) {
            const QRgb p = rgb.pixel(x, y);
            ++n.total;
            n.magenta += isMagenta(p);
            n.white += isWhiteDot(p);
            n.cyan += isCyanSquare(p);
            n.front += matchesHue(p, sceneColors::kFrontFace);
            n.back += matchesHue(p, sceneColors::kBackFace);
            n.undefined += matchesHue(p, sceneColors::kUndefinedVbo);
        }
    return n;
}

long long countEqual(const Field* field, int value) {
    if (!field || !field->labels())
        return 0;
    return std::count(field->labels()->begin(), field->labels()->end(), value);
}

// The point ids of cell `i` of `cells`.
std::vector<vtkIdType> cellIds(vtkCellArray* cells, vtkIdType i) {
    vtkNew<vtkIdList> ids;
    cells->GetCellAtId(i, ids);
    std::vector<vtkIdType> out;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
        out.push_back(ids->GetId(k));
    return out;
}

} // namespace

class TestConsistentView : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void overlayDataMatchesHandMadeFields();
    void overlaysNeedTheirFields();
    void stepsEveryPhaseOnSpot();
    void inconsistentOutlinesAfterContourInsertion();
    void contourVerticesAndCuspsAreMarked();
    void coloursByVbo();
    void radialOverlaysFromTheSide();

private:
    // After a step: the stepper, the overlays and their actions against the
    // snapshot.
    void checkPhase(int phase);

    MainWindow* window_ = nullptr;
};

void TestConsistentView::initTestCase() {
    window_ = new MainWindow;
    window_->setInteractive(false);
    window_->resize(1400, 850);
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_));
}

void TestConsistentView::cleanupTestCase() {
    delete window_;
    window_ = nullptr;
}

void TestConsistentView::overlayDataMatchesHandMadeFields() {
    Snapshot s =
        makeInputSnapshot(std::make_shared<const PolygonMesh>(makeProceduralShape("sphere", 12)));
    const TriangleMesh& mesh = *s.mesh;
    const Index nf = mesh.faceCount(), nv = mesh.vertexCount(), ne = mesh.edgeCount();
    std::vector<int> consistent(nf, 1), radial(nf, 0), standard(nf, 0), vbo(nf, 1);
    for (Index f = 0; f < nf; f += 7)
        consistent[f] = 0;
    for (Index f = 3; f < nf; f += 5)
        radial[f] = 1;
    for (Index f = 3; f < nf; f += 10)
        standard[f] = 1; // a subset of the radial faces
    std::vector<int> label(nv, 1), cusp(nv, 0);
    for (Index v = 0; v < nv; v += 4)
        label[v] = 0;
    for (Index v = 0; v < nv; v += 12)
        cusp[v] = 1;
    std::vector<int> radialEdge(ne, 0);
    for (Index e = 1; e < ne; e += 9)
        radialEdge[e] = 1;
    vbo[2] = 0;
    vbo[5] = -1;
    using L = FieldLocation;
    s.setField(fields::kConsistent, {L::Face, consistent, ""});
    s.setField(fields::kRadial, {L::Face, radial, ""});
    s.setField(fields::kStandardRadial, {L::Face, standard, ""});
    s.setField(fields::kVbo, {L::Face, vbo, ""});
    s.setField(fields::kLabel, {L::Vertex, label, ""});
    s.setField(fields::kCusp, {L::Vertex, cusp, ""});
    s.setField(fields::kRadialEdge, {L::Edge, radialEdge, ""});
    // Powell-Sabin: patch (1), macro-patch (2) and cut (3) edges, and cones.
    std::vector<int> patchEdge(ne, 0), cone(nv, 0);
    for (Index e = 2; e < ne; e += 5)
        patchEdge[e] = 1 + e % 3;
    for (Index v = 1; v < nv; v += 15)
        cone[v] = 1;
    s.setField(fields::kPatchEdge, {L::Edge, patchEdge, ""});
    s.setField(fields::kCone, {L::Vertex, cone, ""});

    // Outlines: one closed 4-id line per inconsistent face, on its corners.
    vtkSmartPointer<vtkPolyData> outlines = inconsistentFaceOutlines(s);
    QVERIFY(outlines);
    QCOMPARE(outlines->GetNumberOfLines(), countEqual(s.field(fields::kConsistent), 0));
    QCOMPARE(outlines->GetNumberOfPolys(), vtkIdType(0));
    vtkIdType line = 0;
    for (Index f = 0; f < nf; ++f) {
        if (consistent[f])
            continue;
        const std::vector<vtkIdType> ids = cellIds(outlines->GetLines(), line++);
        const Triangle& t = mesh.triangle(f);
        QCOMPARE(ids, (std::vector<vtkIdType>{t[0], t[1], t[2], t[0]}));
        double p[3];
        outlines->GetPoint(ids[1], p);
        QVERIFY((Vec3(p[0], p[1], p[2]) - mesh.position(t[1])).norm() == 0.0);
    }

    // Radial tint: every radial face, standard ones flagged.
    vtkSmartPointer<vtkPolyData> tint = radialFacesToPolyData(s);
    QVERIFY(tint);
    QCOMPARE(tint->GetNumberOfPolys(), countEqual(s.field(fields::kRadial), 1));
    auto* kinds = vtkIntArray::SafeDownCast(tint->GetCellData()->GetArray(kVtkStandardRadialArray));
    QVERIFY(kinds);
    long long flagged = 0;
    for (vtkIdType i = 0; i < kinds->GetNumberOfTuples(); ++i)
        flagged += kinds->GetValue(i);
    QCOMPARE(flagged, countEqual(s.field(fields::kStandardRadial), 1));

    // Markers: C vertices (label 0) and cusps, at the vertices' positions.
    vtkSmartPointer<vtkPolyData> contour = markedVerticesToPolyData(s, fields::kLabel, 0);
    vtkSmartPointer<vtkPolyData> cusps = markedVerticesToPolyData(s, fields::kCusp, 1);
    QVERIFY(contour && cusps);
    QCOMPARE(contour->GetNumberOfVerts(), countEqual(s.field(fields::kLabel), 0));
    QCOMPARE(cusps->GetNumberOfVerts(), countEqual(s.field(fields::kCusp), 1));
    QCOMPARE(cusps->GetNumberOfPoints(), cusps->GetNumberOfVerts());
    double p[3];
    cusps->GetPoint(1, p);
    QVERIFY((Vec3(p[0], p[1], p[2]) - mesh.position(12)).norm() == 0.0);

    // Radial edges: one line per tagged edge, between its end points.
    vtkSmartPointer<vtkPolyData> edges = markedEdgesToPolyData(s, fields::kRadialEdge);
    QVERIFY(edges);
    QCOMPARE(edges->GetNumberOfLines(), countEqual(s.field(fields::kRadialEdge), 1));
    const std::vector<vtkIdType> first = cellIds(edges->GetLines(), 0);
    const Index h = mesh.edgeHalfedge(1);
    QCOMPARE(first, (std::vector<vtkIdType>{mesh.from(h), mesh.to(h)}));

    // VBO is a colourable face label field.
    QCOMPARE(faceLabelFieldNames(s), std::vector<std::string>{fields::kVbo});
    vtkSmartPointer<vtkIntArray> labels = faceLabelsToCellArray(s, fields::kVbo);
    QVERIFY(labels);
    QCOMPARE(labels->GetNumberOfTuples(), vtkIdType(nf));
    QCOMPARE(labels->GetValue(2), 0);
    QCOMPARE(labels->GetValue(5), -1);

    // The same counts in a view, and as the overlays' element counts.
    SceneView3D view;
    view.resize(320, 240);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    QSignalSpy changed(&view, &SceneView3D::overlaysChanged);
    view.setSnapshot(s);
    QCOMPARE(changed.count(), 1);
    QCOMPARE(view.overlayElementCount(SceneOverlay::InconsistentFaces),
             countEqual(s.field(fields::kConsistent), 0));
    QCOMPARE(view.overlayElementCount(SceneOverlay::RadialFaces),
             countEqual(s.field(fields::kRadial), 1));
    QCOMPARE(view.overlayElementCount(SceneOverlay::ContourVertices),
             countEqual(s.field(fields::kLabel), 0));
    QCOMPARE(view.overlayElementCount(SceneOverlay::Cusps), countEqual(s.field(fields::kCusp), 1));
    QCOMPARE(view.overlayElementCount(SceneOverlay::RadialEdges),
             countEqual(s.field(fields::kRadialEdge), 1));
    QCOMPARE(view.overlayElementCount(SceneOverlay::PatchEdges),
             static_cast<long long>(std::count_if(patchEdge.begin(), patchEdge.end(),
                                                  [](int edgeLabel) { return edgeLabel != 0; })));
    QCOMPARE(view.overlayElementCount(SceneOverlay::Cones), countEqual(s.field(fields::kCone), 1));
    // The patch edges keep their label as cell scalars (one colour each).
    vtkPolyData* patchLines = view.overlayData(SceneOverlay::PatchEdges);
    QVERIFY(patchLines && patchLines->GetCellData()->GetScalars());
    QCOMPARE(patchLines->GetCellData()->GetScalars()->GetRange()[1], 3.0);
    for (int i = 0; i < kSceneOverlayCount; ++i)
        QVERIFY(view.isOverlayShown(static_cast<SceneOverlay>(i)));
    view.setOverlayEnabled(SceneOverlay::Cusps, false);
    QVERIFY(!view.isOverlayShown(SceneOverlay::Cusps));
    QVERIFY(view.isOverlayAvailable(SceneOverlay::Cusps));
    QVERIFY(!view.grabImage().isNull());
    // The input snapshot has none of these fields.
    view.setSnapshot(makeInputSnapshot(s.cage));
    QCOMPARE(changed.count(), 2);
    for (int i = 0; i < kSceneOverlayCount; ++i) {
        QVERIFY(!view.isOverlayAvailable(static_cast<SceneOverlay>(i)));
        QCOMPARE(view.overlayElementCount(static_cast<SceneOverlay>(i)), 0LL);
    }
    QVERIFY(!view.isOverlayEnabled(SceneOverlay::Cusps)); // the choice is kept
}

void TestConsistentView::overlaysNeedTheirFields() {
    Snapshot s =
        makeInputSnapshot(std::make_shared<const PolygonMesh>(makeProceduralShape("sphere", 8)));
    QVERIFY(!inconsistentFaceOutlines(s));
    QVERIFY(!radialFacesToPolyData(s));
    QVERIFY(!markedVerticesToPolyData(s, fields::kLabel, 0));
    QVERIFY(!markedEdgesToPolyData(s, fields::kRadialEdge));
    QVERIFY(faceLabelFieldNames(s).empty());
    using L = FieldLocation;
    // Wrong sizes, locations or types are not shown.
    s.setField(fields::kConsistent, {L::Face, std::vector<int>(3, 0), ""});
    s.setField(fields::kLabel, {L::Face, std::vector<int>(s.mesh->faceCount(), 0), ""});
    s.setField(fields::kRadialEdge, {L::Edge, std::vector<double>(s.mesh->edgeCount(), 1.0), ""});
    s.setField(fields::kVbo, {L::Vertex, std::vector<int>(s.mesh->vertexCount(), 1), ""});
    QVERIFY(!inconsistentFaceOutlines(s));
    QVERIFY(!markedVerticesToPolyData(s, fields::kLabel, 0));
    QVERIFY(!markedEdgesToPolyData(s, fields::kRadialEdge));
    QVERIFY(faceLabelFieldNames(s).empty());
    QVERIFY(!faceLabelsToCellArray(s, fields::kVbo));
    // Present but empty: available with no element.
    s.setField(fields::kConsistent, {L::Face, std::vector<int>(s.mesh->faceCount(), 1), ""});
    vtkSmartPointer<vtkPolyData> none = inconsistentFaceOutlines(s);
    QVERIFY(none);
    QCOMPARE(none->GetNumberOfLines(), vtkIdType(0));
}

void TestConsistentView::checkPhase(int phase) {
    const Runner* runner = window_->runner();
    QVERIFY(runner);
    QCOMPARE(runner->completedPhases(), phase + 1);
    const Snapshot& s = runner->snapshot(phase + 1);
    const PhaseStepper* stepper = window_->phaseStepper();
    const QString where = QString::fromStdString(s.phaseName);

    // Every counter of the snapshot, with its value, once.
    std::map<QString, double> shown;
    for (const auto& [name, value] : stepper->displayedCounters(phase, true))
        QVERIFY2(shown.emplace(name, value).second, qPrintable(where + ": twice: " + name));
    QCOMPARE(shown.size(), s.counters.size());
    for (const Counter& c : s.counters) {
        const QString name = QString::fromStdString(c.name);
        QVERIFY2(shown.count(name), qPrintable(where + ": missing " + name));
        QCOMPARE(shown.at(name), c.value);
    }
    // The changed ones are listed first, the others in the collapsed group.
    for (const auto& [name, value] : stepper->displayedCounters(phase))
        QVERIFY(std::isnan(runner->snapshot(phase).counter(name.toStdString(), std::nan(""))) ||
                runner->snapshot(phase).counter(name.toStdString()) != value);
    QVERIFY(!stepper->displayedTime(phase).isEmpty());
    QStringList notes;
    for (const std::string& note : s.notes)
        notes << QString::fromStdString(note);
    QCOMPARE(stepper->displayedNotes(phase), notes);

    // Overlays exactly where the fields are, with their element counts; the
    // counters the phase publishes agree with the fields.
    const SceneView3D* view = window_->sceneView();
    const struct {
        SceneOverlay overlay;
        const char* field;
        int value;
        const char* counter;
    } expected[] = {
        {SceneOverlay::InconsistentFaces, fields::kConsistent, 0, "inconsistent faces"},
        {SceneOverlay::RadialFaces, fields::kRadial, 1, "radial faces"},
        {SceneOverlay::ContourVertices, fields::kLabel, 0, "contour vertices"},
        {SceneOverlay::Cusps, fields::kCusp, 1, "cusps"},
        {SceneOverlay::RadialEdges, fields::kRadialEdge, 1, "radial edges"},
        {SceneOverlay::PatchEdges, fields::kPatchEdge, 1, ""},
        {SceneOverlay::Cones, fields::kCone, 1, ""},
    };
    for (const auto& e : expected) {
        const bool has = s.field(e.field) != nullptr;
        QVERIFY2(view->isOverlayAvailable(e.overlay) == has, qPrintable(where + ": " + e.field));
        QCOMPARE(window_->overlayAction(e.overlay)->isVisible(), has);
        if (!has)
            continue;
        long long n = countEqual(s.field(e.field), e.value);
        if (e.overlay == SceneOverlay::RadialFaces && s.field(fields::kStandardRadial)) {
            // Tinted: radial or standard radial.
            const auto& r = *s.field(fields::kRadial)->labels();
            const auto& st = *s.field(fields::kStandardRadial)->labels();
            n = 0;
            for (size_t f = 0; f < r.size(); ++f)
                n += r[f] != 0 || st[f] != 0;
        }
        QCOMPARE(view->overlayElementCount(e.overlay), n);
        if (const double counter = s.counter(e.counter, -1.0);
            counter >= 0.0 && e.overlay != SceneOverlay::RadialFaces)
            QVERIFY2(counter == static_cast<double>(n),
                     qPrintable(QStringLiteral("%1: counter %2 = %3, field %4")
                                    .arg(where, e.counter)
                                    .arg(counter)
                                    .arg(n)));
    }
    QCOMPARE(view->labelFields().empty(), s.field(fields::kVbo) == nullptr);
}

void TestConsistentView::stepsEveryPhaseOnSpot() {
    const QString spot = QStringLiteral(CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj");
    QVERIFY(window_->openMesh(spot));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(window_->setMethod(QStringLiteral("consistent")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
    // The form hands the method its defaults, tiny tolerances included.
    const Runner* runner = window_->runner();
    QVERIFY(runner);
    for (const ParameterSpec& spec : runner->method().parameters)
        if (spec.type == ParameterType::Double)
            QVERIFY2(runner->parameters().getDouble(spec.name) ==
                         std::get<double>(spec.defaultValue),
                     spec.name.c_str());
    // Typing a tiny value in scientific notation reaches the method.
    auto* tolerance = qobject_cast<QDoubleSpinBox*>(
        window_->methodPanel()->editor(QStringLiteral("chart-tolerance")));
    QVERIFY(tolerance);
    QCOMPARE(tolerance->text(), QStringLiteral("1e-09"));
    tolerance->selectAll();
    QTest::keyClicks(tolerance, QStringLiteral("3e-11"));
    QTest::keyClick(tolerance, Qt::Key_Return);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->runner()->parameters().getDouble("chart-tolerance"), 3e-11);
    tolerance->setValue(1e-9);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->runner()->parameters().getDouble("chart-tolerance"), 1e-9);
    window_->resetPhases();
    QCOMPARE(window_->completedPhases(), 0);
    for (int i = 0; i < kSceneOverlayCount; ++i) {
        QVERIFY(!window_->sceneView()->isOverlayAvailable(static_cast<SceneOverlay>(i)));
        QVERIFY(!window_->overlayAction(static_cast<SceneOverlay>(i))->isVisible());
    }
    const int phases = window_->runner()->phaseCount();
    QVERIFY(phases >= 3);
    for (int phase = 0; phase < phases; ++phase) {
        window_->stepPhase();
        QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
        QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
        checkPhase(phase);
        if (QTest::currentTestFailed())
            return;
        const Snapshot& s = window_->runner()->current();
        qInfo("%-22s %7.1f ms: faces %g, inconsistent %g, undefined VBOs %g, FB edges %g, C "
              "vertices %g, cusps %g, radial faces %g, radial edges %g, post-condition "
              "violations %lld",
              s.phaseName.c_str(), s.phaseSeconds * 1000.0, s.counter(counters::kFaces),
              s.counter(counters::kInconsistentFaces), s.counter(counters::kUndefinedVBOs),
              s.counter(counters::kFBEdgesLeft), s.counter(counters::kContourVertices),
              s.counter(counters::kCusps), s.counter(counters::kRadialFaces),
              s.counter(counters::kRadialEdges), s.invariantViolations());
        window_->sceneView()->grabImage().save(grabPath(
            QStringLiteral("phase%1_%2").arg(phase).arg(QString::fromStdString(s.phaseName))));
    }
    QVERIFY(window_->runner()->atEnd());
    // Back to contour insertion for the image checks.
    const int insertion = window_->runner()->method().phaseIndex("contour-insertion");
    QVERIFY(insertion >= 0);
    window_->runToPhase(insertion + 1);
    QCOMPARE(window_->currentSnapshot().phaseName, std::string("contour-insertion"));
    checkPhase(insertion);
    window_->resetViewToAnalysisCamera();
    QVERIFY(window_->sceneView()->viewMatchesAnalysisCamera());
}

void TestConsistentView::inconsistentOutlinesAfterContourInsertion() {
    SceneView3D* view = window_->sceneView();
    const Snapshot s = window_->currentSnapshot();
    QCOMPARE(s.phaseName, std::string("contour-insertion"));
    QAction* outlines = window_->overlayAction(SceneOverlay::InconsistentFaces);
    QVERIFY(outlines->isVisible());
    outlines->setChecked(true);
    QVERIFY(view->isOverlayShown(SceneOverlay::InconsistentFaces));
    // The cusp squares share the outlines' layer and would cover some.
    window_->overlayAction(SceneOverlay::Cusps)->setChecked(false);
    const QImage on = view->grabImage();
    on.save(grabPath(QStringLiteral("inconsistent_on")));
    const Pixels withOutlines = countPixels(on);

    // What the outlines should cover: the edges of the inconsistent faces,
    // projected with the view's camera and drawn with the outline's width
    // into an image of the same size (drawn over everything, so nothing
    // hides them; the sliver faces along the contour have nearly coincident
    // edges, which the drawing accounts for).
    const Camera camera = view->viewCamera();
    QCOMPARE(camera.viewport.width, on.width());
    QCOMPARE(camera.viewport.height, on.height());
    const std::vector<int>& consistent = *s.field(fields::kConsistent)->labels();
    const TriangleMesh& mesh = *s.mesh;
    QImage reference(on.size(), QImage::Format_RGB32);
    reference.fill(Qt::black);
    long long inconsistent = 0;
    {
        QPainter painter(&reference);
        painter.setPen(QPen(Qt::white, sceneColors::kInconsistentOutlineWidth, Qt::SolidLine,
                            Qt::FlatCap, Qt::BevelJoin));
        for (Index f = 0; f < mesh.faceCount(); ++f) {
            if (consistent[f])
                continue;
            ++inconsistent;
            // Segment by segment, as VTK draws wide lines (no joins).
            const Triangle& t = mesh.triangle(f);
            for (int i = 0; i < 3; ++i) {
                const Vec2 a = camera.project(mesh.position(t[i])).pixel;
                const Vec2 b = camera.project(mesh.position(t[(i + 1) % 3])).pixel;
                painter.drawLine(QPointF(a.x(), a.y()), QPointF(b.x(), b.y()));
            }
        }
    }
    long long expected = 0;
    for (int y = 0; y < reference.height(); ++y)
        for (int x = 0; x < reference.width(); ++x)
            expected += qRed(reference.pixel(x, y)) > 127;
    QCOMPARE(static_cast<double>(inconsistent), s.counter(counters::kInconsistentFaces));
    const double ratio = expected > 0 ? double(withOutlines.magenta) / double(expected) : 0.0;
    qInfo("contour-insertion: %lld inconsistent faces: %lld magenta pixels = %.3f%% of the "
          "%dx%d image (%.1f per face); the projected outlines cover %lld pixels: "
          "measured/expected %.2f",
          inconsistent, withOutlines.magenta,
          100.0 * double(withOutlines.magenta) / double(withOutlines.total), on.width(),
          on.height(), inconsistent ? double(withOutlines.magenta) / double(inconsistent) : 0.0,
          expected, ratio);
    if (inconsistent == 0) {
        QCOMPARE(withOutlines.magenta, 0LL);
    } else {
        QVERIFY2(
            ratio > 0.6 && ratio < 1.5,
            qPrintable(QStringLiteral("ratio %1: %2").arg(ratio).arg(withOutlines.describe())));
    }
    window_->overlayAction(SceneOverlay::Cusps)->setChecked(true);

    outlines->setChecked(false);
    QVERIFY(!view->isOverlayShown(SceneOverlay::InconsistentFaces));
    const QImage off = view->grabImage();
    off.save(grabPath(QStringLiteral("inconsistent_off")));
    const Pixels without = countPixels(off);
    qInfo("overlay off: %s", qPrintable(without.describe()));
    QCOMPARE(without.magenta, 0LL);
    outlines->setChecked(true);
}

void TestConsistentView::contourVerticesAndCuspsAreMarked() {
    SceneView3D* view = window_->sceneView();
    const Snapshot s = window_->currentSnapshot();
    const long long cVertices = countEqual(s.field(fields::kLabel), 0);
    const long long cusps = countEqual(s.field(fields::kCusp), 1);
    QVERIFY2(cVertices > 0, "contour insertion left no C vertex");
    QCOMPARE(view->overlayElementCount(SceneOverlay::ContourVertices), cVertices);
    QCOMPARE(view->overlayElementCount(SceneOverlay::Cusps), cusps);

    window_->overlayAction(SceneOverlay::ContourVertices)->setChecked(true);
    window_->overlayAction(SceneOverlay::Cusps)->setChecked(true);
    const QImage on = view->grabImage();
    on.save(grabPath(QStringLiteral("markers_on")));
    const Pixels marked = countPixels(on);
    window_->overlayAction(SceneOverlay::ContourVertices)->setChecked(false);
    window_->overlayAction(SceneOverlay::Cusps)->setChecked(false);
    const Pixels plain = countPixels(view->grabImage());
    qInfo("%lld C vertices, %lld cusps; markers on: %s; off: %s", cVertices, cusps,
          qPrintable(marked.describe()), qPrintable(plain.describe()));
    // Some C vertices are hidden behind the surface; the visible ones are
    // white dots, a few pixels each.
    QVERIFY2(marked.white > 20 && marked.white > 10 * std::max(1LL, plain.white),
             qPrintable(marked.describe()));
    if (cusps > 0)
        QVERIFY2(marked.cyan >= 20, qPrintable(marked.describe())); // drawn over everything
    QCOMPARE(plain.cyan, 0LL);
    window_->overlayAction(SceneOverlay::ContourVertices)->setChecked(true);
    window_->overlayAction(SceneOverlay::Cusps)->setChecked(true);
}

void TestConsistentView::coloursByVbo() {
    SceneView3D* view = window_->sceneView();
    QComboBox* selector = window_->colorSelector();
    const int index = selector->findData(QString(fields::kVbo));
    QVERIFY2(index >= 0, "VBO is not offered in the Colour-by selector");
    QCOMPARE(selector->itemText(index), QStringLiteral("Front/back (VBO)"));
    selector->setCurrentIndex(index);
    QCOMPARE(window_->colorField(), QString(fields::kVbo));
    QVERIFY(view->showsFaceLabels());
    QVERIFY(!view->showsFacing());
    QVERIFY(!view->isScalarBarVisible());
    QVERIFY(window_->colorLegend()->text().contains(QStringLiteral("undefined")));
    // The tint would mix with the face colours.
    window_->overlayAction(SceneOverlay::RadialFaces)->setChecked(false);

    // Before contour insertion some faces have an undefined VBO (green);
    // after it none should.
    const Runner* runner = window_->runner();
    const int insertion = runner->method().phaseIndex("contour-insertion");
    window_->runToPhase(insertion);
    QCOMPARE(window_->colorField(), QString(fields::kVbo));
    const Snapshot before = window_->currentSnapshot();
    const long long undefinedBefore = countEqual(before.field(fields::kVbo), 0);
    const QImage imageBefore = view->grabImage();
    imageBefore.save(grabPath(QStringLiteral("vbo_before_insertion")));
    const Pixels pixelsBefore = countPixels(imageBefore);
    window_->runToPhase(insertion + 1);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    const Snapshot after = window_->currentSnapshot();
    const long long undefinedAfter = countEqual(after.field(fields::kVbo), 0);
    const QImage imageAfter = view->grabImage();
    imageAfter.save(grabPath(QStringLiteral("vbo_after_insertion")));
    const Pixels pixelsAfter = countPixels(imageAfter);
    qInfo("VBO colouring: %s: %lld undefined, %s; %s: %lld undefined, %s", before.phaseName.c_str(),
          undefinedBefore, qPrintable(pixelsBefore.describe()), after.phaseName.c_str(),
          undefinedAfter, qPrintable(pixelsAfter.describe()));
    QVERIFY(pixelsAfter.front > 0.02 * pixelsAfter.total);
    if (undefinedBefore > 0)
        QVERIFY2(pixelsBefore.undefined > 0, qPrintable(pixelsBefore.describe()));
    if (undefinedAfter == 0)
        QVERIFY2(pixelsAfter.undefined < 0.0005 * pixelsAfter.total,
                 qPrintable(pixelsAfter.describe()));

    // Back to facing.
    selector->setCurrentIndex(selector->findData(QString(fields::kFacing)));
    QVERIFY(view->showsFacing());
    QVERIFY(window_->colorLegend()->text().contains(QStringLiteral("front")));
    window_->overlayAction(SceneOverlay::RadialFaces)->setChecked(true);
    window_->grab().save(grabPath(QStringLiteral("window")));
}

void TestConsistentView::radialOverlaysFromTheSide() {
    const Runner* runner = window_->runner();
    const int radial = runner->method().phaseIndex("radial-edge-insertion");
    QVERIFY2(radial >= 0, "the consistent method has no radial-edge-insertion phase");
    window_->runToPhase(radial + 1);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    const Snapshot s = window_->currentSnapshot();
    SceneView3D* view = window_->sceneView();
    const long long tinted = view->overlayElementCount(SceneOverlay::RadialFaces);
    const long long edges = view->overlayElementCount(SceneOverlay::RadialEdges);
    QCOMPARE(static_cast<double>(edges), s.counter(counters::kRadialEdges));
    QVERIFY(tinted >= s.counter(counters::kRadialFaces));
    QVERIFY2(tinted > 0, "radial edge insertion made no radial face on spot");
    // Radial triangles stand in the radial planes, so the analysis camera
    // sees them edge-on: look from the side.
    view->orbit(60.0, 25.0);
    QAction* tint = window_->overlayAction(SceneOverlay::RadialFaces);
    QAction* radialEdges = window_->overlayAction(SceneOverlay::RadialEdges);
    QVERIFY(tint->isVisible() && radialEdges->isVisible());
    tint->setChecked(true);
    radialEdges->setChecked(true);
    const QImage on = view->grabImage();
    on.save(grabPath(QStringLiteral("radial_on")));
    tint->setChecked(false);
    const QImage noTint = view->grabImage();
    radialEdges->setChecked(false);
    const QImage off = view->grabImage();
    off.save(grabPath(QStringLiteral("radial_off")));
    const auto differing = [](const QImage& a, const QImage& b) {
        const QImage x = a.convertToFormat(QImage::Format_RGB32);
        const QImage y = b.convertToFormat(QImage::Format_RGB32);
        long long n = 0;
        for (int j = 0; j < x.height(); ++j)
            for (int i = 0; i < x.width(); ++i) {
                const QRgb p = x.pixel(i, j), q = y.pixel(i, j);
                n += std::abs(qRed(p) - qRed(q)) + std::abs(qGreen(p) - qGreen(q)) +
                         std::abs(qBlue(p) - qBlue(q)) >
                     60;
            }
        return n;
    };
    const long long byTint = differing(on, noTint), byEdges = differing(noTint, off);
    qInfo("%s, orbited: %lld tinted faces change %lld pixels, %lld radial edges %lld pixels",
          s.phaseName.c_str(), tinted, byTint, edges, byEdges);
    QVERIFY2(byTint > 100, qPrintable(QString::number(byTint)));
    if (edges > 0)
        QVERIFY2(byEdges > 100, qPrintable(QString::number(byEdges)));
    tint->setChecked(true);
    radialEdges->setChecked(true);
    window_->resetViewToAnalysisCamera();
}

int main(int argc, char** argv) {
    setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    TestConsistentView test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_consistent_view.moc"
