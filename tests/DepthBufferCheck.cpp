#include "DepthBufferCheck.h"

#include "VtkCameraConversion.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

namespace contour::testing {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::Matrix4d toEigen(vtkMatrix4x4* m) {
    Eigen::Matrix4d e;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            e(i, j) = m->GetElement(i, j);
    return e;
}

double ratio(double num, double den) {
    return den > 0.0 ? num / den : 1.0;
}

} // namespace

Eigen::Vector3d DepthImage::project(const Vec3& p) const {
    const Eigen::Vector4d h(p.x(), p.y(), p.z(), 1.0);
    const Eigen::Vector4d clip = worldToNdc * h;
    const Eigen::Vector4d view = worldToView * h;
    const double x = clip.x() / clip.w(), y = clip.y() / clip.w();
    return {0.5 * (x + 1.0) * width, 0.5 * (1.0 - y) * height, -view.z()};
}

double DepthImage::eyeDepthFromBuffer(double z) const {
    // OpenGL depth range [0, 1] from NDC z in [-1, 1], with VTK's projection
    // built on the clipping range (n, f) as distances from the camera.
    const double n = nearPlane, f = farPlane;
    if (orthographic)
        return n + z * (f - n); // z_ndc = (2d − (f + n)) / (f − n)
    const double zNdc = 2.0 * z - 1.0;
    return 2.0 * f * n / ((f + n) - zNdc * (f - n)); // z_ndc = (f+n)/(f−n) − 2fn/((f−n)d)
}

