#include "engine/signature/take_movement.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "formats/frame_file/clip_range_take.h"
#include "formats/motion/body_kinematics.h"

namespace motif {
namespace {

using Vec = Eigen::Vector3d;

// The landmarks read, in a fixed order; those the skeleton lacks (-1) are left out.
std::vector<int> LandmarkJoints(const BodyLandmarks& body) {
  std::vector<int> joints;
  for (int joint : {body.head, body.left.upper_arm, body.right.upper_arm, body.left.elbow,
                    body.right.elbow, body.left.wrist, body.right.wrist, body.left.knee,
                    body.right.knee, body.left.ankle, body.right.ankle}) {
    if (joint >= 0) joints.push_back(joint);
  }
  return joints;
}

// The rest pose's head (or chest) to the midpoint of the ankles: the unit of every length.
double BodyHeight(const Skeleton& skeleton, const BodyLandmarks& body) {
  const std::vector<Eigen::Quaterniond> identity(skeleton.joint_count(),
                                                 Eigen::Quaterniond::Identity());
  std::vector<Eigen::Quaterniond> world;
  const std::vector<Vec> rest = JointPositions(skeleton, Vec::Zero(), identity.data(), &world);
  const int top = body.head >= 0 ? body.head : body.chest;
  if (top < 0 || body.left.ankle < 0 || body.right.ankle < 0) return 0;
  return (rest[top] - 0.5 * (rest[body.left.ankle] + rest[body.right.ankle])).norm();
}

// `offset` turned by -heading about the vertical Y axis: into the body's own frame.
Vec WithoutHeading(const Vec& offset, double heading) {
  const double c = std::cos(-heading);
  const double s = std::sin(-heading);
  return {c * offset.x() + s * offset.z(), offset.y(), -s * offset.x() + c * offset.z()};
}

// A take as read: per frame the landmarks in the body frame (in body heights), the root's world
// position and the heading.
struct BodyTrack {
  double fps = 0;
  double height = 0;
  std::vector<std::vector<Vec>> landmarks;
  std::vector<Vec> root;
  std::vector<double> headings;
  size_t frames() const { return root.size(); }
};

Result<BodyTrack> ReadBodyTrack(const FrameFileReader& reader, const ClipInfo& clip,
                                const BodyLandmarks& body) {
  MOTIF_ASSIGN_OR_RETURN(Take take, ReadClipRangeAsTake(reader, clip, 0, clip.frame_count));
  std::vector<float> rows;
  MOTIF_RETURN_IF_ERROR(reader.ReadFrames(clip.first_frame, clip.frame_count, &rows));
  BodyTrack track;
  track.fps = take.fps;
  track.height = BodyHeight(take.skeleton, body);
  if (!(track.height > 0)) {
    return Status::InvalidArgument("clip " + clip.name +
                                   ": no body height (head and ankles coincide at rest)");
  }
  const std::vector<int> joints = LandmarkJoints(body);
  const FrameLayout layout = reader.layout();
  std::vector<Eigen::Quaterniond> world;
  for (size_t frame = 0; frame < take.frame_count(); ++frame) {
    const double heading = rows[frame * layout.stride() + layout.heading_offset()];
    const std::vector<Vec> points = JointPositions(take.skeleton, take.root_positions[frame],
                                                   &take.rotation(frame, 0), &world);
    std::vector<Vec> local;
    for (int joint : joints) {
      local.push_back(WithoutHeading(points[joint] - points[body.pelvis], heading) / track.height);
    }
    track.landmarks.push_back(std::move(local));
    track.root.push_back(take.root_positions[frame]);
    track.headings.push_back(heading);
  }
  return track;
}

// shares and windings from the frame-to-frame motion of each landmark.
void SummariseLandmarks(const BodyTrack& track, TakeMovement* movement) {
  const size_t count = track.landmarks.front().size();
  std::vector<double> path(count, 0.0);
  std::vector<Vec> low = track.landmarks.front();
  std::vector<Vec> high = low;
  for (size_t frame = 1; frame < track.frames(); ++frame) {
    for (size_t idx = 0; idx < count; ++idx) {
      const Vec& point = track.landmarks[frame][idx];
      path[idx] += (point - track.landmarks[frame - 1][idx]).norm();
      low[idx] = low[idx].cwiseMin(point);
      high[idx] = high[idx].cwiseMax(point);
    }
  }
  double total = 0;
  for (double length : path) total += length;
  for (size_t idx = 0; idx < count; ++idx) {
    movement->shares.push_back(total > 0 ? path[idx] / total : 1.0 / static_cast<double>(count));
    const double extent = (high[idx] - low[idx]).norm() + 1e-6;
    movement->windings.push_back(std::log1p(path[idx] / extent));
  }
}

// travel: the root's mean horizontal speed, net turn and total turning per second.
void SummariseTravel(const BodyTrack& track, TakeMovement* movement) {
  double distance = 0;
  double turning = 0;
  for (size_t frame = 1; frame < track.frames(); ++frame) {
    const Vec step = track.root[frame] - track.root[frame - 1];
    distance += std::hypot(step.x(), step.z());
    turning += std::abs(track.headings[frame] - track.headings[frame - 1]);
  }
  const double seconds = static_cast<double>(track.frames()) / track.fps;
  const double moves = static_cast<double>(track.frames() - 1);
  movement->travel = {distance * track.fps / moves / track.height,
                      (track.headings.back() - track.headings.front()) / seconds,
                      turning / seconds};
}

// One row per step of 1 / kMovementStepsPerSecond: the landmarks' velocities over the take's
// mean landmark speed, the root's forward and sideways velocity (body frame) and the yaw rate.
void SampleSteps(const BodyTrack& track, const std::vector<size_t>& at, TakeMovement* movement) {
  const size_t count = track.landmarks.front().size();
  const Eigen::Index rows = static_cast<Eigen::Index>(at.size() - 1);
  Eigen::MatrixXd steps(rows, static_cast<Eigen::Index>(3 * count + 3));
  double speed = 0;
  for (Eigen::Index row = 0; row < rows; ++row) {
    const size_t from = at[row];
    const size_t to = at[row + 1];
    const double dt = static_cast<double>(to - from) / track.fps;
    for (size_t idx = 0; idx < count; ++idx) {
      const Vec velocity = (track.landmarks[to][idx] - track.landmarks[from][idx]) / dt;
      steps.block<1, 3>(row, static_cast<Eigen::Index>(3 * idx)) = velocity.transpose();
    }
    speed += steps.row(row).head(static_cast<Eigen::Index>(3 * count)).norm();
    const Vec root =
        WithoutHeading(track.root[to] - track.root[from], track.headings[from]) / dt / track.height;
    steps.row(row).tail<3>() << root.x(), root.z(),
        (track.headings[to] - track.headings[from]) / dt;
  }
  speed = speed / static_cast<double>(rows) + 1e-9;
  steps.leftCols(static_cast<Eigen::Index>(3 * count)) /= speed;
  movement->steps = std::move(steps);
}

// Frames from one step to the next: round(fps / kMovementStepsPerSecond), at least 1.
size_t StepStride(double fps) {
  return static_cast<size_t>(std::max(1.0, std::round(fps / kMovementStepsPerSecond)));
}

// The frames the steps sample: every StepStride-th.
std::vector<size_t> StepFrames(const BodyTrack& track) {
  const size_t stride = StepStride(track.fps);
  std::vector<size_t> at;
  for (size_t frame = 0; frame < track.frames(); frame += stride) at.push_back(frame);
  return at;
}

// DTW of two step sequences, Euclidean local cost, divided by n + m.
double StepsDtw(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  const Eigen::Index m = b.rows();
  std::vector<double> previous(static_cast<size_t>(m), std::numeric_limits<double>::infinity());
  std::vector<double> current(static_cast<size_t>(m));
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    for (Eigen::Index j = 0; j < m; ++j) {
      const double cost = (a.row(i) - b.row(j)).norm();
      double best = i == 0 ? (j == 0 ? 0.0 : current[j - 1]) : previous[j];
      if (i > 0 && j > 0) best = std::min({best, current[j - 1], previous[j - 1]});
      current[j] = best + cost;
    }
    std::swap(previous, current);
  }
  return previous[m - 1] / static_cast<double>(a.rows() + m);
}

// One pair's two terms before scaling: the summaries' distance and the steps' DTW.
struct PairTerms {
  double summary = 0;
  double steps = 0;
};

PairTerms TermsBetween(const std::vector<TakeMovement>& takes, const Eigen::MatrixXd& summaries,
                       size_t a, size_t b) {
  return {(summaries.row(static_cast<Eigen::Index>(a)) -
           summaries.row(static_cast<Eigen::Index>(b)))
              .norm(),
          StepsDtw(takes[a].steps, takes[b].steps)};
}

// The summaries as rows, every column z-scored over the takes and each block weighed by one
// over the square root of its size.
Eigen::MatrixXd WeighedSummaries(const std::vector<TakeMovement>& takes) {
  const auto blocks = {&TakeMovement::shares, &TakeMovement::windings, &TakeMovement::travel};
  Eigen::Index columns = 0;
  for (auto block : blocks) columns += static_cast<Eigen::Index>((takes.front().*block).size());
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(takes.size()), columns);
  Eigen::Index column = 0;
  for (auto block : blocks) {
    const size_t size = (takes.front().*block).size();
    for (size_t idx = 0; idx < size; ++idx, ++column) {
      for (size_t take = 0; take < takes.size(); ++take) {
        rows(static_cast<Eigen::Index>(take), column) = (takes[take].*block)[idx];
      }
      Eigen::VectorXd values = rows.col(column);
      const double mean = values.mean();
      const double sd = std::sqrt((values.array() - mean).square().mean());
      const double scale = sd > 1e-12 ? 1.0 / (sd * std::sqrt(static_cast<double>(size))) : 0.0;
      rows.col(column) = (values.array() - mean) * scale;
    }
  }
  return rows;
}

