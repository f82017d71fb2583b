#include "contours/consistent/edits/OptimizationSweep.h"

#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/predicates/FaceClassification.h"

namespace contour::consistent {

void sweepInconsistent(ConsistentMesh& m, int maxSweeps, bool visitVertices,
                       OptimizationTally& tally, const std::function<bool(Index)>& tryMove,
                       const std::function<void()>& checkCancelled) {
    std::vector<Index> faces = inconsistentFaces(m);
    tally.before = static_cast<long long>(faces.size());
    while (tally.sweeps < maxSweeps && !faces.empty()) {
        ++tally.sweeps;
        long long accepted = 0;
        for (Index x : visitVertices ? verticesOf(m, faces) : faces) {
            if (checkCancelled)
                checkCancelled();
            // Face moves keep face indices valid within a sweep; an earlier
            // move may have fixed or rewritten this face.
            if (!visitVertices && faceIsConsistent(m, x))
                continue;
            ++tally.tried;
            accepted += tryMove(x);
        }
        tally.accepted += accepted;
        if (accepted == 0)
            break;
        faces = inconsistentFaces(m);
        tally.sweepLimitHit = tally.sweeps == maxSweeps && !faces.empty();
    }
}

} // namespace contour::consistent
