#pragma once
// The view graph (tutorial §4.5; Bénard 2014 §8.3, after Grabli et al. 2010):
// a snapshot's curves cut at every point where their visibility may change
// (the nodes), into chains whose visibility is constant, each with its
// quantitative invisibility (QI) and the rule that decided it. Data only:
// algorithms/visibility builds and fills it; the exporters and the widgets
// read it.
#include "pipeline/Curve.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace contour {

// Tutorial §4.3 / Bénard 2014 §8.1–8.2: the only points where a curve's
// visibility can change.
enum class ViewNodeType {
    CurtainFold,             // a cusp of the contour: a convex (exterior) contour edge meets a
                             // concave (interior) one
    BoundaryCurtainFold,     // a boundary vertex where one boundary edge is occluded by the
                             // vertex's one-ring and the other is not (tutorial app. C.2)
    ImageIntersection,       // T-junction: a near curve passes in front of a far curve in 2D
    ContourBoundaryJunction, // Y: a contour ends on a boundary (a shared mesh vertex)
    Bifurcation,             // three or more curve edges of one type meet at a vertex
    SurfaceIntersectionEnd,  // a surface-intersection curve meets a contour or boundary on
                             // the surface
    CurveEnd,                // an open end with no other curve there (should not occur on a
                             // closed, clean mesh; kept so nothing is dropped silently)
    HiddenFoldCrossing,      // a fold edge of the mesh that lies on no drawn curve passes in
                             // front of a curve in 2D (consistent meshes: only next to
                             // inconsistent faces): a real QI step of the mesh (+2), but no
                             // T-junction of the drawn curves; nearChains are unused
};
const char* toString(ViewNodeType type);
// Nodes where something passes in front of a curve in the image: T-junctions
// and hidden-fold crossings (the far chains step by qiStep at both).
inline bool isImageCrossing(ViewNodeType type) {
    return type == ViewNodeType::ImageIntersection || type == ViewNodeType::HiddenFoldCrossing;
}

// Bénard 2014 §9 / Grabli 2010: a node seen through its visible chains only.
enum class ViewNodeClass { Hidden, DeadEnd, Connector, Junction };
const char* toString(ViewNodeClass nodeClass);

// How a chain's visibility was decided. Written into the JSON report, the
// SVG (data-rule) and the inspector, so every value can be traced.
enum class VisibilityRule {
    Unknown,
    RayTest,             // one ray from a point of the chain to the camera; QI = occluders
    Propagation,         // same QI as a chain met at a node without a singularity
    ImageIntersection,   // far side of a T-junction: +2 behind a contour, +1 behind a boundary
    CurtainFold,         // far side of a curtain fold: + the one-ring faces that occlude it
    ConcaveContour,      // concave contour edges are invisible (tutorial theorem B.0.1)
    BackFace,            // a curve lying only on back faces is invisible
    MajorityVote,        // consistent contours: the majority plus one of the segments'
                         // ray tests (Bénard 2014 §8.4)
    AmbiguityCusps,      // §8.4 rule (a): a chain between two cusps whose other chains are
                         // visible
    AmbiguityShortChain, // §8.4 rule (b): a short chain between two T-junctions whose mates
                         // are visible
    AmbiguityBoundary,   // §8.4 rule (c): a boundary chain joined to a visible chain
    CuspConsistency,     // §8.4, Fig. 23: an isolated cusp pair's expected pattern
    AmbiguousInvisible,  // still ambiguous after resolution: invisible by the paper's rule
    HeuristicVote,       // interpolated contours: vote over several ray tests (tutorial §6.2.4)
};
const char* toString(VisibilityRule rule);

struct ViewChain {
    CurveType type = CurveType::Contour;
    Index curve = kInvalidIndex; // index into Snapshot::curves
    SegmentSource source = SegmentSource::MeshEdge;

    // The chain's points in 3D and in pixels (Camera::project: x right, y
    // down), and each point's camera depth. n points make n − 1 segments; a
    // closed chain (a whole curve with no node on it) repeats its first point
    // last.
    std::vector<Vec3> points;
    std::vector<Vec2> image;
    std::vector<double> depth;
    // Per segment: the mesh element it comes from (an edge, or a face for
    // interpolated contours and surface intersections; see `source`) and, for
    // surface intersections, the second face.
    std::vector<Index> segmentElement;
    std::vector<Index> segmentSecondFace;
    // Per segment, when segments are ray-tested one by one (consistent and
    // interpolated contours): the occluder count, −1 if not tested, and
    // whether the test is ambiguous (Bénard 2014 §8.4).
    std::vector<int> segmentRayQi;
    std::vector<std::uint8_t> segmentAmbiguous;

    bool closed = false;
    Index startNode = kInvalidIndex; // both invalid for a closed chain
    Index endNode = kInvalidIndex;

