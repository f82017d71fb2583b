#pragma once
// Catmull-Clark and Loop limit surfaces, evaluated exactly through
// OpenSubdiv's Far API (docs/dev/architecture.md): a topology refiner adaptively
// refined around extraordinary vertices and creases, a patch table of
// B-spline (regular), box-spline (Loop) and end-cap patches, and a patch map
// from ptex coordinates to patches.
//
// Domain (see SmoothSurface.h):
//   - Catmull-Clark: the cage subdivided once, all quads. A level-1 quad is
//     either a quarter of a base quad (whose ptex face is the whole quad) or
//     a whole ptex sub-face of a base n-gon; each domain face keeps its ptex
//     face and the affine map from its (u, v) to ptex (s, t).
//   - Loop: the cage triangles, one ptex face each, with the same (u, v).
// Domain vertices sit at their limit positions.
//
// Evaluation corrects two slips of Far::PatchTable::EvaluateBasis in
// OpenSubdiv 3.5 (docs/dev/debian-traps.md), checked by finite differences in
// tests/test_subdivision_surface.cpp:
//   (1) on a 180-degree rotated triangular sub-patch (Loop), the second
//       derivative weights come out with the wrong sign;
//   (2) under a non-quad base face (a Catmull-Clark ptex sub-face) the
//       derivative weights are scaled for one level too many: first
//       derivatives 2x, second derivatives 4x too large.
#include "surface/SmoothSurface.h"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace contour {

struct SubdivisionOptions {
    // Depth of adaptive feature isolation around extraordinary vertices and
    // semi-sharp features (1..10). Only the end-cap patches, which shrink by
    // half per level, are approximate; level 8 leaves them 2^-8 of a base face.
    int isolationLevel = 8;

    enum class Boundary {
        EdgeOnly,     // boundary edges interpolate the cage boundary curve
        EdgeAndCorner // and boundary vertices of valence 2 are sharp corners
    };
    Boundary boundary = Boundary::EdgeAndCorner;

    // The patches that stand in for the limit surface in the tiny region left
    // around each extraordinary vertex after isolation (OpenSubdiv end caps).
    // Both kinds interpolate the exact limit position and tangent plane at the
    // vertex and match their neighbours in position along shared edges. They
    // differ in their derivatives (measured on spot and bob, relative errors):
    //   Gregory basis (default; 20 control points, 18 on triangles): the
    //     tangent plane is continuous across the cap's edges (normals agree
    //     to 1e-10), but OpenSubdiv 3.5 differentiates an approximation of the
    //     rational Gregory blend, so inside a cap the derivatives are not those
    //     of the positions: about 1e-2 for first and 4e-2 for second
    //     derivatives against finite differences.
    //   B-spline basis (16 or 12 points): a polynomial patch whose derivatives
    //     are exact for the patch (C2 inside), but the tangent plane jumps
    //     across the cap's edges: normals differ by up to 1e-3 at level 8 and
    //     5e-2 at level 3.
    // Gregory is the default because contour extraction needs the normal, and
    // so g = (c - p) . n, to be continuous across faces; with isolation level
    // 8 a cap is 1/256 of a base face across, so the inexact derivatives touch
    // a vanishing part of the surface (none of the finite-difference samples
    // of the tests, which stay 0.05 away from the domain faces' corners).
    enum class EndCap { GregoryBasis, BSplineBasis };
    EndCap endCap = EndCap::GregoryBasis;

    // Use the cage's edge creases and corner sharpness (PolygonMesh::creases,
    // PolygonMesh::cornerSharpness, e.g. from OBJ "t crease" tags).
    bool creases = true;
};

class SubdivisionSurface final : public SmoothSurface {
public:
    // Throws std::invalid_argument when `kind` is not CatmullClark or Loop,
    // when Loop is asked of a cage with non-triangle faces, on a face with
    // fewer than 3 corners or bad crease data, or when OpenSubdiv rejects the
    // topology.
    static std::unique_ptr<SubdivisionSurface> create(const PolygonMesh& cage, SurfaceKind kind,
                                                      const SubdivisionOptions& options = {});
    ~SubdivisionSurface() override;

    SurfaceKind kind() const override { return kind_; }
    std::string description() const override;
    const SubdivisionOptions& options() const { return options_; }

    SurfacePoint evaluate(const Preimage& p) const override;
    SurfacePoint evaluateFirstOrder(const Preimage& p) const override;
    Vec3 evaluatePosition(const Preimage& p) const override;
    void evaluate(std::span<const Preimage> preimages, std::span<SurfacePoint> out) const override;

    // Sizes, for reports and benchmarks.
    int patchCount() const;
    int endCapPatchCount() const;
    int ptexFaceCount() const;

    // Where a domain face lies in ptex space: ptex (s, t) = origin + J (u, v).
    struct PtexChart {
        int ptexFace = -1;
        double s0 = 0.0, t0 = 0.0;                         // origin
        double j00 = 1.0, j01 = 0.0, j10 = 0.0, j11 = 1.0; // J, row-major
    };
    const PtexChart& chart(Index face) const { return charts_.at(static_cast<size_t>(face)); }

private:
    struct Impl;
    SubdivisionSurface(SurfaceKind kind, const SubdivisionOptions& options);

    SurfaceKind kind_;
    SubdivisionOptions options_;
    std::vector<PtexChart> charts_; // one per domain face
    // evaluate() up to derivatives of order `order` (0, 1 or 2); the others
    // are left zero. The weights and sums of each order are computed as for
    // order 2, so the values computed are the same bits.
    // (A template so that each order's loops have constant bounds.)
    template <int Order> SurfacePoint evaluateUpTo(const Preimage& p) const;
    std::unique_ptr<Impl> impl_;
};

} // namespace contour