DepthImage renderDepth(const TriangleMesh& mesh, const Camera& camera, int scale) {
    if (scale < 1)
        throw std::invalid_argument("renderDepth: scale must be at least 1");
    DepthImage image;
    image.scale = scale;
    image.width = camera.viewport.width * scale;
    image.height = camera.viewport.height * scale;
    image.orthographic = camera.isOrthographic();

    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(mesh.vertexCount());
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        points->SetPoint(v, mesh.position(v).data());
    vtkNew<vtkCellArray> cells;
    for (const Triangle& t : mesh.triangles()) {
        const vtkIdType ids[3] = {t[0], t[1], t[2]};
        cells->InsertNextCell(3, ids);
    }
    vtkNew<vtkPolyData> poly;
    poly->SetPoints(points);
    poly->SetPolys(cells);

    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(poly);
    mapper->ScalarVisibilityOff();
    // No polygon offset: the buffer must hold the faces' own depths.
    mapper->SetResolveCoincidentTopologyToOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    vtkNew<vtkRenderer> renderer;
    renderer->AddActor(actor);
    renderer->SetBackground(0.0, 0.0, 0.0);
    // One offscreen window for every render: each window holds its own X
    // connection, and opening one per view can run the X server (shared
    // with the other suites under ctest -j2) out of connections.
    static const vtkSmartPointer<vtkRenderWindow> shared = [] {
        auto w = vtkSmartPointer<vtkRenderWindow>::New();
        w->SetOffScreenRendering(1);
        w->SetMultiSamples(0); // one depth sample per pixel, read back as is
        return w;
    }();
    vtkRenderWindow* window = shared;
    window->SetSize(image.width, image.height);
    window->AddRenderer(renderer);
    // Detached again however this function leaves.
    struct Detach {
        vtkRenderWindow* window;
        vtkRenderer* renderer;
        ~Detach() { window->RemoveRenderer(renderer); }
    } detach{window, renderer};

    vtkCamera* vtkCam = renderer->GetActiveCamera();
    applyCameraToVtk(camera, vtkCam);
    // A clipping range that holds the whole mesh with a margin. In
    // orthographic projection the scene may lie behind the analysis eye (its
    // rays run past the scene), so the VTK camera steps back along the view
    // direction; eye depths are then measured from there, for the buffer and
    // the points alike.
    const Vec3 forward = camera.forward();
    double dMin = kInf, dMax = -kInf;
    for (const Vec3& p : mesh.positions()) {
        const double d = (p - camera.eye).dot(forward);
        dMin = std::min(dMin, d);
        dMax = std::max(dMax, d);
    }
    if (!(dMax >= dMin))
        throw std::invalid_argument("renderDepth: empty mesh");
    const double range = std::max(dMax - dMin, 1e-9 * std::max(1.0, std::abs(dMax)));
    if (camera.isOrthographic()) {
        const double back = std::max(0.0, range - dMin);
        const Vec3 position = camera.eye - back * forward;
        const Vec3 focal = camera.target - back * forward;
        vtkCam->SetPosition(position.data());
        vtkCam->SetFocalPoint(focal.data());
        vtkCam->SetClippingRange(dMin + back - 0.05 * range, dMax + back + 0.05 * range);
    } else {
        if (dMin <= 0.0)
            throw std::invalid_argument("renderDepth: part of the mesh is behind the eye");
        vtkCam->SetClippingRange(0.5 * dMin, dMax + 0.05 * range);
    }

    window->Render();
    const int* size = window->GetSize();
    if (size[0] != image.width || size[1] != image.height)
        throw std::runtime_error("renderDepth: the offscreen window is " + std::to_string(size[0]) +
                                 "x" + std::to_string(size[1]) + ", not the " +
                                 std::to_string(image.width) + "x" + std::to_string(image.height) +
                                 " asked for");
    const double* clip = vtkCam->GetClippingRange(); // as used, after any clamping
    image.nearPlane = clip[0];
    image.farPlane = clip[1];
    const double aspect = static_cast<double>(image.width) / image.height;
    image.worldToNdc = toEigen(vtkCam->GetCompositeProjectionTransformMatrix(aspect, -1.0, 1.0));
    image.worldToView = toEigen(vtkCam->GetViewTransformMatrix());

    std::vector<float> z(static_cast<size_t>(image.width) * image.height);
    if (!window->GetZbufferData(0, 0, image.width - 1, image.height - 1, z.data()))
        throw std::runtime_error("renderDepth: could not read the depth buffer");
    image.eyeDepth.assign(z.size(), kInf);
    for (int y = 0; y < image.height; ++y) {
        const int row = image.height - 1 - y; // OpenGL rows run bottom-up
        for (int x = 0; x < image.width; ++x) {
            const double value = z[static_cast<size_t>(row) * image.width + x];
            if (value < 1.0)
                image.eyeDepth[static_cast<size_t>(y) * image.width + x] =
                    image.eyeDepthFromBuffer(value);
        }
    }

    const BoundingBox box = mesh.boundingBox();
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p((corner & 1) ? box.max.x() : box.min.x(),
                     (corner & 2) ? box.max.y() : box.min.y(),
                     (corner & 4) ? box.max.z() : box.min.z());
        const Vec2 ours = camera.project(p).pixel;
        const Eigen::Vector3d theirs = image.project(p);
        image.cameraMismatchPixels =
            std::max(image.cameraMismatchPixels, (ours - theirs.head<2>() / scale).norm());
    }
    return image;
}

DepthVerdict depthVerdict(const DepthImage& image, const Vec3& p, const DepthCheckOptions& options,
                          bool crease) {
    const Eigen::Vector3d q = image.project(p);
    const int x = static_cast<int>(std::floor(q.x())), y = static_cast<int>(std::floor(q.y()));
    if (x < 0 || y < 0 || x >= image.width || y >= image.height || q.z() < image.nearPlane ||
        q.z() > image.farPlane)
        return DepthVerdict::Outside;
    const int r = options.neighbourhood;
    double farthest = -kInf, farthestFinite = -kInf, nearest = kInf;
    for (int j = std::max(0, y - r); j <= std::min(image.height - 1, y + r); ++j)
        for (int i = std::max(0, x - r); i <= std::min(image.width - 1, x + r); ++i) {
            const double d = image.at(i, j);
            farthest = std::max(farthest, d);
            if (std::isfinite(d)) {
                farthestFinite = std::max(farthestFinite, d);
                nearest = std::min(nearest, d);
            }
        }
    double allowance = options.relativeTolerance * q.z();
    if (crease && nearest <= farthestFinite)
        allowance += farthestFinite - nearest;
    return q.z() <= farthest + allowance ? DepthVerdict::Visible : DepthVerdict::Occluded;
}

