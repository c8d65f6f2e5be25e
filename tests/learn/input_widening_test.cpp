#include "learn/networks/input_widening.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "core/error.hpp"

namespace mimic {
namespace {

torch::serialize::InputArchive saved_archive(torch::nn::Module& m) {
  torch::serialize::OutputArchive out;
  m.save(out);
  std::ostringstream bytes;
  out.save_to(bytes);
  std::istringstream in(bytes.str());
  torch::serialize::InputArchive a;
  a.load_from(in);
  return a;
}

}  // namespace

TEST(InputWidening, ColumnsMoveByTheInputsAddedAfterEachBlock) {
  // Two frames of 3 with 2 context inputs after each: 0 1 2 | 5 6 7.
  EXPECT_EQ(widened_columns(6, 3, 2, 2), (std::vector<std::int64_t>{0, 1, 2, 5, 6, 7}));
  // One state of 2, then a 2-value action that moves by the one block's context: 0 1 | 3 4.
  EXPECT_EQ(widened_columns(4, 2, 1, 1), (std::vector<std::int64_t>{0, 1, 3, 4}));
  EXPECT_EQ(widened_columns(3, 3, 1, 0), (std::vector<std::int64_t>{0, 1, 2}));
  EXPECT_THROW(widened_columns(5, 3, 2, 1), Error);  // two blocks of 3 do not fit 5
}

TEST(InputWidening, SavedPartsGoToTheirNamesPlacesInEachFrame) {
  const std::vector<ObservationSlice> saved = {{"state", 0, 3}, {"phase", 3, 1}};
  // A 2-value part between them: state 0 1 2, (new 3 4), phase 5; two frames of 6.
  const std::vector<ObservationSlice> now = {{"state", 0, 3}, {"offset", 3, 2}, {"phase", 5, 1}};
  EXPECT_EQ(mapped_columns(saved, now, 2), (std::vector<std::int64_t>{0, 1, 2, 5, 6, 7, 8, 11}));
  EXPECT_EQ(mapped_columns(saved, saved, 1), (std::vector<std::int64_t>{0, 1, 2, 3}));
  auto message = [&](const std::vector<ObservationSlice>& layout) {
    try {
      mapped_columns(saved, layout, 1);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({{"state", 0, 3}}), "observation part 'phase' of the saved network is not in the config's observation");
  EXPECT_EQ(message({{"phase", 0, 1}, {"state", 1, 3}}),
            "observation part 'phase' of the saved network comes earlier in the config's observation (parts may be added, not reordered)");
  EXPECT_EQ(message({{"state", 0, 4}, {"phase", 4, 1}}), "observation part 'state' had 3 values, the config's has 4");
}

TEST(InputWidening, SavedColumnsGoToTheirPlacesAndTheRestIsFilled) {
  const torch::Tensor w = torch::tensor({1.0f, 2.0f, 3.0f, 4.0f}).view({2, 2});
  const torch::Tensor wide = widen_columns(w, {0, 2}, 3, 0.0);
  EXPECT_TRUE(torch::equal(wide, torch::tensor({1.0f, 0.0f, 2.0f, 3.0f, 0.0f, 4.0f}).view({2, 3})));
  const torch::Tensor v = widen_columns(torch::tensor({5.0, 6.0}, torch::kFloat64), {1, 2}, 3, 0.5);
  EXPECT_TRUE(torch::equal(v, torch::tensor({0.5, 5.0, 6.0}, torch::kFloat64)));
  EXPECT_THROW(widen_columns(w, {0, 1, 2}, 4, 0.0), Error);  // 2 saved columns, 3 places
}

TEST(InputWidening, AWidenedNetworkComputesWhatTheSavedOneDidWhateverTheNewInputsHold) {
  torch::manual_seed(3);
  torch::nn::Sequential narrow(torch::nn::Linear(3, 4), torch::nn::Tanh(), torch::nn::Linear(4, 2));
  torch::nn::Sequential wide(torch::nn::Linear(5, 4), torch::nn::Tanh(), torch::nn::Linear(4, 2));
  auto archive = saved_archive(*narrow);
  const auto kept = widened_columns(3, 3, 1, 2);  // a 2-input one-hot after the state
  load_widened(*wide, archive, kept, 5);
  const torch::Tensor x = torch::randn({6, 3});
  const torch::Tensor expected = narrow->forward(x).detach();
  for (const torch::Tensor& context : {torch::tensor({1.0f, 0.0f}), torch::tensor({0.0f, 1.0f}), torch::tensor({7.0f, -3.0f})}) {
    const torch::Tensor with_context = torch::cat({x, context.expand({6, 2})}, 1);
    EXPECT_TRUE(torch::allclose(wide->forward(with_context), expected, 1e-6, 1e-6));
  }
  // The new inputs' weights are zero and trainable; the rest are the saved ones.
  const torch::Tensor first = wide[0]->as<torch::nn::Linear>()->weight;
  EXPECT_TRUE(torch::equal(first.slice(1, 3, 5), torch::zeros({4, 2})));
  EXPECT_TRUE(torch::equal(first.slice(1, 0, 3), narrow[0]->as<torch::nn::Linear>()->weight));
  EXPECT_TRUE(first.requires_grad());
}

TEST(InputWidening, ANetworkGainingAnEncoderOverANewPartComputesWhatTheSavedOneDid) {
  // A saved policy over 3 inputs; the new one reads them and a new 4-value part through an
  // encoder, which the first layer sees after the saved inputs: its weights there start at zero.
  torch::manual_seed(4);
  NetworkConfig plain;
  plain.hidden = {6};
  FeatureNet saved(3, 2, plain);
  NetworkConfig with_encoder = plain;
  with_encoder.encoder.input = "height_map";
  with_encoder.encoder.hidden = {5};
  resolve_encoder(with_encoder, {{"body", 0, 3}, {"height_map", 3, 4}}, "test");
  FeatureNet wide(7, 2, with_encoder);
  auto archive = saved_archive(*saved);
  load_widened(*wide, archive, {0, 1, 2}, 7);
  const torch::Tensor x = torch::randn({4, 3});
  for (const double h : {0.0, 1.5, -4.0}) {
    const torch::Tensor with_map = torch::cat({x, torch::full({4, 4}, h)}, 1);
    EXPECT_TRUE(torch::allclose(wide->forward(with_map), saved->forward(x), 1e-6, 1e-6)) << h;
  }
  // A saved input that would land in the encoder's part is refused.
  FeatureNet reads_map(7, 2, plain);
  auto whole = saved_archive(*reads_map);
  EXPECT_THROW(load_widened(*wide, whole, {0, 1, 2, 3, 4, 5, 6}, 7), Error);
}

TEST(InputWidening, OtherShapesAndGrusAreRefusedByName) {
  torch::nn::Sequential saved(torch::nn::Linear(3, 4));
  torch::nn::Sequential other(torch::nn::Linear(5, 6));  // another hidden width: not a widening
  auto a = saved_archive(*saved);
  try {
    load_widened(*other, a, widened_columns(3, 3, 1, 2), 5);
    FAIL() << "loaded a 4-row weight into 6 rows";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("parameter 'weight' saved as [4, 3], the config's network has [6, 5]"), std::string::npos) << e.what();
  }
  torch::nn::GRU gru(torch::nn::GRUOptions(3, 4));
  auto g = saved_archive(*gru);
  torch::nn::GRU wider(torch::nn::GRUOptions(5, 4));
  try {
    load_widened(*wider, g, widened_columns(3, 3, 1, 2), 5);
    FAIL() << "widened a GRU";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("GRU"), std::string::npos) << e.what();
  }
}

}  // namespace mimic
