// Sampler factory: the samplers by the names the command line and job files use.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/sampler.h"

namespace prism {

std::vector<std::string> sampler_names();  // the default first

// Whether the sampler's points are stratified in nets of power-of-two blocks of sample indices
// (Owen-scrambled Sobol), so that the first m and the next m samples of a pixel are two such nets.
bool sampler_is_stratified(const std::string& name);

// Throws std::invalid_argument naming the known samplers for an unknown name.
std::unique_ptr<Sampler> make_sampler(const std::string& name, uint64_t seed);

// `count` samplers for the lanes of a packet, drawing the values make_sampler's would. Where a
// sampler has work that lanes in the same pixel can share, they share it (Sobol's seed cache).
// They belong to one thread.
std::vector<std::unique_ptr<Sampler>> make_lane_samplers(const std::string& name, uint64_t seed, int count);

}  // namespace prism
