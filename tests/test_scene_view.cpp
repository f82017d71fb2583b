// Colouring the 3D view by a snapshot's scalar fields: the
// symmetric range and the diverging colour map, the list of colourable
// fields, a standalone SceneView3D on hand-made vertex and face fields (with
// NaN), and the real workbench window on the Catmull-Clark limit surface of
// the torus sample, coloured by radial curvature, Gaussian curvature and g,
// then by facing again. Needs a display: run under
// `xvfb-run -a -s "-screen 0 1600x1200x24"` (Mesa llvmpipe).
#include "DivergingColorMap.h"
#include "FieldLabels.h"
#include "MainWindow.h"
#include "MethodPanel.h"
#include "SceneColors.h"
#include "SceneView3D.h"
#include "SnapshotToVtk.h"
#include "SurfaceFormat.h"
#include "mesh/ProceduralShapes.h"
#include "pipeline/FieldNames.h"

#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QFileInfo>
#include <QSpinBox>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>
#include <vtkLookupTable.h>
#include <vtkSmartPointer.h>

using namespace contour;

namespace {

constexpr int kIdleTimeoutMs = 120000;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

QString grabPath(const QString& name) {
    return QDir::temp().filePath(QStringLiteral("test_scene_view_%1.png").arg(name));
}

double hueDistance(double a, double b) {
    const double d = std::fmod(std::abs(a - b), 360.0);
    return std::min(d, 360.0 - d);
}

// The two halves of the diverging map. Shading scales a colour, so hue and
// saturation tell them apart: the cool half is blue (hue ~215-232°), the warm
// half goes from salmon (~20°) to crimson (~348°); the light centre and the
// grey background and NaN are unsaturated.
bool isCool(const QColor& c) {
    return c.hsvSaturationF() > 0.2 && c.valueF() > 0.12 &&
           hueDistance(c.hsvHueF() * 360.0, 225.0) < 25.0;
}
bool isWarm(const QColor& c) {
    return c.hsvSaturationF() > 0.2 && c.valueF() > 0.12 &&
           hueDistance(c.hsvHueF() * 360.0, 5.0) < 30.0;
}
bool isNanGrey(const QColor& c) {
    const SceneColor& nan = sceneColors::kNanValue;
    // Unshaded-ish NaN grey: neutral, between the dark background and the
    // light centre of the map.
    return c.hsvSaturationF() < 0.05 && std::abs(c.redF() - nan.r) < 0.12;
}
bool matchesHue(const QColor& pixel, const SceneColor& reference) {
    const QColor ref = reference.toQColor();
    if (pixel.hsvSaturationF() < 0.6 * ref.hsvSaturationF() || pixel.valueF() < 0.15)
        return false;
    return hueDistance(pixel.hsvHueF() * 360.0, ref.hsvHueF() * 360.0) < 12.0;
}

struct Counts {
    long long total = 0, cool = 0, warm = 0, front = 0, back = 0, bright = 0, nan = 0;
    double coolFraction() const { return total ? double(cool) / double(total) : 0.0; }
    double warmFraction() const { return total ? double(warm) / double(total) : 0.0; }
    double frontFraction() const { return total ? double(front) / double(total) : 0.0; }
    // Share of the cool half among the coloured (signed) pixels.
    double coolShare() const { return cool + warm ? double(cool) / double(cool + warm) : 0.0; }
};

// Pixels of `image` inside `inside` (whole image when null) and outside
// `outside`.
Counts count(const QImage& image, const QRect& inside = {}, const QRect& outside = {}) {
    Counts n;
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    const QRect area = inside.isNull() ? rgb.rect() : inside.intersected(rgb.rect());
    for (int y = area.top(); y <= area.bottom(); ++y)
        for (int x = area.left(); x <= area.right(); ++x) {
            if (!outside.isNull() && outside.contains(x, y))
                continue;
            const QColor c = QColor::fromRgb(rgb.pixel(x, y));
            ++n.total;
            n.cool += isCool(c);
            n.warm += isWarm(c);
            n.front += matchesHue(c, sceneColors::kFrontFace);
            n.back += matchesHue(c, sceneColors::kBackFace);
            n.nan += isNanGrey(c);
            n.bright += c.red() >= 225 && c.green() >= 225 && c.blue() >= 225;
        }
    return n;
}

QString describe(const Counts& c) {
    return QStringLiteral("cool %1, warm %2 (cool share %3), front %4, back %5, bright %6 of %7")
        .arg(c.coolFraction(), 0, 'f', 3)
        .arg(c.warmFraction(), 0, 'f', 3)
        .arg(c.coolShare(), 0, 'f', 2)
        .arg(c.frontFraction(), 0, 'f', 3)
        .arg(double(c.back) / double(std::max(1LL, c.total)), 0, 'f', 3)
        .arg(c.bright)
        .arg(c.total);
}

QColor tableColor(vtkLookupTable* table, double value) {
    double rgb[3];
    table->GetColor(value, rgb);
    return QColor::fromRgbF(static_cast<float>(rgb[0]), static_cast<float>(rgb[1]),
                            static_cast<float>(rgb[2]));
}

} // namespace

