// The yaml tests' comparison of two rigs: every field, exactly.
#pragma once

#include "models/rig.h"

namespace metrosync {

void expectSameRig(const Rig& a, const Rig& b);

}  // namespace metrosync
