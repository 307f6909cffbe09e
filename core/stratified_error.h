// Stratified error: how far below its sample variance a stratified sampler's pixel means err,
// measured from the film's half sums (Film::Halves) and pooled over a window of pixels.
#pragma once

#include <vector>

#include "core/film.h"

namespace prism {

// Each pixel's factor f in [kMinStratificationFactor, 1], top row first: the variance of its mean
// is about f times the variance its samples would give their mean were they independent (the
// sample variance over n, what Film::variance_of_mean reports). 1 where the film holds no
// evidence (no valid halves nearby, or no variance). See stratified_error.cpp for the estimator.
std::vector<double> stratification_factors(const Film& film);

// Pixels whose half sums are pooled: those within this many pixels in x and in y.
inline constexpr int kStratificationRadius = 4;
// The lowest factor trusted: a window of constant-looking halves is not proof of no error.
inline constexpr double kMinStratificationFactor = 1.0 / 16;

}  // namespace prism
