#pragma once
// An independent dense answer for the contour of the powell-sabin method's
// fitted spline (Capouellez et al. 2023 §4), for the tests and the drawing
// benchmark. The spline is wrapped as a SmoothSurface so that the reference
// oracle (reference/DenseGroundTruth.h: lattice sampling of g, marching
// triangles, cusps where the radial curvature changes sign) runs on it
// unchanged. It shares only the spline's evaluation (Ps12Patch.h) with the
// method: no conic, chaining, cusp or view-graph code.
//
// Topology is compared by contour components: connected components of the
// contour set, curves meeting at a cone point counting as one (the normal
// vanishes at cones, where several loops meet, §4.2). On the oracle's side
// loops passing through the lattice ring around the same cone are merged;
// on the method's side the chaining's chains are joined at the view
// graph's Bifurcation (cone) nodes.
#include "camera/Camera.h"
#include "contours/powell_sabin/ConeLayout.h"
#include "contours/powell_sabin/PowellSabinSpline.h"
#include "pipeline/Snapshot.h"
#include "reference/DenseGroundTruth.h"
#include "surface/SmoothSurface.h"

#include <memory>
#include <utility>
#include <vector>

namespace contour::testing {

// The spline over the layout's triangles: domain face f is layout triangle
// f, its local (u, v) mapped affinely to the face's corner uv (corner 0 at
// (0, 0), 1 at (1, 0), 2 at (0, 1)). Positions are the spline's, in the
// view's transformed coordinates (ProjectiveTransform.h).
class PowellSabinSurface final : public SmoothSurface {
public:
    PowellSabinSurface(std::shared_ptr<const powell_sabin::ConeLayout> layout,
                       std::shared_ptr<const powell_sabin::PowellSabinSpline> spline);

    SurfaceKind kind() const override;
    std::string description() const override;
    using SmoothSurface::evaluate;
    SurfacePoint evaluate(const Preimage& p) const override;

    // The patch (12 f + l) whose sub-triangle holds the preimage, and the
    // barycentric coordinates there.
    std::pair<Index, Vec3> locate(const Preimage& p) const;
    // The layout's uv of a preimage.
    Vec2 uvOf(const Preimage& p) const;

