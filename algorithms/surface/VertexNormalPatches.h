#pragma once
// Vertex-normal patches of van Overveld & Wyvill, "An algorithm for polygon
// subdivision based on vertex normals" (../shared/papers; reading notes with
// errata in ../shared/notes, PART B). Every cage polygon is replaced by
// quadratic Bézier pieces built from its own corner positions and vertex
// normals only:
//   - each edge becomes a cubic Bézier p0..p3 tangent to the planes normal to
//     n0 and n3 (§2.4), then two C1 quadratics (§2.3 step 2, Fig. 2);
//   - each corner gets an interior control point by the parallelogram rule
//     (§2.6);
//   - a triangle becomes a 15-point net read as 4 quadratic triangular Bézier
//     sub-patches, a quad a 5x5 net of 4 biquadratic patches, an n-gon
//     (n > 4) a fan of n such triangles around an apex (§2.5).
// The surface is C0 across cage edges (a shared edge's curve depends on that
// edge's two vertices and normals only) and its tangent plane at a cage
// vertex is the plane normal to the vertex normal; along cage edges and
// inside polygons it is only C0 in general (the paper makes no stronger
// claim). Evaluation of the patches is exact.
#include "surface/SmoothSurface.h"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace contour {

// How the two inner control points of a cage edge are chosen (§2.4).
enum class EdgeControlMethod {
    MinimalCurvature,   // §2.4 "minimal curvature" (method B): minimise ∫|p''|²
    MaximallyStretched, // §2.4 "maximally stretched configuration" (method A)
};
const char* toString(EdgeControlMethod method); // "minimal-curvature", "maximally-stretched"
EdgeControlMethod edgeControlMethodFromName(const std::string& name);

struct VertexNormalPatchOptions {
    EdgeControlMethod edgeMethod = EdgeControlMethod::MinimalCurvature;
    // §2.5, n > 4: apex = λ a_c + (1 − λ) a_i (a_c: mean of the corners, a_i:
    // mean of the interior control points). The paper gives no value and
    // only asks that λ avoid inflections ("buckling") between the apex and
    // the corners. We take λ = 0, the apex at the mean of the interior
    // points: for a regular (symmetric) polygon the apex is then at the
    // height of the interior points, so every fan patch has the same tangent
    // plane there and the surface falls off monotonically from the apex.
    // λ > 0 sinks the apex into a dimple (an inflection: on the cap of a
    // hexagonal prism of height 1 the surface rises outwards from the apex
    // with slope +0.12 at λ = 0.5); λ < 0 raises a cone-like peak with a
    // crease at the apex (7.4° at λ = −0.25 on a dodecahedron). The price: on
    // a dodecahedron inscribed in the unit sphere the apex lies 0.058 inside
    // the sphere (λ ≈ −0.39 would put it on the sphere, with a crease of
    // about 11° at the apex). Tested in test_vertex_normal_patches (apexLambda).
    double apexLambda = 0.0;
    // §2.8: at a vertex on the border of an open mesh, project the averaged
    // normal into the plane through its two border edges.
    bool boundaryNormalsInBorderPlane = true;
    // Our addition (the paper is silent): the §2.8 projection is skipped when
    // the averaged normal leans more than this many degrees out of the border
    // plane (the plane is then nearly the surface's tangent plane, e.g. the
    // corner of a flat sheet, and the projection would be near zero or turn
    // the normal by ~90°). Also skipped when the two border edges are
    // collinear (no plane).
    double boundaryMaxTiltDegrees = 60.0;
};

