#pragma once
// The contour generator's per-patch segments joined across patch boundaries
// (Capouellez et al. 2023 §4.2, "View graph construction"): on the C1 spline
// the contours are continuous across patch sides and form disjoint closed
// loops, except that several loops may meet at a cone point. Chains stop at
// cones (visibility is never propagated through them) and at the surface
// boundary, so a loop through a cone comes out as an open chain from cone to
// cone.
//
// An end on a patch side meets the end of the neighbouring patch at the
// mapped parameter along the shared side (PatchAdjacency.h); an end at a patch
// corner meets an end at the same split point in any patch around it; the
// ends inside a patch (the halves of an ellipse) meet within the patch.
#include "contours/powell_sabin/PatchAdjacency.h"
#include "contours/powell_sabin/PatchContour.h"

#include <span>
#include <string>
#include <vector>

namespace contour::powell_sabin {

struct ContourChainOptions {
    // Two ends on a shared side match when their parameters along it differ
    // by at most this (a fraction of the side), and an end this close to a
    // side's end is at the patch corner; inside a patch, relative to its
    // longest side. 1e-9 is the padding of the paper's code (reading notes
    // A.3.3, "pad_amount").
    double padding = 1e-9;
    // Second chance for ends that found no partner within `padding`, such as
    // a side crossed at a grazing angle, where the two patches' independent
    // roots differ by more than round-off: matches up to this gap, and corner
    // snapping up to this distance from a corner, are made and counted in
    // ContourChaining::looseJoins. Not from the paper.
    double looseTolerance = 1e-6;
};

// Segment `segment` traversed from t0 to t1, or from t1 to t0 when reversed.
struct ChainLink {
    Index segment = kInvalidIndex;
    bool reversed = false;
};

enum class ChainEndKind {
    Cone,      // at a cone point (node)
    Boundary,  // on the surface boundary (patch side, or a boundary node)
    Unmatched, // an error: no partner found (ContourChaining::firstUnmatched)
};
const char* toString(ChainEndKind kind);

struct ChainEnd {
    ChainEndKind kind = ChainEndKind::Unmatched;
    Index node = kInvalidIndex; // the corner node when the end is at a corner
    Index patch = kInvalidIndex;
    int side = -1; // the patch side of the end, -1 at a corner or inside
};

struct ContourChain {
    std::vector<ChainLink> links; // in traversal order
    bool closed = false;
    ChainEnd front, back; // of an open chain: before links.front(), after links.back()
};

struct ContourChaining {
    std::vector<ContourChain> chains;
    Index closedLoops = 0;
    Index openChains = 0;
    Index coneEnds = 0;     // chain ends at cones
    Index boundaryEnds = 0; // chain ends on the surface boundary
    // Errors: segment ends without a partner (each is also an Unmatched
    // chain end), and the first of them described.
    Index unmatchedEnds = 0;
    std::string firstUnmatched;
    // Diagnostics of the joins made.
    Index sideJoins = 0;     // across a patch side
    Index cornerJoins = 0;   // at a patch corner that is not a cone
    Index interiorJoins = 0; // inside one patch
    Index looseJoins = 0;    // of the above, those beyond `padding`
    // Largest gap of a side or interior join (parameter along the side, or
    // uv distance over the patch's longest side).
    double maxJoinGap = 0.0;
    // Largest cosine between the two outgoing 3D tangents of a corner join
    // (-1: the contour passes straight through; -2 when there is none).
    double maxCornerTangentCosine = -2.0;
};

// Joins `segments` (ends on the sides given by startSide / endSide) into
// chains. Every segment is in exactly one chain; a loop starts at its
// lowest-numbered segment, traversed from t0. Ends without a partner are
// counted and kept as Unmatched chain ends, never dropped. Throws
// std::invalid_argument when `adjacency` and `spline` have different patch
// counts, for a segment whose patch is out of range, whose interval is empty
// or not finite, whose curve is not finite at an end, or whose side index is
// not in -1..2, and for options that are not 0 <= padding <= looseTolerance < 0.5.
ContourChaining chainContours(std::span<const ContourSegment> segments,
                              const PatchAdjacency& adjacency, const PowellSabinSpline& spline,
                              const ContourChainOptions& options = {});

} // namespace contour::powell_sabin
