// TensorType: the element types of a tensor file's tensors (docs/formats/tensor_file.md,
// section 5), their sizes and names. A leaf, so that the format (tensor_file_format.h) does not
// include the file class (tensor_file.h).
// Thread-safety: pure functions.
#pragma once

#include <cstddef>
#include <cstdint>

namespace motif {

enum class TensorType : uint8_t { kU8 = 1, kU16 = 2, kU32 = 3, kU64 = 4, kF32 = 5, kF64 = 6 };

// Bytes of one element; 0 for an unknown type.
size_t TensorTypeBytes(TensorType type);
// "u8", "u16", "u32", "u64", "f32", "f64".
const char* TensorTypeName(TensorType type);

}  // namespace motif
