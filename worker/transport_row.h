#pragma once
// Moved to core/transport_row.h: the runtime's `eval` traces the dense T row by
// row exactly as the bake does, and runtime/ may not depend on worker/
// (DESIGN.md §6).
#include "core/transport_row.h"  // IWYU pragma: export
