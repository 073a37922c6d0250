// motifmine search ARCHIVE (--clip NAME [--start S --end E] | --query FILE.bvh) [--top K]:
// example-based retrieval with motion signatures (engine/words/window_search.h).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/distance/pose_features.h"
#include "engine/report/words_report_html.h"
#include "engine/signature/clip_words.h"
#include "engine/signature/word_grid.h"
#include "engine/words/movement_search.h"
#include "engine/words/range_query.h"
#include "engine/words/window_search.h"
#include "engine/words/word_embedder.h"
#include "engine/words/word_model.h"
#include "formats/import/take_importer.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/resample.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

// "0.53 s" for `frames` at `fps`.
std::string Seconds(uint64_t frames, double fps) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f s", frames / fps);
  return text;
}

// Holds a take's first frame for `before` frames and its last for `after` (the root stands
// still there): a query shorter than one word becomes one word long.
void HoldEdgeFrames(uint64_t before, uint64_t after, Take* take) {
  const size_t joints = take->joint_count();
  const size_t frames = take->frame_count();
  std::vector<Eigen::Vector3d> positions(before, take->root_positions.front());
  positions.insert(positions.end(), take->root_positions.begin(), take->root_positions.end());
  positions.insert(positions.end(), after, take->root_positions.back());
  std::vector<Eigen::Quaterniond> rotations;
  rotations.reserve((frames + before + after) * joints);
  for (uint64_t frame = 0; frame < before; ++frame) {
    rotations.insert(rotations.end(), take->rotations.begin(), take->rotations.begin() + joints);
  }
  rotations.insert(rotations.end(), take->rotations.begin(), take->rotations.end());
  for (uint64_t frame = 0; frame < after; ++frame) {
    rotations.insert(rotations.end(), take->rotations.end() - joints, take->rotations.end());
  }
  take->root_positions = std::move(positions);
  take->rotations = std::move(rotations);
}

// A fitted query shorter than one word, padded to one by holding its edge frames (half before,
// half after); returns the note saying so, or "" when it was long enough.
std::string PadToOneWord(const WordOptions& word_options, Take* fitted) {
  const uint64_t frames = fitted->frame_count();
  uint64_t needed = std::max<uint64_t>(frames, 1);
  while (WordGrid(needed, fitted->fps, word_options).word_count() == 0) ++needed;
  if (needed == frames) return "";
  const uint64_t before = (needed - frames) / 2;
  HoldEdgeFrames(before, needed - frames - before, fitted);
  const double fps = fitted->fps;
  return "the query is " + Seconds(frames, fps) + " (" + std::to_string(frames) +
         " frames), shorter than one motion word (" + Seconds(needed, fps) + ", " +
         std::to_string(needed) + " frames): padded to " + Seconds(needed, fps) +
         " by holding its first frame for " + std::to_string(before) + " frames and its last for " +
         std::to_string(needed - frames - before);
}

// The motifs of the words of a motion file: imported, fitted to the archive's skeleton and rate,
// padded to one word if shorter (*note says so), cut into words, embedded with the archive's
// embedding and assigned to its motifs.
Result<std::vector<uint32_t>> QueryFileMotifs(const std::string& path,
                                              const FrameFileReader& reader,
                                              const LoadedWords& words,
                                              const std::vector<float>& weights, int threads,
                                              Take* fitted, std::string* note) {
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
  if (fitted->frame_count() == 0) return Status::InvalidArgument(path + ": has no frame");
  *note = PadToOneWord(words.signatures.words, fitted);
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

// A search that ran: what the page and search.json say of the query, and the matches.
struct SearchRun {
  SearchPageInfo info;
  std::string query_kind;  // "clip-range", "take" or "file"
  Take query_take;         // a file query, fitted to the archive: its keyframes head the page
  RangeQuery range;        // a clip-range query: its words
  SearchResult result;
};

// The clip names of `clips`, as a JSON array.
nlohmann::json ClipNames(const FrameFileReader& reader, const std::vector<uint32_t>& clips) {
  nlohmann::json names = nlohmann::json::array();
  for (uint32_t clip : clips) names.push_back(reader.clips()[clip].name);
  return names;
}

// Why the takes of result.wordless_clips were not compared.
const char* LeftOutReason(const SearchResult& result) {
  return result.distance == "movement" ? "too short to compare by movement (under two 0.1 s steps)"
                                       : "no motion word (shorter than one word)";
}

nlohmann::json MatchJson(const SearchResult& result, const FrameFileReader& reader, size_t rank) {
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
                          {"distance", match.distance},
                          {"rank_in_take", match.rank_in_take},
                          {"whole_take", match.whole_take}};
  if (!result.whole_take) {
    nlohmann::json profile = nlohmann::json::array();
    for (float value : result.profiles[rank]) {
      profile.push_back(std::isnan(value) ? nlohmann::json(nullptr) : nlohmann::json(value));
    }
    entry["profile"] = profile;
  }
  return entry;
}

