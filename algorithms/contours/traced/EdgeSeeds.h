#pragma once
// Seeds of the traced contour on domain edges (Summers 2016 §3.4.2.2): the
// points of every domain edge where g changes sign. On an edge inside one
// polynomial patch (EdgePolynomials.h) the roots are isolated by Descartes'
// rule on g's Bernstein coefficients with de Casteljau subdivision, so none
// is missed; on the other edges (extraordinary vertices, end caps) g is
// sampled densely and each sign change is bisected on the surface, which
// misses a pair of roots closer than a sample step. Every root is then
// polished by Newton steps along the edge on the true g.
//
// Each root also records which way the contour crosses the edge: the
// contour is oriented with the front side on its right (ContourCorrector.h),
// so it leaves one of the edge's faces and enters the other there.
#include "camera/Camera.h"
#include "contours/traced/EdgePolynomials.h"

#include <memory>
#include <vector>

namespace contour::traced {

struct EdgeRoot {
    Index edge = kInvalidIndex; // into EdgePolynomials::edges
    double t = 0.0;             // along the edge, in its first face's chart
    // The root in the chart of the face the contour leaves and of the face
    // it enters (kInvalidIndex face on a boundary).
    Preimage exitSide, entrySide;
    Vec3 position = Vec3::Zero();
    double g = 0.0;        // the true g at the root after polishing
    bool certified = true; // isolated by Descartes' rule (false: sampled)
};

struct EdgeSeedOptions {
    int maxDepth = 40;        // subdivision depth before a root cluster is given up
    double gTolerance = 0.0;  // |g| the polished roots aim for (length units)
    int polishIterations = 4; // Newton steps along the edge on the true g
};

struct EdgeSeeds {
    std::vector<EdgeRoot> roots;
    // Per domain face, the roots on its boundary where the contour leaves it.
    std::vector<std::vector<Index>> exitsOfFace;
    long long certifiedEdges = 0, sampledEdges = 0;
    long long unresolvedClusters = 0; // Descartes pieces given up at max depth
    long long vanishingEdges = 0;     // g = 0 along the whole edge
    long long tangentRoots = 0;       // the contour crosses no side at the root
};

EdgeSeeds findEdgeSeeds(const SmoothSurface& surface, const EdgePolynomials& polynomials,
                        const Camera& camera, const EdgeSeedOptions& options);

} // namespace contour::traced
