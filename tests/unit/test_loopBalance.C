/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    LoopBalance: the pair loop's chunks, evened out by the threads' times.
    Synthetic workloads with known costs per item: the chunks always cover
    the range once and in order, the times even out, and one outlier
    moves a boundary by at most the step's limit. Claimed blocks (a thread
    done with its chunk takes blocks of the others'): under real threads
    with one of them held up until the others are done, every item is
    taken exactly once, the held thread's chunk is partly taken by the
    others, and the times recorded for part of a chunk are extrapolated to
    the whole. (That the pair loop's results do not depend on who takes a
    pair is the thread-count tests' part: 1 thread = 2 threads,
    test_integration.C and others.)
\*---------------------------------------------------------------------------*/

#include "LoopBalance.H"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <random>
#include <thread>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace iceDEM;

namespace
{

//- The chunks of a team of T threads over n items: contiguous, in thread
//  order, covering [0, n) once
void expectPartition(const LoopBalance& b, int T, int n)
{
    int next = 0;
    for (int t = 0; t < T; ++t)
    {
        int begin, end;
        b.chunk(t, T, n, begin, end);
        EXPECT_EQ(begin, next) << "thread " << t;
        EXPECT_LE(begin, end) << "thread " << t;
        next = end;
    }
    EXPECT_EQ(next, n);
}

//- Thread t's chunk of n items in a team of T threads is [begin, end)
void expectChunk(const LoopBalance& b, int t, int T, int n, int begin, int end)
{
    int first, last;
    b.chunk(t, T, n, first, last);
    EXPECT_EQ(first, begin) << "thread " << t << " of " << T;
    EXPECT_EQ(last, end) << "thread " << t << " of " << T;
}

//- Each thread's time for its chunk under the cost per item 'cost'
std::vector<double> chunkTimes
(
    const LoopBalance& b, int T, const std::vector<double>& cost
)
{
    const int n = static_cast<int>(cost.size());
    std::vector<double> times(T, 0);
    for (int t = 0; t < T; ++t)
    {
        int begin, end;
        b.chunk(t, T, n, begin, end);
        for (int k = begin; k < end; ++k) times[t] += cost[k];
    }
    return times;
}

//- Evaluations of the loop: times recorded, then rebalanced
void run(LoopBalance& b, int T, const std::vector<double>& cost, int evaluations)
{
    for (int e = 0; e < evaluations; ++e)
    {
        const std::vector<double> times = chunkTimes(b, T, cost);
        for (int t = 0; t < T; ++t) b.record(t, T, times[t]);
        b.rebalance(T);
    }
}

} // anonymous namespace


TEST(LoopBalance, equalChunksAtFirstAndForAnotherTeamSize)
{
    LoopBalance b;
    b.resize(2);
    expectChunk(b, 0, 2, 1000, 0, 500);
    expectChunk(b, 1, 2, 1000, 500, 1000);

    // Moved for a team of two, a team of one (a region not entered in
    // parallel) takes everything, one of three equal thirds
    std::vector<double> cost(1000, 1.0);
    for (int k = 0; k < 300; ++k) cost[k] = 3;
    run(b, 2, cost, 100);
    expectChunk(b, 0, 1, 1000, 0, 1000);
    expectChunk(b, 1, 3, 999, 333, 666);
}


TEST(LoopBalance, timesEvenOut)
{
    // The expensive items first (the structure's pairs come first in the
    // pair order): equal counts give two threads times 1100 and 500
    for (const int T : {2, 3, 4})
    {
        std::vector<double> cost(1000, 1.0);
        for (int k = 0; k < 300; ++k) cost[k] = 3;
        LoopBalance b;
        b.resize(T);
        const std::vector<double> before = chunkTimes(b, T, cost);
        run(b, T, cost, 200);
        expectPartition(b, T, 1000);
        const std::vector<double> after = chunkTimes(b, T, cost);
        double total = 0, largestBefore = 0, largest = 0;
        for (int t = 0; t < T; ++t)
        {
            total += after[t];
            largestBefore = std::max(largestBefore, before[t]);
            largest = std::max(largest, after[t]);
        }
        // Within the cost of the dearest item of the ideal share (the
        // items are whole: no split is closer in general)
        EXPECT_LE(largest, total/T + 3) << T << " threads";
        EXPECT_GT(largestBefore, total/T + 100) << T << " threads";
    }
}


TEST(LoopBalance, anOutlierMovesABoundaryLittle)
{
    const int n = 100000;
    std::vector<double> cost(n, 1.0);
    LoopBalance b;
    b.resize(2);
    run(b, 2, cost, 10);
    int begin0, end0;
    b.chunk(0, 2, n, begin0, end0);
    EXPECT_EQ(end0, n/2);

    // Thread 0 held up once by a factor of 100
    std::vector<double> times = chunkTimes(b, 2, cost);
    b.record(0, 2, 100*times[0]);
    b.record(1, 2, times[1]);
    b.rebalance(2);
    int begin1, end1;
    b.chunk(0, 2, n, begin1, end1);
    EXPECT_LT(end1, end0);
    EXPECT_LE(end0 - end1, 0.005*n + 1);

    // ...and it comes back as the times even out again
    run(b, 2, cost, 10);
    b.chunk(0, 2, n, begin1, end1);
    EXPECT_EQ(end1, n/2);
}