nlohmann::json SearchJson(const SearchRun& run, const FrameFileReader& reader,
                          const std::string& query_file) {
  const SearchResult& result = run.result;
  const SearchPageInfo& info = run.info;
  const std::string& query_kind = run.query_kind;
  nlohmann::json json;
  json["version"] = 2;
  json["archive"] = info.archive;
  // The version searched (read once, so an import appending meanwhile does not change it).
  json["archive_generation"] = reader.summary().generation;
  nlohmann::json query = {{"kind", query_kind}, {"words", info.query_words}};
  if (info.query_in_archive) {
    query["clip"] = reader.clips()[info.query_clip].name;
    query["start"] = info.query_start;
    query["end"] = info.query_end;
    if (query_kind == "clip-range") {
      query["word_start"] = run.range.word_frames.first;
      query["word_end"] = run.range.word_frames.end;
      query["padded"] = run.range.padded;
    }
  } else {
    query["file"] = query_file;
  }
  json["query"] = query;
  json["distance"] = result.distance;
  json["motifs"] = info.motifs;
  json["windows"] = result.windows;
  json["overlap"] = "shared source frame";
  json["shorter_takes"] = result.shorter_takes;  // compared whole: fewer words than the query
  json["shorter"] = ClipNames(reader, result.shorter_clips);
  nlohmann::json left_out = nlohmann::json::array();
  for (uint32_t clip : result.wordless_clips) {
    if (info.query_in_archive && clip == info.query_clip) continue;
    left_out.push_back({{"clip", reader.clips()[clip].name}, {"reason", LeftOutReason(result)}});
  }
  json["left_out"] = left_out;
  json["notes"] = run.info.notes;
  json["seconds"] = info.seconds;
  nlohmann::json matches = nlohmann::json::array();
  for (size_t rank = 0; rank < result.matches.size(); ++rank) {
    matches.push_back(MatchJson(result, reader, rank));
  }
  json["matches"] = matches;
  return json;
}

// The command line of `search`, read back and checked.
struct SearchCommandOptions {
  std::string archive;
  std::string clip_name;   // a clip query (or a range of it: has_range), or
  std::string query_file;  // a file query: exactly one of the two is given
  bool has_range = false;
  uint64_t start = 0;
  uint64_t end = 0;
  std::string weights_path;
  uint32_t top = 10;
  int threads = 0;
  std::string distance = "emd";  // or "movement": whole takes only, no words files
  WordsReaderOutput output;
  bool movement() const { return distance == "movement"; }
};

void AddSearchOptions(CommandSpec& spec) {
  spec.name = "search";
  spec.usage =
      "motifmine search ARCHIVE (--clip NAME [--start S --end E] | --query FILE.bvh) "
      "[--top K] [--distance emd|movement] [--out DIR]";
  spec.summary =
      "Finds the motions of ARCHIVE most like a query, by the Earth Mover's Distance between\n"
      "motion signatures (run `motifmine words` first). With a frame range of a clip, or a\n"
      "BVH/AMC file, a window of as many words as the query slides along every take; a take\n"
      "gives several windows, none sharing a frame with another (or with the query), ranked\n"
      "together. A query shorter than one word is padded to one, a take shorter than the query\n"
      "compared whole. With a whole clip (no range), the other takes are ranked whole;\n"
      "--distance movement ranks them by their movement instead, the same action in another\n"
      "style before another action (docs/guide.md, \"search\").\n"
      "Writes DIR/search.json and DIR/search.html.";
  spec.options.add_options()("clip", po::value<std::string>()->default_value(""),
                             "query: a clip of the archive")(
      "start", po::value<uint64_t>(), "first frame of the query range (clip-relative)")(
      "end", po::value<uint64_t>(), "end of the query range (exclusive)")(
      "query", po::value<std::string>()->default_value(""),
      "query: a BVH (or ASF/AMC) file, embedded with the archive's embedding")(
      "top", po::value<uint32_t>()->default_value(10), "matches (windows) to keep, in all")(
      "distance", po::value<std::string>()->default_value("emd"),
      "emd (motion signatures) or movement (a whole clip: what moves and how, style-blind; "
      "no words files needed)");
  AddTableFlags(spec, {"weights"});
  AddWordsReaderOptions(spec, "PREFIX.mwe, .mwm, .mws", "search");
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
}

