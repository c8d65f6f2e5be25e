#include "control/network.hpp"

#include <cmath>

#include "control/dense_kernel.hpp"
#include "core/error.hpp"

namespace mimic {

namespace {

std::string shape_text(const std::vector<std::uint32_t>& shape) {
  std::string s = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
  return s + "]";
}

const char* kind_name(NamedArray::Kind k) {
  return k == NamedArray::Kind::Text ? "text" : k == NamedArray::Kind::Float32 ? "float32" : "float64";
}

// The file's [rows, cols] matrix, transposed to [cols, rows].
FloatMatrix transposed(const std::vector<float>& v, std::uint32_t rows, std::uint32_t cols) {
  return Eigen::Map<const FloatMatrix>(v.data(), rows, cols).transpose();
}

Eigen::VectorXf vector_of(const std::vector<float>& v) { return Eigen::Map<const Eigen::VectorXf>(v.data(), static_cast<Eigen::Index>(v.size())); }

}  // namespace

ArrayTable::ArrayTable(std::vector<NamedArray> arrays, std::string source) : source_(std::move(source)) {
  for (NamedArray& a : arrays) arrays_.emplace(a.name, std::move(a));
}

void ArrayTable::fail(const std::string& message) const { throw Error(source_ + ": " + message); }

const NamedArray& ArrayTable::at(const std::string& name) const {
  const auto it = arrays_.find(name);
  if (it == arrays_.end()) fail("no array '" + name + "'");
  return it->second;
}

std::string ArrayTable::text(const std::string& name) const {
  const NamedArray& a = at(name);
  if (a.kind != NamedArray::Kind::Text) fail("array '" + name + "' is " + kind_name(a.kind) + ", expected text");
  return a.text;
}

double ArrayTable::scalar(const std::string& name) const {
  const NamedArray& a = at(name);
  if (a.kind != NamedArray::Kind::Float64 || !a.shape.empty()) fail("array '" + name + "' is not a float64 scalar");
  if (!std::isfinite(a.f64[0])) fail("array '" + name + "' is not finite");
  return a.f64[0];
}

int ArrayTable::count(const std::string& name, int lo, int hi) const {
  const double v = scalar(name);
  if (v != std::floor(v) || v < lo || v > hi)
    fail("array '" + name + "' is " + std::to_string(v) + ", expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<int>(v);
}

namespace {

// The values of array `a` when it is of `kind` and `shape` and every value is finite.
template <class T>
const std::vector<T>& checked(const ArrayTable& t, const NamedArray& a, NamedArray::Kind kind, const std::vector<T>& values,
                              const std::vector<std::uint32_t>& shape) {
  if (a.kind != kind) t.fail("array '" + a.name + "' is " + kind_name(a.kind) + ", expected " + kind_name(kind));
  if (a.shape != shape) t.fail("array '" + a.name + "' has shape " + shape_text(a.shape) + ", expected " + shape_text(shape));
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      t.fail("array '" + a.name + "' holds a value that is not finite (" + std::to_string(values[i]) + " at " + std::to_string(i) + ")");
  return values;
}

}  // namespace

const std::vector<float>& ArrayTable::floats(const std::string& name, const std::vector<std::uint32_t>& shape) const {
  const NamedArray& a = at(name);
  return checked(*this, a, NamedArray::Kind::Float32, a.f32, shape);
}

const std::vector<double>& ArrayTable::doubles(const std::string& name, const std::vector<std::uint32_t>& shape) const {
  const NamedArray& a = at(name);
  return checked(*this, a, NamedArray::Kind::Float64, a.f64, shape);
}

Network Network::read(const ArrayTable& t, const std::string& prefix, int input_size, int history, Activation activation) {
  Network n;
  n.input_size_ = input_size, n.history_ = history, n.activation_ = activation;
  if (history < 1 || input_size < 1 || input_size % history != 0)
    t.fail(prefix + ": an input of " + std::to_string(input_size) + " values is not " + std::to_string(history) + " equal frames");
  auto size_of = [&](const std::string& name, std::size_t dim) -> std::uint32_t {
    const NamedArray& a = t.at(name);
    if (a.shape.size() <= dim) t.fail("array '" + name + "' has rank " + std::to_string(a.shape.size()) + ", expected " + std::to_string(dim + 1) + " or more");
    return a.shape[dim];
  };
  auto width = static_cast<std::uint32_t>(input_size);
  if (history > 1) {
    const std::string g = prefix + ".gru.";
    const std::uint32_t frame = width / static_cast<std::uint32_t>(history);
    const std::uint32_t gates = size_of(g + "weight_ih_l0", 0), hidden = gates / 3;
    if (hidden == 0 || gates % 3 != 0) t.fail("array '" + g + "weight_ih_l0' has " + std::to_string(gates) + " rows, not 3 gates of a positive size");
    Gru gru;
    gru.weight_ih = transposed(t.floats(g + "weight_ih_l0", {gates, frame}), gates, frame);
    gru.weight_hh = transposed(t.floats(g + "weight_hh_l0", {gates, hidden}), gates, hidden);
    gru.bias_ih = vector_of(t.floats(g + "bias_ih_l0", {gates}));
    gru.bias_hh = vector_of(t.floats(g + "bias_hh_l0", {gates}));
    n.gru_ = std::move(gru);
    width = hidden;
  }
  // Layers "<at>.K.weight" and "<at>.K.bias" from K = 0 while they exist, chained from `width`.
  auto read_layers = [&](const std::string& at, std::vector<Linear>& layers) {
    for (int k = 0;; ++k) {
      const std::string w = at + "." + std::to_string(k) + ".weight", b = at + "." + std::to_string(k) + ".bias";
      if (!t.has(w)) {
        if (k == 0) t.fail("no array '" + w + "': the network has no layer");
        break;
      }
      const std::uint32_t out = size_of(w, 0);
      const std::vector<float>& weights = t.floats(w, {out, width});
      layers.push_back({transposed(weights, out, width), Eigen::Map<const FloatMatrix>(weights.data(), out, width), vector_of(t.floats(b, {out}))});
      width = out;
    }
  };
  if (t.has(prefix + ".encoder_offset")) {
    if (history > 1) t.fail(prefix + ": an encoder with history " + std::to_string(history) + " (it reads one frame)");
    Encoder e;
    e.size = t.count(prefix + ".encoder_size", 1, input_size);
    e.offset = t.count(prefix + ".encoder_offset", 0, input_size - e.size);
    width = static_cast<std::uint32_t>(e.size);
    read_layers(prefix + ".encoder", e.layers);
    width += static_cast<std::uint32_t>(input_size - e.size);
    n.encoder_ = std::move(e);
  }
  read_layers(prefix + ".layers", n.layers_);
  return n;
}

FloatMatrix Network::forward(const FloatMatrix& x) const {
  if (x.cols() != input_size_)
    throw Error("network input has " + std::to_string(x.cols()) + " values, expected " + std::to_string(input_size_));
  FloatMatrix h;
  if (gru_) {
    // PyTorch's GRU (seed 004 section 5.1's encoder), from a zero state over the frames in order:
    // r = s(W_ir x + b_ir + W_hr h + b_hr), z = s(... z ...), n = tanh(W_in x + b_in + r (W_hn h + b_hn)),
    // h' = (1 - z) n + z h.
    const Eigen::Index frame = input_size_ / history_, hidden = gru_->bias_hh.size() / 3;
    h = FloatMatrix::Zero(x.rows(), hidden);
    auto sigmoid = [](float v) { return 1.0f / (1.0f + std::exp(-v)); };
    for (int f = 0; f < history_; ++f) {
      const FloatMatrix xf = x.middleCols(f * frame, frame);
      FloatMatrix gi(x.rows(), 3 * hidden), gh(x.rows(), 3 * hidden);
      dense_forward(xf.data(), static_cast<int>(xf.rows()), static_cast<int>(frame), gru_->weight_ih.data(), gru_->bias_ih.data(),
                    static_cast<int>(3 * hidden), gi.data());
      dense_forward(h.data(), static_cast<int>(h.rows()), static_cast<int>(hidden), gru_->weight_hh.data(), gru_->bias_hh.data(),
                    static_cast<int>(3 * hidden), gh.data());
      for (Eigen::Index i = 0; i < x.rows(); ++i)
        for (Eigen::Index j = 0; j < hidden; ++j) {
          const float r = sigmoid(gi(i, j) + gh(i, j));
          const float z = sigmoid(gi(i, hidden + j) + gh(i, hidden + j));
          const float c = std::tanh(gi(i, 2 * hidden + j) + r * gh(i, 2 * hidden + j));
          h(i, j) = (1.0f - z) * c + z * h(i, j);
        }
    }
  }
  FloatMatrix in = gru_ ? std::move(h) : x;
  if (encoder_) {
    // The encoder's part through its tanh layers; the first layer reads the rest, then the code.
    const Encoder& e = *encoder_;
    const FloatMatrix code = run_layers(e.layers, x.middleCols(e.offset, e.size), Activation::Tanh, true);
    const Eigen::Index after = input_size_ - e.offset - e.size;
    in.resize(x.rows(), input_size_ - e.size + code.cols());
    in << x.leftCols(e.offset), x.rightCols(after), code;
  }
  return run_layers(layers_, std::move(in), activation_, false);
}

FloatMatrix Network::run_layers(const std::vector<Linear>& layers, FloatMatrix in, Activation activation, bool activate_last) {
  FloatMatrix y;
  for (std::size_t k = 0; k < layers.size(); ++k) {
    const Linear& l = layers[k];
    y.resize(in.rows(), l.weight.cols());
    if (in.rows() == 1)
      dense_forward_one(in.data(), static_cast<int>(in.cols()), l.weight_out.data(), l.bias.data(), static_cast<int>(l.weight.cols()), y.data());
    else
      dense_forward(in.data(), static_cast<int>(in.rows()), static_cast<int>(in.cols()), l.weight.data(), l.bias.data(), static_cast<int>(l.weight.cols()),
                    y.data());
    if (k + 1 < layers.size() || activate_last) {
      if (activation == Activation::Relu) y = y.cwiseMax(0.0f);
      else y = y.array().tanh().matrix();
    }
    if (k + 1 < layers.size()) std::swap(in, y);
  }
  return y;
}

long long Network::parameters() const {
  long long n = 0;
  if (gru_) n += gru_->weight_ih.size() + gru_->weight_hh.size() + gru_->bias_ih.size() + gru_->bias_hh.size();
  for (const Linear& l : layers_) n += l.weight.size() + l.bias.size();  // one layout counted
  if (encoder_)
    for (const Linear& l : encoder_->layers) n += l.weight.size() + l.bias.size();
  return n;
}

}  // namespace mimic
