// Each layer of the 3D view (widgets/scene/) built alone from snapshots of a
// sample mesh run here with contour::Runner: what it draws (actor
// visibility, cells and points of its poly data, colours of cells), a
// frustum only when the cameras differ, the highlight of a face picked in an
// offscreen render of the mesh layer alone, and the motion copy's colours.
// Needs a display for the offscreen render: run under
// `xvfb-run -a -s "-screen 0 1600x1200x24"` (Mesa llvmpipe).
#include "MotionMesh.h"
#include "SceneColors.h"
#include "SurfaceFormat.h"
#include "VtkCameraConversion.h"
#include "contours/Methods.h"
#include "mesh/io/MeshReader.h"
#include "pipeline/FieldNames.h"
#include "pipeline/Runner.h"
#include "scene/CageLayer.h"
#include "scene/ConsistentOverlayLayer.h"
#include "scene/CurveLayer.h"
#include "scene/FrustumLayer.h"
#include "scene/HighlightLayer.h"
#include "scene/MeshColoringLayer.h"
#include "scene/MotionCopyLayer.h"
#include "scene/ViewGraphLayer.h"

#include <QApplication>
#include <QtTest>
#include <algorithm>
#include <set>
#include <vtkCellData.h>
#include <vtkCellPicker.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

using namespace contour;

namespace {

constexpr Viewport kViewport{400, 300};

std::shared_ptr<const PolygonMesh> sample(const char* name) {
    return std::make_shared<const PolygonMesh>(
        readMesh(std::string(CONTOUR_SOURCE_DIR) + "/samples/" + name));
}

Camera framingCamera(const PolygonMesh& mesh) {
    return Camera::framing(mesh.boundingBox(), Vec3(0.55, 0.45, 1.0), kViewport);
}

std::vector<Snapshot> runAll(const std::string& method, std::shared_ptr<const PolygonMesh> mesh) {
    const Method& m = *findMethod(method);
    Runner runner(m, makeInputSnapshot(mesh), framingCamera(*mesh),
                  ParameterSet::defaults(m.parameters));
    runner.runToEnd();
    return runner.snapshots();
}

// The integer face or vertex field `name`, or null.
const std::vector<int>* labels(const Snapshot& s, const char* name) {
    const Field* field = s.field(name);
    return field ? field->labels() : nullptr;
}

long long countOf(const std::vector<int>& values, int value) {
    return std::count(values.begin(), values.end(), value);
}

Index firstWith(const std::vector<int>& values, int value) {
    const auto it = std::find(values.begin(), values.end(), value);
    return it == values.end() ? kInvalidIndex : static_cast<Index>(it - values.begin());
}

// Lookup tables hold bytes: a colour comes back within half a step of 1/255.
bool sameColor(const std::array<double, 3>& rgb, const SceneColor& c,
               double tolerance = 0.5 / 255.0 + 1e-9) {
    return std::abs(rgb[0] - c.r) <= tolerance && std::abs(rgb[1] - c.g) <= tolerance &&
           std::abs(rgb[2] - c.b) <= tolerance;
}

std::array<unsigned char, 3> bytes(const SceneColor& c) {
    const auto byte = [](double v) {
        return static_cast<unsigned char>(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5);
    };
    return {byte(c.r), byte(c.g), byte(c.b)};
}

std::array<unsigned char, 3> cellColor(vtkPolyData* poly, vtkIdType cell) {
    auto* colors = vtkUnsignedCharArray::SafeDownCast(poly->GetCellData()->GetScalars());
    std::array<unsigned char, 3> rgb{};
    if (colors)
        colors->GetTypedTuple(cell, rgb.data());
    return rgb;
}

long long uniqueCageEdges(const PolygonMesh& cage) {
    std::set<std::pair<Index, Index>> edges;
    for (Index f = 0; f < cage.faceCount(); ++f) {
        const auto corners = cage.face(f);
        for (size_t i = 0; i < corners.size(); ++i) {
            const Index a = corners[i], b = corners[(i + 1) % corners.size()];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    }
    return static_cast<long long>(edges.size());
}

} // namespace

class TestSceneLayers : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void meshColoringByFacing();
    void meshColoringByFieldsAndLabels();
    void curvesGiveWayToTheViewGraph();
    void consistentOverlays();
    void viewGraphChainsAndNodes();
    void frustumOnlyWhenCamerasDiffer();
    void controlCage();
    void highlightOfAPickedFace();
    void motionCopyTakesItsFacesColours();

private:
    std::shared_ptr<const PolygonMesh> cage_;
    Snapshot meshFinal_;       // the mesh method at its end
    Snapshot consistentFinal_; // the consistent method at its end
};

