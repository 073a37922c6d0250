// BuildWords: the `motifmine words` job (Aristidou et al. 2018; docs/design/signatures.md): the
// word embedding trained on the archive (or loaded), every word of the archive embedded, the
// motifs (k-means of the embedded words) and every take's TF-IDF signature, written beside the
// archive as three tensor files (docs/formats/tensor_file.md):
//
//   ARCHIVE.mwe   the embedding (kind "embedding"); ARCHIVE.mwe.checkpoint while training
//   ARCHIVE.mwm   the motifs (kind "motifs")
//   ARCHIVE.mws   the signatures and every word's motif (kind "signatures")
//
// Stages and reuse (each file records what it was made from; a stage runs again only when that
// changed, and everything after it):
//  1. embedding: reused when the file's training key (the archive's identity and every option
//     that changes the weights) is this run's; training resumes from the checkpoint, written
//     after each epoch, when its key matches; with `embedding_in`, that file is loaded instead
//     (trained on any archive of the same skeleton and weights) and nothing is trained;
//     training = the word pool (word_pool.h), its DTW neighbours (dtw_neighbours.h), the epochs
//     (embedding_trainer.h), the held-out triplet accuracy;
//  2. motifs: reused when made from this embedding file (its identity) on this archive with the
//     same k and seed; else every word is embedded (streamed from the archive a batch at a time)
//     and clustered (k_means.h);
//  3. signatures: reused when made from this motifs file on this archive; else each word's motif
//     (from step 2's assignments, or the words embedded again) and the TF-IDF signatures.
// Every file is written atomically; a run killed at any point and started again ends with the
// same files. Memory: the pool (training only: ~1.8 KB a word and copy, `pool.max_words` words),
// and D floats plus a motif id per archive word (132 bytes a word at D = 32).
// Thread-safety: one run per archive at a time (it holds an flock on ARCHIVE.mws.lock).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/embedding/dtw_neighbours.h"
#include "engine/embedding/embedding_trainer.h"
#include "engine/embedding/word_pool.h"
#include "engine/signature/word_grid.h"

namespace motif {

struct WordsPaths {
  std::string embedding;   // .mwe
  std::string motifs;      // .mwm
  std::string signatures;  // .mws
};

// ARCHIVE (without .mfs) + ".mwe", ".mwm", ".mws".
WordsPaths DefaultWordsPaths(const std::string& archive_path);

struct WordsOptions {
  WordOptions words;
  std::string weights_path;  // per-joint weights file; empty: the skeleton's defaults
  std::string embedding_in;  // load this embedding instead of training one
  WordPoolOptions pool;      // words, seed and threads are set from this struct
  DtwNeighbourOptions neighbours;
  EmbeddingTrainOptions train;
  uint32_t motifs = 100;  // k
  uint32_t kmeans_iterations = 100;
  uint64_t seed = 1;            // of every random choice
  int threads = 0;              // 0: all cores
  uint32_t batch_words = 1024;  // words embedded per streamed batch
  std::function<void(const std::string&, uint64_t, uint64_t, const std::string&)> progress;
  // (stage, done, total, unit)
  std::function<void(const std::string&)> note;
  // Called after each training epoch once its checkpoint is written; a non-OK status stops the
  // run there and is returned (cancellation; the next run resumes from that checkpoint).
  std::function<Status(uint32_t)> after_epoch;
};

struct WordsReport {
  uint64_t archive_generation = 0;  // the version read (once: a later append does not change it)
  uint64_t clips = 0;
  uint64_t takes = 0;  // clips with at least one word
  uint64_t words = 0;
  uint32_t motifs = 0;
  uint32_t dims = 0;
  bool embedding_reused = false;
  bool embedding_loaded = false;    // from embedding_in
  uint32_t resumed_from_epoch = 0;  // 0: trained from scratch (or not trained)
  bool motifs_reused = false;
  bool signatures_reused = false;
  uint64_t pool_words = 0;
  std::vector<double> epoch_loss;
  TripletAccuracy accuracy;
  double kmeans_inertia = 0;
  uint32_t kmeans_iterations = 0;
  double seconds_pool = 0, seconds_neighbours = 0, seconds_train = 0, seconds_embed = 0,
         seconds_kmeans = 0, seconds_signatures = 0;
  WordsPaths paths;
};

// The key of a training: a fingerprint of the archive's identity and of every option that
// changes the trained weights.
uint64_t TrainingKey(uint64_t archive_identity, const std::vector<float>& joint_weights,
                     const WordsOptions& options);

// Runs the job. InvalidArgument: bad options, an archive with no word, an embedding_in that
// does not fit the archive; Busy: another run holds the lock; errors of the reader and the file
// system pass through (what was already written stays valid).
Result<WordsReport> BuildWords(const std::string& archive_path, const WordsPaths& paths,
                               const WordsOptions& options);

}  // namespace motif
