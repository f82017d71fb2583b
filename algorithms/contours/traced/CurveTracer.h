#pragma once
// Predictor-corrector tracing of the contour generator g = 0 on the limit
// surface (Summers 2016 §3.4.2.1, after Li, Sun & Yang 1998), one domain
// face's chart at a time:
//   - predictor: a step of length h along the unit tangent (-g_v, g_u)/|∇g|
//     (the front side on the right: every curve keeps one orientation
//     across faces, ContourCorrector.h);
//   - corrector: Newton steps back onto g = 0;
//   - the step is accepted when the corrector converged, moved the point by
//     less than half a step, the tangent turned by less than max-turn, and
//     the chord's midpoint lies within max-deviation of g = 0 (|g| / |∇g|,
//     in domain parameters); otherwise h is halved, and after an accepted
//     step it grows again up to max-step (Summers: a fixed 0.1);
//   - a step that leaves the face ends at the edge root (EdgeSeeds.h) where
//     the contour leaves it, the one nearest to the chord's exit point, and
//     tracing continues in the face across from that root's other side.
// So a curve passes through the edge roots themselves; a root reached is
// used, which suppresses the duplicates Summers removes by hand (one curve
// per loop, however many roots it passes), and a curve from an edge root
// closes when it comes back to its first root. Curves from interior seeds
// (InteriorSeeds.h) must stay in their face and close on their start.
#include "camera/Camera.h"
#include "contours/traced/EdgeSeeds.h"
#include "contours/traced/InteriorSeeds.h"

#include <vector>

namespace contour::traced {

struct TracedPoint {
    Preimage preimage; // in the chart of the segment that starts here (the last point of an
                       // open curve: of the one that ends here)
    Vec3 position = Vec3::Zero();
    double g = 0.0;
    Index edgeRoot = kInvalidIndex; // the EdgeSeeds root it is, if any
};

struct TracedSegment {
    Index face = kInvalidIndex;
    Vec2 a = Vec2::Zero(), b = Vec2::Zero(); // ends in `face`'s chart
};

enum class CurveEnd {
    Closed,
    Boundary,  // left the surface through a boundary edge
    Stalled,   // the step fell below min-step
    Singular,  // ∇g vanished on the curve (the zero set is not a curve there)
    Collision, // reached a root another curve had used
    TooLong,   // max-steps reached
    AlongEdge, // crossed edges without roots too often: the contour runs along an edge
};
const char* toString(CurveEnd end);

struct TracedCurve {
    bool closed = false;
    bool interior = false; // from an interior seed (a loop inside one face)
    CurveEnd end = CurveEnd::Closed;
    std::vector<TracedPoint> points;
    std::vector<TracedSegment> segments; // closed: points.size(), the last joins back
};

struct TracerOptions {
    double maxStep = 0.1;          // domain parameters (Summers 2016: 0.1)
    double minStep = 1e-6;         // below it the curve stalls
    double maxDeviation = 1e-3;    // of the chord's midpoint from g = 0, domain parameters
    double maxTurn = 0.3;          // radians per step
    double gTolerance = 0.0;       // |g| of an accepted point (length units)
    double singularGradient = 0.0; // |∇g| below this is a singular point
    int maxSteps = 200000;         // per curve
    int maxRootlessCrossings = 64; // per curve, before it counts as running along an edge
};

struct TracerStats {
    long long steps = 0, rejectedSteps = 0;
    long long stalls = 0, recoveredStalls = 0;
    long long collisions = 0, singularPoints = 0;
    long long joinedPieces = 0;          // open pieces joined end to start
    long long rootlessCrossings = 0;     // edges crossed where they have no root (tangent contact)
    long long unreachedRoots = 0;        // edge roots no curve passed
    long long interiorSeedsOnCurves = 0; // interior seeds already on a traced curve
    long long interiorSeedsLeavingFace = 0;
    double maxAbsG = 0.0;
};

std::vector<TracedCurve> traceContours(const SmoothSurface& surface, const Camera& camera,
                                       const EdgeSeeds& seeds, const InteriorSeeds& interior,
                                       const TracerOptions& options, TracerStats* stats);

} // namespace contour::traced
