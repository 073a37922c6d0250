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

  TrainingState state = trainer.InitialState();
  const std::string checkpoint_path = paths.embedding + ".checkpoint";
  Result<TensorFile> checkpoint_file = ReadTensorFile(checkpoint_path, kCheckpointKind);
  if (checkpoint_file.ok()) {
    EmbeddingModel stored;
    Result<TrainingState> stored_state = CheckpointFromTensorFile(*checkpoint_file, &stored);
    if (stored_state.ok() && stored.training_key == key &&
        stored_state->parameters.size() == state.parameters.size() &&
        stored_state->epochs_done <= train.epochs) {
      state = std::move(stored_state.value());
      report->resumed_from_epoch = state.epochs_done;
      if (options.note) {
        options.note("resuming training after epoch " + std::to_string(state.epochs_done) +
                     " from " + checkpoint_path);
      }
    }
  }
  MOTIF_RETURN_IF_ERROR(trainer.Train(&state, [&](const TrainingState& done) {
    MOTIF_RETURN_IF_ERROR(WriteTensorFile(checkpoint_path, CheckpointToTensorFile(model, done)));
    return options.after_epoch ? options.after_epoch(done.epochs_done) : Status::Ok();
  }));
  model.net = trainer.NetOf(state);
  model.epoch_loss = state.epoch_loss;
  model.epoch_active = state.epoch_active;
  model.accuracy = trainer.HeldOutAccuracy(model.net);
  report->seconds_train = SecondsSince(start);
  MOTIF_RETURN_IF_ERROR(WriteTensorFile(paths.embedding, EmbeddingToTensorFile(model),
                                        PosixFileSystem(), &stage.identity));
  std::error_code ignored;  // a left-over checkpoint is harmless: its key no longer matters
  std::filesystem::remove(checkpoint_path, ignored);
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

