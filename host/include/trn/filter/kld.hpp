#pragma once
// The KLD-sampling bound (dissertation eq. 2.22, Fox 2003): the particle count that keeps the
// Kullback-Leibler distance between the sampled and the true posterior below epsilon with
// probability `upper_quantile`, when the particles occupy k histogram bins:
//   n = (k-1)/(2 eps) * (1 - 2/(9(k-1)) + sqrt(2/(9(k-1))) * z)^3,  z = standard normal quantile.
#include <cstddef>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

// Inverse of the standard normal CDF, p in (0, 1) (Acklam's rational approximation refined by one
// Halley step: accurate to ~1e-15). Throws trn::Error outside (0, 1).
double normal_quantile(double p);

// The bound for k occupied bins (0 for k <= 1: one bin says nothing about the spread).
double kld_bound(std::size_t occupied_bins, double epsilon, double upper_quantile);

}  // namespace trn::filter
TRN_API_END
