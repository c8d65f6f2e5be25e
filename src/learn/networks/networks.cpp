#include "learn/networks/networks.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"

namespace mimic {

void truncated_normal_(torch::Tensor t, double std) {
  torch::NoGradGuard no_grad;
  t.normal_(0.0, std);
  for (int round = 0; round < 100; ++round) {
    const torch::Tensor outside = t.abs() > 2.0 * std;
    if (!outside.any().item<bool>()) return;
    t.masked_scatter_(outside, torch::randn({outside.sum().item<std::int64_t>()}, t.options()) * std);
  }
  t.clamp_(-2.0 * std, 2.0 * std);
}

std::int64_t parameter_count(const torch::nn::Module& m) {
  std::int64_t n = 0;
  for (const auto& p : m.parameters()) n += p.numel();
  return n;
}

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : std::uint64_t{1} << 40;
}

void check_fits_memory(double bytes, const std::string& what) {
  const auto available = static_cast<double>(physical_memory_bytes());
  if (bytes <= available) return;
  char text[160];
  std::snprintf(text, sizeof text, "about %.1f GiB, more than this machine's %.1f GiB of memory", bytes / 1073741824.0, available / 1073741824.0);
  throw Error(what + " takes " + text);
}

// Trainable values of a FeatureNet of this shape, counted before any is allocated.
double feature_net_parameters(int input_size, int out_size, const NetworkConfig& cfg, std::string& shape) {
  double n = 0, width = input_size;
  shape = std::to_string(input_size);
  if (cfg.history > 1) {
    const double frame = static_cast<double>(input_size) / cfg.history, g = cfg.gru_size;
    n += 3 * (frame * g + g * g + 2 * g);
    width = g;
    shape += " -> GRU " + std::to_string(cfg.gru_size);
  }
  if (cfg.encoder.enabled()) {
    double e = cfg.encoder.size;
    shape += " (" + std::to_string(cfg.encoder.size) + " " + cfg.encoder.input;
    for (int h : cfg.encoder.hidden) n += (e + 1) * h, e = h, shape += " -> " + std::to_string(h);
    shape += ")";
    width += e - cfg.encoder.size;
  }
  for (int h : cfg.hidden) n += (width + 1) * h, width = h, shape += " -> " + std::to_string(h);
  shape += " -> " + std::to_string(out_size);
  return n + (width + 1) * out_size;
}

namespace {

void init_linear(torch::nn::Linear& l, const std::string& kind, double scale) {
  torch::NoGradGuard no_grad;
  if (kind == "orthogonal")
    torch::nn::init::orthogonal_(l->weight, scale);
  else
    truncated_normal_(l->weight, scale);
  torch::nn::init::zeros_(l->bias);
}

}  // namespace

FeatureNetImpl::FeatureNetImpl(int input_size, int out_size, const NetworkConfig& cfg)
    : input_size_(input_size), history_(cfg.history), relu_(cfg.activation == "relu") {
  if (input_size < 1 || out_size < 1) throw Error("network: input and output sizes must be positive");
  if (input_size % cfg.history != 0)
    throw Error("network: input of " + std::to_string(input_size) + " values is not " + std::to_string(cfg.history) + " equal frames");
  // Before anything is allocated: weights, gradients and Adam's two moments, 4 bytes each.
  std::string shape;
  const double parameters = feature_net_parameters(input_size, out_size, cfg, shape);
  check_fits_memory(16 * parameters, "a network " + shape + " (" + std::to_string(static_cast<long long>(parameters)) +
                                         " parameters) trained with Adam");
  int width = input_size;
  if (history_ > 1) {
    gru_ = register_module("gru", torch::nn::GRU(torch::nn::GRUOptions(input_size / history_, cfg.gru_size).batch_first(true)));
    torch::NoGradGuard no_grad;
    for (auto& p : gru_->named_parameters()) {
      if (p.key().find("weight") != std::string::npos) torch::nn::init::orthogonal_(p.value());
      else torch::nn::init::zeros_(p.value());
    }
    width = cfg.gru_size;
  }
  // Hidden gain: sqrt(2) for ReLU, 5/3 for tanh (torch's calculate_gain), or the truncated std.
  const double hidden_scale = cfg.init == "orthogonal" ? (relu_ ? std::sqrt(2.0) : 5.0 / 3.0) : cfg.init_std;
  if (cfg.encoder.enabled()) {
    const EncoderConfig& e = cfg.encoder;
    if (history_ > 1) throw Error("network: an encoder needs history 1");
    if (e.offset < 0 || e.size < 1 || e.offset + e.size > input_size)
      throw Error("network: the encoder's input '" + e.input + "' is not resolved within the " + std::to_string(input_size) + " inputs");
    encoder_cfg_ = e;
    encoder_ = register_module("encoder", torch::nn::ModuleList());
    int from = e.size;
    for (int h : e.hidden) {
      torch::nn::Linear l(from, h);
      init_linear(l, cfg.init, cfg.init == "orthogonal" ? 5.0 / 3.0 : cfg.init_std);  // tanh layers
      encoder_->push_back(l);
      from = h;
    }
    width = input_size - e.size + from;
  }
  first_width_ = width;
  layers_ = register_module("layers", torch::nn::ModuleList());
  for (int h : cfg.hidden) {
    torch::nn::Linear l(width, h);
    init_linear(l, cfg.init, hidden_scale);
    layers_->push_back(l);
    width = h;
  }
  torch::nn::Linear out(width, out_size);
  init_linear(out, cfg.output_init, cfg.output_scale);
  layers_->push_back(out);
}

