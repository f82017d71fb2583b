#pragma once
// An independent, dense answer for the topology of the smooth contour
// generator (Bénard 2014 §6.1). It shares only the SmoothSurface evaluation and
// SurfaceFields (g and the radial curvature) with the workbench: no contour
// method, no chaining code.
//
// What it does, per domain face of the surface:
//   - samples g = (c - f(u)) · n(u) on a lattice with N steps per side (quads:
//     the (N+1)^2 grid; triangles: the triangular lattice i + j <= N, split
//     into N^2 small triangles);
//   - extracts g = 0 by marching squares (quads; saddle cells decided by the
//     asymptotic decider of the bilinear interpolant) and marching triangles,
//     with g > 0 front and g <= 0 back (the interpolated method's rule);
//   - places each crossing on its lattice edge by linear interpolation, then
//     refines it with a few regula-falsi steps on the true g.
// Lattice points on a shared domain edge or corner are one global sample
// (numbered by domain topology, evaluated once), and a crossing on a lattice
// edge is computed once for the edge (in the lowest-numbered face that has
// it), so both faces see identical values and positions and loops close.
// Cusps are the points of a loop where the radial curvature, evaluated at the
// refined crossings, changes sign (NaN values are skipped).
//
// Known limits: loops entirely inside one lattice cell, and pairs of close
// contour branches crossing one lattice edge twice, are missed (the
// "sub-triangle loops" of Bénard 2014's simplified orientation, at the
// lattice's scale); a cusp pair closer than one lattice step along a loop can
// cancel out; cusps are located only to within one lattice segment.
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"
#include "surface/SmoothSurface.h"

#include <memory>
#include <vector>

namespace contour {

struct GroundTruthOptions {
    int samples = 64;    // lattice steps N per domain face side
    int refineSteps = 4; // regula-falsi steps on the true g per crossing (0: linear only)
};

struct GroundTruthCusp {
    Vec3 position = Vec3::Zero();
    int loop = -1;
};

struct GroundTruthLoop {
    bool closed = false;
    std::vector<Vec3> points;            // refined crossings, in order
    std::vector<Preimage> preimages;     // the same, as preimages
    std::vector<double> radialCurvature; // at each point, NaN where undefined
    std::vector<Index> faces;            // domain faces crossed, sorted, unique
    // The domain face of each lattice segment, in order: segment k joins
    // points k and k + 1 (the last one of a closed loop joins back to 0).
    std::vector<Index> segmentFaces;
    int cusps = 0;
};

struct GroundTruth {
    int samples = 0;
    std::vector<GroundTruthLoop> loops;
    std::vector<GroundTruthCusp> cusps;
    double seconds = 0.0; // time of compute() for this view

    int closedLoops() const;
    int openLoops() const { return static_cast<int>(loops.size()) - closedLoops(); }
    // Whether `other` (the same view at another lattice) has the same loops
    // and cusps: a view where the two agree is settled and can judge a method.
    bool sameTopology(const GroundTruth& other) const {
        return closedLoops() == other.closedLoops() && openLoops() == other.openLoops() &&
               cusps.size() == other.cusps.size();
    }
};

// The image-space crossings of the ground truth's contour (all loops, visible
// or not, each with itself and the others): pairs of projected lattice
// segments that cross properly, i.e. the T-junctions of an exact view graph
// (tutorial ch. 4). Crossings closer than a lattice step to a cusp may be
// missed, like the cusps themselves. Crossings that bound a loop with less
// than `smallLoopPixels` of arc on each side (core/SmallLoopCrossings.h:
// the lattice's zig-zags next to cusps) are left out, as the view graph
// leaves them out with the same value (t-junction-min-loop); 0 counts all.
int imageCrossings(const GroundTruth& truth, const Camera& camera, double smallLoopPixels = 0.0);

// The same count for a method's contour curves (snapshot curves of type
// Contour): proper crossings of their projected segments, in double, with
// no code shared with the view-graph builder. It tells the view graph's
// own exactness (T-junctions against the crossings of its input) apart
// from the input's fidelity (these crossings against the ground truth's).
int imageCrossings(const std::vector<Polyline>& curves, const Camera& camera,
                   double smallLoopPixels = 0.0);

// Samples the view-independent part (positions and unit normals at every
// lattice point) once; compute() then extracts the contour for any camera.
class DenseGroundTruth {
public:
    DenseGroundTruth(std::shared_ptr<const SmoothSurface> surface, GroundTruthOptions options = {});

