#pragma once
// An independent check of a view graph's visibility: the
// triangle mesh is rasterized by VTK offscreen (OpenGL, under xvfb) at
// `scale` times the camera's viewport, the depth buffer is read back and
// converted to eye depth, and every chain of the graph is sampled in image
// space and compared with it. It shares no code with algorithms/visibility
// (no ray casting, no QI, no propagation): only the mesh, the camera and the
// widget's camera conversion (applyCameraToVtk). Points are projected with
// VTK's own matrices, so they land on the pixels the rasterizer wrote.
//
// Fairness at depth discontinuities: a contour lies exactly on one (the
// silhouette), and the surface next to it inside the silhouette is nearer
// than the contour itself by a large amount at grazing angles. So a point
// is called visible when its eye depth d is at most the FARTHEST buffer
// depth of a (2r+1)² neighbourhood of rendered pixels (r = 1: 3×3 at 2×,
// i.e. ±0.5 viewport pixel) plus a relative tolerance: d ≤ max + tol·d.
// Beyond a visible silhouette lies the background or something farther, so
// the max sees it. A hidden point has an occluder in front of its whole
// neighbourhood, except within about half a pixel of the occluder's own
// silhouette: a hidden curve that coincides in the image with a visible
// silhouette (a back edge right behind it, the hidden branch next to a
// cusp, the far side of a T-junction) counts as visible. The check leans
// towards "visible" there, which lowers the hidden-length agreement, never
// the visible one; such length is reported apart when a graph-visible chain
// runs within `coverRadius` of it (the drawing shows a line there anyway).
// The relative tolerance (1e-4) only absorbs the rasterizer's float
// arithmetic (a 24-bit buffer over the clipping range resolves ~1e-7 of the
// depth): a small fold of a consistent mesh hides its inner branch by well
// under 1 % of the depth and must still count as hidden. Surface-intersection
// points get the neighbourhood's depth spread on top (see depthVerdict).
// Points within `nodeExclusion` viewport pixels of a node, outside the image,
// or outside the depth range are excluded and their length counted.
//
// Debugging: writeComparisonImage draws the outcome of every sample.
#include "camera/Camera.h"
#include "mesh/TriangleMesh.h"
#include "pipeline/ViewGraph.h"

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace contour::testing {

// The depth buffer of one rendering, as eye depths (distance along the
// viewing direction from the rendering camera's position), with the
// projection that produced it.
struct DepthImage {
    int width = 0;  // rendered pixels (scale × viewport width)
    int height = 0; // rendered pixels
    int scale = 2;
    // Row-major, top row first (y down like Camera::project); +inf where the
    // background shows.
    std::vector<double> eyeDepth;
    Eigen::Matrix4d worldToNdc = Eigen::Matrix4d::Identity(); // VTK's composite projection
    Eigen::Matrix4d worldToView = Eigen::Matrix4d::Identity();
    double nearPlane = 0.0, farPlane = 0.0;
    bool orthographic = false;
    // Largest distance, in viewport pixels, between Camera::project and
    // VTK's projection over the mesh's bounding-box corners: the two cameras
    // must agree or the comparison means nothing.
    double cameraMismatchPixels = 0.0;

    double at(int x, int y) const { return eyeDepth[static_cast<size_t>(y) * width + x]; }
    // A world point in rendered pixels (x right, y down) and its eye depth.
    Eigen::Vector3d project(const Vec3& p) const;
    // The normalized depth-buffer value [0, 1] at eye depth d, and back.
    double eyeDepthFromBuffer(double z) const;
};

struct DepthCheckOptions {
    int scale = 2;                   // rendered pixels per viewport pixel
    double sampleStep = 0.5;         // rendered pixels between samples along a chain
    int neighbourhood = 1;           // radius in rendered pixels: 1 = 3×3
    double relativeTolerance = 1e-4; // of the point's eye depth
    double nodeExclusion = 1.0;      // viewport pixels around every node
    double coverRadius = 1.0;        // viewport pixels, see DepthLengths::hiddenButVisibleCovered
};

enum class DepthVerdict { Visible, Occluded, Outside };

// Lengths in viewport pixels.
struct DepthLengths {
    double visibleAgree = 0.0;       // graph visible, buffer visible
    double visibleButOccluded = 0.0; // graph visible, buffer occluded
    double hiddenButVisible = 0.0;   // graph hidden, buffer visible
    // Of hiddenButVisible, the length within coverRadius of a sample of a
    // chain the graph calls visible: the drawing has a line there anyway
    // (typically a hidden curve that coincides in the image with a visible
    // silhouette, which the neighbourhood test cannot tell apart).
    double hiddenButVisibleCovered = 0.0;
    double hiddenAgree = 0.0;      // graph hidden, buffer occluded
    double undecided = 0.0;        // chains with qi < 0 (compared length, not judged)
    double excludedOutside = 0.0;  // outside the image or the depth range
    double excludedNearNode = 0.0; // within nodeExclusion of a node
    long long samples = 0;

    double graphVisible() const { return visibleAgree + visibleButOccluded; }
    double graphHidden() const { return hiddenAgree + hiddenButVisible; }
    double compared() const { return graphVisible() + graphHidden(); }
    // Agreeing length over compared length; 1 when nothing was compared.
    double agreement() const;
    // Of the length the graph calls visible, the share the buffer confirms.
    double visibleAgreement() const;
    // Of the length the graph calls hidden, the share the buffer confirms.
    double hiddenAgreement() const;
    // Of the length the buffer sees, the share the graph calls visible: a
    // graph that hides everything has a perfect visibleAgreement() and a
    // zero here (a deleted silhouette shows here, not there).
    double bufferVisibleDrawn() const;
    // The same, counting hiddenButVisibleCovered as drawn: how much of what
    // the buffer sees the drawing misses.
    double bufferVisibleCovered() const;
    DepthLengths& operator+=(const DepthLengths& o);
};

struct DepthAgreement {
    std::array<DepthLengths, 3> byType{}; // indexed by CurveType
    DepthLengths all;
    // Per chain of the graph compared (empty after summing several graphs),
    // to name the chains that disagree.
    std::vector<DepthLengths> byChain;
    double cameraMismatchPixels = 0.0; // max over the renderings summed in
    DepthAgreement& operator+=(const DepthAgreement& o);
    // One line per curve type with length, then the total.
    std::string summary() const;
    // The chains of `graph` (the one compared) whose disagreeing length
    // exceeds `minPixels`: index, type, QI, rule, length, disagreement.
    std::string disagreements(const ViewGraph& graph, double minPixels = 1.0) const;
};

// Renders `mesh` seen by `camera` offscreen at scale × its viewport.
DepthImage renderDepth(const TriangleMesh& mesh, const Camera& camera, int scale = 2);

// `crease`: the point lies where two sheets cross (a surface intersection).
// Both sheets are nearer than the crossing on either side of it, by their
// depth slope times the distance, so the neighbourhood's depth spread
// (farthest − nearest finite depth) is added to the tolerance there.
DepthVerdict depthVerdict(const DepthImage& image, const Vec3& p, const DepthCheckOptions& options,
                          bool crease = false);

// Samples every chain of the graph (qi == 0 is "visible"; simplification is
// ignored: it is a drawing choice, not visibility) and compares.
DepthAgreement compareWithDepth(const ViewGraph& graph, const DepthImage& image,
                                const DepthCheckOptions& options = {});

// A picture of the comparison, for a human: the buffer in grey (near
// light), each sample coloured by its outcome (green: both visible, red:
// graph visible but occluded, blue: both hidden, magenta: graph hidden but
// visible, yellow: excluded) and nodes as white crosses. Binary PPM.
void writeComparisonImage(const std::string& path, const ViewGraph& graph, const DepthImage& image,
                          const DepthCheckOptions& options = {});

// renderDepth + compareWithDepth.
DepthAgreement checkVisibilityWithDepth(const ViewGraph& graph, const TriangleMesh& mesh,
                                        const Camera& camera,
                                        const DepthCheckOptions& options = {});

} // namespace contour::testing
