#pragma once
// Small conversions between LibTorch archives and the state they hold (bytes, vectors, random
// generators), shared by checkpoints and the reward sources that save themselves into them.
#include <torch/torch.h>

#include <Eigen/Core>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace mimic::archive {

inline torch::Tensor bytes_tensor(const std::string& s) {
  return torch::from_blob(const_cast<char*>(s.data()), {static_cast<std::int64_t>(s.size())}, torch::kUInt8).clone();
}
inline std::string tensor_bytes(const torch::Tensor& t) {
  const torch::Tensor c = t.contiguous();
  return std::string(reinterpret_cast<const char*>(c.data_ptr<std::uint8_t>()), static_cast<std::size_t>(c.numel()));
}
inline torch::Tensor vec_tensor(const Eigen::VectorXd& v) {
  return torch::from_blob(const_cast<double*>(v.data()), {v.size()}, torch::kFloat64).clone();
}
inline Eigen::VectorXd tensor_vec(const torch::Tensor& t) {
  const torch::Tensor c = t.contiguous().to(torch::kFloat64);
  return Eigen::Map<const Eigen::VectorXd>(c.data_ptr<double>(), c.numel());
}
template <class Rng>
std::string rng_text(const Rng& rng) {
  std::ostringstream os;
  os << rng;
  return os.str();
}
template <class Rng>
void set_rng(Rng& rng, const std::string& text, const std::string& what) {
  std::istringstream is(text);
  is >> rng;
  if (!is) throw Error("generator state '" + what + "' is unreadable");
}
// A fresh tensor per key: reading into a used one would try to resize the archive's storage.
inline torch::Tensor get(torch::serialize::InputArchive& a, const std::string& key) {
  torch::Tensor t;
  a.read(key, t);
  return t;
}

}  // namespace mimic::archive
