// BVH parsing: turns the text of a .bvh file into a Take (formats/motion/take.h) with the file's
// own skeleton, before canonicalisation and before any first-frame (T-pose) handling; the
// importer (take_importer.h) does those.
//
// What is accepted:
//   - any hierarchy with one ROOT, joints in file order (parents first), names as written (a
//     name may contain spaces: the rest of the ROOT/JOINT line up to an optional '{');
//   - keywords in any letter case, tokens separated by spaces or tabs, LF or CRLF line ends;
//   - per joint 0..6 channels in any order (no channel twice); Joint::channels records them;
//   - "Frames:" / "Frame Time:" with spaces or tabs (or nothing) after the colon;
//   - one frame per line, numbers in any std::from_chars form (a leading '+' is allowed).
// How motion is read:
//   - a joint's rotation is the composition of its rotation channels in the listed order,
//     R(c0) * R(c1) * ..., angles in degrees (quaternion_math.h's convention), identity when it
//     has none;
//   - the root position comes from the root's position channels; a component without a channel
//     is the root's OFFSET component. Position channels of other joints are accepted and ignored
//     (motifmine's takes carry joint rotations only; bone lengths come from the OFFSETs);
//   - an End Site becomes Joint::has_end_site / end_site of its joint (a second End Site of the
//     same joint is an error);
//   - fps is 1 / Frame Time, snapped to the nearest integer when within 0.01 % of it (BVH files
//     store a rounded frame time: ".0083333" is 120.0005 fps and means 120); fps_override > 0
//     replaces it. The Frame Time must still be a number in [kMinBvhFrameTime,
//     kMaxBvhFrameTime]: 1 to 1,000,000 frames per second (the importer resamples a take to
//     the archive's rate, so a frame time of hours would make millions of frames).
// Every error is InvalidArgument "<file>:<line>: <problem>", e.g. "05_01.bvh:412: frame 3 has
// 95 values, the hierarchy declares 96 channels" (frames counted from 0). Rejected: a missing
// HIERARCHY/ROOT/MOTION, unbalanced braces, several ROOTs, unknown keywords or channel names, a
// CHANNELS count that does not match its names, missing or non-numeric OFFSET values, NaN or
// infinite numbers, a frame line with too few or too many values, fewer or more frame lines than
// "Frames:" declares, zero frames, a frame time outside [1e-6, 1] seconds, duplicate joint names.
// Thread-safety: a pure function.
#pragma once

#include <string>
#include <string_view>

#include "common/status.h"
#include "formats/motion/take.h"

namespace motif {

// The accepted range of "Frame Time:", in seconds.
inline constexpr double kMinBvhFrameTime = 1e-6;
inline constexpr double kMaxBvhFrameTime = 1.0;

// Parses `text`, the content of the file `file_name` (used in messages and as
// Take::source_path). The take's name, content_hash and meters_per_unit are left unset; its
// skeleton has family "custom". InvalidArgument on malformed input.
Result<Take> ParseBvh(std::string_view text, const std::string& file_name, double fps_override = 0);

// The skeleton of the HIERARCHY section alone, as ParseBvh reads it but before a static root is
// moved (`text` may end anywhere after the hierarchy). The same errors for the hierarchy.
Result<Skeleton> ParseBvhSkeleton(std::string_view text, const std::string& file_name);

}  // namespace motif
