#pragma once
// One vertex of the consistent method's per-view mesh (Bénard, Hertzmann &
// Kass 2014 §4, §6): its preimage u_i on the smooth surface's domain, its
// position f(u_i), its limit normal n(u_i), g(u_i) = (c - f) · n (eq. 1),
// the radial curvature and a label F / B / C, with its provenance (initial /
// inserted / shifted, and the phase that last changed it).
#include "surface/SmoothSurface.h"

#include <cstdint>

namespace contour::consistent {

// R_S at a vertex (Bénard 2014 §4): sign of g, or C for an inserted root.
enum class VertexLabel : std::int8_t { Back = -1, Contour = 0, Front = 1 };
enum class Provenance : std::int8_t { Initial = 0, Inserted = 1, Shifted = 2, Wiggled = 3 };

inline VertexLabel labelFromG(double g) {
    return g > 0.0 ? VertexLabel::Front : g < 0.0 ? VertexLabel::Back : VertexLabel::Contour;
}

struct MeshVertex {
    Preimage preimage;
    Vec3 position = Vec3::Zero(); // f(u)
    Vec3 normal = Vec3::Zero();   // n(u), unit
    double g = 0.0;               // (c - f(u)) · n(u)
    double radialCurvature = 0.0; // SurfaceFields.h convention, NaN where undefined
    // Only the final normal wiggle (§6.4) moves a vertex off the
    // surface: position = f(u) + normalOffset * n(u).
    double normalOffset = 0.0;
    bool cusp = false; // a C vertex inserted at a cusp (g = 0 and κr = 0, §6.2 d)
    VertexLabel label = VertexLabel::Contour;
    Provenance provenance = Provenance::Initial;
    int phase = 0; // the phase index that created or last changed the vertex
};

} // namespace contour::consistent
