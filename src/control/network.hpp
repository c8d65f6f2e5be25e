#pragma once
// A policy or value network evaluated with Eigen, in float32, as learn/networks/networks.hpp's FeatureNet
// computes it with LibTorch: an optional GRU over the last `history` frames (its final hidden
// state), then linear layers with ReLU or tanh between them. Immutable once loaded: one Network
// may be shared by any number of threads.
#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/array_file.hpp"

namespace mimic {

using FloatMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A model file's arrays by name, with the checks every reader needs. Errors name `source`.
class ArrayTable {
 public:
  ArrayTable(std::vector<NamedArray> arrays, std::string source);
  bool has(const std::string& name) const { return arrays_.count(name) > 0; }
  const std::string& source() const { return source_; }
  std::string text(const std::string& name) const;
  double scalar(const std::string& name) const;
  int count(const std::string& name, int lo, int hi) const;  // an integer-valued scalar in [lo, hi]
  // A float32 array of exactly this shape, every value finite.
  const std::vector<float>& floats(const std::string& name, const std::vector<std::uint32_t>& shape) const;
  const std::vector<double>& doubles(const std::string& name, const std::vector<std::uint32_t>& shape) const;
  const NamedArray& at(const std::string& name) const;
  [[noreturn]] void fail(const std::string& message) const;

 private:
  std::map<std::string, NamedArray> arrays_;
  std::string source_;
};

class Network {
 public:
  enum class Activation { Relu, Tanh };
  // The arrays under `prefix` ("policy.net", "value.net"): optional "gru.weight_ih_l0",
  // "gru.weight_hh_l0", "gru.bias_ih_l0", "gru.bias_hh_l0" (history > 1), or an optional
  // encoder (seed 002's: "encoder_offset" and "encoder_size", the input columns it reads, and
  // tanh layers "encoder.K.weight", "encoder.K.bias"; the first layer reads the other inputs, then
  // its outputs), then "layers.K.weight" [out, in] and "layers.K.bias" [out] for K = 0, 1, ...
  // Error naming the file and the array where a shape does not chain from `input_size` or a value
  // is not finite.
  static Network read(const ArrayTable& arrays, const std::string& prefix, int input_size, int history, Activation activation);

  int input_size() const { return input_size_; }
  int output_size() const { return static_cast<int>(layers_.back().bias.size()); }
  int history() const { return history_; }
  // Outputs [batch, output_size] for inputs [batch, input_size] (frames oldest first).
  FloatMatrix forward(const FloatMatrix& x) const;
  long long parameters() const;

 private:
  // Weights input-major, the transpose of the file's (LibTorch's) [out, in]: dense_kernel.hpp.
  // Both layouts of a layer's weights: batch 1 streams the output-major one, batches the other.
  struct Linear {
    FloatMatrix weight;      // [in, out]
    FloatMatrix weight_out;  // [out, in], as in the file
    Eigen::VectorXf bias;
  };
  struct Gru {
    FloatMatrix weight_ih, weight_hh;  // [frame, 3 hidden], [hidden, 3 hidden]; gates r, z, n
    Eigen::VectorXf bias_ih, bias_hh;
  };
  struct Encoder {
    int offset = 0, size = 0;
    std::vector<Linear> layers;  // tanh after each
  };
  int input_size_ = 0, history_ = 1;
  Activation activation_ = Activation::Relu;
  std::optional<Gru> gru_;
  std::optional<Encoder> encoder_;
  std::vector<Linear> layers_;
  // `in` through `layers`, `activation` between them (and after the last where activate_last).
  static FloatMatrix run_layers(const std::vector<Linear>& layers, FloatMatrix in, Activation activation, bool activate_last);
};

}  // namespace mimic
