#pragma once
// Small helpers shared by the two halves of the Haar product
// (core/haar_product.cc, core/haar_product_terms.cc).
#include <cstdio>
#include <cstdlib>

namespace wavebake::haar_product {

// The products' preconditions are programming errors (a factor built for
// another cubemap), not bad input.
inline void CheckOrDie(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "HaarProduct: %s\n", what);
  std::abort();
}

inline bool NonZero(const float* rgb) { return rgb[0] != 0 || rgb[1] != 0 || rgb[2] != 0; }

}  // namespace wavebake::haar_product
