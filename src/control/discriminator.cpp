#include "control/discriminator.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace mimic {

namespace {

Network::Activation activation_named(const ArrayTable& t, const std::string& name) {
  const std::string a = t.text(name);
  if (a == "relu") return Network::Activation::Relu;
  if (a == "tanh") return Network::Activation::Tanh;
  t.fail("array '" + name + "' is '" + a + "', expected relu or tanh");
}

// LibTorch's softplus (beta 1, threshold 20) in float32.
float softplus(float x) { return x > 20.0f ? x : std::log1p(std::exp(x)); }

constexpr int kMaxColumns = 1 << 20;

}  // namespace

int SkillDiscriminator::width() const {
  return transition == "s" ? state_width() : transition == "ss" ? 2 * state_width() : state_width() + action_size;
}

SkillDiscriminator SkillDiscriminator::read(const ArrayTable& t, int index, int frame_size, int action_size) {
  const std::string p = "discriminator." + std::to_string(index) + ".";
  SkillDiscriminator d;
  d.source = t.text(p + "source");
  d.context = t.count(p + "context", -1, 1 << 16);
  d.transition = t.text(p + "transition");
  if (d.transition != "s" && d.transition != "ss" && d.transition != "sa")
    t.fail("array '" + p + "transition' is '" + d.transition + "', expected s, ss or sa");
  const NamedArray& columns = t.at(p + "columns");
  if (columns.shape.size() != 1 || columns.shape[0] > kMaxColumns) t.fail("array '" + p + "columns' is not a list of observation entries");
  for (const double c : t.doubles(p + "columns", {columns.shape[0]})) {
    if (c != std::floor(c) || c < 0 || c >= frame_size)
      t.fail("array '" + p + "columns' holds " + std::to_string(c) + ", not an entry of a frame of " + std::to_string(frame_size) + " values");
    d.columns.push_back(static_cast<int>(c));
  }
  d.contexts = t.count(p + "contexts", 0, 1 << 16);
  const int context_offset = t.count(p + "context_offset", -1, frame_size);
  if (d.contexts > 0 && (context_offset < 0 || context_offset + d.contexts > frame_size))
    t.fail("array '" + p + "context_offset': a context of " + std::to_string(d.contexts) + " values does not fit a frame of " + std::to_string(frame_size));
  d.action_size = action_size;
  d.loss = t.text(p + "loss");
  if (d.loss != "bce" && d.loss != "hinge") t.fail("array '" + p + "loss' is '" + d.loss + "', expected bce or hinge");
  d.reward = t.text(p + "reward");
  if (d.reward != "neg_log_one_minus_d" && d.reward != "log_d" && d.reward != "logit")
    t.fail("array '" + p + "reward' is '" + d.reward + "', expected neg_log_one_minus_d, log_d or logit");
  d.reward_clip = t.scalar(p + "reward_clip");
  d.reward_offset = t.scalar(p + "reward_offset");
  const auto width = static_cast<std::uint32_t>(d.width());
  const std::vector<float>& mean = t.floats(p + "input_mean", {width});
  const std::vector<float>& sd = t.floats(p + "input_std", {width});
  if (std::any_of(sd.begin(), sd.end(), [](float v) { return !(v > 0); })) t.fail("array '" + p + "input_std' holds a value that is not > 0");
  d.input_mean = Eigen::Map<const Eigen::RowVectorXf>(mean.data(), d.width());
  d.input_std = Eigen::Map<const Eigen::RowVectorXf>(sd.data(), d.width());
  const int history = t.count(p + "history", 1, 1024);
  d.net = Network::read(t, p + "net", d.width(), history, activation_named(t, p + "activation"));
  return d;
}

