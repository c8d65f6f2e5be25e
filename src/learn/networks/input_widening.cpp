#include "learn/networks/input_widening.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "learn/networks/networks.hpp"

namespace mimic {

std::vector<std::int64_t> widened_columns(std::int64_t saved_width, std::int64_t block_width, std::int64_t blocks, std::int64_t added) {
  if (block_width < 1 || blocks < 0 || added < 0 || saved_width < block_width * blocks)
    throw Error("widened_columns: " + std::to_string(blocks) + " blocks of " + std::to_string(block_width) + " do not fit " +
                std::to_string(saved_width) + " inputs");
  std::vector<std::int64_t> kept(static_cast<std::size_t>(saved_width));
  for (std::int64_t i = 0; i < saved_width; ++i) kept[static_cast<std::size_t>(i)] = i + added * std::min(i / block_width, blocks);
  return kept;
}

namespace {
std::int64_t frame_width(const std::vector<ObservationSlice>& layout) {
  std::int64_t w = 0;
  for (const ObservationSlice& s : layout) w = std::max<std::int64_t>(w, s.offset + s.size);
  return w;
}
}  // namespace

std::vector<std::int64_t> mapped_columns(const std::vector<ObservationSlice>& saved_layout, const std::vector<ObservationSlice>& layout,
                                         std::int64_t frames) {
  const std::int64_t saved_width = frame_width(saved_layout), width = frame_width(layout);
  std::vector<std::int64_t> in_frame(static_cast<std::size_t>(saved_width), -1);
  auto next = layout.begin();
  for (const ObservationSlice& s : saved_layout) {
    auto same_name = [&](const ObservationSlice& n) { return n.name == s.name; };
    const auto found = std::find_if(next, layout.end(), same_name);
    if (found == layout.end()) {
      const bool earlier = std::find_if(layout.begin(), next, same_name) != next;
      throw Error("observation part '" + s.name + "' of the saved network " +
                  (earlier ? "comes earlier in the config's observation (parts may be added, not reordered)" : "is not in the config's observation"));
    }
    if (found->size != s.size)
      throw Error("observation part '" + s.name + "' had " + std::to_string(s.size) + " values, the config's has " + std::to_string(found->size));
    for (int i = 0; i < s.size; ++i) in_frame[static_cast<std::size_t>(s.offset + i)] = found->offset + i;
    next = found + 1;
  }
  if (std::find(in_frame.begin(), in_frame.end(), -1) != in_frame.end()) throw Error("mapped_columns: the saved layout has gaps");
  std::vector<std::int64_t> kept;
  kept.reserve(static_cast<std::size_t>(frames * saved_width));
  for (std::int64_t f = 0; f < frames; ++f)
    for (const std::int64_t c : in_frame) kept.push_back(f * width + c);
  return kept;
}

torch::Tensor widen_columns(const torch::Tensor& saved, const std::vector<std::int64_t>& kept, std::int64_t new_width, double fill) {
  const auto n = static_cast<std::int64_t>(kept.size());
  if (saved.dim() < 1 || saved.dim() > 2 || saved.size(-1) != n)
    throw Error("widen_columns: a saved tensor of " + std::to_string(saved.size(-1)) + " columns for " + std::to_string(n) + " kept");
  std::vector<std::int64_t> shape = saved.sizes().vec();
  shape.back() = new_width;
  torch::Tensor out = torch::full(shape, fill, saved.options());
  const torch::Tensor index = torch::tensor(kept, torch::kInt64);
  out.index_copy_(saved.dim() - 1, index, saved);
  return out;
}

void load_widened(torch::nn::Module& module, torch::serialize::InputArchive& archive, const std::vector<std::int64_t>& kept,
                  std::int64_t new_width) {
  if (dynamic_cast<torch::nn::GRUImpl*>(&module) != nullptr)
    throw Error("a GRU's per-frame inputs cannot be widened (network.history > 1): start the run from scratch");
  const torch::NoGradGuard no_grad;
  auto copy_into = [&](const std::string& key, torch::Tensor& target, bool is_buffer) {
    torch::Tensor saved;
    archive.read(key, saved, is_buffer);
    if (saved.sizes() == target.sizes()) {
      target.copy_(saved);
    } else if (saved.dim() == 2 && target.dim() == 2 && saved.size(0) == target.size(0) &&
               saved.size(1) == static_cast<std::int64_t>(kept.size()) && target.size(1) == new_width) {
      target.copy_(widen_columns(saved, kept, new_width, 0.0));
    } else {
      throw Error("parameter '" + key + "' saved as " + c10::str(saved.sizes()) + ", the config's network has " + c10::str(target.sizes()));
    }
  };
  if (const auto* net = dynamic_cast<const FeatureNetImpl*>(&module); net && net->encoder()) {
    // A network with an encoder: the saved inputs land in its first layer's input, past the
    // encoder's part; a saved network without an encoder leaves the encoder as initialised.
    std::vector<std::int64_t> first;
    for (const std::int64_t c : kept) {
      first.push_back(net->first_layer_column(c));
      if (first.back() < 0)
        throw Error("the saved network reads the encoder's input '" + net->encoder()->input + "' directly: start the run from scratch");
    }
    for (auto& child : module.named_children()) {
      torch::serialize::InputArchive sub;
      if (child.key() == "encoder") {
        if (archive.try_read("encoder", sub)) load_widened(*child.value(), sub, {}, 0);
      } else {
        archive.read(child.key(), sub);
        load_widened(*child.value(), sub, first, net->first_layer_width());
      }
    }
    return;
  }
  for (auto& p : module.named_parameters(/*recurse=*/false)) copy_into(p.key(), p.value(), false);
  for (auto& b : module.named_buffers(/*recurse=*/false)) copy_into(b.key(), b.value(), true);
  for (auto& child : module.named_children()) {
    torch::serialize::InputArchive sub;
    archive.read(child.key(), sub);
    load_widened(*child.value(), sub, kept, new_width);
  }
}

}  // namespace mimic
