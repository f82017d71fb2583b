#pragma once
// Seeds for contour loops that lie inside one domain face and so cross no
// edge (Summers 2016 §3.3: edge roots alone miss them). g vanishes on such a
// loop and not inside it, so the disc it bounds holds an extremum of g.
// Summers seeds every level-set loop from the Morse-Smale complex of g;
// this is not that construction. Here the critical points are found by
// Newton's method on grad g = 0 started from the discrete extrema of g on a
// lattice of each face (interior nodes larger or smaller than all their
// neighbours), and each extremum casts rays in the chart until g changes
// sign: the first sign change on each ray is a point of a loop around it.
// Not certified: an extremum that no lattice node sees (a loop much smaller
// than the lattice step next to a steeper trend of g) is missed.
#include "camera/Camera.h"
#include "surface/SmoothSurface.h"

#include <memory>
#include <vector>

namespace contour::traced {

// Positions and unit normals on each face's lattice (view-independent).
struct FaceLattice {
    int steps = 0;
    std::vector<size_t> offset; // per face, its first node
    std::vector<Vec2> uv;       // per node
    std::vector<Vec3> positions, normals;
};

std::shared_ptr<const FaceLattice> sharedFaceLattice(const std::shared_ptr<const SmoothSurface>& s,
                                                     int steps);

struct InteriorSeed {
    Preimage point;         // on g = 0
    Preimage criticalPoint; // the extremum it was cast from
};

struct InteriorSeedOptions {
    int raysPerExtremum = 8;
    int newtonIterations = 12;
    double gTolerance = 0.0; // |g| the seeds are corrected to
};

struct InteriorSeeds {
    std::vector<InteriorSeed> seeds;
    long long candidates = 0; // discrete extrema of the lattices
    long long criticalPoints = 0, extrema = 0, saddles = 0;
};

InteriorSeeds findInteriorSeeds(const SmoothSurface& surface, const FaceLattice& lattice,
                                const Camera& camera, const InteriorSeedOptions& options);

} // namespace contour::traced