    const SmoothSurface& surface() const { return *surface_; }
    const std::shared_ptr<const SmoothSurface>& surfacePtr() const { return surface_; }
    const GroundTruthOptions& options() const { return options_; }
    double samplingSeconds() const { return samplingSeconds_; }
    size_t sampleCount() const { return positions_.size(); }

    GroundTruth compute(const Camera& camera) const;

private:
    // Global sample index of lattice point (i, j) of face f.
    Index node(Index f, int i, int j) const;

    std::shared_ptr<const SmoothSurface> surface_;
    GroundTruthOptions options_;
    double samplingSeconds_ = 0.0;
    // Numbering: domain vertices, then N - 1 per domain edge (from its lower
    // vertex), then each face's interior points.
    std::vector<Index> faceEdge_;       // 4 per face: global edge of local edge e
    std::vector<Index> edgeLow_;        // per global edge, its lower vertex
    std::vector<Index> interiorOffset_; // per face, first interior sample
    std::vector<Vec3> positions_;
    std::vector<Vec3> normals_;
};

// The topology of a method's contour (a snapshot with curves, and the
// per-face field domain_face of the surface phase) against the ground truth.
// Loops are matched greedily by the overlap (Jaccard index) of their sets of
// crossed domain faces.
struct TopologyComparison {
    int truthLoops = 0, truthOpenLoops = 0;
    int methodLoops = 0, methodOpenLoops = 0;
    int matchedLoops = 0;     // pairs with at least one common face
    int sameFaceLoops = 0;    // matched pairs whose face sets are equal
    double meanJaccard = 0.0; // over truth loops (unmatched count 0); 1 if none
    int facesOnlyInTruth = 0, facesOnlyInMethod = 0, facesInBoth = 0; // over matched pairs
    int truthCusps = 0;
    int methodCusps = -1; // the snapshot's "cusps" counter, -1 when it has none
    // With a camera: how far (image pixels) each face crossed by only one side
    // of a matched pair lies from the other side's curve, as the largest
    // distance from that side's points in the face to the other side's
    // nearest contour segment. A chord that cuts a domain face's corner where
    // the true contour grazes it misses the face by a fraction of a pixel; a
    // wrong topology misses it by much more.
    double worstMismatchPixels = 0.0; // 0 when every face set matches
    int mismatchesBeyond = 0;         // faces farther than toleranceMismatchPixels
    double toleranceMismatchPixels = 0.0;

    bool loopCountsMatch() const {
        return truthLoops == methodLoops && truthOpenLoops == methodOpenLoops;
    }
    bool faceSetsMatch() const { return loopCountsMatch() && sameFaceLoops == truthLoops; }
    bool cuspCountsMatch() const { return methodCusps == truthCusps; }
    // Every truth loop matched, and each face in one set only lies within
    // the tolerance of the other side's curve (needs the camera).
    bool faceSetsMatchWithinTolerance() const {
        return loopCountsMatch() && matchedLoops == truthLoops && mismatchesBeyond == 0;
    }
};

// The domain faces each contour polyline of the snapshot crosses (sorted,
// unique): per segment, the domain face of its triangle (segments from
// faces), or of both triangles on its edge (segments on mesh edges).
struct MethodLoop {
    bool closed = false;
    std::vector<Index> faces;
    // Points of the curve and the domain face each lies in (segment ends,
    // or the samples of the preimage interpolation).
    std::vector<std::pair<Index, Vec3>> facePoints;
};
std::vector<MethodLoop> methodLoops(const Snapshot& snapshot);
// For meshes whose vertices carry preimages (the consistent method: fields
// preimage_face and preimage_uv): the domain faces a contour edge passes
// through, from its endpoints' preimages interpolated across the domain
// (appendix B charts) at several points along the edge; a triangle's domain
// face would also count the faces its other corners reach into.
std::vector<MethodLoop> methodLoopsFromPreimages(const Snapshot& snapshot,
                                                 std::shared_ptr<const SmoothSurface> surface);

// `surface` given and the snapshot has preimages: methodLoopsFromPreimages,
// otherwise methodLoops.
// With `camera`, the face sets are also compared within
// `tolerancePixels` (worstMismatchPixels, mismatchesBeyond).
TopologyComparison compareTopology(const GroundTruth& truth, const Snapshot& snapshot,
                                   std::shared_ptr<const SmoothSurface> surface = nullptr,
                                   const Camera* camera = nullptr, double tolerancePixels = 1.0);

} // namespace contour