void TestSceneLayers::initTestCase() {
    cage_ = sample("spot_control_mesh.obj");
    meshFinal_ = runAll("mesh", cage_).back();
    consistentFinal_ = runAll("consistent", cage_).back();
    QVERIFY(labels(meshFinal_, fields::kFacing));
    QVERIFY(consistentFinal_.mesh);
}

void TestSceneLayers::meshColoringByFacing() {
    MeshColoringLayer layer;
    QCOMPARE(layer.actorCount(), 2); // the mesh and the scalar bar
    QCOMPARE(layer.visibleActorCount(), 0);
    layer.update(meshFinal_);
    const TriangleMesh& mesh = *meshFinal_.mesh;
    QCOMPARE(layer.faceCount(), static_cast<long long>(mesh.faceCount()));
    QCOMPARE(layer.meshData()->GetNumberOfPoints(), static_cast<vtkIdType>(mesh.vertexCount()));
    QVERIFY(layer.showsFacing());
    QVERIFY(!layer.isScalarBarVisible());
    QCOMPARE(layer.visibleActorCount(), 1);
    const std::vector<int>& facing = *labels(meshFinal_, fields::kFacing);
    const Index front = firstWith(facing, 1), back = firstWith(facing, -1);
    QVERIFY(front != kInvalidIndex && back != kInvalidIndex);
    QVERIFY(sameColor(layer.faceColor(front), sceneColors::kFrontFace));
    QVERIFY(sameColor(layer.faceColor(back), sceneColors::kBackFace));
    // The drawn box is the mesh's.
    const std::array<double, 6> box = layer.visibleBounds();
    const BoundingBox expected = mesh.boundingBox();
    QVERIFY(std::abs(box[0] - expected.min.x()) < 1e-9);
    QVERIFY(std::abs(box[5] - expected.max.z()) < 1e-9);

    // Before the facing phase: one plain colour.
    layer.update(makeInputSnapshot(cage_));
    QVERIFY(!layer.showsFacing());
    QVERIFY(sameColor(layer.faceColor(0), sceneColors::kUnclassifiedFace));

    layer.setVisible(false);
    QCOMPARE(layer.visibleActorCount(), 0);
    layer.setVisible(true);
    layer.update(Snapshot{});
    QCOMPARE(layer.visibleActorCount(), 0);
    QVERIFY(!layer.meshData());
}

void TestSceneLayers::meshColoringByFieldsAndLabels() {
    MeshColoringLayer layer;
    layer.update(consistentFinal_);
    QVERIFY(!layer.scalarFields().empty());
    const std::string field = layer.scalarFields().front();
    layer.setColorField(field);
    QVERIFY(layer.showsScalarField());
    QCOMPARE(layer.displayedColorField(), field);
    QVERIFY(layer.isScalarBarVisible());
    QCOMPARE(layer.visibleActorCount(), 2);
    QVERIFY(!layer.scalarBarTitle().empty());

    // Where the field is most negative the face is on the blue side of the
    // map, where most positive on the red side.
    const Field* values = consistentFinal_.field(field);
    QVERIFY(values);
    const TriangleMesh& mesh = *consistentFinal_.mesh;
    std::vector<double> faceValues;
    const auto* doubles = std::get_if<std::vector<double>>(&values->values);
    QVERIFY(doubles);
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        if (values->location == FieldLocation::Face) {
            faceValues.push_back((*doubles)[static_cast<size_t>(f)]);
        } else {
            double mean = 0.0;
            for (const Index v : mesh.triangle(f))
                mean += (*doubles)[static_cast<size_t>(v)] / 3.0;
            faceValues.push_back(mean);
        }
    }
    const auto lowest = std::min_element(faceValues.begin(), faceValues.end());
    const auto highest = std::max_element(faceValues.begin(), faceValues.end());
    QVERIFY(*lowest < 0.0 && *highest > 0.0);
    const auto cool = layer.faceColor(static_cast<Index>(lowest - faceValues.begin()));
    const auto warm = layer.faceColor(static_cast<Index>(highest - faceValues.begin()));
    QVERIFY(cool[2] > cool[0]);
    QVERIFY(warm[0] > warm[2]);

    // By VBO: F and B in the facing colours.
    const std::vector<int>* vbo = labels(consistentFinal_, fields::kVbo);
    QVERIFY(vbo);
    layer.setColorField(fields::kVbo);
    QVERIFY(layer.showsFaceLabels());
    QVERIFY(!layer.isScalarBarVisible());
    QVERIFY(sameColor(layer.faceColor(firstWith(*vbo, 1)), sceneColors::kFrontFace));
    QVERIFY(sameColor(layer.faceColor(firstWith(*vbo, -1)), sceneColors::kBackFace));

    // A snapshot without the field falls back to facing, and keeps the choice.
    layer.update(meshFinal_);
    QCOMPARE(layer.displayedColorField(), std::string(fields::kFacing));
    QCOMPARE(layer.colorField(), std::string(fields::kVbo));
}

