#include "surface/SubdivisionSurface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <stdexcept>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace contour {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

namespace {

// A point for OpenSubdiv's primvar refiner and stencil tables.
struct OsdPoint {
    double x = 0.0, y = 0.0, z = 0.0;
    void Clear(void* = nullptr) { x = y = z = 0.0; }
    void AddWithWeight(const OsdPoint& p, double w) {
        x += w * p.x;
        y += w * p.y;
        z += w * p.z;
    }
};

// The most control points of any patch: 20 for a Gregory basis patch (16
// B-spline, 12 Loop box-spline, 18 triangular Gregory).
constexpr int kMaxPatchPoints = 20;

// The cage in OpenSubdiv's form; the arrays must outlive the refiner's
// construction only.
struct CageDescriptor {
    std::vector<int> vertsPerFace;
    std::vector<Far::Index> faceVertices;
    std::vector<Far::Index> creaseVertices;
    std::vector<float> creaseWeights;
    std::vector<Far::Index> cornerVertices;
    std::vector<float> cornerWeights;
    Far::TopologyDescriptor descriptor;

    CageDescriptor(const PolygonMesh& cage, bool useCreases) {
        const Index n = cage.vertexCount();
        vertsPerFace.reserve(static_cast<size_t>(cage.faceCount()));
        faceVertices.reserve(cage.indices.size());
        for (Index f = 0; f < cage.faceCount(); ++f) {
            const auto corners = cage.face(f);
            if (corners.size() < 3)
                throw std::invalid_argument("subdivision surface: face " + std::to_string(f) +
                                            " has " + std::to_string(corners.size()) +
                                            " corners (at least 3 are needed)");
            for (const Index v : corners) {
                if (v < 0 || v >= n)
                    throw std::invalid_argument("subdivision surface: face " + std::to_string(f) +
                                                " uses vertex " + std::to_string(v) +
                                                ", which does not exist");
                faceVertices.push_back(v);
            }
            vertsPerFace.push_back(static_cast<int>(corners.size()));
        }
        const auto checkSharpness = [](double s, const std::string& what) {
            if (!std::isfinite(s) || s < 0.0)
                throw std::invalid_argument("subdivision surface: " + what + " has sharpness " +
                                            std::to_string(s) + " (must be finite and >= 0)");
        };
        if (useCreases) {
            for (const auto& c : cage.creases) {
                const std::string what =
                    "crease (" + std::to_string(c.a) + ", " + std::to_string(c.b) + ")";
                if (c.a < 0 || c.a >= n || c.b < 0 || c.b >= n)
                    throw std::invalid_argument("subdivision surface: " + what +
                                                " names a vertex that does not exist");
                checkSharpness(c.sharpness, what);
                creaseVertices.push_back(c.a);
                creaseVertices.push_back(c.b);
                creaseWeights.push_back(static_cast<float>(c.sharpness));
            }
            for (const auto& [v, sharpness] : cage.cornerSharpness) {
                const std::string what = "corner " + std::to_string(v);
                if (v < 0 || v >= n)
                    throw std::invalid_argument("subdivision surface: " + what +
                                                " is not a vertex");
                checkSharpness(sharpness, what);
                cornerVertices.push_back(v);
                cornerWeights.push_back(static_cast<float>(sharpness));
            }
        }
        descriptor.numVertices = n;
        descriptor.numFaces = cage.faceCount();
        descriptor.numVertsPerFace = vertsPerFace.data();
        descriptor.vertIndicesPerFace = faceVertices.data();
        descriptor.numCreases = static_cast<int>(creaseWeights.size());
        descriptor.creaseVertexIndexPairs = creaseVertices.data();
        descriptor.creaseWeights = creaseWeights.data();
        descriptor.numCorners = static_cast<int>(cornerWeights.size());
        descriptor.cornerVertexIndices = cornerVertices.data();
        descriptor.cornerWeights = cornerWeights.data();
    }
};

using RefinerFactory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;

std::unique_ptr<Far::TopologyRefiner> makeRefiner(const CageDescriptor& cage, SurfaceKind kind,
                                                  const SubdivisionOptions& options) {
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(options.boundary == SubdivisionOptions::Boundary::EdgeAndCorner
                                        ? Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                        : Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    sdc.SetCreasingMethod(Sdc::Options::CREASE_UNIFORM);
    const Sdc::SchemeType scheme =
        kind == SurfaceKind::Loop ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK;
    std::unique_ptr<Far::TopologyRefiner> refiner(
        RefinerFactory::Create(cage.descriptor, RefinerFactory::Options(scheme, sdc)));
    if (!refiner)
        throw std::invalid_argument(std::string("subdivision surface: OpenSubdiv rejected the "
                                                "cage's topology for ") +
                                    toString(kind) + " subdivision");
    return refiner;
}

} // namespace

struct SubdivisionSurface::Impl {
    std::unique_ptr<Far::TopologyRefiner> refiner; // adaptively refined
    std::unique_ptr<Far::PatchTable> patchTable;
    std::unique_ptr<Far::PatchMap> patchMap;
    std::vector<double> points; // xyz of refined vertices, then local points
    bool triangular = false;    // Loop: triangular patches
    int endCaps = 0;
};

SubdivisionSurface::SubdivisionSurface(SurfaceKind kind, const SubdivisionOptions& options)
    : kind_(kind), options_(options), impl_(std::make_unique<Impl>()) {}

SubdivisionSurface::~SubdivisionSurface() = default;

std::unique_ptr<SubdivisionSurface> SubdivisionSurface::create(const PolygonMesh& cage,
                                                               SurfaceKind kind,
                                                               const SubdivisionOptions& options) {
    if (kind != SurfaceKind::CatmullClark && kind != SurfaceKind::Loop)
        throw std::invalid_argument(std::string("subdivision surface: ") + toString(kind) +
                                    " is not a subdivision scheme (use catmull-clark or loop)");
    if (options.isolationLevel < 1 || options.isolationLevel > 10)
        throw std::invalid_argument("subdivision surface: isolation level " +
                                    std::to_string(options.isolationLevel) +
                                    " is out of range (1 to 10)");
    if (cage.faceCount() == 0)
        throw std::invalid_argument("subdivision surface: the cage has no faces");
    if (kind == SurfaceKind::Loop)
        for (Index f = 0; f < cage.faceCount(); ++f)
            if (cage.face(f).size() != 3)
                throw std::invalid_argument(
                    "Loop subdivision needs a cage made only of triangles, but face " +
                    std::to_string(f) + " has " + std::to_string(cage.face(f).size()) +
                    " corners (use Catmull-Clark, or triangulate the cage)");

    std::unique_ptr<SubdivisionSurface> surface(new SubdivisionSurface(kind, options));
    Impl& impl = *surface->impl_;
    impl.triangular = kind == SurfaceKind::Loop;
    const CageDescriptor descriptor(cage, options.creases);

    // Patches. Double precision all the way: stencils and basis weights.
    Far::PatchTableFactory::Options patchOptions(static_cast<unsigned>(options.isolationLevel));
    patchOptions.SetPatchPrecision<double>();
    patchOptions.SetEndCapType(options.endCap == SubdivisionOptions::EndCap::GregoryBasis
                                   ? Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS
                                   : Far::PatchTableFactory::Options::ENDCAP_BSPLINE_BASIS);
    // Infinitely sharp creases and corners become exact regular patches
    // instead of being isolated down to end caps.
    patchOptions.useInfSharpPatch = true;
    patchOptions.generateVaryingTables = false;
    patchOptions.generateVaryingLocalPoints = false;
    impl.refiner = makeRefiner(descriptor, kind, options);
    impl.refiner->RefineAdaptive(patchOptions.GetRefineAdaptiveOptions());
    impl.patchTable.reset(Far::PatchTableFactory::Create(*impl.refiner, patchOptions));
    if (!impl.patchTable)
        throw std::runtime_error("subdivision surface: OpenSubdiv built no patch table");
    impl.patchMap = std::make_unique<Far::PatchMap>(*impl.patchTable);
    for (int a = 0; a < impl.patchTable->GetNumPatchArrays(); ++a)
        for (int i = 0; i < impl.patchTable->GetNumPatches(a); ++i)
            if (!impl.patchTable->GetPatchParam(a, i).IsRegular())
                ++impl.endCaps;

    // Control points: the cage, every refined level, then the local points of
    // the end caps (computed from all of those).
    const int refinedCount = impl.refiner->GetNumVerticesTotal();
    const int localCount = impl.patchTable->GetNumLocalPoints();
    std::vector<OsdPoint> points(static_cast<size_t>(refinedCount + localCount));
    for (Index v = 0; v < cage.vertexCount(); ++v)
        points[static_cast<size_t>(v)] = {cage.positions[v].x(), cage.positions[v].y(),
                                          cage.positions[v].z()};
    {
        const Far::PrimvarRefinerReal<double> primvar(*impl.refiner);
        OsdPoint* src = points.data();
        for (int level = 1; level <= impl.refiner->GetMaxLevel(); ++level) {
            OsdPoint* dst = src + impl.refiner->GetLevel(level - 1).GetNumVertices();
            primvar.Interpolate(level, src, dst);
            src = dst;
        }
    }
    if (localCount > 0) {
        const auto* stencils = impl.patchTable->GetLocalPointStencilTable<double>();
        if (!stencils)
            throw std::logic_error("subdivision surface: local points without stencils");
        stencils->UpdateValues(points.data(), points.data() + refinedCount);
    }
    impl.points.resize(points.size() * 3);
    for (size_t i = 0; i < points.size(); ++i) {
        impl.points[3 * i] = points[i].x;
        impl.points[3 * i + 1] = points[i].y;
        impl.points[3 * i + 2] = points[i].z;
    }

    // The domain and its charts in ptex space.
    const Far::PtexIndices ptex(*impl.refiner);
    PolygonMesh& domain = surface->domain_;
    std::vector<PtexChart>& charts = surface->charts_;
    if (kind == SurfaceKind::Loop) {
        domain.positions = cage.positions;
        domain.indices = cage.indices;
        domain.offsets = cage.offsets;
        charts.resize(static_cast<size_t>(cage.faceCount()));
        for (Index f = 0; f < cage.faceCount(); ++f)
            charts[static_cast<size_t>(f)].ptexFace = ptex.GetFaceId(f);
    } else {
        // The level-1 topology: the adaptive refiner only refines where it
        // must, so a second refiner subdivides the whole cage once.
        const std::unique_ptr<Far::TopologyRefiner> once = makeRefiner(descriptor, kind, options);
        once->RefineUniform(Far::TopologyRefiner::UniformOptions(1));
        const Far::TopologyLevel& base = once->GetLevel(0);
        const Far::TopologyLevel& level1 = once->GetLevel(1);
        std::vector<OsdPoint> refined(static_cast<size_t>(level1.GetNumVertices()));
        {
            const OsdPoint* src = points.data();
            OsdPoint* dst = refined.data();
            Far::PrimvarRefinerReal<double>(*once).Interpolate(1, src, dst);
        }
        domain.positions.reserve(refined.size());
        for (const OsdPoint& p : refined)
            domain.positions.emplace_back(p.x, p.y, p.z);
        charts.resize(static_cast<size_t>(level1.GetNumFaces()));
        std::vector<std::array<Index, 4>> faces(charts.size());
        for (Index f = 0; f < base.GetNumFaces(); ++f) {
            const auto corners = base.GetFaceVertices(f);
            const auto edges = base.GetFaceEdges(f);
            const auto children = base.GetFaceChildFaces(f);
            const int n = corners.size();
            const bool quad = n == 4;
            const Index faceChild = base.GetFaceChildVertex(f);
            for (int i = 0; i < children.size(); ++i) {
                const Index child = children[i];
                // Ptex coordinates of a level-1 vertex of this base face: on a
                // quad, its corners, edge midpoints and centre; on an n-gon,
                // the corners of sub-face i: the corner at (0,0), the
                // midpoint of the edge after it at (1,0), the centre at
                // (1,1) and the midpoint of the edge before it at (0,1).
                const auto ptexCoordinates = [&](Index w) -> Vec2 {
                    if (w == faceChild)
                        return quad ? Vec2(0.5, 0.5) : Vec2(1.0, 1.0);
                    for (int k = 0; k < n; ++k) {
                        if (w == base.GetVertexChildVertex(corners[k])) {
                            if (quad)
                                return cornerCoordinates(true, k);
                            if (k == i)
                                return Vec2(0.0, 0.0);
                        }
                        if (w == base.GetEdgeChildVertex(edges[k])) {
                            if (quad)
                                return 0.5 * (cornerCoordinates(true, k) +
                                              cornerCoordinates(true, (k + 1) % 4));
                            if (k == i)
                                return Vec2(1.0, 0.0);
                            if (k == (i + n - 1) % n)
                                return Vec2(0.0, 1.0);
                        }
                    }
                    throw std::logic_error("subdivision surface: level-1 vertex " +
                                           std::to_string(w) + " is not on base face " +
                                           std::to_string(f));
                };
                const auto childCorners = level1.GetFaceVertices(child);
                if (childCorners.size() != 4)
                    throw std::logic_error("subdivision surface: level-1 face is not a quad");
                std::array<Vec2, 4> q;
                for (int k = 0; k < 4; ++k)
                    q[static_cast<size_t>(k)] = ptexCoordinates(childCorners[k]);
                // (s, t) = q0 + u (q1 - q0) + v (q3 - q0); q2 must complete
                // the parallelogram.
                const Vec2 eu = q[1] - q[0], ev = q[3] - q[0];
                if ((q[0] + eu + ev - q[2]).norm() > 1e-12)
                    throw std::logic_error("subdivision surface: level-1 face " +
                                           std::to_string(child) +
                                           " is not a parallelogram in ptex space");
                PtexChart chart;
                chart.ptexFace = ptex.GetFaceId(f) + (quad ? 0 : i);
                chart.s0 = q[0].x();
                chart.t0 = q[0].y();
                chart.j00 = eu.x();
                chart.j10 = eu.y();
                chart.j01 = ev.x();
                chart.j11 = ev.y();
                charts[static_cast<size_t>(child)] = chart;
                std::copy(childCorners.begin(), childCorners.end(),
                          faces[static_cast<size_t>(child)].begin());
            }
        }
        for (const auto& corners : faces)
            domain.addFace(corners);
    }
    surface->buildAdjacency();

    // Domain vertices at their limit positions (from any face that uses them;
    // the surface agrees across faces).
    std::vector<Preimage> cornerPreimage(static_cast<size_t>(domain.vertexCount()));
    for (Index f = 0; f < domain.faceCount(); ++f) {
        const auto corners = domain.face(f);
        for (int k = 0; k < static_cast<int>(corners.size()); ++k) {
            const Vec2 uv = cornerCoordinates(corners.size() == 4, k);
            cornerPreimage[static_cast<size_t>(corners[k])] = {f, uv.x(), uv.y()};
        }
    }
    tbb::parallel_for(Index(0), domain.vertexCount(), [&](Index v) {
        const Preimage& p = cornerPreimage[static_cast<size_t>(v)];
        if (p.face != kInvalidIndex)
            domain.positions[static_cast<size_t>(v)] = surface->evaluate(p).position;
    });
    return surface;
}

std::string SubdivisionSurface::description() const {
    const bool loop = kind_ == SurfaceKind::Loop;
    const bool gregory = options_.endCap == SubdivisionOptions::EndCap::GregoryBasis;
    std::string text = std::string(loop ? "Loop" : "Catmull-Clark") +
                       " limit surface (OpenSubdiv, adaptive isolation level " +
                       std::to_string(options_.isolationLevel) + "): exact " +
                       (loop ? "box-spline" : "bicubic B-spline") + " patches except " +
                       std::to_string(impl_->endCaps) + " " + (gregory ? "Gregory" : "B-spline") +
                       " end-cap patches next to extraordinary vertices, each 1/" +
                       std::to_string(1 << options_.isolationLevel) +
                       " of a base face across, where position and derivatives are approximate";
    text += gregory ? " (exact limit position and tangent plane at the vertex, watertight)."
                    : " (exact derivatives inside, but the tangent plane jumps slightly across "
                      "their edges).";
    return text;
}

int SubdivisionSurface::patchCount() const {
    return impl_->patchTable->GetNumPatchesTotal();
}

int SubdivisionSurface::endCapPatchCount() const {
    return impl_->endCaps;
}

int SubdivisionSurface::ptexFaceCount() const {
    return impl_->patchTable->GetNumPtexFaces();
}

SurfacePoint SubdivisionSurface::evaluate(const Preimage& p) const {
    return evaluateUpTo<2>(p);
}

SurfacePoint SubdivisionSurface::evaluateFirstOrder(const Preimage& p) const {
    return evaluateUpTo<1>(p);
}

Vec3 SubdivisionSurface::evaluatePosition(const Preimage& p) const {
    return evaluateUpTo<0>(p).position;
}

template <int Order> SurfacePoint SubdivisionSurface::evaluateUpTo(const Preimage& p) const {
    constexpr int order = Order;
    if (p.face < 0 || p.face >= domain_.faceCount())
        throw std::out_of_range("subdivision surface: preimage face " + std::to_string(p.face) +
                                " does not exist");
    const PtexChart& c = charts_[static_cast<size_t>(p.face)];
    // Ptex coordinates, clamped to the ptex face (a preimage slightly outside
    // its face evaluates on the face's border).
    double s = std::clamp(c.s0 + c.j00 * p.u + c.j01 * p.v, 0.0, 1.0);
    double t = std::clamp(c.t0 + c.j10 * p.u + c.j11 * p.v, 0.0, 1.0);
    if (impl_->triangular && s + t > 1.0) {
        const double excess = 0.5 * (s + t - 1.0);
        s -= excess;
        t -= excess;
    }

    const Far::PatchTable& table = *impl_->patchTable;
    const Far::PatchTable::PatchHandle* handle = impl_->patchMap->FindPatch(c.ptexFace, s, t);
    if (!handle)
        throw std::logic_error("subdivision surface: no patch at ptex face " +
                               std::to_string(c.ptexFace));
    // OpenSubdiv computes each order's weights independently of whether the
    // others are asked for (null pointers skip them), so fewer orders give
    // the same weights for those computed.
    double w[6][kMaxPatchPoints];
    table.EvaluateBasis(*handle, s, t, w[0], order >= 1 ? w[1] : nullptr,
                        order >= 1 ? w[2] : nullptr, order >= 2 ? w[3] : nullptr,
                        order >= 2 ? w[4] : nullptr, order >= 2 ? w[5] : nullptr);
    constexpr int rows = order >= 2 ? 6 : order == 1 ? 3 : 1;

    // Combine the control points: position and the five derivatives in ptex
    // coordinates.
    const auto cvs = table.GetPatchVertices(*handle);
    const double* points = impl_->points.data();
    double sum[6][3] = {};
    for (int i = 0; i < cvs.size(); ++i) {
        const double* q = points + 3 * static_cast<size_t>(cvs[i]);
        for (int k = 0; k < rows; ++k) {
            sum[k][0] += w[k][i] * q[0];
            sum[k][1] += w[k][i] * q[1];
            sum[k][2] += w[k][i] * q[2];
        }
    }
    const auto vec = [&](int k, double scale) {
        return Vec3(scale * sum[k][0], scale * sum[k][1], scale * sum[k][2]);
    };
    SurfacePoint out;
    out.position = vec(0, 1.0);
    if constexpr (order == 0)
        return out;

    // The two EvaluateBasis slips (see the header): under a non-quad base
    // face the weights are scaled by 2^depth where 2^(depth-1) is right; on
    // a rotated triangle the second derivatives have the wrong sign.
    const Far::PatchParam param = table.GetPatchParam(*handle);
    double d1 = 1.0, d2 = 1.0;
    if (param.NonQuadRoot()) {
        d1 = 0.5;
        d2 = 0.25;
    }
    if (impl_->triangular && param.IsTriangleRotated())
        d2 = -d2;
    const Vec3 ps = vec(1, d1), pt = vec(2, d1);

    // Chain rule from ptex (s, t) to the domain face's (u, v); the map is
    // affine, so only first-order terms of J appear.
    out.du = c.j00 * ps + c.j10 * pt;
    out.dv = c.j01 * ps + c.j11 * pt;
    if constexpr (order == 1)
        return out;
    const Vec3 pss = vec(3, d2), pst = vec(4, d2), ptt = vec(5, d2);
    out.duu = c.j00 * c.j00 * pss + 2.0 * c.j00 * c.j10 * pst + c.j10 * c.j10 * ptt;
    out.duv = c.j00 * c.j01 * pss + (c.j00 * c.j11 + c.j01 * c.j10) * pst + c.j10 * c.j11 * ptt;
    out.dvv = c.j01 * c.j01 * pss + 2.0 * c.j01 * c.j11 * pst + c.j11 * c.j11 * ptt;
    return out;
}

void SubdivisionSurface::evaluate(std::span<const Preimage> preimages,
                                  std::span<SurfacePoint> out) const {
    if (preimages.size() != out.size())
        throw std::invalid_argument("evaluate: preimages and output differ in size");
    tbb::parallel_for(tbb::blocked_range<size_t>(0, preimages.size(), 1024),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i != range.end(); ++i)
                              out[i] = evaluate(preimages[i]);
                      });
}

} // namespace contour
