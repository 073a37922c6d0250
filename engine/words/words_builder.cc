#include "engine/words/words_builder.h"

#include <chrono>
#include <filesystem>
#include <sstream>

#include "common/byte_coding.h"
#include "common/file_lock.h"
#include "common/seconds_since.h"
#include "engine/distance/pose_features.h"
#include "engine/embedding/embedding_file.h"
#include "engine/signature/frame_resampler.h"
#include "engine/signature/k_means.h"
#include "engine/signature/tf_idf.h"
#include "engine/signature/word_stream.h"
#include "engine/words/word_embedder.h"
#include "engine/words/word_files.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {
namespace {

using Clock = std::chrono::steady_clock;

// The options with the shared ones (word geometry, seed, threads) put where each stage reads them.
WordsOptions Resolve(const WordsOptions& in) {
  WordsOptions options = in;
  options.pool.words = options.words;
  options.pool.seed = options.seed;
  options.pool.threads = options.threads;
  options.neighbours.seed = options.seed;
  options.neighbours.threads = options.threads;
  options.train.seed = options.seed;
  options.train.threads = options.threads;
  return options;
}

Status Validate(const WordsOptions& options) {
  MOTIF_RETURN_IF_ERROR(ValidateWordOptions(options.words));
  MOTIF_RETURN_IF_ERROR(ValidateWordPoolOptions(options.pool));
  if (options.motifs == 0 || options.motifs > 65535) {
    return Status::InvalidArgument("words: the number of motifs must be in [1, 65535]");
  }
  if (options.kmeans_iterations == 0) {
    return Status::InvalidArgument("words: k-means needs at least one iteration");
  }
  if (options.batch_words == 0) return Status::InvalidArgument("words: batch_words must be >= 1");
  if (options.neighbours.k == 0 || options.neighbours.probes == 0) {
    return Status::InvalidArgument("words: DTW neighbours and probes must be at least 1");
  }
  EmbeddingTrainOptions train = options.train;
  train.shape.frames = options.words.word_frames;
  train.shape.input_channels = 4;  // any valid value: the real one comes from the skeleton
  return ValidateEmbeddingTrainOptions(train);
}

// The trained embedding of the archive: reused, resumed or trained.
struct EmbeddingStage {
  EmbeddingModel model;
  uint64_t identity = 0;
};

// The checkpoint's state, when it is of this training (same key and parameter count) and not
// past its epochs: training goes on after its last epoch.
void ResumeFromCheckpoint(const std::string& checkpoint_path, uint64_t key, uint32_t epochs,
                          const WordsOptions& options, TrainingState* state, WordsReport* report) {
  Result<TensorFile> checkpoint_file = ReadTensorFile(checkpoint_path, kCheckpointKind);
  if (!checkpoint_file.ok()) return;
  EmbeddingModel stored;
  Result<TrainingState> stored_state = CheckpointFromTensorFile(*checkpoint_file, &stored);
  if (stored_state.ok() && stored.training_key == key &&
      stored_state->parameters.size() == state->parameters.size() &&
      stored_state->epochs_done <= epochs) {
    *state = std::move(stored_state.value());
    report->resumed_from_epoch = state->epochs_done;
    if (options.note) {
      options.note("resuming training after epoch " + std::to_string(state->epochs_done) +
                   " from " + checkpoint_path);
    }
  }
}

// Trains the network from its initial (or checkpointed) state, writing a checkpoint after each
// epoch, then the embedding file; the checkpoint goes once the embedding is written.
Status TrainAndWriteEmbedding(const EmbeddingTrainer& trainer, const WordsPaths& paths,
                              const WordsOptions& options, uint32_t epochs, EmbeddingStage* stage,
                              WordsReport* report) {
  EmbeddingModel& model = stage->model;
  TrainingState state = trainer.InitialState();
  const std::string checkpoint_path = paths.embedding + ".checkpoint";
  ResumeFromCheckpoint(checkpoint_path, model.training_key, epochs, options, &state, report);
  MOTIF_RETURN_IF_ERROR(trainer.Train(&state, [&](const TrainingState& done) {
    MOTIF_RETURN_IF_ERROR(WriteTensorFile(checkpoint_path, CheckpointToTensorFile(model, done)));
    return options.after_epoch ? options.after_epoch(done.epochs_done) : Status::Ok();
  }));
  model.net = trainer.NetOf(state);
  model.epoch_loss = state.epoch_loss;
  model.epoch_active = state.epoch_active;
  model.accuracy = trainer.HeldOutAccuracy(model.net);
  MOTIF_RETURN_IF_ERROR(WriteTensorFile(paths.embedding, EmbeddingToTensorFile(model),
                                        PosixFileSystem(), &stage->identity));
  std::error_code ignored;  // a left-over checkpoint is harmless: its key no longer matters
  std::filesystem::remove(checkpoint_path, ignored);
  return Status::Ok();
}

Result<EmbeddingStage> TrainEmbedding(const FrameFileReader& reader,
                                      const std::vector<float>& weights, const WordsPaths& paths,
                                      const WordsOptions& options, uint64_t key,
                                      WordsReport* report) {
  auto progress = [&](const char* stage, const char* unit) {
    return [&options, stage, unit](uint64_t done, uint64_t total) {
      if (options.progress) options.progress(stage, done, total, unit);
    };
  };
  Clock::time_point start = Clock::now();
  WordPoolOptions pool_options = options.pool;
  pool_options.progress = progress("pool", "clips");
  MOTIF_ASSIGN_OR_RETURN(WordPool pool, WordPool::Build(reader, weights, pool_options));
  report->seconds_pool = SecondsSince(start);
  report->pool_words = pool.size();

  start = Clock::now();
  DtwNeighbourOptions neighbour_options = options.neighbours;
  neighbour_options.progress = progress("neighbours", "words");
  MOTIF_ASSIGN_OR_RETURN(auto neighbours, FindDtwNeighbours(pool, neighbour_options));
  report->seconds_neighbours = SecondsSince(start);

  start = Clock::now();
  EmbeddingTrainOptions train = options.train;
  train.progress = progress("train", "batches");
  MOTIF_ASSIGN_OR_RETURN(EmbeddingTrainer trainer,
                         EmbeddingTrainer::Create(pool, std::move(neighbours), train));
  MOTIF_ASSIGN_OR_RETURN(FrameResampler resampler,
                         FrameResampler::Create(reader.layout(), weights));
  EmbeddingStage stage;
  EmbeddingModel& model = stage.model;
  model.net = trainer.initial_net();
  model.words = options.words;
  model.joints = resampler.joints();
  model.joint_weights = resampler.weights();
  model.archive_identity = reader.summary().identity;
  model.training_key = key;
  model.seed = options.seed;
  model.pool_words = pool.size();
  MOTIF_RETURN_IF_ERROR(
      TrainAndWriteEmbedding(trainer, paths, options, train.epochs, &stage, report));
  report->seconds_train = SecondsSince(start);
  return stage;
}

Result<EmbeddingStage> LoadEmbedding(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(TensorFile file, ReadTensorFile(path, kEmbeddingKind));
  Result<EmbeddingModel> model = EmbeddingFromTensorFile(file);
  if (!model.ok()) return model.status().WithContext(path);
  return EmbeddingStage{std::move(model.value()), file.identity()};
}

}  // namespace

