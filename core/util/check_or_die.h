#pragma once
// Preconditions whose violation is a bug in the caller, not bad input: inputs
// are checked with absl::Status before they reach the hot loops that use this.
#include <cstdio>
#include <cstdlib>

namespace wavebake {

// Prints "<who>: <what>" and aborts unless `ok`. `who` comes first so that
// swapping it with the condition does not compile.
inline void CheckOrDie(const char* who, bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "%s: %s\n", who, what);
  std::abort();
}

}  // namespace wavebake
