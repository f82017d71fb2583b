#pragma once
// Builds the smooth surface of a control cage by kind (Catmull-Clark and Loop
// limit surfaces through OpenSubdiv, vertex-normal patches), and caches it per
// cage so that a GUI session or a 26-view batch builds it once.
#include "surface/SmoothSurface.h"

#include <memory>
#include <optional>
#include <string>

namespace contour {

// Catmull-Clark for a cage with any face that is not a triangle (quad meshes
// and mixed meshes), Loop for an all-triangle cage.
SurfaceKind automaticSurfaceKind(const PolygonMesh& cage);

// "catmull-clark", "loop", "vertex-normal-patches" (toString(SurfaceKind)),
// or nothing for any other name.
std::optional<SurfaceKind> surfaceKindFromName(const std::string& name);

// Builds the surface with the default options of its class. Throws
// std::invalid_argument (or the class's own error) when the cage does not
// suit the kind, e.g. Loop on a cage with quads.
std::shared_ptr<const SmoothSurface> makeSmoothSurface(const PolygonMesh& cage, SurfaceKind kind);

struct CachedSmoothSurface {
    std::shared_ptr<const SmoothSurface> surface;
    double buildSeconds = 0.0; // how long building it took, when it was built
    bool fromCache = false;    // true when an earlier call built it
};

// makeSmoothSurface() through a small cache keyed by (cage, kind). Entries
// hold the cage weakly and die with it. Thread-safe; concurrent calls for the
// same key build once and share the result (or the error).
CachedSmoothSurface cachedSmoothSurface(const std::shared_ptr<const PolygonMesh>& cage,
                                        SurfaceKind kind);

} // namespace contour