void TestSceneLayers::curvesGiveWayToTheViewGraph() {
    CurveLayer layer;
    layer.update(meshFinal_);
    QVERIFY(meshFinal_.curves && !meshFinal_.curves->empty());
    QCOMPARE(layer.curveCount(), static_cast<int>(meshFinal_.curves->size()));
    QCOMPARE(layer.curveData()->GetNumberOfLines(),
             static_cast<vtkIdType>(meshFinal_.curves->size()));
    QCOMPARE(layer.visibleActorCount(), meshFinal_.viewGraph ? 0 : 1);
    Snapshot withGraph = meshFinal_;
    withGraph.viewGraph = consistentFinal_.viewGraph;
    QVERIFY(withGraph.viewGraph);
    layer.update(withGraph);
    QCOMPARE(layer.visibleActorCount(), 0);
}

void TestSceneLayers::consistentOverlays() {
    ConsistentOverlayLayer layer;
    QCOMPARE(layer.actorCount(), kSceneOverlayCount);
    layer.update(meshFinal_);
    for (int i = 0; i < kSceneOverlayCount; ++i)
        QVERIFY(!layer.isAvailable(static_cast<SceneOverlay>(i)));
    QCOMPARE(layer.visibleActorCount(), 0);

    layer.update(consistentFinal_);
    const std::vector<int>* consistent = labels(consistentFinal_, fields::kConsistent);
    QVERIFY(consistent);
    QVERIFY(layer.isAvailable(SceneOverlay::InconsistentFaces));
    QCOMPARE(layer.elementCount(SceneOverlay::InconsistentFaces), countOf(*consistent, 0));
    QCOMPARE(static_cast<double>(layer.elementCount(SceneOverlay::InconsistentFaces)),
             consistentFinal_.counter("inconsistent faces"));
    if (const std::vector<int>* cusps = labels(consistentFinal_, fields::kCusp)) {
        QCOMPARE(layer.elementCount(SceneOverlay::Cusps), countOf(*cusps, 1));
        QCOMPARE(layer.data(SceneOverlay::Cusps)->GetNumberOfVerts(), countOf(*cusps, 1));
    }
    const std::vector<int>* label = labels(consistentFinal_, fields::kLabel);
    QVERIFY(label);
    QCOMPARE(layer.elementCount(SceneOverlay::ContourVertices), countOf(*label, 0));
    QVERIFY(layer.elementCount(SceneOverlay::ContourVertices) > 0);

    // Disabled: not drawn, still available; the tint is not drawn while moving.
    const int shown = layer.visibleActorCount();
    QVERIFY(shown > 0);
    layer.setEnabled(SceneOverlay::ContourVertices, false);
    QVERIFY(!layer.isShown(SceneOverlay::ContourVertices));
    QVERIFY(layer.isAvailable(SceneOverlay::ContourVertices));
    QCOMPARE(layer.visibleActorCount(), shown - 1);
    if (layer.isAvailable(SceneOverlay::RadialFaces)) {
        QVERIFY(layer.isShown(SceneOverlay::RadialFaces));
        layer.setMotionDrawing(true);
        QVERIFY(!layer.isShown(SceneOverlay::RadialFaces));
        layer.setMotionDrawing(false);
    }
    layer.setVisible(false);
    QCOMPARE(layer.visibleActorCount(), 0);
}