FloatMatrix SkillDiscriminator::outputs(const Eigen::MatrixXd& obs, const Eigen::MatrixXd& next_obs, const Eigen::MatrixXd& actions,
                                        int held) const {
  const Eigen::Index n = next_obs.rows();
  const int needed = columns.empty() ? 0 : *std::max_element(columns.begin(), columns.end()) + 1;
  auto fits = [&](const Eigen::MatrixXd& m, const char* what) {
    if (m.rows() != n || m.cols() < needed)
      throw Error(source + ": " + what + " are " + std::to_string(m.rows()) + " rows of " + std::to_string(m.cols()) + " values; its features read " +
                  std::to_string(n) + " rows of at least " + std::to_string(needed));
  };
  if (transition != "s") fits(obs, "observations");
  fits(next_obs, "next observations");
  if (transition == "sa" && (actions.rows() != n || actions.cols() != action_size))
    throw Error(source + ": actions are " + std::to_string(actions.rows()) + " rows of " + std::to_string(actions.cols()) +
                " values; it scores (s, a) with " + std::to_string(action_size) + " action values");
  if (contexts > 0 && (held < 0 || held >= contexts))
    throw Error(source + ": its discriminator takes a behaviour context: give one of 0 to " + std::to_string(contexts - 1));
  if (contexts == 0 && held >= 0 && context < 0) throw Error(source + ": its discriminator has no behaviour context");
  FloatMatrix x(n, width());
  const int c = static_cast<int>(columns.size()), w = state_width();
  auto put_state = [&](Eigen::Index i, int at, const Eigen::MatrixXd& states) {
    for (int k = 0; k < c; ++k) x(i, at + k) = static_cast<float>(states(i, columns[static_cast<std::size_t>(k)]));
    for (int j = 0; j < contexts; ++j) x(i, at + c + j) = j == held ? 1.0f : 0.0f;
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    if (transition == "s") {
      put_state(i, 0, next_obs);
      continue;
    }
    put_state(i, 0, obs);
    if (transition == "ss")
      put_state(i, w, next_obs);
    else
      for (int k = 0; k < action_size; ++k) x(i, w + k) = static_cast<float>(actions(i, k));
  }
  x = ((x.rowwise() - input_mean).array().rowwise() / input_std.array()).matrix();
  return net.forward(x);
}

Eigen::VectorXd SkillDiscriminator::rewards(const Eigen::MatrixXd& obs, const Eigen::MatrixXd& next_obs, const Eigen::MatrixXd& actions,
                                            int held) const {
  const FloatMatrix out = outputs(obs, next_obs, actions, held);
  const Eigen::Index n = out.rows();
  const auto clip = static_cast<float>(reward_clip);
  Eigen::VectorXd r(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    float sum = 0.0f;
    for (Eigen::Index h = 0; h < out.cols(); ++h) {
      const float o = out(i, h);
      if (loss == "hinge") sum += std::clamp(o, -1.0f, 1.0f);
      else if (reward == "neg_log_one_minus_d") sum += std::min(softplus(o), clip);
      else if (reward == "log_d") sum += std::max(-softplus(-o), -clip);
      else sum += std::clamp(o, -clip, clip);
    }
    r[i] = static_cast<double>(sum / static_cast<float>(out.cols()) + static_cast<float>(reward_offset));
  }
  return r;
}

Eigen::VectorXd SkillDiscriminator::switch_scores(const Eigen::MatrixXd& obs, const Eigen::MatrixXd& next_obs, const Eigen::MatrixXd& actions,
                                                  int held) const {
  const FloatMatrix out = outputs(obs, next_obs, actions, held);
  Eigen::VectorXd r(out.rows());
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    double sum = 0;
    for (Eigen::Index h = 0; h < out.cols(); ++h) {
      const double o = out(i, h);
      sum += loss == "hinge" ? std::clamp(o, -1.0, 1.0) : 2.0 / (1.0 + std::exp(-o)) - 1.0;
    }
    r[i] = sum / static_cast<double>(out.cols());
  }
  return r;
}

}  // namespace mimic