double DepthLengths::agreement() const {
    return ratio(visibleAgree + hiddenAgree, compared());
}
double DepthLengths::visibleAgreement() const {
    return ratio(visibleAgree, graphVisible());
}
double DepthLengths::hiddenAgreement() const {
    return ratio(hiddenAgree, graphHidden());
}
double DepthLengths::bufferVisibleDrawn() const {
    return ratio(visibleAgree, visibleAgree + hiddenButVisible);
}
double DepthLengths::bufferVisibleCovered() const {
    return ratio(visibleAgree + hiddenButVisibleCovered, visibleAgree + hiddenButVisible);
}

DepthLengths& DepthLengths::operator+=(const DepthLengths& o) {
    visibleAgree += o.visibleAgree;
    visibleButOccluded += o.visibleButOccluded;
    hiddenButVisible += o.hiddenButVisible;
    hiddenButVisibleCovered += o.hiddenButVisibleCovered;
    hiddenAgree += o.hiddenAgree;
    undecided += o.undecided;
    excludedOutside += o.excludedOutside;
    excludedNearNode += o.excludedNearNode;
    samples += o.samples;
    return *this;
}

DepthAgreement& DepthAgreement::operator+=(const DepthAgreement& o) {
    for (size_t t = 0; t < byType.size(); ++t)
        byType[t] += o.byType[t];
    all += o.all;
    byChain.clear();
    cameraMismatchPixels = std::max(cameraMismatchPixels, o.cameraMismatchPixels);
    return *this;
}

std::string DepthAgreement::summary() const {
    std::ostringstream out;
    out.setf(std::ios::fixed);
    auto line = [&](const char* name, const DepthLengths& l) {
        out.precision(1);
        out << name << ": visible " << l.graphVisible() << " px (occluded " << l.visibleButOccluded
            << "), hidden " << l.graphHidden() << " px (visible " << l.hiddenButVisible
            << ", of which next to a visible chain " << l.hiddenButVisibleCovered << "), undecided "
            << l.undecided << ", excluded near nodes " << l.excludedNearNode << " outside "
            << l.excludedOutside;
        out.precision(3);
        out << "; agreement " << 100.0 * l.agreement() << " %, visible "
            << 100.0 * l.visibleAgreement() << " %, hidden " << 100.0 * l.hiddenAgreement()
            << " %, buffer-visible drawn " << 100.0 * l.bufferVisibleDrawn() << " % (covered "
            << 100.0 * l.bufferVisibleCovered() << " %)\n";
    };
    const CurveType types[] = {CurveType::Contour, CurveType::Boundary,
                               CurveType::SurfaceIntersection};
    for (CurveType t : types) {
        const DepthLengths& l = byType[static_cast<size_t>(t)];
        if (l.samples > 0)
            line(toString(t), l);
    }
    line("all", all);
    return out.str();
}

std::string DepthAgreement::disagreements(const ViewGraph& graph, double minPixels) const {
    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(1);
    for (size_t c = 0; c < byChain.size() && c < graph.chains.size(); ++c) {
        const DepthLengths& l = byChain[c];
        const double wrong = l.visibleButOccluded + l.hiddenButVisible;
        if (wrong <= minPixels)
            continue;
        const ViewChain& chain = graph.chains[c];
        out << "chain " << c << " (" << toString(chain.type) << ", qi " << chain.qi << ", "
            << toString(chain.decidedBy) << (chain.conflict ? ", conflict" : "")
            << (chain.ambiguous ? ", ambiguous" : "") << "): compared " << l.compared()
            << " px, disagrees on " << wrong << " px\n";
    }
    return out.str();
}

