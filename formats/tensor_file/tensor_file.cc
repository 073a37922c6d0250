#include "formats/tensor_file/tensor_file.h"

#include <bit>
#include <cstring>
#include <unordered_set>

#include "common/file_util.h"
#include "formats/tensor_file/tensor_file_format.h"

namespace motif {

// The data are the in-memory bytes of the elements: the format is little-endian.
static_assert(std::endian::native == std::endian::little,
              "tensor files assume a little-endian host");

namespace {

template <typename T>
Tensor MakeTensor(const std::string& name, TensorType type, uint8_t rank, uint64_t rows,
                  uint64_t cols, std::span<const T> values) {
  MOTIF_CHECK(values.size() == rows * cols);
  Tensor tensor;
  tensor.name = name;
  tensor.type = type;
  tensor.rank = rank;
  tensor.rows = rows;
  tensor.cols = cols;
  tensor.data.assign(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  return tensor;
}

}  // namespace

void TensorFile::Add(Tensor tensor) {
  MOTIF_CHECK(Find(tensor.name) == nullptr);
  tensors_.push_back(std::move(tensor));
}

void TensorFile::AddU8(const std::string& name, std::span<const uint8_t> values) {
  Add(MakeTensor(name, TensorType::kU8, 1, values.size(), 1, values));
}
void TensorFile::AddU16(const std::string& name, std::span<const uint16_t> values) {
  Add(MakeTensor(name, TensorType::kU16, 1, values.size(), 1, values));
}
void TensorFile::AddU32(const std::string& name, std::span<const uint32_t> values) {
  Add(MakeTensor(name, TensorType::kU32, 1, values.size(), 1, values));
}
void TensorFile::AddU64(const std::string& name, std::span<const uint64_t> values) {
  Add(MakeTensor(name, TensorType::kU64, 1, values.size(), 1, values));
}
void TensorFile::AddF32(const std::string& name, std::span<const float> values) {
  Add(MakeTensor(name, TensorType::kF32, 1, values.size(), 1, values));
}
void TensorFile::AddF64(const std::string& name, std::span<const double> values) {
  Add(MakeTensor(name, TensorType::kF64, 1, values.size(), 1, values));
}
void TensorFile::AddF32Matrix(const std::string& name, uint64_t rows, uint64_t cols,
                              std::span<const float> values) {
  Add(MakeTensor(name, TensorType::kF32, 2, rows, cols, values));
}
void TensorFile::AddF64Matrix(const std::string& name, uint64_t rows, uint64_t cols,
                              std::span<const double> values) {
  Add(MakeTensor(name, TensorType::kF64, 2, rows, cols, values));
}
void TensorFile::AddString(const std::string& name, const std::string& text) {
  AddU8(name, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

const Tensor* TensorFile::Find(const std::string& name) const {
  for (const Tensor& tensor : tensors_) {
    if (tensor.name == name) return &tensor;
  }
  return nullptr;
}

template <typename T>
Result<std::vector<T>> TensorFile::Read(const std::string& name, TensorType type, uint8_t rank,
                                        uint64_t rows, uint64_t cols) const {
  const std::string where = kind_ + " file: tensor '" + name + "'";
  const Tensor* tensor = Find(name);
  if (tensor == nullptr) return Status::Corruption(where + " is missing");
  if (tensor->type != type) {
    return Status::Corruption(where + " is " + TensorTypeName(tensor->type) + ", expected " +
                              TensorTypeName(type));
  }
  if (tensor->rank != rank || (rows != kAnyCount && tensor->rows != rows) ||
      (cols != kAnyCount && tensor->cols != cols)) {
    auto shape = [](uint8_t r, uint64_t a, uint64_t b) {
      auto text = [](uint64_t v) {
        return v == kAnyCount ? std::string("any") : std::to_string(v);
      };
      return r == 1 ? "[" + text(a) + "]" : "[" + text(a) + " x " + text(b) + "]";
    };
    return Status::Corruption(where + " has shape " +
                              shape(tensor->rank, tensor->rows, tensor->cols) + ", expected " +
                              shape(rank, rows, cols));
  }
  std::vector<T> values(tensor->element_count());
  if (!values.empty()) std::memcpy(values.data(), tensor->data.data(), tensor->data.size());
  return values;
}

Result<std::vector<uint8_t>> TensorFile::U8(const std::string& name, uint64_t count) const {
  return Read<uint8_t>(name, TensorType::kU8, 1, count, 1);
}
Result<std::vector<uint16_t>> TensorFile::U16(const std::string& name, uint64_t count) const {
  return Read<uint16_t>(name, TensorType::kU16, 1, count, 1);
}
Result<std::vector<uint32_t>> TensorFile::U32(const std::string& name, uint64_t count) const {
  return Read<uint32_t>(name, TensorType::kU32, 1, count, 1);
}
Result<std::vector<uint64_t>> TensorFile::U64(const std::string& name, uint64_t count) const {
  return Read<uint64_t>(name, TensorType::kU64, 1, count, 1);
}
Result<std::vector<float>> TensorFile::F32(const std::string& name, uint64_t count) const {
  return Read<float>(name, TensorType::kF32, 1, count, 1);
}
Result<std::vector<double>> TensorFile::F64(const std::string& name, uint64_t count) const {
  return Read<double>(name, TensorType::kF64, 1, count, 1);
}
Result<std::vector<float>> TensorFile::F32Matrix(const std::string& name, uint64_t rows,
                                                 uint64_t cols) const {
  return Read<float>(name, TensorType::kF32, 2, rows, cols);
}
Result<std::vector<double>> TensorFile::F64Matrix(const std::string& name, uint64_t rows,
                                                  uint64_t cols) const {
  return Read<double>(name, TensorType::kF64, 2, rows, cols);
}
Result<uint64_t> TensorFile::ScalarU64(const std::string& name) const {
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint64_t> values, U64(name, 1));
  return values[0];
}
Result<double> TensorFile::ScalarF64(const std::string& name) const {
  MOTIF_ASSIGN_OR_RETURN(std::vector<double> values, F64(name, 1));
  return values[0];
}
Result<std::string> TensorFile::String(const std::string& name) const {
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint8_t> values, U8(name));
  return std::string(values.begin(), values.end());
}
Result<std::pair<uint64_t, uint64_t>> TensorFile::Shape(const std::string& name) const {
  const Tensor* tensor = Find(name);
  if (tensor == nullptr) {
    return Status::Corruption(kind_ + " file: tensor '" + name + "' is missing");
  }
  return std::make_pair(tensor->rows, tensor->cols);
}

Result<std::string> EncodeTensorFile(const TensorFile& file, uint64_t* identity) {
  std::string problem = tensor_file::KindProblem(file.kind());
  if (!problem.empty()) return Status::InvalidArgument("tensor file: " + problem);
  if (file.tensors().size() > tensor_file::kMaxTensors) {
    return Status::InvalidArgument("tensor file: more than " +
                                   std::to_string(tensor_file::kMaxTensors) + " tensors");
  }
  std::unordered_set<std::string> names;
  std::string table;
  std::string data;
  const uint64_t data_start =
      tensor_file::kHeaderBytes + file.tensors().size() * tensor_file::kEntryBytes;
  for (const Tensor& tensor : file.tensors()) {
    problem = tensor_file::NameProblem(tensor.name);
    if (!problem.empty()) return Status::InvalidArgument(file.kind() + " file: " + problem);
    if (!names.insert(tensor.name).second) {
      return Status::InvalidArgument(file.kind() + " file: two tensors named '" + tensor.name +
                                     "'");
    }
    if ((tensor.rank != 1 && tensor.rank != 2) || (tensor.rank == 1 && tensor.cols != 1) ||
        TensorTypeBytes(tensor.type) == 0 ||
        tensor.data.size() != tensor.element_count() * TensorTypeBytes(tensor.type)) {
      return Status::InvalidArgument(file.kind() + " file: tensor '" + tensor.name +
                                     "': bad type, rank or data size");
    }
    data.append(tensor_file::AlignUp(data.size()) - data.size(), '\0');
    tensor_file::TableEntry entry;
    entry.name = tensor.name;
    entry.type = tensor.type;
    entry.rank = tensor.rank;
    entry.rows = tensor.rows;
    entry.cols = tensor.cols;
    entry.offset = data_start + data.size();
    entry.bytes = tensor.data.size();
    entry.checksum = Checksum64(tensor.data.data(), tensor.data.size());
    entry.EncodeTo(&table);
    data += tensor.data;
  }
  tensor_file::FileHeader header;
  header.kind = file.kind();
  header.tensor_count = static_cast<uint32_t>(file.tensors().size());
  header.data_bytes = data.size();
  header.table_checksum = Checksum64(table.data(), table.size());
  std::string bytes;
  bytes.reserve(data_start + data.size());
  const uint64_t checksum = header.EncodeTo(&bytes);
  bytes += table;
  bytes += data;
  if (identity != nullptr) *identity = checksum;
  return bytes;
}

Status WriteTensorFile(const std::string& path, const TensorFile& file, FileSystem* file_system,
                       uint64_t* identity) {
  Result<std::string> bytes = EncodeTensorFile(file, identity);
  if (!bytes.ok()) return bytes.status().WithContext(path);
  if (file_system == nullptr) return Status::InvalidArgument(path + ": no file system");
  return AtomicWriteFile(path, *bytes, file_system);
}

Result<TensorFile> DecodeTensorFile(const std::string& bytes, const std::string& name,
                                    const std::string& expected_kind) {
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  const uint64_t size = bytes.size();
  tensor_file::FileHeader header;
  uint64_t identity = 0;
  Status status = tensor_file::FileHeader::DecodeFrom(data, size, &header, &identity);
  if (!status.ok()) return status.WithContext(name);
  if (!expected_kind.empty() && header.kind != expected_kind) {
    return Status::InvalidArgument(name + ": a tensor file of kind '" + header.kind + "', not '" +
                                   expected_kind + "'");
  }
  const uint64_t table_bytes =
      static_cast<uint64_t>(header.tensor_count) * tensor_file::kEntryBytes;
  if (Checksum64(data + header.header_bytes, table_bytes) != header.table_checksum) {
    return Status::Corruption(name + ": table at offset " + Hex(header.header_bytes) +
                              ": checksum mismatch");
  }
  TensorFile file(header.kind);
  std::unordered_set<std::string> names;
  uint64_t expected_offset = header.header_bytes + table_bytes;
  for (uint32_t idx = 0; idx < header.tensor_count; ++idx) {
    const uint64_t entry_offset = header.header_bytes + idx * tensor_file::kEntryBytes;
    const std::string where =
        name + ": table entry " + std::to_string(idx) + " at offset " + Hex(entry_offset);
    tensor_file::TableEntry entry;
    status = tensor_file::TableEntry::DecodeFrom(data + entry_offset, &entry);
    if (!status.ok()) return status.WithContext(where);
    if (!names.insert(entry.name).second) {
      return Status::Corruption(where + ": a second tensor named '" + entry.name + "'");
    }
    // Tensors follow each other in table order, each at the next multiple of 8, padding zero.
    const uint64_t aligned = tensor_file::AlignUp(expected_offset);
    if (entry.offset != aligned || entry.bytes > size || entry.offset > size - entry.bytes) {
      return Status::Corruption(where + ": tensor '" + entry.name + "' at offset " +
                                Hex(entry.offset) + " (" + std::to_string(entry.bytes) +
                                " bytes) is not at " + Hex(aligned) + " or not within the file");
    }
    for (uint64_t offset = expected_offset; offset < aligned; ++offset) {
      if (data[offset] != 0) {
        return Status::Corruption(name + ": padding byte at offset " + Hex(offset) +
                                  " is not zero");
      }
    }
    if (Checksum64(data + entry.offset, entry.bytes) != entry.checksum) {
      return Status::Corruption(name + ": tensor '" + entry.name + "' at offset " +
                                Hex(entry.offset) + ": checksum mismatch");
    }
    Tensor tensor;
    tensor.name = entry.name;
    tensor.type = entry.type;
    tensor.rank = entry.rank;
    tensor.rows = entry.rows;
    tensor.cols = entry.cols;
    tensor.data.assign(bytes, entry.offset, entry.bytes);
    file.Add(std::move(tensor));
    expected_offset = entry.offset + entry.bytes;
  }
  if (expected_offset != size) {
    return Status::Corruption(name + ": " + std::to_string(size - expected_offset) +
                              " bytes after the last tensor at offset " + Hex(expected_offset));
  }
  file.set_identity(identity);
  return file;
}

Result<TensorFile> ReadTensorFile(const std::string& path, const std::string& expected_kind) {
  MOTIF_ASSIGN_OR_RETURN(std::string bytes, ReadRegularFile(path));
  return DecodeTensorFile(bytes, path, expected_kind);
}

}  // namespace motif