class TestSceneView : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void rangeIsSymmetricAndIgnoresNaN();
    void rangeIsRobustToOutliers();
    void rangeOfDegenerateValues();
    void lookupTableIsDivergingWithGreyNaN();
    void listsScalarFields();
    void standaloneViewColoursVertexAndFaceFields();
    void torusCurvatureColours();
    void gShowsBothSignsFromTheSide();
    void backToFacing();
    void choiceSurvivesSnapshotChanges();
    void everySmoothSurfaceIsColourable_data();
    void everySmoothSurfaceIsColourable();

private:
    // Selects `field` through the window's selector, as a user does.
    void chooseInSelector(const QString& field);
    QImage grabScene(const QString& name);

    MainWindow* window_ = nullptr;
};

void TestSceneView::initTestCase() {
    window_ = new MainWindow;
    window_->setInteractive(false);
    window_->resize(1400, 850);
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_));
}

void TestSceneView::cleanupTestCase() {
    delete window_;
    window_ = nullptr;
}

void TestSceneView::chooseInSelector(const QString& field) {
    QComboBox* selector = window_->colorSelector();
    const int index = selector->findData(field);
    QVERIFY2(index >= 0, qPrintable(field + QStringLiteral(" is not listed")));
    selector->setCurrentIndex(index);
    QCOMPARE(window_->colorField(), field);
    QCOMPARE(selector->currentData().toString(), field);
}

QImage TestSceneView::grabScene(const QString& name) {
    const QImage image = window_->sceneView()->grabImage();
    image.save(grabPath(name));
    return image;
}

void TestSceneView::rangeIsSymmetricAndIgnoresNaN() {
    const std::vector<double> values{-3.0, kNaN, 1.0, 2.0, kNaN, -0.5};
    const SymmetricRange range = symmetricRange(values, 1.0);
    QCOMPARE(range.halfWidth, 3.0);
    QCOMPARE(range.low(), -range.high());
    QCOMPARE(range.nanCount, 2LL);
    QCOMPARE(range.finiteCount, 4LL);
    // Only |value| counts: mirrored values give the same range.
    std::vector<double> mirrored = values;
    for (double& v : mirrored)
        v = -v;
    QCOMPARE(symmetricRange(mirrored).halfWidth, symmetricRange(values).halfWidth);
    // Infinities are left out like NaN (but are not NaN).
    const SymmetricRange withInf = symmetricRange(
        std::vector<double>{1.0, std::numeric_limits<double>::infinity(), -2.0}, 1.0);
    QCOMPARE(withInf.halfWidth, 2.0);
    QCOMPARE(withInf.nanCount, 0LL);
}

