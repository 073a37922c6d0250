#!/usr/bin/env bash
# The test suite once more under sanitizers (docs/reliability.md, "Sanitizers"); .ci/run calls it
# after scripts/test.sh.
#
#   scripts/test_sanitizers.sh [asan|tsan|all]     (default: all)
#
# asan: the tests of the code that reads what a user hands it and of the engine's index-heavy
#       kernels (asan_targets below) built with AddressSanitizer (with LeakSanitizer), and
#       UndefinedBehaviorSanitizer on common/ and formats/, every report fatal, in build-asan/.
#       The tool, its CLI tests, the orchestration (pipeline, reindex, report, the words and
#       graph commands), the clustering and the study programs are not built there
#       (docs/reliability.md, "Sanitizers"). The scale tests listed in asan_skip below are left out too (they run the same code as the
#       tests kept, on archives 10 to 100 times larger, and take 20 s to 6 min each under ASan);
#       MOTIF_SANITIZE_ALL=1 builds and runs every test.
# tsan: the tests of the parallel parts (every test that compares thread counts or reads from
#       many threads, selected by name below), built as one program (tests/threads) with
#       ThreadSanitizer in build-tsan/, against
#       a oneTBB built with ThreadSanitizer too: Debian's own source of the installed libtbb-dev
#       (apt-get source, so a deb-src entry for Debian's archive is added when missing), in
#       build-tsan/onetbb/ (once; ~1 CPU minute). TSan cannot see the synchronisation inside an
#       uninstrumented libtbb, and reports every hand-over of data to a task as a race.
# Both builds use -O1 -g1 (fast enough to compile and run, stacks with file and line) and skip
# the benchmarks. MOTIF_JOBS sets the parallel jobs (default 2).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${MOTIF_JOBS:-2}"
which="${1:-all}"
case "$which" in asan|tsan|all) ;; *) sed -n '2,22p' "${BASH_SOURCE[0]}" >&2; exit 2 ;; esac
"$root/scripts/install_deps.sh"

# Left out of the ASan run: tests over large archives (timed under ASan at 2026-11-25), each
# with a smaller sibling that is kept (in parentheses).
asan_skip=(
  'MotionSynthesizerStreaming\.MemoryStaysFlatOverMillionsOfFrames'  # (MotionSynthesizer.*)
  'MineInterrupt\.'                                 # (crash tests of the writers, MotifmineMine.*)
  'PlantedMotifs\.'                                 # (cluster and grower tests on planted cases)
  'LshSearchTest\.RankingByPositionCodeKeepsRecallWithHalfTheBudget'  # (LshSearchTest.*)
  'LshSearchHeavyBucket\.'                          # (LshIndexTest.*)
  'LshSearchRealTakes\.'                            # (LshSearchTest.* on synthetic archives)
  'RealBvhAndAsfAmcArchivesHaveTheIndexedClipsAndFrames'  # (ImportIntoArchive.* on small takes)
  'LshSearchTest\.RecallOnSyntheticArchive'
  'LshSearchTest\.ChainingSeedsColumnsWithTheirPredecessorsNeighbours'
  'AuditTrellis\.LshRecallOnAPlantedSyntheticArchive'
  'BuildTrellis\.ResumesAnInterruptedBuildToTheSameFile'  # (TrellisFileCrashTest.*)
  'BuildTrellis\.ReusesAFinishedTrellisAndRebuildsWhenAParameterChanges'
  'MotionSynthesizer\.TruthIsKnownBeforeRunAndValid'
  'RealData\.'                                      # (the parsers' tests; every real take)
  'EpsilonEstimator\.ReproducesTheMeasuredFiguresOnTheRealTakes'
  'DtwNeighbours\.DefaultSearchFindsMostTrueNeighbours'  # (DtwNeighbours.* on fewer words)
  'EmbeddingTrainer\.TrainingLowersTheLoss'        # (EmbeddingTrainer.*, which train too)
  'crash_harness'                                   # (a Python harness around the tool)
  'DamageSweep\.'   # 7,000 runs of the tool (FrameFileCorruption.*: the same sweep in-process)
  'hostile_inputs'  # a memory limit on the address space, which ASan's shadow memory exceeds
  'install_and_example'  # builds a program without the sanitizer against the installed library
  'python_tests'    # Debian's python3 cannot load a module built with ASan without preloading it
  'PublicApi\.MineFindsTheTools'  # (MotifmineMine.*: the same pipeline through the tool)
  'ReindexFailureTest\.AWriteFailingAtAnyStep'  # (ReindexFailureTest.AFullFileSystem*, crash tests)
  'LshSearchTest\.QuaternionSignFlipGivesTheSameColumns'  # (LshSearchTest.*)
  'MpiMine\.AKilledRank'  # 80 s under ASan (MpiMine.OneToFour*: the same ranks, and MineInterrupt.*)
  'MpiMine\.RankZeroMakesTheSyntheticArchive'  # 31 s under ASan (MpiMine.OneToFour*)
  # 45 s under ASan, most of it DTW over every window (TakeSegmentationTest.*, DTW included)
  'WordsCliTest\.SegmentWritesItsDocumentAndPageWithAndWithoutLabels'
  'SegmentCli\.BuildsTheWordsItNeedsWhenTheyAreMissing'  # 38 s: 30 epochs (WordsCliTest.Words*)
)
# The test programs built and run under ASan (UBSan on common/ and formats/): the code that reads
# what a user hands it (the file formats, the importers, their fuzz regressions) and the engine's
# kernels that index the mapped archive and trellis or raw arrays (distance, LSH, the trellis and
# its update, the grower, the transport problems of the signatures). Not the clustering and the
# synthesizer's own tests (docs/reliability.md, "Sanitizers"): they work on std and Eigen
# containers of what those kernels hand them, and the synthesizer runs under ASan as the source
# of the other tests' archives.
asan_targets=(common_test motion_test frame_file_test import_test export_test trellis_file_test
              paths_file_test tensor_file_test format_checks_test ingest_test distance_test
              lsh_test trellis_test trellis_update_test grow_test signature_test
              fuzz_amc_parser_regression_test fuzz_asf_parser_regression_test
              fuzz_bvh_parser_regression_test fuzz_frame_file_reader_regression_test
              fuzz_paths_file_reader_regression_test fuzz_trellis_file_reader_regression_test)
