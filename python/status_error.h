// A failed motifmine::Status on its way to Python: thrown by Check, turned into motifmine.Error
// (with the message and the code) by the module's one exception translator
// (motifmine_module.cc).
#pragma once

#include <motifmine/motifmine.h>

namespace motifmine_python {

struct StatusError {
  motifmine::Status status;
};

inline void Check(const motifmine::Status& status) {
  if (!status.ok()) throw StatusError{status};
}

}  // namespace motifmine_python
