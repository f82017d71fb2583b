// Chaining segments into polylines: loops, open chains, bifurcations.
#include "contours/common/ContourChaining.h"

#include <QtTest>

using namespace contour;

class TestChaining : public QObject {
    Q_OBJECT
private slots:
    void closedLoop() {
        const std::vector<ChainSegment> s{{2, 3, 0}, {0, 1, 1}, {3, 0, 2}, {1, 2, 3}};
        const auto chains = chainSegments(s, 4);
        QCOMPARE(chains.size(), size_t(1));
        QVERIFY(chains[0].closed);
        QCOMPARE(chains[0].nodes.size(), size_t(4));
        QCOMPARE(chains[0].segments.size(), size_t(4));
        QCOMPARE(chains[0].nodes.front(), 0);
    }
    void openChain() {
        const std::vector<ChainSegment> s{{1, 2, 0}, {0, 1, 1}, {2, 3, 2}};
        const auto chains = chainSegments(s, 5);
        QCOMPARE(chains.size(), size_t(1));
        QVERIFY(!chains[0].closed);
        QCOMPARE(chains[0].nodes, (std::vector<Index>{0, 1, 2, 3}));
    }
    // A figure eight: two loops sharing node 0 (degree 4). Chains stop at the
    // bifurcation, and every segment is used exactly once.
    void bifurcation() {
        const std::vector<ChainSegment> s{{0, 1, 0}, {1, 2, 1}, {2, 0, 2},
                                          {0, 3, 3}, {3, 4, 4}, {4, 0, 5}};
        const auto chains = chainSegments(s, 5);
        QCOMPARE(chains.size(), size_t(2));
        std::vector<int> used(s.size(), 0);
        for (const Chain& c : chains) {
            QVERIFY(!c.closed);
            QCOMPARE(c.nodes.front(), 0);
            QCOMPARE(c.nodes.back(), 0);
            for (Index i : c.segments)
                ++used[i];
        }
        QCOMPARE(used, std::vector<int>(6, 1));
    }
    void twoComponents() {
        const std::vector<ChainSegment> s{{5, 6, 0}, {6, 7, 1}, {7, 5, 2}, {0, 1, 3}};
        const auto chains = chainSegments(s, 8);
        QCOMPARE(chains.size(), size_t(2));
        int closed = 0;
        for (const Chain& c : chains)
            closed += c.closed;
        QCOMPARE(closed, 1);
    }
    void empty() { QVERIFY(chainSegments({}, 10).empty()); }
};

QTEST_APPLESS_MAIN(TestChaining)
#include "test_chaining.moc"
