#include "contours/traced/CurveTracer.h"

#include "contours/traced/ContourCorrector.h"
#include "contours/traced/DomainFaceGeometry.h"
#include "core/SegmentDistance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace contour::traced {

const char* toString(CurveEnd end) {
    switch (end) {
    case CurveEnd::Closed:
        return "closed";
    case CurveEnd::Boundary:
        return "boundary";
    case CurveEnd::Stalled:
        return "stalled";
    case CurveEnd::Singular:
        return "singular";
    case CurveEnd::Collision:
        return "collision";
    case CurveEnd::TooLong:
        return "too-long";
    case CurveEnd::AlongEdge:
        return "along-edge";
    }
    return "unknown";
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct StepPoint {
    Vec2 uv = Vec2::Zero();
    ContourSample sample;
};

enum class FaceEnd { Exit, Crossed, Closed, LeftFace, Stalled, Singular, TooLong };

struct FaceTrace {
    FaceEnd end = FaceEnd::Stalled;
    Index exitRoot = kInvalidIndex;
    // Crossed: the curve left through `crossingEdge` where the edge has no
    // root (a contour tangent to the edge, or running along it, within the
    // tolerance): the next point, just across, in this face's chart.
    int crossingEdge = -1;
    StepPoint crossing;
    Vec2 crossingBoundary = Vec2::Zero(); // where the chord to it crosses the edge
    std::vector<StepPoint> points; // accepted points after the start, without the exit root
};

class Tracer {
public:
    Tracer(const SmoothSurface& surface, const Camera& camera, const EdgeSeeds& seeds,
           const TracerOptions& options, TracerStats& stats)
        : surface_(surface), camera_(camera), seeds_(seeds), options_(options), stats_(stats) {
        corrector_.gTolerance = options.gTolerance;
    }

    StepPoint sampleAt(Index face, const Vec2& uv) const {
        return {uv, sampleContourField(surface_, camera_, {face, uv.x(), uv.y()})};
    }

    Vec2 exitUv(Index root) const {
        const Preimage& p = seeds_.roots[static_cast<size_t>(root)].exitSide;
        return {p.u, p.v};
    }

    void startCurve() { stepsThisCurve_ = 0; }

    // The chord's midpoint's distance to g = 0 (first order), in parameters.
    double deviation(Index face, const Vec2& a, const Vec2& b) const {
        const StepPoint m = sampleAt(face, 0.5 * (a + b));
        const double n = m.sample.gradient.norm();
        return n > 0.0 ? std::abs(m.sample.g) / n : kInfinity;
    }

    FaceTrace traceFace(Index face, const StepPoint& start, bool interior) {
        const bool quad = surface_.isQuad(face);
        const double cosTurn = std::cos(options_.maxTurn);
        const Vec2 startTangent = contourTangent(start.sample.gradient);
        FaceTrace out;
        StepPoint x = start;
        double h = options_.maxStep;
        int accepted = 0;
        for (;;) {
            if (++stepsThisCurve_ > options_.maxSteps) {
                out.end = FaceEnd::TooLong;
                return out;
            }
            if (!(x.sample.gradient.norm() > options_.singularGradient)) {
                ++stats_.singularPoints;
                out.end = FaceEnd::Singular;
                return out;
            }
            ++stats_.steps;
            const Vec2 tangent = contourTangent(x.sample.gradient);
            const Vec2 predicted = x.uv + h * tangent;
            bool reject = false, leaving = false;
            Vec2 leaveTo = predicted;
            StepPoint y;
            if (!insideFace(quad, predicted)) {
                leaving = true;
            } else {
                const CorrectedPoint c =
                    correctOntoContour(surface_, camera_, face, predicted, corrector_);
                if (!c.converged || (c.uv - predicted).norm() > 0.5 * h) {
                    reject = true;
                } else if (!insideFace(quad, c.uv)) {
                    leaving = true;
                    leaveTo = c.uv;
                } else {
                    y = {c.uv, c.sample};
                    reject = contourTangent(y.sample.gradient).dot(tangent) < cosTurn ||
                             deviation(face, x.uv, y.uv) > options_.maxDeviation;
                }
            }
            if (leaving && interior) {
                // A long step can cut across the face's edge next to a small
                // loop: the curve leaves only if a short step does too.
                if (h <= 4.0 * options_.maxDeviation) {
                    out.end = FaceEnd::LeftFace;
                    return out;
                }
                leaving = false;
                reject = true;
            }
            if (leaving) {
                const FaceExit exit = segmentExit(quad, x.uv, leaveTo);
                const Vec2 boundary = x.uv + exit.s * (leaveTo - x.uv);
                Index best = kInvalidIndex;
                double d1 = kInfinity, d2 = kInfinity;
                for (Index r : seeds_.exitsOfFace[static_cast<size_t>(face)]) {
                    const double d = (exitUv(r) - boundary).norm();
                    if (d < d1) {
                        d2 = d1;
                        d1 = d;
                        best = r;
                    } else if (d < d2) {
                        d2 = d;
                    }
                }
                // The nearest root where the contour leaves the face, when it
                // is unambiguous and the chord to it stays on the curve.
                if (best != kInvalidIndex && d1 <= 2.0 * h &&
                    (d2 > 2.0 * d1 || h <= 2.0 * options_.minStep) &&
                    deviation(face, x.uv, exitUv(best)) <= options_.maxDeviation) {
                    out.end = FaceEnd::Exit;
                    out.exitRoot = best;
                    return out;
                }
                // No root where a short step leaves: the contour touches the
                // edge or runs along it (a view not in general position), so
                // the step crosses into the neighbour without a root.
                if (h <= 4.0 * options_.maxDeviation &&
                    surface_.neighbor(face, exit.edge).face != kInvalidIndex) {
                    const CorrectedPoint c =
                        correctOntoContour(surface_, camera_, face, predicted, corrector_);
                    if (c.converged && (c.uv - predicted).norm() <= 0.5 * h) {
                        const FaceExit across = segmentExit(quad, x.uv, c.uv);
                        out.end = FaceEnd::Crossed;
                        out.crossingEdge = across.edge >= 0 ? across.edge : exit.edge;
                        out.crossing = {c.uv, c.sample};
                        out.crossingBoundary =
                            across.edge >= 0 ? Vec2(x.uv + across.s * (c.uv - x.uv)) : boundary;
                        return out;
                    }
                }
                reject = true;
            }
            if (reject) {
                ++stats_.rejectedSteps;
                h *= 0.5;
                if (h >= options_.minStep)
                    continue;
                ++stats_.stalls;
                if (recover(face, x, tangent, interior, start, out))
                    return out;
                out.end = FaceEnd::Stalled;
                return out;
            }
            ++accepted;
            // Summers 2016 §3.4.2.1: stop when the curve is back at its start.
            if (interior && accepted >= 3 &&
                pointSegmentDistance(start.uv, x.uv, y.uv) <= 0.5 * h + options_.maxDeviation &&
                contourTangent(y.sample.gradient).dot(startTangent) > 0.5) {
                out.end = FaceEnd::Closed;
                return out;
            }
            out.points.push_back(y);
            x = y;
            h = std::min(1.5 * h, options_.maxStep);
        }
    }

private:
    // A stalled step next to where the curve must go: the nearest exit root
    // ahead, or (interior loops) the start, within the recovery radius.
    bool recover(Index face, const StepPoint& x, const Vec2& tangent, bool interior,
                 const StepPoint& start, FaceTrace& out) {
        const double radius = 20.0 * options_.maxDeviation;
        if (interior) {
            if ((start.uv - x.uv).norm() <= radius) {
                ++stats_.recoveredStalls;
                out.end = FaceEnd::Closed;
                return true;
            }
            return false;
        }
        Index best = kInvalidIndex;
        double bestDistance = radius;
        for (Index r : seeds_.exitsOfFace[static_cast<size_t>(face)]) {
            const Vec2 d = exitUv(r) - x.uv;
            if (d.dot(tangent) >= 0.0 && d.norm() <= bestDistance) {
                bestDistance = d.norm();
                best = r;
            }
        }
        if (best == kInvalidIndex)
            return false;
        ++stats_.recoveredStalls;
        out.end = FaceEnd::Exit;
        out.exitRoot = best;
        return true;
    }

    const SmoothSurface& surface_;
    const Camera& camera_;
    const EdgeSeeds& seeds_;
    TracerOptions options_;
    TracerStats& stats_;
    CorrectorOptions corrector_;
    long long stepsThisCurve_ = 0;
};

CurveEnd curveEnd(FaceEnd end) {
    switch (end) {
    case FaceEnd::Singular:
        return CurveEnd::Singular;
    case FaceEnd::TooLong:
        return CurveEnd::TooLong;
    default:
        return CurveEnd::Stalled;
    }
}

void addPoint(TracedCurve& c, Index face, const StepPoint& p) {
    c.points.push_back(
        {{face, p.uv.x(), p.uv.y()}, p.sample.point.position, p.sample.g, kInvalidIndex});
}

void addRootPoint(TracedCurve& c, const EdgeRoot& root, Index index) {
    const Preimage& p = root.entrySide.face != kInvalidIndex ? root.entrySide : root.exitSide;
    c.points.push_back({p, root.position, root.g, index});
}

// Segments of one face's trace from `from`, each point added after it.
Vec2 appendFaceTrace(TracedCurve& c, Index face, const Vec2& from, const FaceTrace& trace) {
    Vec2 previous = from;
    for (const StepPoint& p : trace.points) {
        c.segments.push_back({face, previous, p.uv});
        addPoint(c, face, p);
        previous = p.uv;
    }
    return previous;
}

} // namespace