// Fills *options; returns -1 to go on, or the exit code after printing the usage error (a query
// that is not exactly one of --clip and --query, a lone --start or --end) or the error.
int ReadSearchOptions(const CommandSpec& spec, const po::variables_map& vm,
                      SearchCommandOptions* options) {
  const auto fail = [](const Status& status) { return ReportError("search", status); };
  options->archive = vm["archive"].as<std::string>();
  options->clip_name = vm["clip"].as<std::string>();
  options->query_file = vm["query"].as<std::string>();
  options->top = vm["top"].as<uint32_t>();
  motifmine::MineOptions table;
  ReadTableFlags(spec, vm, &table);
  options->threads = table.threads;
  if (options->clip_name.empty() == options->query_file.empty()) {
    std::fprintf(stderr, "motifmine search: give either --clip NAME or --query FILE\nusage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  if (vm.count("start") != vm.count("end") || (!options->query_file.empty() && vm.count("start"))) {
    std::fprintf(stderr,
                 "motifmine search: --start and --end go together, with --clip\n"
                 "usage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  options->distance = vm["distance"].as<std::string>();
  if (options->distance != "emd" && !options->movement()) {
    return fail(Status::InvalidOption("distance", "must be emd or movement, not '" +
                                                      options->distance + "'"));
  }
  if (options->movement() && (vm.count("start") || !options->query_file.empty())) {
    std::fprintf(stderr,
                 "motifmine search: --distance movement compares whole takes: give --clip NAME "
                 "without --start and --end\nusage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  options->has_range = vm.count("start") > 0;
  if (options->has_range) {
    options->start = vm["start"].as<uint64_t>();
    options->end = vm["end"].as<uint64_t>();
  }
  options->weights_path = table.weights_path;
  Result<WordsReaderOutput> output = WordsReaderOutputFrom(vm, options->archive, "search");
  if (!output.ok()) return fail(output.status());
  options->output = std::move(output.value());
  return -1;
}

Result<uint32_t> FindQueryClip(const FrameFileReader& frames, const SearchCommandOptions& options) {
  uint32_t clip = UINT32_MAX;
  for (uint32_t idx = 0; idx < frames.clips().size(); ++idx) {
    if (frames.clips()[idx].name == options.clip_name) clip = idx;
  }
  if (clip == UINT32_MAX) {
    return Status::NotFound(options.archive + ": no clip named '" + options.clip_name +
                            "' (motifmine info lists them)");
  }
  return clip;
}

// The note on a range query padded to one word.
std::string PaddedRangeNote(const RangeQuery& range, double fps) {
  const std::string shorter = range.range.count() < range.one_word_frames
                                  ? ", shorter than one motion word (" +
                                        Seconds(range.one_word_frames, fps) + ", " +
                                        std::to_string(range.one_word_frames) + " frames)"
                                  : ", holding no motion word";
  return "the query is " + Seconds(range.range.count(), fps) + " (frames " +
         std::to_string(range.range.first) + "-" + std::to_string(range.range.end) + ")" + shorter +
         ": padded to " + Seconds(range.word_frames.count(), fps) +
         " by taking the word centred on it, frames " + std::to_string(range.word_frames.first) +
         "-" + std::to_string(range.word_frames.end);
}

// Frames [start, end) of `clip`: its words slide along every take; windows sharing a frame with
// the query in its own clip are left out.
Result<SearchResult> SearchQueryRange(const SearchCommandOptions& options,
                                      const FrameFileReader& frames, const LoadedWords& words,
                                      uint32_t clip, SearchRun* run) {
  const uint64_t start = options.start;
  const uint64_t end = options.end;
  Result<RangeQuery> range = RangeQueryWords(frames, words, clip, start, end);
  if (!range.ok()) {
    return range.status().WithContext("--start " + std::to_string(start) + " --end " +
                                      std::to_string(end));
  }
  run->range = *range;
  const WindowQuery query = ToWindowQuery(*range, words);
  if (range->padded) run->info.notes.push_back(PaddedRangeNote(*range, frames.fps()));
  run->info.notes.push_back("windows of " + options.clip_name + " sharing a frame with frames " +
                            std::to_string(query.exclude_start_frame) + "-" +
                            std::to_string(query.exclude_end_frame) +
                            " (the query and the words it reads) are left out");
  SearchPageInfo& info = run->info;
  info.query_start = start;
  info.query_end = end;
  info.query_words = query.motifs.size();
  info.query_text = "clip " + options.clip_name + " frames " + std::to_string(start) + "\u2013" +
                    std::to_string(end);
  run->query_kind = "clip-range";
  return SlidingWindowSearch(frames, words, query, options.top, options.threads);
}

// A whole clip: the other takes ranked whole.
Result<SearchResult> SearchQueryTake(const SearchCommandOptions& options,
                                     const FrameFileReader& frames, const LoadedWords& words,
                                     uint32_t clip, SearchRun* run) {
  SearchPageInfo& info = run->info;
  info.query_start = 0;
  info.query_end = frames.clips()[clip].frame_count;
  info.query_words = words.signatures.clip_words[clip];
  info.query_text = "the whole of clip " + options.clip_name;
  run->info.notes.push_back("clip " + options.clip_name + " itself is left out");
  run->query_kind = "take";
  return WholeTakeSearch(frames, words, clip, options.top, options.threads);
}

// A whole clip by movement: the other takes ranked whole, no words read.
Result<SearchResult> SearchMovementTake(const SearchCommandOptions& options,
                                        const FrameFileReader& frames, uint32_t clip,
                                        SearchRun* run) {
  SearchPageInfo& info = run->info;
  info.query_start = 0;
  info.query_end = frames.clips()[clip].frame_count;
  info.query_text = "the whole of clip " + options.clip_name;
  run->info.notes.push_back("clip " + options.clip_name + " itself is left out");
  run->query_kind = "take";
  return WholeTakeMovementSearch(frames, clip, options.top, options.threads);
}

// A motion file, embedded with the archive's embedding: its words slide along every take.
Result<SearchResult> SearchQueryFile(const SearchCommandOptions& options,
                                     const FrameFileReader& frames, const LoadedWords& words,
                                     SearchRun* run) {
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights,
                         LoadDistanceWeights(frames.skeleton(), options.weights_path));
  WindowQuery query;
  std::string note;
  MOTIF_ASSIGN_OR_RETURN(query.motifs, QueryFileMotifs(options.query_file, frames, words, weights,
                                                       options.threads, &run->query_take, &note));
  if (!note.empty()) run->info.notes.push_back(note);
  SearchPageInfo& info = run->info;
  info.query_words = query.motifs.size();
  info.query_text = "file " + options.query_file;
  info.query_take = &run->query_take;
  run->query_kind = "file";
  return SlidingWindowSearch(frames, words, query, options.top, options.threads);
}

// Runs the query the options name into *run (which must stay where it is: run->info points
// into it for a file query).
Status SearchArchive(const SearchCommandOptions& options, const FrameFileReader& frames,
                     const LoadedWords& words, SearchRun* run) {
  const auto start_time = std::chrono::steady_clock::now();
  run->info.archive = options.archive;
  run->info.motifs = words.motifs.motif_count();
  Result<SearchResult> result = Status::InvalidArgument("no query");
  if (!options.clip_name.empty()) {
    MOTIF_ASSIGN_OR_RETURN(const uint32_t clip, FindQueryClip(frames, options));
    run->info.query_in_archive = true;
    run->info.query_clip = clip;
    if (options.movement()) {
      result = SearchMovementTake(options, frames, clip, run);
    } else {
      result = options.has_range ? SearchQueryRange(options, frames, words, clip, run)
                                 : SearchQueryTake(options, frames, words, clip, run);
    }
  } else {
    result = SearchQueryFile(options, frames, words, run);
  }
  if (!result.ok()) return result.status();
  run->result = std::move(result.value());
  run->info.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return Status::Ok();
}

Status WriteSearchFiles(const SearchCommandOptions& options, const FrameFileReader& frames,
                        const SearchRun& run) {
  const nlohmann::json json = SearchJson(run, frames, options.query_file);
  MOTIF_RETURN_IF_ERROR(AtomicWriteFile(options.output.json_path, json.dump(2) + "\n"));
  return WriteSearchHtml(options.output.html_path, run.result, frames, run.info);
}

// The takes `clips` names, up to a screenful; search.json lists them all.
std::string ClipList(const FrameFileReader& frames, const std::vector<uint32_t>& clips) {
  constexpr size_t kNamed = 10;
  std::string names;
  for (size_t idx = 0; idx < clips.size() && idx < kNamed; ++idx) {
    names += (idx ? ", " : ": ") + frames.clips()[clips[idx]].name;
  }
  if (clips.size() > kNamed) names += " and " + WithCommas(clips.size() - kNamed) + " more";
  return names;
}

// The takes of fewer words than the query (compared whole) and those of none (left out).
void PrintSearchShorter(const FrameFileReader& frames, const SearchRun& run) {
  const SearchResult& result = run.result;
  if (result.shorter_takes > 0) {
    std::printf(
        "  shorter      %s of fewer words than the query's %s, each compared whole (one "
        "window of all its words)%s\n",
        CountOf(result.shorter_takes, "take").c_str(), WithCommas(run.info.query_words).c_str(),
        ClipList(frames, result.shorter_clips).c_str());
  }
  std::vector<uint32_t> wordless;
  for (uint32_t clip : result.wordless_clips) {
    if (!run.info.query_in_archive || clip != run.info.query_clip) wordless.push_back(clip);
  }
  if (!wordless.empty()) {
    std::printf("  left out     %s: %s%s\n", CountOf(wordless.size(), "take").c_str(),
                LeftOutReason(result), ClipList(frames, wordless).c_str());
  }
}

void PrintSearchSummary(const SearchCommandOptions& options, const FrameFileReader& frames,
                        const SearchRun& run) {
  const SearchResult& result = run.result;
  const bool movement = result.distance == "movement";
  std::printf("motifmine search: %s, query %s (%s)\n", options.archive.c_str(),
              run.info.query_text.c_str(),
              movement ? "by movement" : CountOf(run.info.query_words, "word").c_str());
  for (const std::string& note : run.info.notes) std::printf("  note         %s\n", note.c_str());
  const double fps = frames.fps();
  for (size_t rank = 0; rank < result.matches.size(); ++rank) {
    const WindowMatch& match = result.matches[rank];
    const std::string in_take = result.whole_take ? ""
                                : match.whole_take
                                    ? "  (the whole take)"
                                    : "  (its take's #" + std::to_string(match.rank_in_take) + ")";
    std::printf("  %2zu. %-20s frames %7llu-%-7llu (%.2f-%.2f s)  %s %.4f%s\n", rank + 1,
                frames.clips()[match.clip].name.c_str(),
                static_cast<unsigned long long>(match.start_frame),
                static_cast<unsigned long long>(match.end_frame), match.start_frame / fps,
                match.end_frame / fps, movement ? "distance" : "EMD", match.distance,
                in_take.c_str());
  }
  std::printf("  compared     %s %s in %.2fs%s\n", WithCommas(result.windows).c_str(),
              movement ? "takes" : "windows", run.info.seconds,
              result.whole_take ? "" : "; a take's matches share no frame");
  PrintSearchShorter(frames, run);
  std::printf("  wrote        %s, %s\n", options.output.json_path.c_str(),
              options.output.html_path.c_str());
}

}  // namespace

int RunSearch(const std::vector<std::string>& args) {
  CommandSpec spec;
  AddSearchOptions(spec);
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const auto fail = [](const Status& status) { return ReportError("search", status); };
  SearchCommandOptions options;
  if (int code = ReadSearchOptions(spec, vm, &options); code >= 0) return code;

  Result<std::unique_ptr<FrameFileReader>> reader = FrameFileReader::Open(options.archive);
  if (!reader.ok()) return fail(reader.status());
  const FrameFileReader& frames = **reader;
  // The movement distance reads no words, so none are loaded for it.
  Result<LoadedWords> words =
      options.movement()
          ? Result<LoadedWords>(LoadedWords())
          : LoadWords(frames, DefaultWordsPaths(options.output.prefix_archive),
                      /*with_embedding=*/!options.query_file.empty());
  if (!words.ok()) return fail(words.status());
  SearchRun run;
  if (Status status = SearchArchive(options, frames, *words, &run); !status.ok()) {
    return fail(status);
  }
  if (Status status = WriteSearchFiles(options, frames, run); !status.ok()) return fail(status);
  PrintSearchSummary(options, frames, run);
  return kExitOk;
}

}  // namespace motif::cli