void TestSceneLayers::viewGraphChainsAndNodes() {
    ViewGraphLayer layer;
    layer.update(meshFinal_);
    QCOMPARE(layer.hasViewGraph(), static_cast<bool>(meshFinal_.viewGraph));
    layer.update(consistentFinal_);
    QVERIFY(layer.hasViewGraph());
    const ViewGraph& graph = *consistentFinal_.viewGraph;
    std::array<long long, 3> byState{};
    for (const ViewChain& chain : graph.chains)
        if (chain.points.size() >= 2)
            ++byState[static_cast<size_t>(chainState(chain))];
    QVERIFY(byState[0] > 0);
    QCOMPARE(layer.chainsShown(ChainState::Visible), byState[0]);
    QCOMPARE(layer.chainsShown(ChainState::Hidden), byState[1]);
    QCOMPARE(layer.chainsShown(ChainState::Simplified), 0LL); // off at first
    layer.setShowSimplifiedCurves(true);
    QCOMPARE(layer.chainsShown(ChainState::Simplified), byState[2]);
    layer.setShowHiddenCurves(false);
    QCOMPARE(layer.chainsShown(ChainState::Hidden), 0LL);

    // Visible chains by QI in the contour colour, black over a scalar field.
    vtkPolyData* visible = layer.chainData(ChainState::Visible);
    QCOMPARE(cellColor(visible, 0), bytes(sceneColors::kContour3D));
    layer.setOverScalarField(true);
    QCOMPARE(cellColor(visible, 0), bytes(sceneColors::kContourOverField));
    layer.setChainColoring(ChainColoring::ByChain);
    QVERIFY(cellColor(visible, 0) != bytes(sceneColors::kContourOverField));

    const long long nodes = layer.nodeData(false)->GetNumberOfVerts();
    QCOMPARE(layer.nodesShown(), nodes); // hidden ones are off with the hidden chains
    layer.setShowNodes(false);
    QCOMPARE(layer.nodesShown(), 0LL);

    layer.update(Snapshot{});
    QVERIFY(!layer.hasViewGraph());
    QCOMPARE(layer.visibleActorCount(), 0);
}

void TestSceneLayers::frustumOnlyWhenCamerasDiffer() {
    FrustumLayer layer;
    const Camera camera = framingCamera(*cage_);
    layer.update(meshFinal_);
    QCOMPARE(layer.visibleActorCount(), 0); // no analysis camera yet
    layer.setAnalysisCamera(camera);
    layer.setViewCamera(camera);
    QCOMPARE(layer.visibleActorCount(), 0);
    QVERIFY(!layer.isShownFor(camera));
    QVERIFY(layer.frustumData()->GetNumberOfLines() > 0);

    const Camera aside = Camera::framing(cage_->boundingBox(), Vec3(-1.0, 0.3, 0.2), kViewport);
    QVERIFY(layer.isShownFor(aside));
    layer.setViewCamera(aside);
    QCOMPARE(layer.visibleActorCount(), 1);
    // The pyramid's apex is the analysis camera's eye.
    const std::array<double, 6> box = layer.visibleBounds();
    QVERIFY(camera.eye.x() >= box[0] - 1e-9 && camera.eye.x() <= box[1] + 1e-9);
    layer.update(Snapshot{});
    QCOMPARE(layer.visibleActorCount(), 0);
}

void TestSceneLayers::controlCage() {
    CageLayer layer;
    layer.update(consistentFinal_);
    QVERIFY(consistentFinal_.cage);
    QCOMPARE(layer.visibleActorCount(), 0); // off by default
    QCOMPARE(layer.edgesShown(), 0LL);
    layer.setShown(true);
    QCOMPARE(layer.visibleActorCount(), 1);
    QCOMPARE(layer.edgesShown(), uniqueCageEdges(*consistentFinal_.cage));
    QCOMPARE(layer.cageData()->GetNumberOfPoints(),
             static_cast<vtkIdType>(consistentFinal_.cage->vertexCount()));
}