// The median of `values` (1 when it is 0 or there are none: nothing to scale by).
double MedianScale(std::vector<double> values) {
  if (values.empty()) return 1;
  std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2),
                   values.end());
  const double median = values[values.size() / 2];
  return median > 0 ? median : 1;
}

// MedianScale of the pairs above the diagonal.
double PairMedian(const Eigen::MatrixXd& distances) {
  std::vector<double> pairs;
  for (Eigen::Index row = 0; row < distances.rows(); ++row) {
    for (Eigen::Index col = row + 1; col < distances.cols(); ++col) {
      pairs.push_back(distances(row, col));
    }
  }
  return MedianScale(std::move(pairs));
}

}  // namespace

uint64_t MovementMinimumFrames(double fps) { return StepStride(fps) + 1; }

Result<TakeMovement> ReadTakeMovement(const FrameFileReader& reader, uint32_t clip,
                                      const BodyLandmarks& landmarks) {
  const ClipInfo& info = reader.clips().at(clip);
  MOTIF_ASSIGN_OR_RETURN(BodyTrack track, ReadBodyTrack(reader, info, landmarks));
  const std::vector<size_t> at = StepFrames(track);
  if (at.size() < 2 || track.landmarks.front().empty()) {
    return Status::InvalidArgument(
        "clip " + info.name + ": too short to compare by movement (" +
        std::to_string(info.frame_count) + " frames; it needs two steps of 0.1 s)");
  }
  TakeMovement movement;
  SummariseLandmarks(track, &movement);
  SummariseTravel(track, &movement);
  SampleSteps(track, at, &movement);
  return movement;
}