std::vector<TracedCurve> traceContours(const SmoothSurface& surface, const Camera& camera,
                                       const EdgeSeeds& seeds, const InteriorSeeds& interior,
                                       const TracerOptions& options, TracerStats* statsOut) {
    TracerStats stats;
    Tracer tracer(surface, camera, seeds, options, stats);
    const size_t rootCount = seeds.roots.size();
    std::vector<std::uint8_t> used(rootCount, 0);
    std::vector<long long> openCurveStartingAt(rootCount, -1);
    std::vector<TracedCurve> curves;
    std::vector<std::uint8_t> joined;
    for (size_t r0 = 0; r0 < rootCount; ++r0) {
        const EdgeRoot& first = seeds.roots[r0];
        // A root where the contour leaves the surface is reached, not started from.
        if (used[r0] || first.entrySide.face == kInvalidIndex)
            continue;
        used[r0] = 1;
        tracer.startCurve();
        TracedCurve c;
        addRootPoint(c, first, static_cast<Index>(r0));
        // Where the curve goes on: a face and a point of it on the curve.
        Index face = first.entrySide.face;
        int rootless = 0;
        Vec2 at(first.entrySide.u, first.entrySide.v);
        for (;;) {
            const StepPoint start = tracer.sampleAt(face, at);
            const FaceTrace trace = tracer.traceFace(face, start, false);
            const Vec2 last = appendFaceTrace(c, face, start.uv, trace);
            if (trace.end == FaceEnd::Crossed) {
                // The point ahead, in the neighbour's chart (evaluating it
                // in this one would clamp it to the face), back onto g = 0.
                const Preimage across = surface.transferAcrossEdge(
                    {face, trace.crossing.uv.x(), trace.crossing.uv.y()}, trace.crossingEdge);
                CorrectorOptions corrector;
                corrector.gTolerance = options.gTolerance;
                const CorrectedPoint there = correctOntoContour(
                    surface, camera, across.face, Vec2(across.u, across.v), corrector);
                if (!there.converged) {
                    c.end = CurveEnd::Stalled;
                    break;
                }
                if (++rootless > options.maxRootlessCrossings) {
                    c.end = CurveEnd::AlongEdge;
                    break;
                }
                c.segments.push_back({face, last, trace.crossingBoundary});
                face = across.face;
                at = there.uv;
                addPoint(c, face, {there.uv, there.sample});
                ++stats.rootlessCrossings;
                continue;
            }
            if (trace.end != FaceEnd::Exit) {
                c.end = curveEnd(trace.end);
                break;
            }
            const Index next = trace.exitRoot;
            const EdgeRoot& exit = seeds.roots[static_cast<size_t>(next)];
            c.segments.push_back({face, last, Vec2(exit.exitSide.u, exit.exitSide.v)});
            if (next == static_cast<Index>(r0)) {
                c.closed = true;
                c.end = CurveEnd::Closed;
                break;
            }
            if (used[static_cast<size_t>(next)]) {
                // An open piece that starts here continues this one.
                const long long k = openCurveStartingAt[static_cast<size_t>(next)];
                if (k >= 0 && !joined[static_cast<size_t>(k)]) {
                    TracedCurve& piece = curves[static_cast<size_t>(k)];
                    c.points.insert(c.points.end(), piece.points.begin(), piece.points.end());
                    c.segments.insert(c.segments.end(), piece.segments.begin(),
                                      piece.segments.end());
                    c.end = piece.end;
                    joined[static_cast<size_t>(k)] = 1;
                    openCurveStartingAt[static_cast<size_t>(next)] = -1;
                    ++stats.joinedPieces;
                } else {
                    ++stats.collisions;
                    addRootPoint(c, exit, next);
                    c.end = CurveEnd::Collision;
                }
                break;
            }
            used[static_cast<size_t>(next)] = 1;
            addRootPoint(c, exit, next);
            if (exit.entrySide.face == kInvalidIndex) {
                c.end = CurveEnd::Boundary;
                break;
            }
            face = exit.entrySide.face;
            at = Vec2(exit.entrySide.u, exit.entrySide.v);
        }
        if (!c.closed)
            openCurveStartingAt[r0] = static_cast<long long>(curves.size());
        curves.push_back(std::move(c));
        joined.push_back(0);
    }
    for (size_t r = 0; r < rootCount; ++r)
        stats.unreachedRoots += !used[r];

    // Interior loops: seeds already on a traced curve are duplicates.
    std::vector<std::vector<TracedSegment>> faceSegments(
        static_cast<size_t>(surface.domain().faceCount()));
    const auto indexSegments = [&](const TracedCurve& c) {
        for (const TracedSegment& s : c.segments)
            faceSegments[static_cast<size_t>(s.face)].push_back(s);
    };
    for (size_t k = 0; k < curves.size(); ++k)
        if (!joined[k])
            indexSegments(curves[k]);
    const double duplicateDistance = 4.0 * options.maxDeviation;
    for (const InteriorSeed& seed : interior.seeds) {
        const Index face = seed.point.face;
        const Vec2 uv(seed.point.u, seed.point.v);
        bool onCurve = false;
        for (const TracedSegment& s : faceSegments[static_cast<size_t>(face)])
            onCurve = onCurve || pointSegmentDistance(uv, s.a, s.b) <= duplicateDistance;
        if (onCurve) {
            ++stats.interiorSeedsOnCurves;
            continue;
        }
        tracer.startCurve();
        const StepPoint start = tracer.sampleAt(face, uv);
        const FaceTrace trace = tracer.traceFace(face, start, true);
        if (trace.end == FaceEnd::LeftFace) {
            ++stats.interiorSeedsLeavingFace;
            continue;
        }
        if (trace.end != FaceEnd::Closed)
            continue;
        TracedCurve c;
        c.interior = true;
        c.closed = true;
        addPoint(c, face, start);
        const Vec2 last = appendFaceTrace(c, face, start.uv, trace);
        c.segments.push_back({face, last, start.uv});
        indexSegments(c);
        curves.push_back(std::move(c));
        joined.push_back(0);
    }

    std::vector<TracedCurve> out;
    for (size_t k = 0; k < curves.size(); ++k)
        if (!joined[k])
            out.push_back(std::move(curves[k]));
    for (const TracedCurve& c : out)
        for (const TracedPoint& p : c.points)
            stats.maxAbsG = std::max(stats.maxAbsG, std::abs(p.g));
    if (statsOut)
        *statsOut = stats;
    return out;
}

} // namespace contour::traced