void TestSceneView::rangeIsRobustToOutliers() {
    // 1000 values in [-1, 1] and one huge value near an "extraordinary vertex".
    std::vector<double> values;
    for (int i = 0; i < 1000; ++i)
        values.push_back(std::sin(0.37 * i));
    values.push_back(-1e6);
    const SymmetricRange range = symmetricRange(values);
    QVERIFY2(range.halfWidth > 0.9 && range.halfWidth <= 1.0,
             qPrintable(QString::number(range.halfWidth)));
    // The 98th percentile by nearest rank on 1..100 is 98.
    std::vector<double> ranks;
    for (int i = 1; i <= 100; ++i)
        ranks.push_back(i % 2 ? i : -i);
    QCOMPARE(symmetricRange(ranks).halfWidth, 98.0);
    QCOMPARE(symmetricRange(ranks, 0.5).halfWidth, 50.0);
}

void TestSceneView::rangeOfDegenerateValues() {
    QCOMPARE(symmetricRange(std::vector<double>{}).halfWidth, 1.0);
    QCOMPARE(symmetricRange(std::vector<double>{kNaN, kNaN}).halfWidth, 1.0);
    QCOMPARE(symmetricRange(std::vector<double>{0.0, 0.0}).halfWidth, 1.0);
    // Mostly zeros: the quantile is 0, the largest |value| is taken.
    std::vector<double> sparse(1000, 0.0);
    sparse[10] = -0.25;
    QCOMPARE(symmetricRange(sparse).halfWidth, 0.25);
}

void TestSceneView::lookupTableIsDivergingWithGreyNaN() {
    vtkSmartPointer<vtkLookupTable> table = makeDivergingLookupTable(2.0);
    double range[2];
    table->GetTableRange(range);
    QCOMPARE(range[0], -2.0);
    QCOMPARE(range[1], 2.0);
    QCOMPARE(table->GetNumberOfTableValues(), static_cast<vtkIdType>(kDivergingTableSize));
    const QColor low = tableColor(table, -2.0), high = tableColor(table, 2.0);
    const QColor centre = tableColor(table, 0.0), nan = tableColor(table, kNaN);
    QVERIFY(isCool(low));
    QVERIFY(isWarm(high));
    QVERIFY(isCool(tableColor(table, -1.0)));
    QVERIFY(isWarm(tableColor(table, 1.0)));
    // Beyond the range: the end colours.
    QCOMPARE(tableColor(table, -50.0), low);
    QCOMPARE(tableColor(table, 50.0), high);
    // The centre is light and neutral; NaN is a darker neutral grey.
    QVERIFY2(centre.hsvSaturationF() < 0.08 && centre.valueF() > 0.8, qPrintable(centre.name()));
    QVERIFY2(nan.hsvSaturationF() < 0.02 && nan.valueF() < 0.6, qPrintable(nan.name()));
    // Symmetric: ±x are equally far from the centre in lightness.
    for (double x : {0.5, 1.0, 1.5})
        QVERIFY(std::abs(tableColor(table, x).lightnessF() - tableColor(table, -x).lightnessF()) <
                0.12);
}

void TestSceneView::listsScalarFields() {
    Snapshot s =
        makeInputSnapshot(std::make_shared<const PolygonMesh>(makeProceduralShape("sphere", 12)));
    const Index vertices = s.mesh->vertexCount(), faces = s.mesh->faceCount();
    s.setField(fields::kRadialCurvature,
               {FieldLocation::Vertex, std::vector<double>(vertices, 1.0), ""});
    s.setField(fields::kG, {FieldLocation::Vertex, std::vector<double>(vertices, 1.0), ""});
    s.setField("a_face_field", {FieldLocation::Face, std::vector<double>(faces, 1.0), ""});
    s.setField("facing", {FieldLocation::Face, std::vector<int>(faces, 1), ""});
    s.setField("wrong_size", {FieldLocation::Vertex, std::vector<double>(3, 1.0), ""});
    s.setField("an_edge_field",
               {FieldLocation::Edge, std::vector<double>(s.mesh->edgeCount(), 1.0), ""});
    const std::vector<std::string> expected{fields::kG, fields::kRadialCurvature, "a_face_field"};
    QCOMPARE(scalarFieldNames(s), expected);
    QCOMPARE(QString::fromStdString(fieldDisplayName(fields::kRadialCurvature)),
             QStringLiteral("radial curvature κr"));
    QCOMPARE(QString::fromStdString(fieldDisplayName(fields::kGaussianCurvature)),
             QStringLiteral("Gaussian curvature K"));
    QCOMPARE(QString::fromStdString(fieldDisplayName(fields::kMeanCurvature)),
             QStringLiteral("mean curvature H"));
    QCOMPARE(fieldDisplayName("a_face_field"), std::string("a_face_field"));
}

