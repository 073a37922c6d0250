#include "formats/tensor_file/tensor_type.h"

namespace motif {

size_t TensorTypeBytes(TensorType type) {
  switch (type) {
    case TensorType::kU8:
      return 1;
    case TensorType::kU16:
      return 2;
    case TensorType::kU32:
      return 4;
    case TensorType::kU64:
      return 8;
    case TensorType::kF32:
      return 4;
    case TensorType::kF64:
      return 8;
  }
  return 0;
}

const char* TensorTypeName(TensorType type) {
  switch (type) {
    case TensorType::kU8:
      return "u8";
    case TensorType::kU16:
      return "u16";
    case TensorType::kU32:
      return "u32";
    case TensorType::kU64:
      return "u64";
    case TensorType::kF32:
      return "f32";
    case TensorType::kF64:
      return "f64";
  }
  return "unknown";
}

}  // namespace motif
