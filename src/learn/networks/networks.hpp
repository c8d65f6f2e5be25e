#pragma once
// Policy and value networks: an MLP trunk, optionally behind a GRU that embeds the last K frames
// of observations (seed 004 section 5.1), with orthogonal or truncated-normal initialisation.
// The policy is a diagonal Gaussian: mean from the network, log sigma a state-independent
// parameter that is trained or fixed (SFV's fixed covariance).
#include <torch/torch.h>

#include "env/env.hpp"
#include "learn/trainer/train_config.hpp"

namespace mimic {

// Inputs are [batch, history * frame] (frames oldest first); outputs [batch, out]. With an
// encoder (cfg.encoder, resolved), inputs [offset, offset + size) go through the encoder's tanh
// layers, and the first layer reads the other inputs in order, then the encoder's outputs.
class FeatureNetImpl : public torch::nn::Module {
 public:
  FeatureNetImpl(int input_size, int out_size, const NetworkConfig& cfg);
  torch::Tensor forward(const torch::Tensor& x);
  int input_size() const { return input_size_; }
  // Where input column c lands in the first layer's input (-1: it feeds the encoder), and that
  // input's width: the identity and input_size without an encoder.
  std::int64_t first_layer_column(std::int64_t c) const;
  std::int64_t first_layer_width() const { return first_width_; }
  const EncoderConfig* encoder() const { return encoder_cfg_.enabled() ? &encoder_cfg_ : nullptr; }

 private:
  int input_size_, history_;
  bool relu_;
  std::int64_t first_width_ = 0;
  EncoderConfig encoder_cfg_;
  torch::nn::GRU gru_{nullptr};
  torch::nn::ModuleList encoder_{nullptr};
  torch::nn::ModuleList layers_;
};
TORCH_MODULE(FeatureNet);

// Resolves cfg.encoder's part to its place in an input of one frame laid out as `layout`: Error
// naming `where` when no part has that name or the network stacks frames. A no-op without one.
void resolve_encoder(NetworkConfig& cfg, const std::vector<ObservationSlice>& layout, const std::string& where);

class GaussianPolicyImpl : public torch::nn::Module {
 public:
  GaussianPolicyImpl(int input_size, int action_size, const PolicyConfig& cfg);
  FeatureNet& net() { return net_; }
  // Mean [batch, actions] and log sigma broadcast to the same shape.
  std::pair<torch::Tensor, torch::Tensor> forward(const torch::Tensor& obs);
  torch::Tensor log_std() const { return log_std_; }
  void set_log_std(double value);  // every action's; for a fixed covariance's schedule

 private:
  FeatureNet net_{nullptr};
  torch::Tensor log_std_;
};
TORCH_MODULE(GaussianPolicy);

class ValueNetImpl : public torch::nn::Module {
 public:
  ValueNetImpl(int input_size, const NetworkConfig& cfg);
  torch::Tensor forward(const torch::Tensor& obs);  // [batch]
  FeatureNet& net() { return net_; }

 private:
  FeatureNet net_{nullptr};
};
TORCH_MODULE(ValueNet);

// The machine's physical memory; Error "<what> takes about X GiB, more than this machine's Y GiB"
// where `bytes` exceed it (checked before a network or a buffer is allocated: a config asking for
// more would otherwise die in the allocator, or swap for hours).
std::uint64_t physical_memory_bytes();
void check_fits_memory(double bytes, const std::string& what);
// Trainable values of a network of this shape (FeatureNet's), counted without allocating;
// `shape` receives it in words ("17 -> 64 -> 64 -> 6").
double feature_net_parameters(int input_size, int out_size, const NetworkConfig& cfg, std::string& shape);

// Normal initialisation redrawn until every value lies within two standard deviations.
void truncated_normal_(torch::Tensor t, double std);
// Number of trainable and fixed parameters.
std::int64_t parameter_count(const torch::nn::Module& m);

}  // namespace mimic