void TestSceneView::standaloneViewColoursVertexAndFaceFields() {
    SceneView3D view;
    view.resize(480, 360);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    auto cage = std::make_shared<const PolygonMesh>(makeProceduralShape("sphere", 32));
    Snapshot s = makeInputSnapshot(cage);
    const TriangleMesh& mesh = *s.mesh;
    // Vertex field: x (both signs), NaN on the cap x > 0.8. Face field: the
    // centroid's y.
    std::vector<double> vertexValues(mesh.vertexCount());
    long long nans = 0;
    for (Index v = 0; v < mesh.vertexCount(); ++v) {
        const double x = mesh.position(v).x();
        vertexValues[v] = x > 0.8 ? kNaN : x;
        nans += x > 0.8;
    }
    std::vector<double> faceValues(mesh.faceCount());
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const Triangle& t = mesh.triangle(f);
        faceValues[f] =
            (mesh.position(t[0]).y() + mesh.position(t[1]).y() + mesh.position(t[2]).y()) / 3.0;
    }
    s.setField("x_with_nan", {FieldLocation::Vertex, vertexValues, "x, NaN for x > 0.8"});
    s.setField("face_y", {FieldLocation::Face, faceValues, "centroid y"});
    // Look along -z: x to the right, y up.
    view.setViewCamera(
        Camera::framing(cage->boundingBox(), Vec3(0.0, 0.0, 1.0), Viewport{480, 360}));
    QSignalSpy changed(&view, &SceneView3D::colorFieldsChanged);
    view.setSnapshot(s);
    QCOMPARE(changed.count(), 1);
    QCOMPARE(view.displayedColorField(), std::string(fields::kFacing));
    QVERIFY(!view.isScalarBarVisible());

    view.setColorField("x_with_nan");
    QVERIFY(view.showsScalarField());
    QVERIFY(!view.showsFacing());
    QVERIFY(view.isScalarBarVisible());
    QCOMPARE(view.scalarBarTitle(), std::string("x_with_nan"));
    QCOMPARE(view.scalarRange().nanCount, nans);
    // |x| reaches 1 on the left; the 98th percentile is a little less.
    QVERIFY2(view.scalarRange().halfWidth > 0.9 && view.scalarRange().halfWidth <= 1.0,
             qPrintable(QString::number(view.scalarRange().halfWidth)));
    QImage image = view.grabImage();
    image.save(grabPath(QStringLiteral("standalone_vertex_field")));
    const QRect bar = view.scalarBarRect();
    QVERIFY(!bar.isEmpty());
    // Left half negative (blue), right half positive (red) and the NaN cap grey.
    const int w = image.width(), h = image.height();
    const Counts left = count(image, QRect(0, 0, w / 2 - 20, h), bar);
    const Counts right = count(image, QRect(w / 2 + 20, 0, w / 2 - 20, h), bar);
    QVERIFY2(left.coolFraction() > 0.1 && left.warm == 0, qPrintable(describe(left)));
    QVERIFY2(right.warmFraction() > 0.05 && right.cool == 0, qPrintable(describe(right)));
    QVERIFY2(right.nan > 200, qPrintable(QStringLiteral("%1 NaN-grey pixels").arg(right.nan)));
    QVERIFY2(left.nan < right.nan / 10,
             qPrintable(QStringLiteral("%1 NaN-grey pixels on the left").arg(left.nan)));
    // The bar shows both halves of the map and its title.
    const Counts inBar = count(image, bar);
    QVERIFY2(inBar.cool > 100 && inBar.warm > 100 && inBar.bright > 20,
             qPrintable(describe(inBar)));

    view.setColorField("face_y");
    QCOMPARE(view.displayedColorField(), std::string("face_y"));
    image = view.grabImage();
    image.save(grabPath(QStringLiteral("standalone_face_field")));
    const Counts bottom = count(image, QRect(0, h / 2 + 20, w, h / 2 - 20), bar);
    const Counts top = count(image, QRect(0, 0, w, h / 2 - 20), bar);
    QVERIFY2(bottom.coolFraction() > 0.1 && bottom.warm == 0, qPrintable(describe(bottom)));
    QVERIFY2(top.warmFraction() > 0.1 && top.cool == 0, qPrintable(describe(top)));

    // A snapshot without the field: facing (here: not classified yet), no bar.
    view.setSnapshot(makeInputSnapshot(cage));
    QCOMPARE(view.displayedColorField(), std::string(fields::kFacing));
    QCOMPARE(view.colorField(), std::string("face_y"));
    QVERIFY(!view.isScalarBarVisible());
    QVERIFY(view.scalarBarRect().isEmpty());
    view.clearScene();
    QVERIFY(view.scalarFields().empty());
}

