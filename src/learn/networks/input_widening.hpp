#pragma once
// Loading saved networks into ones with more inputs: a trained single-behaviour policy (and its
// discriminator) starting a behaviour-context run, whose inputs gain a one-hot after each state,
// or a policy whose observation gained a named part (reference_root, say). The saved weights go
// to their inputs' new places and the new inputs' weights start at zero, so the widened network
// computes what the saved one did whatever the new inputs hold.
#include <torch/torch.h>

#include <cstdint>
#include <string>
#include <vector>

#include "env/env.hpp"

namespace mimic {

// Where each saved input lands when `added` inputs follow each of the first `blocks` blocks of
// `block_width` inputs (frames of the policy's input, states of a discriminator's transition);
// inputs after those blocks (a transition's action) move by blocks × added.
std::vector<std::int64_t> widened_columns(std::int64_t saved_width, std::int64_t block_width, std::int64_t blocks, std::int64_t added);

// Where each input of an observation laid out as `saved_layout` lands in one laid out as `layout`,
// both stacked `frames` times: every saved part must be in `layout` under its name and with its
// size, in the same order; the other parts of `layout` are new. Throws Error naming a saved part
// that is missing, resized or out of order.
std::vector<std::int64_t> mapped_columns(const std::vector<ObservationSlice>& saved_layout, const std::vector<ObservationSlice>& layout,
                                         std::int64_t frames);

// `saved` [rows, kept.size()] (or a vector of kept.size()) put at columns `kept` of a
// [rows, new_width] (new_width) tensor filled with `fill` elsewhere.
torch::Tensor widen_columns(const torch::Tensor& saved, const std::vector<std::int64_t>& kept, std::int64_t new_width, double fill);

// Module::load, except that a 2-D parameter saved with kept.size() columns where the module has
// new_width is widened by widen_columns (zeros). Any other difference of shape is an error naming
// the parameter; so is a module with a GRU (its per-frame inputs are not widened here).
void load_widened(torch::nn::Module& module, torch::serialize::InputArchive& archive, const std::vector<std::int64_t>& kept,
                  std::int64_t new_width);

}  // namespace mimic