namespace {

// Calls f(p, pixel, weight) at the samples of one chain: `step` rendered
// pixels apart, at the middle of equal parts of each segment, weighted by
// their length in viewport pixels.
template <class F>
void forEachSample(const ViewChain& chain, const DepthImage& image, double step, F&& f) {
    for (size_t s = 0; s + 1 < chain.points.size(); ++s) {
        const Vec3& a = chain.points[s];
        const Vec3& b = chain.points[s + 1];
        const double length = (image.project(b).head<2>() - image.project(a).head<2>()).norm();
        if (!std::isfinite(length))
            continue;
        const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
        const double weight = length / n / image.scale;
        for (int k = 0; k < n; ++k) {
            const Vec3 p = a + ((k + 0.5) / n) * (b - a);
            f(p, Vec2(image.project(p).head<2>()), weight);
        }
    }
}

// The samples of the graph-visible chains on a grid of cells `radius` wide,
// to ask whether a point lies within `radius` of one.
class SampleGrid {
public:
    explicit SampleGrid(double radius) : radius_(radius) {}
    void add(const Vec2& q) { cells_[key(cell(q.x()), cell(q.y()))].push_back(q); }
    bool near(const Vec2& q) const {
        const long long cx = cell(q.x()), cy = cell(q.y());
        for (long long i = cx - 1; i <= cx + 1; ++i)
            for (long long j = cy - 1; j <= cy + 1; ++j) {
                const auto it = cells_.find(key(i, j));
                if (it == cells_.end())
                    continue;
                for (const Vec2& o : it->second)
                    if ((o - q).squaredNorm() <= radius_ * radius_)
                        return true;
            }
        return false;
    }

private:
    long long cell(double x) const { return static_cast<long long>(std::floor(x / radius_)); }
    static long long key(long long i, long long j) { return i * 1000003LL + j; }
    double radius_;
    std::unordered_map<long long, std::vector<Vec2>> cells_;
};

} // namespace

DepthAgreement compareWithDepth(const ViewGraph& graph, const DepthImage& image,
                                const DepthCheckOptions& options) {
    DepthAgreement result;
    result.cameraMismatchPixels = image.cameraMismatchPixels;
    const double scale = image.scale;
    const double exclusion = options.nodeExclusion * scale; // rendered pixels
    std::vector<Vec2> nodes;
    nodes.reserve(graph.nodes.size());
    for (const ViewNode& node : graph.nodes)
        nodes.push_back(node.image * scale);
    auto nearNode = [&](const Vec2& q) {
        for (const Vec2& n : nodes)
            if ((q - n).squaredNorm() <= exclusion * exclusion)
                return true;
        return false;
    };
    SampleGrid drawn(std::max(options.coverRadius * scale, 1e-6));
    for (const ViewChain& chain : graph.chains)
        if (chain.qi == 0)
            forEachSample(chain, image, options.sampleStep,
                          [&](const Vec3&, const Vec2& q, double) { drawn.add(q); });

    result.byChain.resize(graph.chains.size());
    for (size_t c = 0; c < graph.chains.size(); ++c) {
        const ViewChain& chain = graph.chains[c];
        DepthLengths& lengths = result.byChain[c];
        const bool crease = chain.type == CurveType::SurfaceIntersection;
        forEachSample(
            chain, image, options.sampleStep, [&](const Vec3& p, const Vec2& q, double weight) {
                ++lengths.samples;
                if (nearNode(q)) {
                    lengths.excludedNearNode += weight;
                    return;
                }
                const DepthVerdict verdict = depthVerdict(image, p, options, crease);
                if (verdict == DepthVerdict::Outside) {
                    lengths.excludedOutside += weight;
                    return;
                }
                const bool bufferVisible = verdict == DepthVerdict::Visible;
                if (chain.qi < 0) {
                    lengths.undecided += weight;
                } else if (chain.qi == 0) {
                    (bufferVisible ? lengths.visibleAgree : lengths.visibleButOccluded) += weight;
                } else if (!bufferVisible) {
                    lengths.hiddenAgree += weight;
                } else {
                    lengths.hiddenButVisible += weight;
                    if (drawn.near(q))
                        lengths.hiddenButVisibleCovered += weight;
                }
            });
    }
    for (size_t c = 0; c < graph.chains.size(); ++c)
        result.byType[static_cast<size_t>(graph.chains[c].type)] += result.byChain[c];
    for (const DepthLengths& l : result.byType)
        result.all += l;
    return result;
}