Eigen::MatrixXd MovementDistanceMatrix(const std::vector<TakeMovement>& takes, int threads,
                                       const std::function<void(uint64_t, uint64_t)>& progress) {
  const auto n = static_cast<Eigen::Index>(takes.size());
  Eigen::MatrixXd summary = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd steps = Eigen::MatrixXd::Zero(n, n);
  if (n < 2) return summary;
  const Eigen::MatrixXd rows = WeighedSummaries(takes);
  std::atomic<uint64_t> done{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n, 1), [&](const auto& range) {
      for (Eigen::Index row = range.begin(); row != range.end(); ++row) {
        for (Eigen::Index col = row + 1; col < n; ++col) {
          const PairTerms terms = TermsBetween(takes, rows, static_cast<size_t>(row),
                                               static_cast<size_t>(col));
          summary(row, col) = summary(col, row) = terms.summary;
          steps(row, col) = steps(col, row) = terms.steps;
        }
        if (progress) progress(++done, static_cast<uint64_t>(n));
      }
    });
  });
  return summary / PairMedian(summary) + steps / PairMedian(steps);
}

std::vector<double> MovementDistancesFrom(const std::vector<TakeMovement>& takes, size_t query,
                                          int threads) {
  const size_t n = takes.size();
  std::vector<double> summary(n, 0.0);
  std::vector<double> steps(n, 0.0);
  if (n < 2) return summary;
  const Eigen::MatrixXd rows = WeighedSummaries(takes);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1), [&](const auto& range) {
      for (size_t other = range.begin(); other != range.end(); ++other) {
        if (other == query) continue;
        const PairTerms terms = TermsBetween(takes, rows, query, other);
        summary[other] = terms.summary;
        steps[other] = terms.steps;
      }
    });
  });
  std::vector<double> others_summary;
  std::vector<double> others_steps;
  for (size_t other = 0; other < n; ++other) {
    if (other == query) continue;
    others_summary.push_back(summary[other]);
    others_steps.push_back(steps[other]);
  }
  const double summary_scale = MedianScale(std::move(others_summary));
  const double steps_scale = MedianScale(std::move(others_steps));
  std::vector<double> distances(n);
  for (size_t other = 0; other < n; ++other) {
    distances[other] = summary[other] / summary_scale + steps[other] / steps_scale;
  }
  return distances;
}

Result<Eigen::MatrixXd> TakeMovementMatrix(
    const FrameFileReader& reader, const std::vector<uint32_t>& clips, int threads,
    const std::function<void(uint64_t, uint64_t)>& progress) {
  MOTIF_ASSIGN_OR_RETURN(BodyLandmarks landmarks, FindBodyLandmarks(reader.skeleton()));
  std::vector<TakeMovement> takes;
  for (uint32_t clip : clips) {
    MOTIF_ASSIGN_OR_RETURN(TakeMovement movement, ReadTakeMovement(reader, clip, landmarks));
    takes.push_back(std::move(movement));
  }
  return MovementDistanceMatrix(takes, threads, progress);
}

}  // namespace motif