    int qi = -1;          // quantitative invisibility; −1 while unknown
    int qiLowerBound = 0; // known before any ray test (concave contour: 1)
    VisibilityRule decidedBy = VisibilityRule::Unknown;
    bool ambiguous = false;      // consistent contours: still ambiguous after the votes
    bool concave = false;        // a contour chain on concave edges (interior, for VBO meshes)
    int rayQi = -1;              // the chain's own ray test, when it had one
    bool conflict = false;       // a ray test and propagation disagree (both kept)
    bool simplifiedAway = false; // hidden by topological simplification (Bénard 2014 §9)
    // QI propagation (tutorial §4.7): the chain this one's QI came from and
    // the node between them; invalid for a seed or before propagation.
    Index propagatedFrom = kInvalidIndex;
    Index propagatedVia = kInvalidIndex;
    // The connected component of the propagation links, and whether a link
    // at this chain disagreed with the QI reached another way.
    Index component = kInvalidIndex;
    bool cycleDisagreement = false;
    double lengthPixels = 0.0;

    bool visible() const { return qi == 0 && !simplifiedAway; }
    std::size_t segmentCount() const { return points.size() < 2 ? 0 : points.size() - 1; }
};

struct ViewNode {
    ViewNodeType type = ViewNodeType::CurveEnd;
    Vec3 position = Vec3::Zero(); // on the surface (for a T-junction: on the far curve)
    Vec2 image = Vec2::Zero();    // pixels
    Index meshVertex = kInvalidIndex;
    // Every chain that starts or ends here (a chain that does both is listed
    // twice).
    std::vector<Index> chains;

    // Curtain folds: the chain the vertex's one-ring occludes less (usually
    // the exterior one) as nearChains[0], the other as farChains[1].
    // T-junctions: the two chains of the near (occluding) curve and of the
    // far curve; farChains[1] is the far chain on the occluded side. Unused
    // entries are kInvalidIndex.
    std::array<Index, 2> nearChains{kInvalidIndex, kInvalidIndex};
    std::array<Index, 2> farChains{kInvalidIndex, kInvalidIndex};
    Vec3 nearPoint = Vec3::Zero(); // T-junction: the near curve's point (on the near surface)
    // The QI step from the near (or unoccluded far) chain to the occluded far
    // chain: +2 behind a contour, +1 behind a boundary, at a curtain fold the
    // one-ring faces that occlude the far edge (≥ 1; 0 at a vertex the
    // near-face test calls a fold but the one-ring does not). 0 when no step
    // applies.
    int qiStep = 0;
    bool unreliable = false; // a near-face test below its threshold (Bénard 2014 fn. 3)
    // A curtain fold at a cusp of the smooth surface (consistent contours: a
    // cusp vertex, Bénard 2014 §6.2 d), its far side and step decided from
    // the surface's radial curvature; false for curtain folds found by a
    // mesh test (convexity, near face, one-ring).
    bool smoothCusp = false;
    // A curtain fold at a cusp vertex where the surface is singular
    // (fields::kSingularCusp): decided by the one-ring test like a mesh
    // fold, its step possibly 0; smoothCusp is false.
    bool singularCusp = false;
    // A T-junction bounding a loop of the polylines smaller than
    // t-junction-min-loop (a bigon of two branches or a branch around a
    // cusp, core/SmallLoopCrossings.h): a zig-zag of the sampled contour, not
    // a crossing of the smooth one. It keeps its node and QI step.
    bool smallLoop = false;
    // Nodes at a mesh vertex (curtain folds, Y junctions, bifurcations),
    // parallel to `chains`: how many faces of the vertex's one-ring occlude
    // that chain's first edge next to the vertex (tutorial app. C.2 test).
    // QI differences between the chains equal the differences of these
    // counts (tutorial §4.7, local overlap tests). Empty for other nodes.
    std::vector<int> localOccluders;
};

// A ray test that disagrees with the QI that propagation gave the same chain.
// Neither value is overwritten: the chain keeps the propagated QI and is
// flagged; the conflict is reported.
struct VisibilityConflict {
    Index chain = kInvalidIndex;
    int propagatedQi = -1;
    int rayQi = -1;
    std::string reason;
    // Which propagation step gave the propagated QI: the chain it came from
    // and the node it crossed (both invalid for a component's seed, which a
    // ray decided); and where the disagreeing ray starts (the midpoint of
    // the chain's middle segment, chainRayQi).
    Index fromChain = kInvalidIndex;
    Index viaNode = kInvalidIndex;
    Vec3 rayOrigin = Vec3::Zero();
    // A ray check whose propagation source agrees with its own ray (or is a
    // seed): the first wrong step on its path. The conflicts downstream of it
    // repeat the same error, so the roots are where to look.
    bool root = false;
};

// The chains counted as reports give them: visible (drawn solid), hidden
// (drawn dashed; not simplified away), simplified away, and across those,
// ambiguous and conflicting ones.
struct ViewChainTally {
    long long visible = 0;
    long long hidden = 0;
    long long simplified = 0;
    long long ambiguous = 0;
    long long conflicting = 0;
    double simplifiedLengthPixels = 0.0;
};

struct ViewGraph {
    std::vector<ViewChain> chains;
    std::vector<ViewNode> nodes;
    std::vector<VisibilityConflict> conflicts;
    long long rayTests = 0;

    // The node's class counting visible chains only (Bénard 2014 §9).
    ViewNodeClass nodeClass(Index node) const;
    ViewChainTally chainTally() const;
    double visibleLengthPixels() const;
    double hiddenLengthPixels() const;
};

} // namespace contour
