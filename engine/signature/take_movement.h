// Whole takes compared by their movement rather than their poses: which parts of the body move,
// how they move (back and forth or in one sweep), where the body travels and turns, and the
// order of it all. A performer's style changes the posture, the amplitude and the tempo of an
// action; this distance is built to be blind to those three (docs/design/signatures.md, §12,
// gives the rule and what it was measured against).
//
// A take is read as its landmarks (head, shoulders, elbows, wrists, knees, ankles:
// body_landmarks.h) in the body's own frame: relative to the pelvis, the heading removed,
// lengths in body heights (the rest pose's head-to-ankles distance). From them:
//  * the summary, three blocks:
//      shares    each landmark's mean speed over the sum of all of theirs (what moves);
//      windings  log(1 + path / extent) per landmark: a sweep is about 1, a wave or a step cycle
//                many (how it moves, whatever the amplitude);
//      travel    the root's mean horizontal speed (body heights per second), its net turn and
//                its total turning (radians per second): where the body goes, left kept apart
//                from right;
//  * the steps: at 10 per second, the landmarks' velocities divided by the take's mean
//    landmark speed (the amplitude removed), the root's forward and sideways velocity and the
//    yaw rate.
// Two takes' distance is Summary + Steps, each divided by its median over the pairs compared:
//  * Summary: the Euclidean distance after every value is z-scored over the takes compared and
//    each block divided by the square root of its size (the three blocks weigh alike);
//  * Steps: dynamic time warping of the step sequences (Euclidean local cost, no band), divided
//    by n + m as take_dtw.h does (the tempo removed).
// Distances depend on the set of takes compared (the z-scores, the medians), not on the thread
// count. Nothing is trained: no seed.
// Thread-safety: pure functions; the matrix runs in its own task_arena.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/motion/body_landmarks.h"

namespace motif {

struct TakeMovement {
  std::vector<double> shares;    // per landmark
  std::vector<double> windings;  // per landmark
  std::vector<double> travel;    // mean speed, net turn rate, turning rate
  Eigen::MatrixXd steps;         // one row per step: 3 per landmark, then forward, sideways, yaw
};

// The steps' rate, per second.
inline constexpr double kMovementStepsPerSecond = 10.0;

// The fewest frames a take at `fps` needs to be compared by movement: two steps.
uint64_t MovementMinimumFrames(double fps);

// The movement of clip `clip` of `reader`. InvalidArgument naming the clip when it has fewer
// than two steps (0.2 s) or the landmarks do not fit the skeleton; the reader's errors.
Result<TakeMovement> ReadTakeMovement(const FrameFileReader& reader, uint32_t clip,
                                      const BodyLandmarks& landmarks);

// Summary + Steps between every pair of `takes` (above). `progress(done, total)` counts rows.
Eigen::MatrixXd MovementDistanceMatrix(
    const std::vector<TakeMovement>& takes, int threads,
    const std::function<void(uint64_t, uint64_t)>& progress = nullptr);

// The distances from takes[query] to every take (0 to itself): Summary + Steps as above, the
// z-scores over all the takes but each term over its median over the query's row, so one query
// costs one row of DTWs (its order can differ a little from the matrix row's).
std::vector<double> MovementDistancesFrom(const std::vector<TakeMovement>& takes, size_t query,
                                          int threads);

// ReadTakeMovement of each of `clips` (the archive's skeleton must be a humanoid
// FindBodyLandmarks reads), then MovementDistanceMatrix.
Result<Eigen::MatrixXd> TakeMovementMatrix(
    const FrameFileReader& reader, const std::vector<uint32_t>& clips, int threads,
    const std::function<void(uint64_t, uint64_t)>& progress = nullptr);

}  // namespace motif
