#pragma once

#include "util/parameters.h"

namespace radiant {

/// max-depth: the path tracer's parameter (multipass's too, for its path passes).
const ParameterSpec &maxDepthParameter();

}  // namespace radiant