WordsPaths DefaultWordsPaths(const std::string& archive_path) {
  std::filesystem::path path(archive_path);
  if (path.extension() == ".mfs") path.replace_extension("");
  const std::string base = path.string();
  return {base + ".mwe", base + ".mwm", base + ".mws"};
}

uint64_t TrainingKey(uint64_t archive_identity, const std::vector<float>& joint_weights,
                     const WordsOptions& in) {
  const WordsOptions options = Resolve(in);
  std::ostringstream key;
  key.precision(17);
  key << "archive=" << archive_identity << " weights=";
  for (float weight : joint_weights) key << weight << ",";
  const WordPoolOptions& pool = options.pool;
  key << " W=" << options.words.word_frames << " S=" << options.words.stride_frames
      << " fps=" << options.words.word_fps << " pool=" << pool.max_words << "/" << pool.warp_copies
      << "/" << pool.warp.min_speed << "/" << pool.warp.max_speed << "/" << pool.held_out_fraction;
  const DtwNeighbourOptions& n = options.neighbours;
  key << " dtw=" << n.k << "/" << n.band_frames << "/" << n.lists << "/" << n.probes << "/"
      << n.max_verified;
  const EmbeddingTrainOptions& t = options.train;
  const EmbeddingNetShape& s = t.shape;
  key << " net=" << s.conv1_channels << "/" << s.conv1_kernel << "/" << s.conv2_channels << "/"
      << s.conv2_kernel << "/" << s.conv2_stride << "/" << s.embedding_dims << " train=" << t.epochs
      << "/" << t.batch_triplets << "/" << t.learning_rate << "/" << t.margin << "/"
      << t.temporal_positives << "/" << t.dtw_positives << "/" << t.far_words << "/"
      << t.mine_semi_hard << " seed=" << options.seed;
  const std::string text = key.str();
  return Checksum64(text.data(), text.size());
}