// The building blocks, exposed for tests and for other code that needs one
// edge's curve.
namespace vnp {

// §2.4: the cubic Bézier p0, p1, p2, p3 of the edge p0 -> p3 with unit vertex
// normals n0, n3, satisfying n0·(p1 − p0) = 0 and n3·(p2 − p3) = 0.
// Swapping the ends swaps p1 and p2.
std::array<Vec3, 4> edgeCubic(const Vec3& p0, const Vec3& n0, const Vec3& p3, const Vec3& n3,
                              EdgeControlMethod method);

// §2.3 step 2 / Fig. 2: a cubic replaced by two quadratics joined C1 at the
// cubic's midpoint: p0, (p0+3p1)/4, (p0+3p1+3p2+p3)/8, (3p2+p3)/4, p3.
// Symmetric: reversing the input reverses the output bit for bit.
std::array<Vec3, 5> cubicToQuadratics(const std::array<Vec3, 4>& cubic);

// §2.7: the normal at the midpoint of the edge p0 -> p3 by quadratic normal
// interpolation, n(1/2) = (n0 + n3)/2 + n_m/4 with
// n_m = −3 ((n0 + n3)·Δ / (Δ·Δ)) Δ, Δ = p3 − p0 (the notes' grouping), unit.
Vec3 quadraticMidpointNormal(const Vec3& p0, const Vec3& n0, const Vec3& p3, const Vec3& n3);

} // namespace vnp

// Output of refine(): a triangle mesh whose triangles remember their cage
// polygon, and one unit normal per vertex.
struct RefinedMesh {
    TriangleMesh mesh;
    std::vector<Vec3> normals;
};

class VertexNormalPatches final : public SmoothSurface {
public:
    // Throws std::invalid_argument on an empty cage, a face with fewer than 3
    // corners, a corner index out of range, a non-finite position, or a used
    // vertex whose averaged normal is zero.
    static std::unique_ptr<VertexNormalPatches>
    create(const PolygonMesh& cage, const VertexNormalPatchOptions& options = {});

    SurfaceKind kind() const override { return SurfaceKind::VertexNormalPatches; }
    std::string description() const override;
    SurfacePoint evaluate(const Preimage& p) const override;
    using SmoothSurface::evaluate;

    // The paper's recursive filter output (§2.5, §2.7), `levels` >= 0 passes:
    // the first pass replaces a triangle by 4 triangles, a quad by 8, an
    // n-gon by 4n, with vertices on the patches and normals by quadratic
    // normal interpolation (§2.7); every later pass applies the triangle
    // scheme again to each triangle with its vertex normals ("quadratic
    // subdivision regime", new normals by averaging). Level 0 is the domain
    // (quads split along the diagonal from corner 0) with the vertex normals.
    // Vertices of passes >= 2 lie on the paper's recursive surface, not on
    // evaluate()'s patches. Throws std::invalid_argument for levels < 0 or
    // an output of more than 100 million triangles.
    RefinedMesh refine(int levels) const;

    const VertexNormalPatchOptions& options() const { return options_; }
    // Unit normal per domain vertex: the cage's vertex normals (§2.8 applied)
    // for cage vertices, then one per apex (see refine()).
    const std::vector<Vec3>& vertexNormals() const { return normals_; }
    Index cageVertexCount() const { return cageVertexCount_; }
    // The cage polygon a domain face comes from.
    Index cageFace(Index domainFace) const { return faces_[domainFace].cageFace; }
    // The control net of a domain face: 15 points for a triangle (index
    // netIndex(j, k) for the Bézier ordinate (4 − j − k, j, k), j counting
    // towards corner 1 and k towards corner 2), 25 for a quad (index i + 5 j,
    // i along u, j along v).
    std::span<const Vec3> controlNet(Index domainFace) const;
    static int netIndex(int j, int k) { return 5 * k - k * (k - 1) / 2 + j; }
    // The cubic of cage edge (a, b), a -> b, as used by the patches.
    std::array<Vec3, 4> cageEdgeCubic(Index a, Index b) const;

private:
    VertexNormalPatches() = default;
    void build(const PolygonMesh& cage);

    struct FaceInfo {
        Index cageFace = kInvalidIndex;
        Index netOffset = 0; // first control point in net_
    };
    VertexNormalPatchOptions options_;
    Index cageVertexCount_ = 0;
    std::vector<Vec3> normals_;
    std::vector<FaceInfo> faces_;
    std::vector<Vec3> net_;
    // Cubic of every cage edge, keyed by (lower vertex << 32 | higher vertex),
    // stored from the lower to the higher vertex.
    std::unordered_map<std::uint64_t, std::array<Vec3, 4>> edgeCubics_;
};

} // namespace contour
