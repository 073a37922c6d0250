#include "engine/embedding/embedding_net.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

#include "common/split_mix64.h"

namespace motif {

namespace {

// The sizes every pass uses, from the shape.
struct Dims {
  explicit Dims(const EmbeddingNetShape& s)
      : c(s.input_channels),
        t1(s.conv1_frames()),
        t2(s.conv2_frames()),
        c1(s.conv1_channels),
        c2(s.conv2_channels),
        d(s.embedding_dims) {}
  Eigen::Index c, t1, t2, c1, c2, d;
};

// The six blocks of a flat parameter vector (the parameters, or a gradient) as Eigen maps.
template <typename Scalar, bool kConst>
struct Blocks {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  using Row = Eigen::Matrix<Scalar, 1, Eigen::Dynamic>;
  using MatrixMap = Eigen::Map<std::conditional_t<kConst, const Matrix, Matrix>>;
  using RowMap = Eigen::Map<std::conditional_t<kConst, const Row, Row>>;
  using Pointer = std::conditional_t<kConst, const Scalar*, Scalar*>;

  Blocks(const EmbeddingNetShape& s, Pointer p)
      : w1(p + s.conv1_weight_offset(), s.conv1_kernel * s.input_channels, s.conv1_channels),
        b1(p + s.conv1_bias_offset(), s.conv1_channels),
        w2(p + s.conv2_weight_offset(), s.conv2_kernel * s.conv1_channels, s.conv2_channels),
        b2(p + s.conv2_bias_offset(), s.conv2_channels),
        w3(p + s.linear_weight_offset(), s.flat_size(), s.embedding_dims),
        b3(p + s.linear_bias_offset(), s.embedding_dims) {}