namespace {

// What the stages of one BuildWords run share: the archive and its weights, the report being
// filled, and each stage's product.
struct WordsBuild {
  std::string archive_path;
  WordsPaths paths;
  WordsOptions options;  // resolved; `words` replaced by a loaded embedding's
  std::unique_ptr<FrameFileReader> reader;
  std::vector<float> weights;
  uint64_t archive_identity = 0;
  WordsReport report;
  EmbeddingStage embedding;
  MotifSet motifs;
  uint64_t motifs_identity = 0;
  SignatureSet signatures;
};

// The archive's words, counted first: bad options fail before anything is trained or written.
Status CountArchiveWords(WordsBuild* build) {
  const std::vector<ClipInfo>& clips = build->reader->clips();
  WordsReport& report = build->report;
  SignatureSet& signatures = build->signatures;
  signatures.archive_identity = build->archive_identity;
  signatures.words = build->options.words;
  for (size_t clip = 0; clip < clips.size(); ++clip) {
    const uint64_t words = ClipWordGrid(*build->reader, clip, build->options.words).word_count();
    signatures.clip_words.push_back(words);
    report.words += words;
    report.takes += words > 0;
  }
  report.clips = clips.size();
  if (report.words < build->options.motifs) {
    return Status::InvalidArgument(build->archive_path + ": " + std::to_string(report.words) +
                                   " words, fewer than the " +
                                   std::to_string(build->options.motifs) + " asked for (motifs)")
        .WithOption("motifs");
  }
  return Status::Ok();
}

// Stage 1, unless the embedding was loaded: the stored one when its training key is this run's,
// else trained (or resumed).
Status ObtainEmbedding(WordsBuild* build) {
  WordsReport& report = build->report;
  if (!report.embedding_loaded) {
    const uint64_t key = TrainingKey(build->archive_identity, build->weights, build->options);
    Result<EmbeddingStage> stored = LoadEmbedding(build->paths.embedding);
    if (stored.ok() && stored->model.training_key == key) {
      build->embedding = std::move(stored.value());
      report.embedding_reused = true;
    } else {
      MOTIF_ASSIGN_OR_RETURN(build->embedding,
                             TrainEmbedding(*build->reader, build->weights, build->paths,
                                            build->options, key, &report));
    }
  }
  const EmbeddingModel& model = build->embedding.model;
  report.epoch_loss = model.epoch_loss;
  report.accuracy = model.accuracy;
  report.pool_words = model.pool_words;
  return Status::Ok();
}

// Stage 2's reuse: the stored motifs, if made from this embedding and archive with these
// options.
void ReuseStoredMotifs(WordsBuild* build) {
  Result<TensorFile> file = ReadTensorFile(build->paths.motifs, kMotifsKind);
  if (!file.ok()) return;
  Result<MotifSet> stored = MotifsFromTensorFile(*file);
  if (stored.ok() && stored->embedding_identity == build->embedding.identity &&
      stored->archive_identity == build->archive_identity && stored->seed == build->options.seed &&
      stored->motif_count() == build->options.motifs &&
      stored->centroids.cols() == static_cast<Eigen::Index>(build->report.dims)) {
    build->motifs = std::move(stored.value());
    build->motifs_identity = file->identity();
    build->report.motifs_reused = true;
  }
}

// Stage 3's reuse: the stored signatures, if made from the reused motifs on this archive with
// this word geometry.
void ReuseStoredSignatures(WordsBuild* build) {
  Result<TensorFile> file = ReadTensorFile(build->paths.signatures, kSignaturesKind);
  if (!file.ok()) return;
  Result<SignatureSet> stored = SignaturesFromTensorFile(*file);
  const WordOptions& words = build->options.words;
  if (stored.ok() && stored->motifs_identity == build->motifs_identity &&
      stored->archive_identity == build->archive_identity &&
      stored->clip_words == build->signatures.clip_words &&
      stored->words.word_frames == words.word_frames &&
      stored->words.stride_frames == words.stride_frames &&
      stored->words.word_fps == words.word_fps) {
    build->report.signatures_reused = true;
    build->signatures = std::move(stored.value());
  }
}

// Every word embedded, streamed from the archive a batch at a time.
Result<RowMatrixXf> EmbedArchiveWords(const WordsBuild& build, const WordEmbedder& embedder) {
  const WordsOptions& options = build.options;
  const uint64_t word_count = build.report.words;
  RowMatrixXf embedded(static_cast<Eigen::Index>(word_count), build.report.dims);
  WordStreamOptions stream_options;
  stream_options.words = options.words;
  stream_options.batch_words = options.batch_words;
  stream_options.keep_rows = true;
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<WordStream> stream,
                         WordStream::Create(*build.reader, build.weights, stream_options));
  WordBatch batch;
  Eigen::Index row = 0;
  for (;;) {
    MOTIF_ASSIGN_OR_RETURN(bool more, stream->Next(&batch));
    if (!more) break;
    embedder.Embed(batch, &embedded, row);
    row += static_cast<Eigen::Index>(batch.size());
    if (options.progress) options.progress("embed", row, word_count, "words");
  }
  MOTIF_CHECK(row == static_cast<Eigen::Index>(word_count));
  return embedded;
}

