// motifmine search ARCHIVE (--clip NAME [--start S --end E] | --query FILE.bvh) [--top K]:
// example-based retrieval with motion signatures (engine/words/window_search.h).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "engine/cli/cli_common.h"
#include "engine/distance/pose_features.h"
#include "engine/report/words_report_html.h"
#include "engine/signature/clip_words.h"
#include "engine/words/window_search.h"
#include "engine/words/word_embedder.h"
#include "engine/words/word_model.h"
#include "formats/import/take_importer.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/resample.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

// The motifs of the words of a motion file: imported, fitted to the archive's skeleton and rate,
// cut into words, embedded with the archive's embedding and assigned to its motifs.
Result<std::vector<uint32_t>> QueryFileMotifs(const std::string& path,
                                              const FrameFileReader& reader,
                                              const LoadedWords& words,
                                              const std::vector<float>& weights, int threads,
                                              Take* fitted) {
  ImportOptions import_options;
  MOTIF_ASSIGN_OR_RETURN(std::vector<TakeSource> sources, DiscoverTakes({path}, import_options));
  if (sources.size() != 1) {
    return Status::InvalidArgument(path + ": expected one BVH or AMC take, found " +
                                   std::to_string(sources.size()));
  }
  MOTIF_ASSIGN_OR_RETURN(Take take, ImportTake(sources[0], import_options));
  if (Status status = ConformToSkeleton(reader.skeleton(), &take); !status.ok()) {
    return status.WithContext(path + ": does not fit the archive's skeleton");
  }
  *fitted = ResampleTake(take, reader.fps());
  const ClipFrames clip = TakeToClipFrames(*fitted);
  MOTIF_ASSIGN_OR_RETURN(ClipWords clip_words,
                         ClipWords::FromRows(clip.rows, reader.fps(), reader.layout(), weights,
                                             words.signatures.words));
  if (clip_words.word_count() == 0) {
    return Status::InvalidArgument(path + ": shorter than one motion word");
  }
  WordBatch batch;
  clip_words.AllWords(&batch, /*keep_rows=*/true);
  MOTIF_ASSIGN_OR_RETURN(WordEmbedder embedder,
                         WordEmbedder::Create(*words.embedding, reader.layout(), weights, threads));
  RowMatrixXf embedded(static_cast<Eigen::Index>(batch.size()), embedder.dims());
  embedder.Embed(batch, &embedded);
  const std::vector<uint16_t> motifs = NearestMotifs(embedded, words.motifs.centroids, threads);
  return std::vector<uint32_t>(motifs.begin(), motifs.end());
}

nlohmann::json SearchJson(const SearchResult& result, const FrameFileReader& reader,
                          const SearchPageInfo& info, const std::string& query_kind,
                          const std::string& query_file) {
  nlohmann::json json;
  json["version"] = 1;
  json["archive"] = info.archive;
  // The version searched (read once, so an import appending meanwhile does not change it).
  json["archive_generation"] = reader.summary().generation;
  nlohmann::json query = {{"kind", query_kind}, {"words", info.query_words}};
  if (info.query_in_archive) {
    query["clip"] = reader.clips()[info.query_clip].name;
    query["start"] = info.query_start;
    query["end"] = info.query_end;
  } else {
    query["file"] = query_file;
  }
  json["query"] = query;
  json["motifs"] = info.motifs;
  json["windows"] = result.windows;
  json["shorter_takes"] = result.shorter_takes;  // left out: fewer words than the query
  nlohmann::json left_out = nlohmann::json::array();
  for (uint32_t clip : result.shorter_clips) {
    left_out.push_back(
        {{"clip", reader.clips()[clip].name}, {"reason", "fewer motion words than the query"}});
  }
  json["left_out"] = left_out;
  json["seconds"] = info.seconds;
  nlohmann::json matches = nlohmann::json::array();
  for (size_t rank = 0; rank < result.matches.size(); ++rank) {
    const WindowMatch& match = result.matches[rank];
    const double fps = reader.fps();
    nlohmann::json entry = {{"rank", rank + 1},
                            {"clip", reader.clips()[match.clip].name},
                            {"start", match.start_frame},
                            {"end", match.end_frame},
                            {"start_seconds", match.start_frame / fps},
                            {"end_seconds", match.end_frame / fps},
                            {"first_word", match.first_word},
                            {"words", match.words},
                            {"distance", match.distance}};
    if (!result.whole_take) {
      nlohmann::json profile = nlohmann::json::array();
      for (float value : result.profiles[rank]) {
        profile.push_back(std::isnan(value) ? nlohmann::json(nullptr) : nlohmann::json(value));
      }
      entry["profile"] = profile;
    }
    matches.push_back(entry);
  }
  json["matches"] = matches;
  return json;
}

}  // namespace