std::int64_t FeatureNetImpl::first_layer_column(std::int64_t c) const {
  if (!encoder_cfg_.enabled()) return c;
  const EncoderConfig& e = encoder_cfg_;
  if (c < e.offset) return c;
  return c < e.offset + e.size ? -1 : c - e.size;
}

torch::Tensor FeatureNetImpl::forward(const torch::Tensor& x) {
  torch::Tensor h = x;
  if (history_ > 1) {
    h = h.view({h.size(0), history_, input_size_ / history_});
    h = std::get<1>(gru_->forward(h)).squeeze(0);  // final hidden state [batch, gru]
  }
  if (encoder_cfg_.enabled()) {
    const EncoderConfig& e = encoder_cfg_;
    torch::Tensor code = h.narrow(1, e.offset, e.size);
    for (std::size_t i = 0; i < encoder_->size(); ++i) code = torch::tanh(encoder_[i]->as<torch::nn::Linear>()->forward(code));
    h = torch::cat({h.narrow(1, 0, e.offset), h.narrow(1, e.offset + e.size, input_size_ - e.offset - e.size), code}, 1);
  }
  const std::size_t n = layers_->size();
  for (std::size_t i = 0; i < n; ++i) {
    h = layers_[i]->as<torch::nn::Linear>()->forward(h);
    if (i + 1 < n) h = relu_ ? torch::relu(h) : torch::tanh(h);
  }
  return h;
}

void resolve_encoder(NetworkConfig& cfg, const std::vector<ObservationSlice>& layout, const std::string& where) {
  EncoderConfig& e = cfg.encoder;
  if (!e.enabled()) return;
  if (cfg.history > 1) throw Error(where + ": an encoder needs history 1 (it reads one frame's part)");
  std::string names;
  for (const ObservationSlice& s : layout) {
    if (s.name == e.input) {
      e.offset = s.offset, e.size = s.size;
      return;
    }
    names += (names.empty() ? "" : ", ") + s.name;
  }
  throw Error(where + ": the encoder's input '" + e.input + "' is not a part of the observation (" + names + ")");
}

GaussianPolicyImpl::GaussianPolicyImpl(int input_size, int action_size, const PolicyConfig& cfg) {
  net_ = register_module("net", FeatureNet(input_size, action_size, cfg.net));
  log_std_ = register_parameter("log_std", torch::full({action_size}, cfg.log_std), cfg.learn_std);
}

void GaussianPolicyImpl::set_log_std(double value) {
  const torch::NoGradGuard no_grad;
  log_std_.fill_(value);
}

std::pair<torch::Tensor, torch::Tensor> GaussianPolicyImpl::forward(const torch::Tensor& obs) {
  torch::Tensor mean = net_->forward(obs);
  return {mean, log_std_.expand_as(mean)};
}

ValueNetImpl::ValueNetImpl(int input_size, const NetworkConfig& cfg) {
  net_ = register_module("net", FeatureNet(input_size, 1, cfg));
}

torch::Tensor ValueNetImpl::forward(const torch::Tensor& obs) { return net_->forward(obs).squeeze(-1); }

}  // namespace mimic
