#pragma once
// Stable keys of the counters phases publish in a Snapshot, with the label a
// user reads (the stepper, the JSON report, the CLI summary). Declared in one
// place, as FieldNames.h does for fields: tests and readers look counters up
// by key, so a label can be reworded without breaking them.
#include <string_view>

namespace contour {

struct CounterName {
    std::string_view key;   // kebab-case, never changes once published
    std::string_view label; // what the stepper and the reports show
};

namespace counters {

// Every snapshot (makeInputSnapshot and the phases that rebuild the mesh).
inline constexpr CounterName kFaces{"faces", "faces"};
inline constexpr CounterName kVertices{"vertices", "vertices"};
inline constexpr CounterName kEdges{"edges", "edges"};
inline constexpr CounterName kBoundaryEdges{"boundary-edges", "boundary edges"};

// The consistent method's cusp retry (a branch decided after
// contour-refinement-retriangulation), the cusp-end-push,
// cusp-end-retriangulation and contour-refinement-retriangulation phases,
// and the normal offsets every phase of §6.4's final step publishes.
inline constexpr CounterName kInconsistentFacesBefore{"inconsistent-faces-before",
                                                      "inconsistent faces before"};
inline constexpr CounterName kCuspRetryTargets{"cusp-retry-targets",
                                               "cusp retry: cusps at inconsistent faces"};
inline constexpr CounterName kCuspRetryRuns{"cusp-retry-runs", "cusp retry: runs"};
inline constexpr CounterName kCuspRetryAdopted{"cusp-retry-adopted",
                                               "cusp retry: run adopted (0: none)"};
inline constexpr CounterName kCuspRetryBroken{"cusp-retry-broken",
                                              "cusp retry: better runs breaking a post-condition"};
inline constexpr CounterName kCuspRetryCusps{"cusp-retry-cusps",
                                             "cusp retry: cusps refined around"};
inline constexpr CounterName kCuspRetryEdgesHalved{"cusp-retry-edges-halved",
                                                   "cusp retry: edges halved"};
inline constexpr CounterName kVerticesOffSurface{"vertices-off-surface",
                                                 "vertices off the surface"};
inline constexpr CounterName kLargestNormalOffsetRatio{"largest-normal-offset-ratio",
                                                       "largest offset / mean one-ring distance"};
inline constexpr CounterName kLargestContourShift{
    "largest-contour-shift", "largest image shift of a C vertex off the surface (px)"};
inline constexpr CounterName kCuspEndsPushed{"cusp-ends-pushed",
                                             "cusp radial ends pushed (extension-cusp-push-final)"};
inline constexpr CounterName kOtherEndsPushed{
    "other-ends-pushed", "other radial ends pushed (extension-push-every-end-final)"};
inline constexpr CounterName kPushWiggleTried{"push-wiggle-tried", "vertices tried after the push"};
inline constexpr CounterName kPushWiggleAccepted{"push-wiggle-accepted",
                                                 "vertices accepted after the push"};
inline constexpr CounterName kPushWiggleRejectedFold{"push-wiggle-rejected-fold",
                                                     "offsets rejected (3D fold) after the push"};
inline constexpr CounterName kCuspEndFacesSearched{
    "cusp-end-faces-searched",
    "faces at a cusp's radial end searched (cusp-end-retriangulation-faces)"};
inline constexpr CounterName kCuspEndFacesSearchedAfterRefinement{
    "cusp-end-faces-searched-after-refinement",
    "faces at a cusp's radial end searched after contour refinement"};
inline constexpr CounterName kCuspEndDiscs{"cusp-end-discs",
                                           "discs re-triangulated at a cusp's radial end"};

} // namespace counters
} // namespace contour