    const powell_sabin::ConeLayout& layout() const { return *layout_; }
    const powell_sabin::PowellSabinSpline& spline() const { return *spline_; }
    // Domain vertices that are cones, and the spline's point at each.
    const std::vector<Index>& cones() const { return cones_; }
    const std::vector<Vec3>& conePoints() const { return conePoints_; }
    // The cone (index into cones()) whose ring holds the preimage: the
    // points of the cone's faces within `fraction` of the way from the cone
    // corner to the opposite side; -1 when none.
    int coneRingAt(const Preimage& p, double fraction) const;
    BoundingBox boundingBox() const; // of the patches' control points

private:
    std::shared_ptr<const powell_sabin::ConeLayout> layout_;
    std::shared_ptr<const powell_sabin::PowellSabinSpline> spline_;
    std::vector<Index> cones_;
    std::vector<Vec3> conePoints_;
};

// The orthographic camera of the transformed space for `view` (the view is
// along +z there, smaller z nearer, §3): eye on the -z side, the same
// viewport, and the pixel scale of `view` (transformed x, y are the
// perspective image's x/d, y/d), so that pixel tolerances mean the same.
// The image is mirrored against `view`'s, which no crossing count sees.
Camera transformedCamera(const Camera& view, const BoundingBox& transformedBox);

// What the oracle finds in one view at one lattice size.
struct OracleFigures {
    int samples = 0;
    int loops = 0;          // of the lattice, before merging at cones
    int coneOnlyLoops = 0;  // loops lying wholly in one cone's ring (left out)
    int keptLoops = 0;      // the others
    int components = 0;     // loops merged at cones
    int conePoints = 0;     // cones the kept loops pass through
    int cusps = 0;          // radial curvature sign changes (DenseGroundTruth), after the rules
    int rawCusps = 0;       // before the zig-zag rule
    int coneCusps = 0;      // sign changes in a cone's ring (left out of both)
    int crossings = 0;      // image crossings away from cones
    int coneCrossings = 0;  // image crossings the cone rings removed
    double maxFacing = 0.0; // largest |tau . n| (unit normal) at the loops' points
};

// How sub-pixel zig-zags of the contour are counted, as the method's view
// graph counts them (its zig-zag-pixels parameter, when it has one; 0 keeps
// every cusp and crossing): along a loop, cusps with less than
// `zigZagPixels` of image arc between neighbours form a cluster that counts
// one cusp when odd and none when even, and crossings that bound a loop
// with less than that arc on each side are left out.
// A cone's ring is the lattice rows of its faces within `coneRingSteps`
// steps of it (at most half way to the opposite side). Around a cone the
// normal is homogeneous of degree 0 (the gradients vanish there, §5.2), so
// the lattice's picture is the same at every N: a contour wedge of small
// angle through the cone is resolved only some steps away from it (6 on
// spot), and tiny loops appear in the cone's cells.
struct OracleRules {
    double zigZagPixels = 0.0;
    int coneRingSteps = 8;
};

// Components, cusps and crossings of `truth` on `surface`, seen by `camera`
// (transformedCamera). Crossings are counted with the loops cut where they
// enter a cone's ring, since the loops meeting at a cone touch there in the
// image too and the method leaves those crossings out.
OracleFigures oracleFigures(const GroundTruth& truth, const PowellSabinSurface& surface,
                            const Camera& camera, const OracleRules& rules = {});

// What the method's view graph says (the visibility snapshot).
struct MethodFigures {
    int chains = 0;     // chaining chains that have view chains
    int components = 0; // those chains joined at Bifurcation nodes
    int cusps = 0;      // CurtainFold nodes at cusps of the surface
    int tJunctions = 0; // ImageIntersection nodes
    int conflicts = 0;  // the view graph's visibility conflicts
    int conePoints = 0; // Bifurcation nodes
};
// Throws std::invalid_argument when the snapshot has no view graph.
MethodFigures methodFigures(const Snapshot& snapshot);

// Connected components of `items` elements joined in pairs (union-find).
int components(int items, const std::vector<std::pair<int, int>>& joins);

// The method against the oracle at N and N/2 samples per layout face. A
// quantity is settled when both lattices agree on it; a view is settled
// when components and cusps are.
struct SplineViewComparison {
    OracleFigures fine, coarse;
    MethodFigures method;
    double oracleSeconds = 0.0;

    bool componentsSettled() const { return fine.components == coarse.components; }
    bool cuspsSettled() const { return fine.cusps == coarse.cusps; }
    bool crossingsSettled() const { return fine.crossings == coarse.crossings; }
    bool settled() const { return componentsSettled() && cuspsSettled(); }
    bool componentsMatch() const { return method.components == fine.components; }
    bool cuspsMatch() const { return method.cusps == fine.cusps; }
    bool tJunctionsMatch() const { return method.tJunctions == fine.crossings; }
};

// Views judged and matched over a set of comparisons: components and cusps
// on the settled views, T-junctions on those whose crossings settle too.
struct OracleTally {
    int views = 0, settled = 0, components = 0, cusps = 0;
    int crossingsSettled = 0, tJunctions = 0;
    void add(const SplineViewComparison& c) {
        ++views;
        if (!c.settled())
            return;
        ++settled;
        components += c.componentsMatch();
        cusps += c.cuspsMatch();
        if (c.crossingsSettled()) {
            ++crossingsSettled;
            tJunctions += c.tJunctionsMatch();
        }
    }
};

// `last` is a powell-sabin snapshot with the spline and a view graph (the
// visibility phase) of `view`. Throws std::invalid_argument otherwise.
SplineViewComparison compareWithOracle(const Snapshot& last, const Camera& view, int samples,
                                       const OracleRules& rules = {});

} // namespace contour::testing