// Stage 2 proper: k-means of the embedded words, written as the motifs file.
Status ClusterWordMotifs(const RowMatrixXf& embedded, WordsBuild* build) {
  const WordsOptions& options = build->options;
  if (options.progress) options.progress("k-means", 0, 1, "runs");
  KMeansOptions kmeans;
  kmeans.k = options.motifs;
  kmeans.seed = options.seed;
  kmeans.max_iterations = options.kmeans_iterations;
  kmeans.threads = options.threads;
  Result<KMeansResult> clustered = RunKMeans(embedded, kmeans);
  if (!clustered.ok()) return clustered.status().WithContext(build->archive_path + ": motifs");
  MotifSet& motifs = build->motifs;
  motifs.centroids = std::move(clustered->centroids);
  motifs.cluster_sizes = std::move(clustered->cluster_sizes);
  motifs.inertia = clustered->inertia;
  motifs.iterations = clustered->iterations;
  motifs.embedding_identity = build->embedding.identity;
  motifs.archive_identity = build->archive_identity;
  motifs.seed = options.seed;
  build->signatures.word_motifs.assign(clustered->assignments.begin(),
                                       clustered->assignments.end());
  MOTIF_RETURN_IF_ERROR(WriteTensorFile(build->paths.motifs, MotifsToTensorFile(motifs),
                                        PosixFileSystem(), &build->motifs_identity));
  if (options.progress) options.progress("k-means", 1, 1, "runs");
  return Status::Ok();
}

// Stage 3 proper: each take's TF-IDF signature over the words' motifs, written as the
// signatures file (a clip without words keeps a zero row).
Status WriteTakeSignatures(WordsBuild* build) {
  const std::vector<ClipInfo>& clips = build->reader->clips();
  SignatureSet& signatures = build->signatures;
  signatures.motifs_identity = build->motifs_identity;
  signatures.motif_count = build->motifs.motif_count();
  std::vector<std::vector<uint32_t>> takes;
  const std::vector<uint64_t> first_words = signatures.ClipFirstWords();
  for (size_t clip = 0; clip < clips.size(); ++clip) {
    if (signatures.clip_words[clip] == 0) continue;
    const auto begin =
        signatures.word_motifs.begin() + static_cast<std::ptrdiff_t>(first_words[clip]);
    takes.emplace_back(begin, begin + static_cast<std::ptrdiff_t>(signatures.clip_words[clip]));
  }
  MOTIF_ASSIGN_OR_RETURN(TfIdf tf_idf, TfIdf::Fit(takes, signatures.motif_count));
  signatures.take_count = tf_idf.take_count();
  signatures.document_frequencies = tf_idf.document_frequencies();
  signatures.signatures.assign(clips.size() * signatures.motif_count, 0.0);
  size_t take = 0;
  for (size_t clip = 0; clip < clips.size(); ++clip) {
    if (signatures.clip_words[clip] == 0) continue;
    MOTIF_ASSIGN_OR_RETURN(std::vector<double> signature, tf_idf.Signature(takes[take++]));
    std::copy(
        signature.begin(), signature.end(),
        signatures.signatures.begin() + static_cast<std::ptrdiff_t>(clip * signatures.motif_count));
  }
  return WriteTensorFile(build->paths.signatures, SignaturesToTensorFile(signatures));
}