void TestSceneView::torusCurvatureColours() {
    QVERIFY(window_->openMesh(QStringLiteral(CONTOUR_SOURCE_DIR "/samples/torus.obj")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->methodName(), QStringLiteral("mesh"));
    // The cage alone has no scalar fields.
    QCOMPARE(window_->colorSelector()->count(), 1);
    QVERIFY(!window_->sceneView()->hasSmoothShading());
    auto* surface =
        qobject_cast<QComboBox*>(window_->methodPanel()->editor(QStringLiteral("surface")));
    QVERIFY(surface);
    surface->setCurrentText(QStringLiteral("catmull-clark"));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
    QVERIFY(window_->runner()->atEnd());
    const Snapshot smooth = window_->currentSnapshot();
    QVERIFY(smooth.field(fields::kRadialCurvature));
    // The limit surface is shaded with its exact normals.
    QVERIFY(window_->sceneView()->hasSmoothShading());

    // Facing first, then every scalar field of the limit surface, named.
    QComboBox* selector = window_->colorSelector();
    QStringList listed;
    for (int i = 0; i < selector->count(); ++i)
        listed << selector->itemData(i).toString();
    const QStringList expected{
        QString(fields::kFacing), QString(fields::kG), QString(fields::kRadialCurvature),
        QString(fields::kGaussianCurvature), QString(fields::kMeanCurvature)};
    QCOMPARE(listed, expected);
    QCOMPARE(selector->itemText(2), QStringLiteral("radial curvature κr"));
    QCOMPARE(selector->currentData().toString(), QString(fields::kFacing));

    SceneView3D* view = window_->sceneView();
    chooseInSelector(fields::kRadialCurvature);
    QVERIFY(view->isScalarBarVisible());
    QCOMPARE(QString::fromStdString(view->scalarBarTitle()), QStringLiteral("radial curvature κr"));
    QVERIFY(view->scalarRange().halfWidth > 0.0);
    QImage image = grabScene(QStringLiteral("torus_kr"));
    const QRect bar = view->scalarBarRect();
    Counts mesh = count(image, {}, bar);
    qInfo("κr: range ±%g, %s", view->scalarRange().halfWidth, qPrintable(describe(mesh)));
    // Seen from the analysis camera the convex outside has κr < 0 (blue) and
    // the saddle-shaped inside κr > 0 in places.
    QVERIFY2(mesh.coolFraction() > 0.05 && mesh.warmFraction() > 0.005, qPrintable(describe(mesh)));
    QVERIFY2(mesh.coolShare() > 0.5 && mesh.coolShare() < 0.99, qPrintable(describe(mesh)));
    // No facing colours under a scalar field.
    QVERIFY2(mesh.front < mesh.total / 1000, qPrintable(describe(mesh)));
    Counts inBar = count(image, bar);
    QVERIFY2(inBar.cool > 200 && inBar.warm > 200 && inBar.bright > 20,
             qPrintable(describe(inBar)));
    // The window, as a person sees it.
    window_->grab().save(grabPath(QStringLiteral("window_kr")));

    chooseInSelector(fields::kGaussianCurvature);
    QCOMPARE(QString::fromStdString(view->scalarBarTitle()),
             QStringLiteral("Gaussian curvature K"));
    image = grabScene(QStringLiteral("torus_gaussian"));
    mesh = count(image, {}, bar);
    qInfo("K: range ±%g, %s", view->scalarRange().halfWidth, qPrintable(describe(mesh)));
    // K = cos v / (r (R + r cos v)): > 0 on the outer half (red), < 0 on the
    // inner half (blue); the inner |K| is larger, so the outer half's red is
    // lighter but still warm. Both take a fair share of the image.
    QVERIFY2(mesh.coolShare() > 0.15 && mesh.coolShare() < 0.85, qPrintable(describe(mesh)));
    QVERIFY2(mesh.coolFraction() > 0.02 && mesh.warmFraction() > 0.02, qPrintable(describe(mesh)));
    const double K = view->scalarRange().halfWidth;
    // r = 0.4, R = 1: |K| reaches 1/(0.4 · 0.6) ≈ 4.2 inside; the 98th
    // percentile lies between the outer maximum (1.8) and that.
    QVERIFY2(K > 1.5 && K < 4.5, qPrintable(QString::number(K)));
}

void TestSceneView::gShowsBothSignsFromTheSide() {
    SceneView3D* view = window_->sceneView();
    chooseInSelector(fields::kG);
    QCOMPARE(QString::fromStdString(view->scalarBarTitle()),
             QString::fromStdString(fieldDisplayName(fields::kG)));
    // Visible points of a closed surface face the camera (g > 0); from the
    // side the analysis camera's back faces show too.
    view->orbit(70.0, 20.0);
    const QImage image = grabScene(QStringLiteral("torus_g_orbited"));
    const Counts mesh = count(image, {}, view->scalarBarRect());
    qInfo("g: range ±%g, %s", view->scalarRange().halfWidth, qPrintable(describe(mesh)));
    QVERIFY2(mesh.coolFraction() > 0.02 && mesh.warmFraction() > 0.02, qPrintable(describe(mesh)));
    window_->resetViewToAnalysisCamera();
}

void TestSceneView::backToFacing() {
    SceneView3D* view = window_->sceneView();
    chooseInSelector(fields::kFacing);
    QVERIFY(view->showsFacing());
    QVERIFY(!view->showsScalarField());
    QVERIFY(!view->isScalarBarVisible());
    view->orbit(70.0, 20.0);
    const QImage image = grabScene(QStringLiteral("torus_facing_orbited"));
    const Counts counts = count(image);
    qInfo("facing: %s", qPrintable(describe(counts)));
    QVERIFY2(counts.frontFraction() > 0.02 && counts.back > 0.02 * counts.total,
             qPrintable(describe(counts)));
    window_->resetViewToAnalysisCamera();
}

void TestSceneView::choiceSurvivesSnapshotChanges() {
    SceneView3D* view = window_->sceneView();
    chooseInSelector(fields::kRadialCurvature);
    const double before = view->scalarRange().halfWidth;
    // A parameter change re-runs from the input (which has no κr): the choice
    // comes back with the new snapshot.
    auto* level = qobject_cast<QSpinBox*>(
        window_->methodPanel()->editor(QStringLiteral("tessellation-level")));
    QVERIFY(level);
    level->setValue(level->value() + 2);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(window_->runner()->atEnd());
    QCOMPARE(window_->colorField(), QString(fields::kRadialCurvature));
    QCOMPARE(window_->colorSelector()->currentData().toString(), QString(fields::kRadialCurvature));
    QVERIFY(view->isScalarBarVisible());
    QVERIFY(std::abs(view->scalarRange().halfWidth - before) < 0.5 * before);

    // Stepping back keeps it while the field exists; the input has none:
    // facing, and the selector lists only facing.
    window_->stepBack();
    QCOMPARE(window_->colorField(), QString(fields::kRadialCurvature));
    window_->resetPhases();
    QCOMPARE(window_->colorField(), QString(fields::kFacing));
    QCOMPARE(window_->colorSelector()->count(), 1);
    QVERIFY(!view->isScalarBarVisible());
    window_->runToEnd();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->colorField(), QString(fields::kRadialCurvature));

    // Without a smooth surface the mesh method publishes no scalar field.
    auto* surface =
        qobject_cast<QComboBox*>(window_->methodPanel()->editor(QStringLiteral("surface")));
    surface->setCurrentText(QStringLiteral("none"));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->colorField(), QString(fields::kFacing));
    QVERIFY(view->showsFacing());
    QVERIFY(!view->isScalarBarVisible());
    // The interpolated method has g on the cage's vertices.
    QVERIFY(window_->setMethod(QStringLiteral("interpolated")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(window_->setColorField(QString(fields::kG)));
    QVERIFY(view->isScalarBarVisible());
    QVERIFY(!window_->setColorField(QString(fields::kRadialCurvature)));
    QCOMPARE(window_->colorField(), QString(fields::kFacing));
}

void TestSceneView::everySmoothSurfaceIsColourable_data() {
    QTest::addColumn<QString>("surface");
    QTest::addColumn<bool>("triangles");
    QTest::newRow("auto") << QStringLiteral("auto") << false;
    QTest::newRow("vertex-normal-patches") << QStringLiteral("vertex-normal-patches") << false;
    QTest::newRow("loop") << QStringLiteral("loop") << true;
}

void TestSceneView::everySmoothSurfaceIsColourable() {
    QFETCH(QString, surface);
    QFETCH(bool, triangles);
    PolygonMesh torus = makeProceduralShape("torus", 24);
    if (triangles) {
        // Loop needs a triangle cage: the torus's triangulation.
        PolygonMesh cage;
        cage.positions = torus.positions;
        const TriangleMesh split = torus.triangulate();
        for (Index f = 0; f < split.faceCount(); ++f) {
            const Triangle& t = split.triangle(f);
            cage.addFace({t[0], t[1], t[2]});
        }
        torus = std::move(cage);
    }
    QVERIFY(window_->setMethod(QStringLiteral("mesh")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(window_->setMesh(std::make_shared<const PolygonMesh>(std::move(torus)),
                             QStringLiteral("torus")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    auto* editor =
        qobject_cast<QComboBox*>(window_->methodPanel()->editor(QStringLiteral("surface")));
    QVERIFY(editor);
    editor->setCurrentText(surface);
    QCOMPARE(editor->currentText(), surface);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
    QVERIFY(window_->runner()->atEnd());
    QVERIFY(window_->setColorField(QString(fields::kGaussianCurvature)));
    const QImage image = grabScene(QStringLiteral("torus_gaussian_") + surface);
    const Counts mesh = count(image, {}, window_->sceneView()->scalarBarRect());
    qInfo("%s K: range ±%g, %s", qPrintable(surface), window_->sceneView()->scalarRange().halfWidth,
          qPrintable(describe(mesh)));
    QVERIFY2(mesh.coolShare() > 0.15 && mesh.coolShare() < 0.85, qPrintable(describe(mesh)));
    QVERIFY(window_->setColorField(QString(fields::kRadialCurvature)));
    QVERIFY(window_->sceneView()->isScalarBarVisible());
    editor->setCurrentText(QStringLiteral("none"));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
}

int main(int argc, char** argv) {
    setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    TestSceneView test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_scene_view.moc"