int RunSearch(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "search";
  spec.usage =
      "motifmine search ARCHIVE (--clip NAME [--start S --end E] | --query FILE.bvh) "
      "[--top K] [--out DIR]";
  spec.summary =
      "Finds the motions of ARCHIVE most like a query, by the Earth Mover's Distance between\n"
      "motion signatures (run `motifmine words` first). With a frame range of a clip, or a\n"
      "BVH/AMC file, a window of as many words as the query slides along every take and each\n"
      "take's best window is ranked; with a whole clip (no range), whole takes are ranked.\n"
      "Writes DIR/search.json and DIR/search.html.";
  spec.options.add_options()("clip", po::value<std::string>()->default_value(""),
                             "query: a clip of the archive")(
      "start", po::value<uint64_t>(), "first frame of the query range (clip-relative)")(
      "end", po::value<uint64_t>(), "end of the query range (exclusive)")(
      "query", po::value<std::string>()->default_value(""),
      "query: a BVH (or ASF/AMC) file, embedded with the archive's embedding")(
      "top", po::value<uint32_t>()->default_value(10), "matches to keep")(
      "weights", po::value<std::string>()->default_value(""),
      "per-joint weights file (as given to `motifmine words`)");
  AddWordsReaderOptions(spec, "PREFIX.mwe, .mwm, .mws", "search");
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const auto fail = [](const Status& status) { return ReportError("search", status); };
  const std::string archive = vm["archive"].as<std::string>();
  const std::string clip_name = vm["clip"].as<std::string>();
  const std::string query_file = vm["query"].as<std::string>();
  const uint32_t top = vm["top"].as<uint32_t>();
  const int threads = vm["threads"].as<int>();
  if (clip_name.empty() == query_file.empty()) {
    std::fprintf(stderr, "motifmine search: give either --clip NAME or --query FILE\nusage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  if (vm.count("start") != vm.count("end") || (!query_file.empty() && vm.count("start"))) {
    std::fprintf(stderr,
                 "motifmine search: --start and --end go together, with --clip\n"
                 "usage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  if (top == 0) return fail(Status::InvalidArgument("--top must be at least 1"));
  Result<WordsReaderOutput> output = WordsReaderOutputFrom(vm, archive, "search");
  if (!output.ok()) return fail(output.status());
  const WordsPaths paths = DefaultWordsPaths(output->prefix_archive);

  Result<std::unique_ptr<FrameFileReader>> reader = FrameFileReader::Open(archive);
  if (!reader.ok()) return fail(reader.status());
  const FrameFileReader& frames = **reader;
  Result<LoadedWords> words = LoadWords(frames, paths, /*with_embedding=*/!query_file.empty());
  if (!words.ok()) return fail(words.status());

  const auto start_time = std::chrono::steady_clock::now();
  SearchPageInfo info;
  info.archive = archive;
  Take query_take;  // a file query, fitted to the archive: its keyframes head the page
  info.motifs = words->motifs.motif_count();
  Result<SearchResult> result = Status::InvalidArgument("no query");
  std::string query_kind;
  if (!clip_name.empty()) {
    uint32_t clip = UINT32_MAX;
    for (uint32_t idx = 0; idx < frames.clips().size(); ++idx) {
      if (frames.clips()[idx].name == clip_name) clip = idx;
    }
    if (clip == UINT32_MAX) {
      return fail(Status::NotFound(archive + ": no clip named '" + clip_name +
                                   "' (motifmine info lists them)"));
    }
    const ClipInfo& info_clip = frames.clips()[clip];
    info.query_in_archive = true;
    info.query_clip = clip;
    if (vm.count("start")) {
      const uint64_t start = vm["start"].as<uint64_t>();
      const uint64_t end = vm["end"].as<uint64_t>();
      if (start >= end || end > info_clip.frame_count) {
        return fail(Status::InvalidArgument("--start " + std::to_string(start) + " --end " +
                                            std::to_string(end) + " is not a range within clip " +
                                            clip_name + "'s " +
                                            std::to_string(info_clip.frame_count) + " frames"));
      }
      Result<std::pair<uint64_t, uint64_t>> range = WordsWithin(frames, *words, clip, start, end);
      if (!range.ok()) return fail(range.status());
      WindowQuery query;
      const std::vector<uint32_t> clip_motifs = words->ClipMotifs(clip);
      query.motifs.assign(clip_motifs.begin() + static_cast<std::ptrdiff_t>(range->first),
                          clip_motifs.begin() + static_cast<std::ptrdiff_t>(range->second));
      query.exclude_clip = clip;
      query.exclude_first_word = range->first;
      query.exclude_end_word = range->second;
      info.query_start = start;
      info.query_end = end;
      info.query_words = query.motifs.size();
      info.query_text =
          "clip " + clip_name + " frames " + std::to_string(start) + "\u2013" + std::to_string(end);
      query_kind = "clip-range";
      result = SlidingWindowSearch(frames, *words, query, top, threads);
    } else {
      info.query_start = 0;
      info.query_end = info_clip.frame_count;
      info.query_words = words->signatures.clip_words[clip];
      info.query_text = "the whole of clip " + clip_name;
      query_kind = "take";
      result = WholeTakeSearch(frames, *words, clip, top, threads);
    }
  } else {
    Result<std::vector<float>> weights =
        LoadDistanceWeights(frames.skeleton(), vm["weights"].as<std::string>());
    if (!weights.ok()) return fail(weights.status());
    Result<std::vector<uint32_t>> motifs =
        QueryFileMotifs(query_file, frames, *words, *weights, threads, &query_take);
    if (!motifs.ok()) return fail(motifs.status());
    WindowQuery query;
    query.motifs = std::move(motifs.value());
    info.query_words = query.motifs.size();
    info.query_text = "file " + query_file;
    info.query_take = &query_take;
    query_kind = "file";
    result = SlidingWindowSearch(frames, *words, query, top, threads);
  }
  if (!result.ok()) return fail(result.status());
  info.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();

  const std::string& json_path = output->json_path;
  const std::string& html_path = output->html_path;
  const nlohmann::json json = SearchJson(*result, frames, info, query_kind, query_file);
  if (Status status = AtomicWriteFile(json_path, json.dump(2) + "\n"); !status.ok()) {
    return fail(status);
  }
  if (Status status = WriteSearchHtml(html_path, *result, frames, info); !status.ok()) {
    return fail(status);
  }
  std::printf("motifmine search: %s, query %s (%s words)\n", archive.c_str(),
              info.query_text.c_str(), WithCommas(info.query_words).c_str());
  const double fps = frames.fps();
  for (size_t rank = 0; rank < result->matches.size(); ++rank) {
    const WindowMatch& match = result->matches[rank];
    std::printf("  %2zu. %-20s frames %7llu-%-7llu (%.2f-%.2f s)  EMD %.4f\n", rank + 1,
                frames.clips()[match.clip].name.c_str(),
                static_cast<unsigned long long>(match.start_frame),
                static_cast<unsigned long long>(match.end_frame), match.start_frame / fps,
                match.end_frame / fps, match.distance);
  }
  std::printf("  compared     %s windows in %.2fs\n", WithCommas(result->windows).c_str(),
              info.seconds);
  if (result->shorter_takes > 0) {
    // Named, up to a screenful; the JSON's "left_out" lists them all.
    constexpr size_t kNamed = 10;
    std::string names;
    for (size_t idx = 0; idx < result->shorter_clips.size() && idx < kNamed; ++idx) {
      names += (idx ? ", " : ": ") + frames.clips()[result->shorter_clips[idx]].name;
    }
    if (result->shorter_clips.size() > kNamed) {
      names += " and " + WithCommas(result->shorter_clips.size() - kNamed) + " more";
    }
    std::printf("  left out     %s shorter than the query (fewer words than its %s)%s\n",
                CountOf(result->shorter_takes, "take").c_str(),
                WithCommas(info.query_words).c_str(), names.c_str());
  }
  std::printf("  wrote        %s, %s\n", json_path.c_str(), html_path.c_str());
  return kExitOk;
}

}  // namespace motif::cli