TEST(LoopBalance, chunksStayAPartitionUnderRandomTimes)
{
    std::mt19937 gen(7);
    std::uniform_real_distribution<double> time(1e-6, 1.0);
    std::uniform_int_distribution<int> items(0, 5000);
    for (const int T : {2, 3, 8})
    {
        LoopBalance b;
        b.resize(T);
        for (int e = 0; e < 2000; ++e)
        {
            for (int t = 0; t < T; ++t) b.record(t, T, time(gen));
            b.rebalance(T);
            expectPartition(b, T, items(gen));
        }
    }
}


TEST(LoopBalance, timesAreUsedOnce)
{
    // The body sums' balance moves at the next evaluation's start, which
    // may come without new times (a step whose team was of another size):
    // then nothing moves
    const int n = 1000;
    LoopBalance b;
    b.resize(2);
    b.record(0, 2, 3.0);
    b.record(1, 2, 1.0);
    b.rebalance(2);
    int begin, end;
    b.chunk(0, 2, n, begin, end);
    const int moved = end;
    EXPECT_LT(moved, n/2);
    for (int e = 0; e < 10; ++e) b.rebalance(2);
    b.chunk(0, 2, n, begin, end);
    EXPECT_EQ(end, moved);

    // Times of one thread only: not used, and not kept for later
    b.record(0, 2, 3.0);
    b.rebalance(2);
    b.record(1, 2, 1.0);
    b.rebalance(2);
    b.chunk(0, 2, n, begin, end);
    EXPECT_EQ(end, moved);
}


TEST(LoopBalance, oneThreadClaimsItsChunkInOrder)
{
    LoopBalance b;
    b.resize(1);
    std::vector<int> seen;
    int blocks = 0;
    forEachClaimedBlock
    (
        b, 0, 1, 1000, 64, []{ return 0.0; },
        [&](int begin, int end, bool own)
        {
            EXPECT_TRUE(own);
            EXPECT_LE(end - begin, 64);
            for (int k = begin; k < end; ++k) seen.push_back(k);
            ++blocks;
        }
    );
    ASSERT_EQ(int(seen.size()), 1000);
    for (int k = 0; k < 1000; ++k) EXPECT_EQ(seen[k], k);
    EXPECT_EQ(blocks, 16);
}


TEST(LoopBalance, aHeldThreadsBlocksAreTakenByTheOthersEveryItemOnce)
{
    #ifdef _OPENMP
    for (const int T : {2, 3})
    {
        const int n = 3000;
        LoopBalance b;
        b.resize(T);
        for (int evaluation = 0; evaluation < 5; ++evaluation)
        {
            std::vector<std::atomic<int>> taken(n);
            for (auto& x : taken) x = 0;
            std::atomic<int> stolen{0};
            // Threads that called work once (each after opening its
            // chunk), and threads other than 0 done with their own chunks
            std::atomic<int> started{0};
            std::atomic<int> othersDone{0};
            int teamSize = 0;
            #pragma omp parallel num_threads(T)
            {
                const int t = omp_get_thread_num();
                const int team = omp_get_num_threads();
                #pragma omp single
                teamSize = team;
                bool first = true;
                bool ownDone = false;
                forEachClaimedBlock
                (
                    b, t, team, n, 32, &omp_get_wtime,
                    [&](int begin, int end, bool own)
                    {
                        if (first)
                        {
                            // Every chunk open before anyone looks at it
                            // (whatever the scheduler does on a busy
                            // machine): the first block is a thread's own
                            first = false;
                            ++started;
                            while (started.load() < team) std::this_thread::yield();
                        }
                        for (int k = begin; k < end; ++k) ++taken[k];
                        if (!own)
                        {
                            ++stolen;
                            if (!ownDone && t != 0) ++othersDone;
                            ownDone = true;
                        }
                        // Thread 0 is held up (another process on its
                        // core) in its first block until the others are
                        // done with their chunks and take from its
                        if (t == 0)
                        {
                            while (othersDone.load() < team - 1) std::this_thread::yield();
                        }
                    }
                );
                // A thread that ended without taking a block (none left)
                if (t != 0 && !ownDone) ++othersDone;
            }
            ASSERT_EQ(teamSize, T);
            for (int k = 0; k < n; ++k)
            {
                ASSERT_EQ(taken[k].load(), 1) << "item " << k << ", T " << T;
            }
            // Thread 0 held its chunk (about n/T items, 32 a block) after
            // its first block until every other thread had taken a block
            // not its own, which thread 0's left blocks ensure: at least
            // one each
            EXPECT_GE(stolen.load(), T - 1) << "T " << T;
            b.rebalance(T);
        }
    }
    #else
    GTEST_SKIP() << "built without OpenMP";
    #endif
}


TEST(LoopBalance, partOfAChunkCountsAsTheWholeAtItsRate)
{
    // Thread 0 did half of its 500 items in 1 s (the rest taken from it),
    // thread 1 all of its 500 in 1 s: as if thread 0 had taken 2 s
    const int n = 1000;
    LoopBalance a, b;
    a.resize(2);
    b.resize(2);
    a.record(0, 2, 1.0, 250, 500);
    a.record(1, 2, 1.0, 500, 500);
    b.record(0, 2, 2.0);
    b.record(1, 2, 1.0);
    a.rebalance(2);
    b.rebalance(2);
    int beginA, endA, beginB, endB;
    a.chunk(0, 2, n, beginA, endA);
    b.chunk(0, 2, n, beginB, endB);
    EXPECT_LT(endA, n/2);
    EXPECT_EQ(endA, endB);
}
