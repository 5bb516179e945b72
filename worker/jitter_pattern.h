#pragma once
// Moved to core/jitter_pattern.h: the runtime's `eval` traces the dense T with
// the bake's own pattern, and runtime/ may not depend on worker/ (DESIGN.md §6).
#include "core/jitter_pattern.h"  // IWYU pragma: export
