// Streaming: generating a large archive through a sink that only counts keeps memory flat (only
// a few clips are ever in flight), and reports the generation speed. Labelled slow.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "engine/synth/motion_synthesizer.h"

namespace motif {
namespace {

// A field of /proc/self/status in kB ("VmRSS", "VmHWM"), or -1.
long ProcStatusKb(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.compare(0, field.size() + 1, field + ":") == 0) {
      return std::strtol(line.c_str() + field.size() + 1, nullptr, 10);
    }
  }
  return -1;
}

uint64_t CountFrames(MotionSynthesizer* synthesizer) {
  uint64_t frames = 0;
  Status status = synthesizer->Run([&](const ClipFrames& clip) {
    frames += clip.info.frame_count;
    return Status::Ok();
  });
  EXPECT_TRUE(status.ok()) << status.ToString();
  return frames;
}

TEST(MotionSynthesizerStreaming, MemoryStaysFlatOverMillionsOfFrames) {
  if (ProcStatusKb("VmHWM") < 0) GTEST_SKIP() << "no /proc/self/status";
  uint64_t frames = 2'000'000;
  if (const char* env = std::getenv("MOTIF_SYNTH_STREAM_FRAMES"))
    frames = std::strtoull(env, nullptr, 10);
  SynthOptions options;
  options.motifs = 20;
  options.seed = 4;
  // Warm up with a small archive of the same kind: the allocator reaches its steady state.
  options.frames = 200'000;
  auto warm_up = MotionSynthesizer::Create(options);
  ASSERT_TRUE(warm_up.ok()) << warm_up.status().ToString();
  ASSERT_EQ(CountFrames(warm_up->get()), options.frames);
  const long peak_before_kb = ProcStatusKb("VmHWM");
  const long rss_before_kb = ProcStatusKb("VmRSS");

  options.frames = frames;
  auto synthesizer = MotionSynthesizer::Create(options);
  ASSERT_TRUE(synthesizer.ok()) << synthesizer.status().ToString();
  const auto begin = std::chrono::steady_clock::now();
  EXPECT_EQ(CountFrames(synthesizer->get()), frames);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  const long peak_after_kb = ProcStatusKb("VmHWM");
  const long rss_after_kb = ProcStatusKb("VmRSS");
  std::printf("%llu frames in %.1f s: %.0f frames/s; VmRSS %ld -> %ld kB, VmHWM %ld -> %ld kB\n",
              static_cast<unsigned long long>(frames), seconds, frames / seconds, rss_before_kb,
              rss_after_kb, peak_before_kb, peak_after_kb);
  RecordProperty("frames_per_second", std::to_string(frames / seconds));
  RecordProperty("peak_growth_kb", std::to_string(peak_after_kb - peak_before_kb));
  // Ten times the frames of the warm-up; the peak may grow only by a few clips' worth.
  EXPECT_LT(peak_after_kb - peak_before_kb, 64 * 1024);
}

}  // namespace
}  // namespace motif
