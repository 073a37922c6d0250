// TensorFile: a list of named arrays of numbers (tensors) under a `kind` ("embedding", "motifs",
// "signatures", ...), and the file that stores it (docs/formats/tensor_file.md, version 1.0): a
// header, a table of the tensors (name, element type, shape, offset, checksum) and their data,
// every byte covered by a checksum. The motion-word files are tensor files: the embedding's
// weights (.mwe), the motifs (.mwm) and the signatures (.mws); each kind's spec lists the tensors
// it must hold (docs/formats/tensor_file.md, section 8).
//
// Writing is whole-file and atomic (temporary file, fsync, rename, directory fsync): a reader sees
// the previous file or the new one. Reading checks every byte (Open validates everything, so a
// file that opens is intact), then the typed getters check each tensor's type and shape against
// what the caller expects, with Corruption naming the file and the tensor.
// Thread-safety: a value type; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/status.h"
#include "common/writable_file.h"
#include "formats/tensor_file/tensor_type.h"

namespace motif {

struct Tensor {
  std::string name;  // 1 to 31 characters of [a-z0-9_.]
  TensorType type = TensorType::kU8;
  uint8_t rank = 1;  // 1: a vector of `rows` elements (cols is 1); 2: a rows x cols matrix
  uint64_t rows = 0;
  uint64_t cols = 1;
  std::string data;  // rows * cols elements, little-endian, row-major

  uint64_t element_count() const { return rows * cols; }
};

class TensorFile {
 public:
  TensorFile() = default;
  explicit TensorFile(std::string kind) : kind_(std::move(kind)) {}

  const std::string& kind() const { return kind_; }
  const std::vector<Tensor>& tensors() const { return tensors_; }
  // The file's fingerprint: its header checksum, which covers the table and through it every
  // tensor's bytes. Set by Encode and by reading; 0 for a file never encoded.
  uint64_t identity() const { return identity_; }
  void set_identity(uint64_t identity) { identity_ = identity; }

  // Appending. A name already present is a bug (checked, aborts), as is a name breaking the
  // rules above (checked by Encode, which returns InvalidArgument).
  void AddU8(const std::string& name, std::span<const uint8_t> values);
  void AddU16(const std::string& name, std::span<const uint16_t> values);
  void AddU32(const std::string& name, std::span<const uint32_t> values);
  void AddU64(const std::string& name, std::span<const uint64_t> values);
  void AddF32(const std::string& name, std::span<const float> values);
  void AddF64(const std::string& name, std::span<const double> values);
  // Matrices (rank 2), row-major: values.size() must be rows * cols (checked, aborts).
  void AddF32Matrix(const std::string& name, uint64_t rows, uint64_t cols,
                    std::span<const float> values);
  void AddF64Matrix(const std::string& name, uint64_t rows, uint64_t cols,
                    std::span<const double> values);
  void AddString(const std::string& name, const std::string& text);  // as u8
  void Add(Tensor tensor);

  // The tensor named `name`, or nullptr.
  const Tensor* Find(const std::string& name) const;

  // Typed reads. Corruption ("<kind> file: tensor 'name' ...") if the tensor is missing, of
  // another type, or not of the expected shape. For vectors, `count` is the expected element
  // count (kAnyCount: any); matrices must be rank 2 with the given rows and cols (kAnyCount for
  // either: any).
  static constexpr uint64_t kAnyCount = UINT64_MAX;
  Result<std::vector<uint8_t>> U8(const std::string& name, uint64_t count = kAnyCount) const;
  Result<std::vector<uint16_t>> U16(const std::string& name, uint64_t count = kAnyCount) const;
  Result<std::vector<uint32_t>> U32(const std::string& name, uint64_t count = kAnyCount) const;
  Result<std::vector<uint64_t>> U64(const std::string& name, uint64_t count = kAnyCount) const;
  Result<std::vector<float>> F32(const std::string& name, uint64_t count = kAnyCount) const;
  Result<std::vector<double>> F64(const std::string& name, uint64_t count = kAnyCount) const;
  Result<std::vector<float>> F32Matrix(const std::string& name, uint64_t rows, uint64_t cols) const;
  Result<std::vector<double>> F64Matrix(const std::string& name, uint64_t rows,
                                        uint64_t cols) const;
  // One u64 / f64 (a vector of one element).
  Result<uint64_t> ScalarU64(const std::string& name) const;
  Result<double> ScalarF64(const std::string& name) const;
  Result<std::string> String(const std::string& name) const;
  // The shape of a tensor: rows (element count for a vector) and cols. Corruption if missing.
  Result<std::pair<uint64_t, uint64_t>> Shape(const std::string& name) const;

 private:
  template <typename T>
  Result<std::vector<T>> Read(const std::string& name, TensorType type, uint8_t rank, uint64_t rows,
                              uint64_t cols) const;

  std::string kind_;
  std::vector<Tensor> tensors_;
  uint64_t identity_ = 0;
};

// The bytes of the file (docs/formats/tensor_file.md), and its identity in *identity if not null.
// InvalidArgument: a kind or a name breaking the rules, a duplicate name, data whose size is not
// the shape's.
Result<std::string> EncodeTensorFile(const TensorFile& file, uint64_t* identity = nullptr);

// Encodes `file` and replaces `path` with it atomically; *identity receives the written file's
// identity if not null. InvalidArgument as EncodeTensorFile (nothing written); IOError /
// ResourceExhausted from the file system.
Status WriteTensorFile(const std::string& path, const TensorFile& file,
                       FileSystem* file_system = PosixFileSystem(), uint64_t* identity = nullptr);

// Decodes and checks every byte (section 6 of the spec). `name` stands for the file in messages.
// Corruption naming the file and the offset or tensor (another major version included);
// InvalidArgument if `expected_kind` is not empty and the file is of another kind.
Result<TensorFile> DecodeTensorFile(const std::string& bytes, const std::string& name,
                                    const std::string& expected_kind = "");

// Reads `path` and decodes it. NotFound if there is no file; IOError if it cannot be read.
Result<TensorFile> ReadTensorFile(const std::string& path, const std::string& expected_kind = "");

}  // namespace motif
