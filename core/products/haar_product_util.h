#pragma once
// Small helpers shared by the two halves of the Haar product
// (core/products/haar_product.cc, core/products/haar_product_terms.cc).
namespace wavebake::haar_product {

inline bool NonZero(const float* rgb) { return rgb[0] != 0 || rgb[1] != 0 || rgb[2] != 0; }

}  // namespace wavebake::haar_product
