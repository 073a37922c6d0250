// EmbeddingNet: the network that maps a motion word to a point of the embedding (Aristidou et al.
// 2018, section 4.2, where an Inception-style CNN trained for 7 days maps words to 736 numbers).
// Here a compact 1-D temporal convolution network with hand-written gradients, on Eigen, trained
// in minutes on a CPU (embedding_trainer.h; docs/design/signatures.md, "The embedding", says
// why this model):
//
//   input X        W x C        the word (word_input.h), standardised per channel:
//                               (x - mean_c) / std_c, with the training words' statistics
//   conv1 + ReLU   T1 x C1      kernel K1, stride 1, no padding: T1 = W - K1 + 1
//   conv2 + ReLU   T2 x C2      kernel K2, stride S2: T2 = (T1 - K2) / S2 + 1
//   linear         D            over the flattened T2 x C2
//   L2 normalise   D            the embedding lies on the unit sphere
//
// At the defaults (W = 16, C = 76 for the 12 CMU joints, K1 = K2 = 3, C1 = C2 = 64, S2 = 2,
// D = 32): T1 = 14, T2 = 6, 39,328 parameters.
//
// A convolution is a matrix product over its unfolded input: the row of output frame t holds the
// K input frames t .. t + K - 1 side by side (they are contiguous in the frame-major input, so
// unfolding is a copy of a slice), and the layer is U W + b with W of (K C_in) x C_out. The
// backward pass is the same products transposed, and the unfolded gradient is folded back onto
// the frames it came from. Parameters live in one flat vector (the optimiser's and the file's
// view): conv1.weight (K1 C x C1, row-major), conv1.bias (C1), conv2.weight (K2 C1 x C2),
// conv2.bias (C2), linear.weight (T2 C2 x D), linear.bias (D).
//
// Templated on the scalar: float for training and use, double for the gradient check.
// Determinism: a batch's results depend only on the batch (Eigen's products run single-threaded
// here; callers parallelise over fixed chunks of a batch).
// Thread-safety: const methods are safe from many threads, each with its own Workspace.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"

namespace motif {

struct EmbeddingNetShape {
  uint32_t frames = 16;         // W
  uint32_t input_channels = 0;  // C
  uint32_t conv1_channels = 64;
  uint32_t conv1_kernel = 3;
  uint32_t conv2_channels = 64;
  uint32_t conv2_kernel = 3;
  uint32_t conv2_stride = 2;
  uint32_t embedding_dims = 32;  // D

  uint32_t conv1_frames() const { return frames - conv1_kernel + 1; }
  uint32_t conv2_frames() const { return (conv1_frames() - conv2_kernel) / conv2_stride + 1; }
  uint32_t flat_size() const { return conv2_frames() * conv2_channels; }
  uint32_t input_size() const { return frames * input_channels; }

  // Offsets of the parameter blocks in the flat vector, and its size.
  size_t conv1_weight_offset() const { return 0; }
  size_t conv1_bias_offset() const;
  size_t conv2_weight_offset() const;
  size_t conv2_bias_offset() const;
  size_t linear_weight_offset() const;
  size_t linear_bias_offset() const;
  size_t parameter_count() const;

  bool operator==(const EmbeddingNetShape&) const = default;
};

// InvalidArgument naming the field: a zero size, a kernel longer than its input, sizes above
// 4096, a convolution with no output frame.
Status ValidateEmbeddingNetShape(const EmbeddingNetShape& shape);

template <typename Scalar>
class EmbeddingNetT {
 public:
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  // What a forward pass keeps for the backward pass. Reused between calls.
  struct Workspace {
    Matrix unfolded1, pre1, unfolded2, pre2, z;
    Vector norms;
    Matrix embeddings;  // the output, B x D
    // Backward scratch.
    Matrix d_z, d_flat, d_pre2, d_unfolded2, d_hidden1;
  };

  EmbeddingNetT() = default;
  // Zero parameters, mean 0 and std 1. Precondition: a valid shape (checked, aborts).
  explicit EmbeddingNetT(const EmbeddingNetShape& shape);

  const EmbeddingNetShape& shape() const { return shape_; }
  const std::vector<Scalar>& parameters() const { return parameters_; }
  std::vector<Scalar>& mutable_parameters() { return parameters_; }
  const std::vector<Scalar>& input_mean() const { return input_mean_; }
  const std::vector<Scalar>& input_std() const { return input_std_; }

  // He initialisation (He et al. 2015) for the ReLU layers, N(0, 2 / fan_in), and N(0, 1 /
  // fan_in) for the linear layer; zero biases. SplitMix64 from `seed` (the same on every
  // platform), parameters drawn in flat-vector order.
  void Initialize(uint64_t seed);
  // Per-channel standardisation (C values each; a std below 1e-6 is taken as 1: a constant
  // channel carries nothing and must not be blown up).
  void SetInputStandardisation(std::vector<Scalar> mean, std::vector<Scalar> std);

  // Embeds the B rows of `input` (B x W C, each a word's input, word_input.h) into
  // workspace->embeddings (B x D, unit rows). A row with z = 0 embeds to 0.
  void Forward(const Eigen::Ref<const Matrix>& input, Workspace* workspace) const;
  // Adds d loss / d parameters to `gradient` (parameter_count() values), given d loss / d
  // embeddings (B x D) of the last Forward on `workspace`.
  void Backward(const Eigen::Ref<const Matrix>& d_embeddings, Workspace* workspace,
                Scalar* gradient) const;

 private:
  EmbeddingNetShape shape_;
  std::vector<Scalar> parameters_;
  std::vector<Scalar> input_mean_;
  std::vector<Scalar> input_std_;
  std::vector<Scalar> input_scale_;  // 1 / std
};

using EmbeddingNet = EmbeddingNetT<float>;

}  // namespace motif