  MatrixMap w1;
  RowMap b1;
  MatrixMap w2;
  RowMap b2;
  MatrixMap w3;
  RowMap b3;
};

}  // namespace

size_t EmbeddingNetShape::conv1_bias_offset() const {
  return conv1_weight_offset() +
         static_cast<size_t>(conv1_kernel) * input_channels * conv1_channels;
}
size_t EmbeddingNetShape::conv2_weight_offset() const {
  return conv1_bias_offset() + conv1_channels;
}
size_t EmbeddingNetShape::conv2_bias_offset() const {
  return conv2_weight_offset() +
         static_cast<size_t>(conv2_kernel) * conv1_channels * conv2_channels;
}
size_t EmbeddingNetShape::linear_weight_offset() const {
  return conv2_bias_offset() + conv2_channels;
}
size_t EmbeddingNetShape::linear_bias_offset() const {
  return linear_weight_offset() + static_cast<size_t>(flat_size()) * embedding_dims;
}
size_t EmbeddingNetShape::parameter_count() const { return linear_bias_offset() + embedding_dims; }

Status ValidateEmbeddingNetShape(const EmbeddingNetShape& shape) {
  const std::pair<const char*, uint32_t> sizes[] = {{"frames", shape.frames},
                                                    {"input_channels", shape.input_channels},
                                                    {"conv1_channels", shape.conv1_channels},
                                                    {"conv1_kernel", shape.conv1_kernel},
                                                    {"conv2_channels", shape.conv2_channels},
                                                    {"conv2_kernel", shape.conv2_kernel},
                                                    {"conv2_stride", shape.conv2_stride},
                                                    {"embedding_dims", shape.embedding_dims}};
  for (const auto& [name, value] : sizes) {
    if (value == 0 || value > 4096) {
      return Status::InvalidArgument(std::string("embedding network: ") + name + " " +
                                     std::to_string(value) + " is not in [1, 4096]");
    }
  }
  if (shape.conv1_kernel > shape.frames) {
    return Status::InvalidArgument("embedding network: conv1_kernel " +
                                   std::to_string(shape.conv1_kernel) + " exceeds the word's " +
                                   std::to_string(shape.frames) + " frames");
  }
  if (shape.conv2_kernel > shape.conv1_frames()) {
    return Status::InvalidArgument("embedding network: conv2_kernel " +
                                   std::to_string(shape.conv2_kernel) + " exceeds conv1's " +
                                   std::to_string(shape.conv1_frames()) + " output frames");
  }
  return Status::Ok();
}

template <typename Scalar>
EmbeddingNetT<Scalar>::EmbeddingNetT(const EmbeddingNetShape& shape)
    : shape_(shape),
      parameters_(shape.parameter_count(), Scalar(0)),
      input_mean_(shape.input_channels, Scalar(0)),
      input_std_(shape.input_channels, Scalar(1)),
      input_scale_(shape.input_channels, Scalar(1)) {
  MOTIF_CHECK(ValidateEmbeddingNetShape(shape).ok());
}

template <typename Scalar>
void EmbeddingNetT<Scalar>::Initialize(uint64_t seed) {
  SplitMix64 random(seed);
  std::fill(parameters_.begin(), parameters_.end(), Scalar(0));
  auto fill = [&](size_t offset, size_t count, double fan_in, double gain) {
    const double deviation = std::sqrt(gain / fan_in);
    for (size_t idx = 0; idx < count; ++idx) {
      parameters_[offset + idx] = static_cast<Scalar>(deviation * random.Gaussian());
    }
  };
  const EmbeddingNetShape& s = shape_;
  const double fan1 = static_cast<double>(s.conv1_kernel) * s.input_channels;
  const double fan2 = static_cast<double>(s.conv2_kernel) * s.conv1_channels;
  fill(s.conv1_weight_offset(), s.conv1_bias_offset() - s.conv1_weight_offset(), fan1, 2.0);
  fill(s.conv2_weight_offset(), s.conv2_bias_offset() - s.conv2_weight_offset(), fan2, 2.0);
  fill(s.linear_weight_offset(), s.linear_bias_offset() - s.linear_weight_offset(), s.flat_size(),
       1.0);
}

template <typename Scalar>
void EmbeddingNetT<Scalar>::SetInputStandardisation(std::vector<Scalar> mean,
                                                    std::vector<Scalar> std) {
  MOTIF_CHECK(mean.size() == shape_.input_channels && std.size() == shape_.input_channels);
  for (size_t channel = 0; channel < std.size(); ++channel) {
    if (!(std[channel] >= Scalar(1e-6))) std[channel] = Scalar(1);
    input_scale_[channel] = Scalar(1) / std[channel];
  }
  input_mean_ = std::move(mean);
  input_std_ = std::move(std);
}

template <typename Scalar>
void EmbeddingNetT<Scalar>::Forward(const Eigen::Ref<const Matrix>& input,
                                    Workspace* workspace) const {
  using MatrixMap = Eigen::Map<const Matrix>;
  const EmbeddingNetShape& s = shape_;
  const Eigen::Index batch = input.rows();
  const Dims dims(s);
  const Eigen::Index c = dims.c, t1 = dims.t1, t2 = dims.t2, c1 = dims.c1, d = dims.d;
  MOTIF_CHECK(input.cols() == static_cast<Eigen::Index>(s.input_size()));
  const Blocks<Scalar, true> weights(s, parameters_.data());

  // Standardise and unfold: row (b, t) of conv1's input holds frames t .. t + K1 - 1 of word b.
  Workspace& ws = *workspace;
  const Eigen::Index window1 = s.conv1_kernel * c;
  ws.unfolded1.resize(batch * t1, window1);
  for (Eigen::Index word = 0; word < batch; ++word) {
    for (Eigen::Index frame = 0; frame < t1; ++frame) {
      Scalar* out = ws.unfolded1.row(word * t1 + frame).data();
      const Scalar* in = input.row(word).data() + frame * c;
      for (Eigen::Index value = 0; value < window1; ++value) {
        const Eigen::Index channel = value % c;
        out[value] = (in[value] - input_mean_[channel]) * input_scale_[channel];
      }
    }
  }
  ws.pre1.noalias() = ws.unfolded1 * weights.w1;
  ws.pre1.rowwise() += weights.b1;

  // conv2 over the ReLU of conv1, frames s * t .. s * t + K2 - 1 (contiguous rows of pre1).
  const Eigen::Index window2 = s.conv2_kernel * c1;
  ws.unfolded2.resize(batch * t2, window2);
  for (Eigen::Index word = 0; word < batch; ++word) {
    for (Eigen::Index frame = 0; frame < t2; ++frame) {
      const Scalar* in = ws.pre1.row(word * t1 + frame * s.conv2_stride).data();
      Scalar* out = ws.unfolded2.row(word * t2 + frame).data();
      for (Eigen::Index value = 0; value < window2; ++value) {
        out[value] = std::max(in[value], Scalar(0));
      }
    }
  }
  ws.pre2.noalias() = ws.unfolded2 * weights.w2;
  ws.pre2.rowwise() += weights.b2;

  // Linear over the flattened ReLU of conv2 (word b's T2 x C2 rows are contiguous).
  const Matrix hidden2 = ws.pre2.cwiseMax(Scalar(0));
  const MatrixMap flat(hidden2.data(), batch, s.flat_size());
  ws.z.noalias() = flat * weights.w3;
  ws.z.rowwise() += weights.b3;
  ws.norms = ws.z.rowwise().norm();
  ws.embeddings.resize(batch, d);
  for (Eigen::Index word = 0; word < batch; ++word) {
    const Scalar norm = ws.norms(word);
    if (norm > Scalar(0)) {
      ws.embeddings.row(word) = ws.z.row(word) / norm;
    } else {
      ws.embeddings.row(word).setZero();
    }
  }
}

template <typename Scalar>
void EmbeddingNetT<Scalar>::Backward(const Eigen::Ref<const Matrix>& d_embeddings,
                                     Workspace* workspace, Scalar* gradient) const {
  using MatrixMap = Eigen::Map<const Matrix>;
  const EmbeddingNetShape& s = shape_;
  Workspace& ws = *workspace;
  const Eigen::Index batch = ws.z.rows();
  const Dims dims(s);
  const Eigen::Index t1 = dims.t1, t2 = dims.t2, c1 = dims.c1, c2 = dims.c2, d = dims.d;
  MOTIF_CHECK(d_embeddings.rows() == batch && d_embeddings.cols() == d);
  const Blocks<Scalar, true> weights(s, parameters_.data());
  Blocks<Scalar, false> g(s, gradient);

  // e = z / |z|: de/dz = (I - e e^T) / |z|.
  ws.d_z.resize(batch, d);
  for (Eigen::Index word = 0; word < batch; ++word) {
    const Scalar norm = ws.norms(word);
    if (norm > Scalar(0)) {
      const auto e = ws.embeddings.row(word);
      const auto g = d_embeddings.row(word);
      ws.d_z.row(word) = (g - e * e.dot(g)) / norm;
    } else {
      ws.d_z.row(word).setZero();
    }
  }
  const Matrix hidden2 = ws.pre2.cwiseMax(Scalar(0));
  const MatrixMap flat(hidden2.data(), batch, s.flat_size());
  g.w3.noalias() += flat.transpose() * ws.d_z;
  g.b3 += ws.d_z.colwise().sum();
  ws.d_flat.noalias() = ws.d_z * weights.w3.transpose();  // batch x T2 C2, i.e. (batch T2) x C2

  // Through conv2's ReLU and product.
  ws.d_pre2 = MatrixMap(ws.d_flat.data(), batch * t2, c2);
  ws.d_pre2.array() *= (ws.pre2.array() > Scalar(0)).template cast<Scalar>();
  g.w2.noalias() += ws.unfolded2.transpose() * ws.d_pre2;
  g.b2 += ws.d_pre2.colwise().sum();
  ws.d_unfolded2.noalias() = ws.d_pre2 * weights.w2.transpose();

  // Fold the unfolded gradient back onto conv1's output frames, then through its ReLU.
  const Eigen::Index window2 = s.conv2_kernel * c1;
  ws.d_hidden1.setZero(batch * t1, c1);
  for (Eigen::Index word = 0; word < batch; ++word) {
    for (Eigen::Index frame = 0; frame < t2; ++frame) {
      Scalar* out = ws.d_hidden1.row(word * t1 + frame * s.conv2_stride).data();
      const Scalar* in = ws.d_unfolded2.row(word * t2 + frame).data();
      for (Eigen::Index value = 0; value < window2; ++value) out[value] += in[value];
    }
  }
  ws.d_hidden1.array() *= (ws.pre1.array() > Scalar(0)).template cast<Scalar>();
  g.w1.noalias() += ws.unfolded1.transpose() * ws.d_hidden1;
  g.b1 += ws.d_hidden1.colwise().sum();
}

template class EmbeddingNetT<float>;
template class EmbeddingNetT<double>;

}  // namespace motif
