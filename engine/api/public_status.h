// The bridge from the engine's motif::Status to the public motifmine::Status.
#pragma once

#include "common/status.h"
#include "motifmine/status.h"

namespace motif {

motifmine::Status ToPublicStatus(const Status& status);

}  // namespace motif
