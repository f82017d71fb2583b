#pragma once
// The bracket [lo, hi] of t in [0, 1] of a regula-falsi root search with the
// Illinois modification: the end kept twice in a row has its value halved,
// so the bracket shrinks from both sides. Written by hand (a few lines; the
// callers evaluate their own function in appendix B charts, which no
// library root finder can drive). Used for the radial root of the parameter
// wiggle (Bénard 2014 §6.4) and the contour points of the cusp search
// (§6.2 d).

namespace contour::consistent {

struct IllinoisBracket {
    double lo = 0.0, hi = 1.0;
    double flo = 0.0, fhi = 0.0; // the function's values at lo and hi
    int side = 0;                // -1: lo was replaced last, +1: hi

    double falsePosition() const { return (lo * fhi - hi * flo) / (fhi - flo); }
    // f = the function at t; sameSignAsLo decides which end t replaces (each
    // caller keeps its own test of the sign).
    void keep(double t, double f, bool sameSignAsLo) {
        if (sameSignAsLo) {
            lo = t;
            flo = f;
            if (side == -1)
                fhi *= 0.5;
            side = -1;
        } else {
            hi = t;
            fhi = f;
            if (side == 1)
                flo *= 0.5;
            side = 1;
        }
    }
};

} // namespace contour::consistent