# The tests ThreadSanitizer runs: the parallel parts, by test name, and the test folders that
# hold them
tsan_tests='ThreadCount|Threads|ManyThreads|Concurrent|Sharded|OneAndTwoThreads|OneOrTwoThreads'
tsan_dirs='engine/lsh;engine/distance;engine/ingest;engine/trellis;engine/signature;engine/cluster;formats/frame_file;formats/trellis_file'
# (tests/threads/CMakeLists.txt builds one program, thread_test, of those folders' sources that
# hold such tests.)

source "$root/scripts/cmake_generator.sh"
configure() {  # configure DIR FLAG...
  local dir="$1"
  shift
  # shellcheck disable=SC2046  # the generator's words
  cmake -S "$root" -B "$dir" $(generator_args "$dir") -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" \
    -DMOTIF_BUILD_BENCHMARKS=OFF -DMOTIF_BUILD_PYTHON=OFF "$@" >/dev/null
}

if [ "$which" != tsan ]; then
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer: the test suite"
  configure "$root/build-asan" -DMOTIF_ENABLE_SANITIZERS=ON
  exclude=()
  if [ "${MOTIF_SANITIZE_ALL:-0}" != 1 ]; then
    cmake --build "$root/build-asan" -j "$jobs" --target "${asan_targets[@]}"
    # The thread tests (tsan_tests below) run under TSan, which is where their parallel code is
    # checked; every one of them in asan_targets is in a tsan_dirs folder. The scripted sweeps
    # (hostile_events: a 600,000-frame archive cut under five commands; option_sweep: 1,806
    # runs of the tool) check exit codes and messages, run in the Release tiers, and would take
    # minutes at the sanitizers' process start-up and speed.
    exclude=(-E "_NOT_BUILT|python_tests|hostile_inputs|hostile_events|option_sweep|crash_harness|install_and_example|$tsan_tests|$(IFS='|'; echo "${asan_skip[*]}")")
  else
    cmake --build "$root/build-asan" -j "$jobs"
  fi
  (cd "$root/build-asan" &&
     ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1 \
     UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
     ctest --output-on-failure -j "$jobs" --timeout 1500 "${exclude[@]}")
fi

if [ "$which" != asan ]; then
  echo "== ThreadSanitizer: the parallel parts"
  tbb_prefix="$root/build-tsan/onetbb/install"
  if [ ! -f "$tbb_prefix/lib/cmake/TBB/TBBConfig.cmake" ]; then
    tbb_version="$(dpkg-query -W -f='${Version}' libtbb-dev)"
    work="$root/build-tsan/onetbb"
    rm -rf "$work"
    mkdir -p "$work"
    if ! (cd "$work" && apt-get source -qq --download-only "onetbb=$tbb_version") 2>/dev/null; then
      echo "adding Debian's source archive (deb-src) to apt, for onetbb's source"
      if [ -f /etc/apt/sources.list.d/debian.sources ]; then  # deb822 (Debian 12 images)
        sed 's/^Types: deb$/Types: deb-src/' /etc/apt/sources.list.d/debian.sources \
          > /etc/apt/sources.list.d/motifmine-deb-src.sources
      else
        sed -n 's/^deb /deb-src /p' /etc/apt/sources.list > /etc/apt/sources.list.d/motifmine-deb-src.list
      fi
      apt-get update -qq
      (cd "$work" && apt-get source -qq --download-only "onetbb=$tbb_version")
    fi
    tar -xf "$work"/onetbb_*.orig.tar.* -C "$work"
    cmake -S "$(ls -d "$work"/oneTBB-*/)" -B "$work/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DTBB_SANITIZE=thread -DTBB_STRICT=OFF -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF \
      -DTBBMALLOC_BUILD=OFF -DCMAKE_INSTALL_PREFIX="$tbb_prefix" >/dev/null
    cmake --build "$work/build" -j "$jobs" >/dev/null
    cmake --install "$work/build" >/dev/null
  fi
  configure "$root/build-tsan" -DMOTIF_ENABLE_TSAN=ON -DTBB_DIR="$tbb_prefix/lib/cmake/TBB" \
    -DMOTIF_TSAN_TEST_DIRS="$tsan_dirs" -DMOTIF_TSAN_TEST_REGEX="$tsan_tests"
  cmake --build "$root/build-tsan" -j "$jobs" --target thread_test
  (cd "$root/build-tsan" &&
     TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 \
     ctest --output-on-failure -j "$jobs" --timeout 1500 -R "$tsan_tests" -E _NOT_BUILT)
fi
