// Error allocation: sharing a pass's samples among pixels so the image's relative MSE falls fastest.
#pragma once

#include <cstdint>
#include <vector>

#include "core/film.h"

namespace prism {

// Each pixel's share of the samples, up to a common factor. A pixel's expected relMSE (the metric
// `prism compare` reports: mean over channels of (a - b)^2 / (b^2 + kRelMseEpsilon)) after n
// samples is R / n, with R = sum over channels of sigma_c^2 / (m_c^2 + epsilon), sigma_c^2 the
// variance of one sample and m_c the mean. For a fixed total of samples, sum R_i / n_i is least
// when n_i is proportional to sqrt(R_i) (Lagrange; Rousselle, Knaus and Zwicker 2011 minimise the
// same error greedily). R_i is estimated from the pixel's eight neighbours only, never from its
// own samples, so how many samples a pixel gets does not depend on their values and its mean
// stays unbiased (a pixel judged by its own samples would stop early after low ones). A film whose
// pixels all estimate zero (no variance seen yet) gets equal weights.
std::vector<double> error_weights(const Film& film);
// The weights from each pixel's R (any measure of a pixel's error whose square falls as 1 / n,
// times n), top row first: the square root of the mean R of its neighbours inside the image,
// equal weights when all are zero. error_weights is this with R of the relMSE.
std::vector<double> neighbour_weights(const std::vector<double>& r, int width, int height);

// Sets target[i] >= counts[i] for every pixel so that the targets add up to `total` (or to as much
// as `cap` per pixel allows), each pixel as close to lambda x weights[i] as the others allow
// (water filling: pixels already past their share keep their counts). The result is a function
// of its arguments alone (ties go to the lower index). Returns the targets' sum.
uint64_t allocate_samples(const std::vector<uint32_t>& counts, const std::vector<double>& weights, uint64_t total,
                          uint32_t cap, std::vector<uint32_t>& target);

}  // namespace prism
