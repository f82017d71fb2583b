#pragma once
// A smooth surface over a parameter domain made of triangles and quads
// (docs/dev/architecture.md). Every smooth surface of the workbench — Catmull-Clark
// and Loop limit surfaces, vertex-normal patches — implements this, and
// everything above (fields, tessellation, consistent contours) uses only it.
//
// The domain is a PolygonMesh whose faces have 3 or 4 corners:
//   - Catmull-Clark: the control cage subdivided once (all quads; Bénard 2014
//     §6.1 starts from this mesh), so that every domain face is a regular
//     parameter patch or a sub-face of one.
//   - Loop: the triangle cage itself.
//   - vertex-normal patches: the cage, with polygons of more than 4 corners
//     split into a fan around an apex vertex (van Overveld & Wyvill §2.5).
// Local coordinates (u, v): on a quad, corner 0 at (0,0), 1 at (1,0), 2 at
// (1,1), 3 at (0,1); on a triangle, corner 0 at (0,0), 1 at (1,0), 2 at
// (0,1). Domain vertices are shared, so the domain is a manifold mesh whose
// faces meet edge to edge: a point on a shared edge has one preimage in each
// of the two faces, related by transferAcrossEdge().
#include "mesh/PolygonMesh.h"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace contour {

struct Preimage {
    Index face = kInvalidIndex; // a face of SmoothSurface::domain()
    double u = 0.0;
    double v = 0.0;
};

// Position and partial derivatives at a preimage, in that face's (u, v).
struct SurfacePoint {
    Vec3 position = Vec3::Zero();
    Vec3 du = Vec3::Zero(), dv = Vec3::Zero();
    Vec3 duu = Vec3::Zero(), duv = Vec3::Zero(), dvv = Vec3::Zero();

    // Unit normal du x dv; outward when the cage's faces are counter-clockwise
    // seen from outside. Zero where du x dv vanishes.
    Vec3 normal() const {
        const Vec3 n = du.cross(dv);
        const double len = n.norm();
        return len > 0.0 ? Vec3(n / len) : Vec3::Zero();
    }
};

enum class SurfaceKind { CatmullClark, Loop, VertexNormalPatches };
const char* toString(SurfaceKind kind); // "catmull-clark", "loop", "vertex-normal-patches"

class SmoothSurface {
public:
    virtual ~SmoothSurface() = default;
    SmoothSurface() = default;
    SmoothSurface(const SmoothSurface&) = delete;
    SmoothSurface& operator=(const SmoothSurface&) = delete;

    virtual SurfaceKind kind() const = 0;
    // A sentence for the UI and reports: what is exact, what is approximate.
    virtual std::string description() const = 0;

    const PolygonMesh& domain() const { return domain_; }
    bool isQuad(Index face) const { return domain_.face(face).size() == 4; }
    bool contains(const Preimage& p) const; // (u, v) inside its face (closed)

    virtual SurfacePoint evaluate(const Preimage& p) const = 0;
    // Cheaper evaluations for callers that need less (hot loops of the
    // consistent method: labels by sign(g), radial-plane root searches). Each
    // returns evaluate()'s exact values (bit for bit) for what it computes;
    // the defaults call evaluate().
    //   evaluateFirstOrder: position, du and dv (second derivatives zero).
    //   evaluatePosition: the position only.
    virtual SurfacePoint evaluateFirstOrder(const Preimage& p) const { return evaluate(p); }
    virtual Vec3 evaluatePosition(const Preimage& p) const { return evaluate(p).position; }
    // Many preimages at once; the default runs evaluate() in a parallel loop.
    virtual void evaluate(std::span<const Preimage> preimages, std::span<SurfacePoint> out) const;

    // The neighbour across local edge `edge` of `face` (edge i runs from
    // corner i to corner i+1): its face and the index of the shared edge in
    // it, or face = kInvalidIndex on a boundary.
    struct EdgeNeighbor {
        Index face = kInvalidIndex;
        int edge = -1;
    };
    EdgeNeighbor neighbor(Index face, int edge) const;

    // Re-expresses p, given in face p.face, in the chart of the face across
    // local edge `edge` (Bénard 2014 appendix B): the affine map that takes the
    // shared edge to itself, corner to corner, extended to the whole plane.
    // Points on the edge map to the same surface point; points slightly
    // outside p.face land slightly inside the neighbour.
    Preimage transferAcrossEdge(const Preimage& p, int edge) const;

    // Local coordinates of corner `corner` of a domain face.
    static Vec2 cornerCoordinates(bool quad, int corner);

protected:
    // Implementations set the domain once in their constructor, then call
    // buildAdjacency().
    PolygonMesh domain_;
    void buildAdjacency();

private:
    std::vector<EdgeNeighbor> neighbors_; // 4 per face (unused slots for triangles)
};

} // namespace contour