// Stages 2 and 3 when the signatures cannot be reused: every word embedded, its motif (k-means,
// or the reused motifs' nearest), then the signatures.
Status MakeMotifsAndSignatures(const WordEmbedder& embedder, WordsBuild* build) {
  WordsReport& report = build->report;
  Clock::time_point start = Clock::now();
  MOTIF_ASSIGN_OR_RETURN(RowMatrixXf embedded, EmbedArchiveWords(*build, embedder));
  report.seconds_embed = SecondsSince(start);

  start = Clock::now();
  if (!report.motifs_reused) {
    MOTIF_RETURN_IF_ERROR(ClusterWordMotifs(embedded, build));
  } else {
    build->signatures.word_motifs =
        NearestMotifs(embedded, build->motifs.centroids, build->options.threads);
  }
  report.seconds_kmeans = SecondsSince(start);

  start = Clock::now();
  MOTIF_RETURN_IF_ERROR(WriteTakeSignatures(build));
  report.seconds_signatures = SecondsSince(start);
  return Status::Ok();
}

// Locks the archive's words files, opens it and reads its weights, and loads the embedding
// from elsewhere, if any (it fixes the word geometry).
Status OpenWordsBuild(const std::string& archive_path, const WordsPaths& paths,
                      const WordsOptions& in, ExclusiveFileLock* lock, WordsBuild* build) {
  build->archive_path = archive_path;
  build->paths = paths;
  build->options = Resolve(in);
  WordsOptions& options = build->options;
  MOTIF_RETURN_IF_ERROR(Validate(options));
  MOTIF_RETURN_IF_ERROR(lock->Acquire(paths.signatures + ".lock",
                                      "another `motifmine words` is working on this archive; "
                                      "nothing was changed",
                                      /*create=*/true));
  MOTIF_ASSIGN_OR_RETURN(build->reader, FrameFileReader::Open(archive_path));
  MOTIF_ASSIGN_OR_RETURN(build->weights,
                         LoadDistanceWeights(build->reader->skeleton(), options.weights_path));
  build->archive_identity = build->reader->summary().identity;
  build->report.archive_generation = build->reader->summary().generation;
  build->report.paths = paths;
  if (!options.embedding_in.empty()) {
    MOTIF_ASSIGN_OR_RETURN(build->embedding, LoadEmbedding(options.embedding_in));
    build->report.embedding_loaded = true;
    options.words = build->embedding.model.words;  // the words the network was trained on
  }
  return Status::Ok();
}

}  // namespace

Result<WordsReport> BuildWords(const std::string& archive_path, const WordsPaths& paths,
                               const WordsOptions& in) {
  ExclusiveFileLock lock;
  WordsBuild build;
  MOTIF_RETURN_IF_ERROR(OpenWordsBuild(archive_path, paths, in, &lock, &build));
  MOTIF_RETURN_IF_ERROR(CountArchiveWords(&build));
  MOTIF_RETURN_IF_ERROR(ObtainEmbedding(&build));
  MOTIF_ASSIGN_OR_RETURN(WordEmbedder embedder,
                         WordEmbedder::Create(build.embedding.model, build.reader->layout(),
                                              build.weights, build.options.threads));
  WordsReport& report = build.report;
  report.dims = embedder.dims();
  ReuseStoredMotifs(&build);
  if (report.motifs_reused) ReuseStoredSignatures(&build);
  if (!report.signatures_reused) MOTIF_RETURN_IF_ERROR(MakeMotifsAndSignatures(embedder, &build));
  report.motifs = build.motifs.motif_count();
  report.kmeans_inertia = build.motifs.inertia;
  report.kmeans_iterations = build.motifs.iterations;
  return report;
}

}  // namespace motif
