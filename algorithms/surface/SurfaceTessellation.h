#pragma once
// Uniform tessellation of a SmoothSurface (Hertzmann & Zorin 2000: the mesh
// is a tessellation of the smooth surface, every vertex a point of it).
//
// Level L: each domain quad becomes an L x L grid of quads, each split into
// two triangles along its shorter 3D diagonal; each domain triangle becomes
// L^2 triangles (the regular split of its barycentric grid). Vertices are
// welded by domain topology, not by position: a domain corner gives one
// vertex, a domain edge L - 1 vertices shared by both faces on it, a face
// its interior grid points. So an all-quad domain with V vertices, E edges
// and F faces gives V + E (L - 1) + F (L - 1)^2 vertices and 2 F L^2
// triangles, and a closed domain gives a closed mesh.
//
// Triangles are counter-clockwise in their face's (u, v), so the mesh has
// the domain's orientation (outward for a cage whose faces are
// counter-clockwise seen from outside).
#include "surface/SmoothSurface.h"

#include <array>
#include <memory>
#include <vector>

namespace contour {

struct SurfaceTessellation {
    int level = 0;
    // Positions are the surface's f(u) at the vertices' preimages. The mesh's
    // sourcePolygon(f) is the domain face of triangle f (for Catmull-Clark a
    // face of the once-subdivided cage, not of the cage itself).
    std::shared_ptr<const TriangleMesh> mesh;
    // Per vertex: the preimage it was evaluated at (a vertex on a shared
    // domain edge or corner has one preimage, in the first face that reached
    // it), the full surface point there (derivatives in that face's chart),
    // and the unit limit normal.
    std::vector<Preimage> preimages;
    std::vector<SurfacePoint> points;
    std::vector<Vec3> normals;
    // Per triangle: the domain face it lies in, and its corners' (u, v) in
    // that face (so a point of the triangle has a preimage by linear
    // interpolation, whichever face a corner vertex's own preimage is in).
    std::vector<Index> sourceFace;
    std::vector<std::array<Vec2, 3>> cornerUv;
};

// Throws std::invalid_argument for a level < 1 or an empty domain.
SurfaceTessellation tessellate(const SmoothSurface& surface, int level);

// tessellate() through a small cache keyed by (surface, level): the
// tessellation depends on the surface only, so every view of a surface (the
// consistent method's initialization, once per view) shares one. Entries
// hold the surface weakly and die with it. Thread-safe.
std::shared_ptr<const SurfaceTessellation>
sharedTessellation(const std::shared_ptr<const SmoothSurface>& surface, int level);

} // namespace contour