void TestSceneLayers::highlightOfAPickedFace() {
    // The mesh layer drawn alone offscreen through the analysis camera.
    MeshColoringLayer mesh;
    mesh.update(meshFinal_);
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetSize(kViewport.width, kViewport.height);
    window->AddRenderer(renderer);
    mesh.addToRenderers(renderer, renderer);
    const Camera camera = framingCamera(*cage_);
    applyCameraToVtk(camera, renderer->GetActiveCamera());
    renderer->ResetCameraClippingRange();
    window->Render();

    // The centre of the image is on the mesh, on a front face.
    const Vec3 centre = cage_->boundingBox().center();
    const ProjectedPoint p = camera.project(centre);
    vtkNew<vtkCellPicker> picker;
    picker->SetTolerance(0.0);
    picker->PickFromListOn();
    picker->AddPickList(mesh.meshActor());
    QVERIFY(picker->Pick(p.pixel.x(), kViewport.height - 1 - p.pixel.y(), 0.0, renderer));
    const auto face = static_cast<Index>(picker->GetCellId());
    QVERIFY(face >= 0 && face < meshFinal_.mesh->faceCount());
    QCOMPARE((*labels(meshFinal_, fields::kFacing))[static_cast<size_t>(face)], 1);

    // And it is drawn in the front colour (shaded: the hue of kFrontFace).
    vtkNew<vtkUnsignedCharArray> pixels;
    const int x = static_cast<int>(p.pixel.x()),
              y = kViewport.height - 1 - static_cast<int>(p.pixel.y());
    window->GetPixelData(x, y, x, y, 0, pixels);
    const QColor drawn(pixels->GetValue(0), pixels->GetValue(1), pixels->GetValue(2));
    const QColor front = sceneColors::kFrontFace.toQColor();
    QVERIFY2(std::abs(drawn.hsvHueF() - front.hsvHueF()) < 0.05,
             qPrintable(drawn.name() + QStringLiteral(" vs ") + front.name()));

    HighlightLayer highlight;
    highlight.update(meshFinal_);
    QCOMPARE(highlight.visibleActorCount(), 0);
    highlight.setSelection(Selection::face(face));
    vtkPolyData* data = highlight.highlightData();
    QVERIFY(data);
    QCOMPARE(data->GetNumberOfLines(), vtkIdType(1));
    QCOMPARE(data->GetNumberOfPoints(), vtkIdType(3));
    const Triangle& t = meshFinal_.mesh->triangle(face);
    for (int i = 0; i < 3; ++i) {
        double q[3];
        data->GetPoint(i, q);
        // VTK points are floats.
        QVERIFY((Vec3(q[0], q[1], q[2]) - meshFinal_.mesh->position(t[i])).norm() <
                1e-6 * cage_->boundingBox().diagonal());
    }
    QCOMPARE(highlight.visibleActorCount(), 1);
    // The selected face does not exist in a snapshot without a mesh.
    highlight.update(Snapshot{});
    QVERIFY(!highlight.highlightData());
    QCOMPARE(highlight.visibleActorCount(), 0);
}

void TestSceneLayers::motionCopyTakesItsFacesColours() {
    MeshColoringLayer coloring;
    coloring.update(meshFinal_);
    MotionCopyLayer copy;
    copy.update(meshFinal_);
    QVERIFY(!copy.isReady());
    const Index target = meshFinal_.mesh->faceCount() / 2;
    MotionMesh built = buildMotionMesh(*meshFinal_.mesh, target);
    QVERIFY(built.data);
    const std::vector<Index> sources = built.sourceFaces;
    copy.setCopy(std::move(built), meshFinal_.mesh);
    QVERIFY(copy.isReady());
    QVERIFY(copy.faceCount() <= meshFinal_.mesh->faceCount());
    QCOMPARE(copy.visibleActorCount(), 0); // only while moving
    copy.recolour(coloring, false);
    for (vtkIdType c : {vtkIdType(0), static_cast<vtkIdType>(sources.size() / 2)}) {
        const std::array<double, 3> rgb = coloring.faceColor(sources[static_cast<size_t>(c)]);
        const SceneColor expected{rgb[0], rgb[1], rgb[2]};
        QCOMPARE(cellColor(copy.copyData(), c), bytes(expected));
    }
    copy.setShown(true);
    QCOMPARE(copy.visibleActorCount(), 1);
    // A copy of another mesh is dropped.
    copy.update(consistentFinal_);
    QVERIFY(!copy.isReady());
    QCOMPARE(copy.visibleActorCount(), 0);
}

int main(int argc, char* argv[]) {
    setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    TestSceneLayers test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_scene_layers.moc"