void writeComparisonImage(const std::string& path, const ViewGraph& graph, const DepthImage& image,
                          const DepthCheckOptions& options) {
    const int w = image.width, h = image.height;
    std::vector<unsigned char> rgb(static_cast<size_t>(w) * h * 3, 0);
    double dMin = kInf, dMax = -kInf;
    for (double d : image.eyeDepth)
        if (std::isfinite(d)) {
            dMin = std::min(dMin, d);
            dMax = std::max(dMax, d);
        }
    for (size_t i = 0; i < image.eyeDepth.size(); ++i) {
        const double d = image.eyeDepth[i];
        const unsigned char g = std::isfinite(d)
                                    ? static_cast<unsigned char>(
                                          60.0 + 150.0 * (dMax - d) / std::max(dMax - dMin, 1e-12))
                                    : 0;
        rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = g;
    }
    auto put = [&](const Eigen::Vector3d& q, unsigned char r, unsigned char g, unsigned char b) {
        const int x = static_cast<int>(std::floor(q.x())), y = static_cast<int>(std::floor(q.y()));
        if (x < 0 || y < 0 || x >= w || y >= h)
            return;
        const size_t i = 3 * (static_cast<size_t>(y) * w + x);
        rgb[i] = r;
        rgb[i + 1] = g;
        rgb[i + 2] = b;
    };
    const double exclusion = options.nodeExclusion * image.scale;
    for (const ViewChain& chain : graph.chains)
        forEachSample(chain, image, options.sampleStep, [&](const Vec3& p, const Vec2& q2, double) {
            const Eigen::Vector3d q(q2.x(), q2.y(), 0.0);
            bool near = false;
            for (const ViewNode& node : graph.nodes)
                near = near || (q2 - node.image * image.scale).norm() <= exclusion;
            const DepthVerdict v =
                depthVerdict(image, p, options, chain.type == CurveType::SurfaceIntersection);
            if (near || v == DepthVerdict::Outside || chain.qi < 0)
                put(q, 255, 230, 0);
            else if (chain.qi == 0)
                v == DepthVerdict::Visible ? put(q, 0, 220, 0) : put(q, 255, 0, 0);
            else
                v == DepthVerdict::Occluded ? put(q, 40, 90, 255) : put(q, 255, 0, 255);
        });
    for (const ViewNode& node : graph.nodes) {
        const Vec2 c = node.image * image.scale;
        for (int d = -4; d <= 4; ++d) {
            put(Eigen::Vector3d(c.x() + d, c.y(), 0), 255, 255, 255);
            put(Eigen::Vector3d(c.x(), c.y() + d, 0), 255, 255, 255);
        }
    }
    std::ofstream out(path, std::ios::binary);
    out << "P6\n" << w << " " << h << "\n255\n";
    out.write(reinterpret_cast<const char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
}

DepthAgreement checkVisibilityWithDepth(const ViewGraph& graph, const TriangleMesh& mesh,
                                        const Camera& camera, const DepthCheckOptions& options) {
    return compareWithDepth(graph, renderDepth(mesh, camera, options.scale), options);
}

} // namespace contour::testing