Result<WordsReport> BuildWords(const std::string& archive_path, const WordsPaths& paths,
                               const WordsOptions& in) {
  WordsOptions options = Resolve(in);
  MOTIF_RETURN_IF_ERROR(Validate(options));
  ExclusiveFileLock lock;
  MOTIF_RETURN_IF_ERROR(lock.Acquire(paths.signatures + ".lock",
                                     "another `motifmine words` is working on this archive; "
                                     "nothing was changed",
                                     /*create=*/true));
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> reader,
                         FrameFileReader::Open(archive_path));
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights,
                         LoadDistanceWeights(reader->skeleton(), options.weights_path));
  const uint64_t archive_identity = reader->summary().identity;
  WordsReport report;
  report.archive_generation = reader->summary().generation;
  report.paths = paths;

  // An embedding from elsewhere fixes the word geometry.
  EmbeddingStage embedding;
  if (!options.embedding_in.empty()) {
    MOTIF_ASSIGN_OR_RETURN(embedding, LoadEmbedding(options.embedding_in));
    report.embedding_loaded = true;
    options.words = embedding.model.words;  // the words the network was trained on
  }

  // The archive's words, counted first: bad options fail before anything is trained or written.
  const std::vector<ClipInfo>& clips = reader->clips();
  SignatureSet signatures;
  signatures.archive_identity = archive_identity;
  signatures.words = options.words;
  for (size_t clip = 0; clip < clips.size(); ++clip) {
    const uint64_t words = ClipWordGrid(*reader, clip, options.words).word_count();
    signatures.clip_words.push_back(words);
    report.words += words;
    report.takes += words > 0;
  }
  report.clips = clips.size();
  if (report.words < options.motifs) {
    return Status::InvalidArgument(archive_path + ": " + std::to_string(report.words) +
                                   " words, fewer than the " + std::to_string(options.motifs) +
                                   " asked for (motifs)")
        .WithOption("motifs");
  }

  // Stage 1: the embedding.
  if (!report.embedding_loaded) {
    const uint64_t key = TrainingKey(archive_identity, weights, options);
    Result<EmbeddingStage> stored = LoadEmbedding(paths.embedding);
    if (stored.ok() && stored->model.training_key == key) {
      embedding = std::move(stored.value());
      report.embedding_reused = true;
    } else {
      MOTIF_ASSIGN_OR_RETURN(embedding,
                             TrainEmbedding(*reader, weights, paths, options, key, &report));
    }
  }
  const EmbeddingModel& model = embedding.model;
  report.epoch_loss = model.epoch_loss;
  report.accuracy = model.accuracy;
  report.pool_words = model.pool_words;
  MOTIF_ASSIGN_OR_RETURN(WordEmbedder embedder,
                         WordEmbedder::Create(model, reader->layout(), weights, options.threads));
  report.dims = embedder.dims();

  // Stage 2: the motifs (reused if made from this embedding and archive with these options).
  MotifSet motifs;
  uint64_t motifs_identity = 0;
  if (Result<TensorFile> file = ReadTensorFile(paths.motifs, kMotifsKind); file.ok()) {
    Result<MotifSet> stored = MotifsFromTensorFile(*file);
    if (stored.ok() && stored->embedding_identity == embedding.identity &&
        stored->archive_identity == archive_identity && stored->seed == options.seed &&
        stored->motif_count() == options.motifs &&
        stored->centroids.cols() == static_cast<Eigen::Index>(report.dims)) {
      motifs = std::move(stored.value());
      motifs_identity = file->identity();
      report.motifs_reused = true;
    }
  }
  if (report.motifs_reused) {
    if (Result<TensorFile> file = ReadTensorFile(paths.signatures, kSignaturesKind); file.ok()) {
      Result<SignatureSet> stored = SignaturesFromTensorFile(*file);
      if (stored.ok() && stored->motifs_identity == motifs_identity &&
          stored->archive_identity == archive_identity &&
          stored->clip_words == signatures.clip_words &&
          stored->words.word_frames == options.words.word_frames &&
          stored->words.stride_frames == options.words.stride_frames &&
          stored->words.word_fps == options.words.word_fps) {
        report.signatures_reused = true;
        signatures = std::move(stored.value());
      }
    }
  }
  if (!report.signatures_reused) {
    // Every word embedded, streamed from the archive a batch at a time.
    Clock::time_point start = Clock::now();
    RowMatrixXf embedded(static_cast<Eigen::Index>(report.words), report.dims);
    WordStreamOptions stream_options;
    stream_options.words = options.words;
    stream_options.batch_words = options.batch_words;
    stream_options.keep_rows = true;
    MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<WordStream> stream,
                           WordStream::Create(*reader, weights, stream_options));
    WordBatch batch;
    Eigen::Index row = 0;
    for (;;) {
      MOTIF_ASSIGN_OR_RETURN(bool more, stream->Next(&batch));
      if (!more) break;
      embedder.Embed(batch, &embedded, row);
      row += static_cast<Eigen::Index>(batch.size());
      if (options.progress) options.progress("embed", row, report.words, "words");
    }
    MOTIF_CHECK(row == static_cast<Eigen::Index>(report.words));
    report.seconds_embed = SecondsSince(start);

    start = Clock::now();
    if (!report.motifs_reused) {
      if (options.progress) options.progress("k-means", 0, 1, "runs");
      KMeansOptions kmeans;
      kmeans.k = options.motifs;
      kmeans.seed = options.seed;
      kmeans.max_iterations = options.kmeans_iterations;
      kmeans.threads = options.threads;
      Result<KMeansResult> clustered = RunKMeans(embedded, kmeans);
      if (!clustered.ok()) return clustered.status().WithContext(archive_path + ": motifs");
      motifs.centroids = std::move(clustered->centroids);
      motifs.cluster_sizes = std::move(clustered->cluster_sizes);
      motifs.inertia = clustered->inertia;
      motifs.iterations = clustered->iterations;
      motifs.embedding_identity = embedding.identity;
      motifs.archive_identity = archive_identity;
      motifs.seed = options.seed;
      signatures.word_motifs.assign(clustered->assignments.begin(), clustered->assignments.end());
      MOTIF_RETURN_IF_ERROR(WriteTensorFile(paths.motifs, MotifsToTensorFile(motifs),
                                            PosixFileSystem(), &motifs_identity));
      if (options.progress) options.progress("k-means", 1, 1, "runs");
    } else {
      signatures.word_motifs = NearestMotifs(embedded, motifs.centroids, options.threads);
    }
    report.seconds_kmeans = SecondsSince(start);

    // Stage 3: the signatures.
    start = Clock::now();
    signatures.motifs_identity = motifs_identity;
    signatures.motif_count = motifs.motif_count();
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
      std::copy(signature.begin(), signature.end(),
                signatures.signatures.begin() +
                    static_cast<std::ptrdiff_t>(clip * signatures.motif_count));
    }
    MOTIF_RETURN_IF_ERROR(WriteTensorFile(paths.signatures, SignaturesToTensorFile(signatures)));
    report.seconds_signatures = SecondsSince(start);
  }
  report.motifs = motifs.motif_count();
  report.kmeans_inertia = motifs.inertia;
  report.kmeans_iterations = motifs.iterations;
  return report;
}

}  // namespace motif
