// The runtime's model reader (control/skill.cpp) and its file format (core/array_file): the bytes
// are pinned against a hand-built file, and every malformed model directory is answered by an
// error naming the file and the problem, never a crash or a wrong action.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include <mujoco/mujoco.h>

#include "control/dense_kernel.hpp"
#include "control/skill_impl.hpp"
#include "core/array_file.hpp"
#include "core/file_io.hpp"
#include "error_message.hpp"
#include "control/transitions.hpp"
#include "mimic/runtime.hpp"
#include "test_data.hpp"

using namespace mimic;
using test::error_of;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

const std::filesystem::path kWalker = std::filesystem::path(MIMIC_SOURCE_DIR) / "models" / "walker_ppo";

TEST(ArrayFile, TheBytesOfAOneScalarFileAreTheDocumentedOnes) {
  // Header: magic, version 1, CRC-32 of the body, the body's size 17; body: 1 entry, a name of
  // length 1 ("a"), kind 2 (float64), rank 0, the double 1.0. CRC from zlib.crc32 in Python.
  const std::string bytes = encode_arrays({NamedArray::of_scalar("a", 1.0)});
  const unsigned char expected[] = {'M', 'I', 'M', 'I', 'C', 'A', 'R', 'R', 1, 0, 0, 0, 0x3e, 0xb6, 0xaa, 0xa4, 17, 0, 0, 0, 0, 0, 0, 0,
                                    1, 0, 0, 0, 1, 0, 'a', 2, 0, 0, 0, 0, 0, 0, 0, 0xf0, 0x3f};
  ASSERT_EQ(bytes.size(), sizeof expected);
  EXPECT_EQ(std::memcmp(bytes.data(), expected, sizeof expected), 0);
  const std::vector<NamedArray> back = decode_arrays(bytes);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].name, "a");
  EXPECT_TRUE(back[0].shape.empty());
  EXPECT_EQ(back[0].f64, std::vector<double>{1.0});
}

TEST(ArrayFile, EveryKindRoundTripsAndBadArraysAreRefusedWhenWritten) {
  const std::vector<NamedArray> arrays = {NamedArray::of_text("t", "two\nlines"), NamedArray::of_floats("w", {2, 3}, {1, 2, 3, 4, 5, -6.5f}),
                                          NamedArray::of_doubles("d", {2}, {0.25, -1e300})};
  const std::vector<NamedArray> back = decode_arrays(encode_arrays(arrays));
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[0].text, "two\nlines");
  EXPECT_EQ(back[1].shape, (std::vector<std::uint32_t>{2, 3}));
  EXPECT_EQ(back[1].f32[5], -6.5f);
  EXPECT_EQ(back[2].f64[1], -1e300);
  EXPECT_TRUE(contains(error_of([] { (void)encode_arrays({NamedArray::of_floats("w", {2, 2}, {1, 2, 3})}); }), "holds 3 values where its shape holds 4"));
  EXPECT_TRUE(contains(error_of([] { (void)encode_arrays({NamedArray::of_scalar("x", 1), NamedArray::of_scalar("x", 2)}); }), "'x' is given twice"));
  EXPECT_TRUE(contains(error_of([] { (void)encode_arrays({NamedArray::of_scalar("a b", 1)}); }), "not printable ASCII"));
  EXPECT_TRUE(contains(error_of([] { (void)encode_arrays({NamedArray::of_floats("r", {1, 1, 1, 1, 1}, {1})}); }), "rank 5, above 4"));
}

TEST(ArrayFile, AnArrayWithAZeroInItsShapeRoundTripsEmpty) {
  // Found by fuzz_runtime_model under UBSan: decoding an empty float array once copied zero bytes
  // into a null pointer.
  const std::vector<NamedArray> back =
      decode_arrays(encode_arrays({NamedArray::of_floats("e", {0, 3}, {}), NamedArray::of_doubles("f", {4, 0}, {}), NamedArray::of_text("t", "")}));
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[0].shape, (std::vector<std::uint32_t>{0, 3}));
  EXPECT_TRUE(back[0].f32.empty());
  EXPECT_EQ(back[1].shape, (std::vector<std::uint32_t>{4, 0}));
  EXPECT_TRUE(back[1].f64.empty());
  EXPECT_EQ(back[2].text, "");
}

// A copy of the walker's model whose networks.mimic went through `edit` (re-encoded: its CRC-32
// is right, so what is refused is the content).
std::filesystem::path edited_model(const std::string& name, const std::function<void(std::vector<NamedArray>&)>& edit) {
  const auto dir = test::temp_dir("runtime_model_" + name);
  std::filesystem::copy_file(kWalker / "config.yaml", dir / "config.yaml");
  std::vector<NamedArray> arrays = decode_arrays(read_text_file(kWalker / "networks.mimic"));
  edit(arrays);
  write_file_atomic(dir / "networks.mimic", encode_arrays(arrays));
  return dir;
}

// The same with the file's bytes edited (what a disk or a transfer does).
std::filesystem::path damaged_model(const std::string& name, const std::function<void(std::string&)>& edit) {
  const auto dir = test::temp_dir("runtime_model_" + name);
  std::filesystem::copy_file(kWalker / "config.yaml", dir / "config.yaml");
  std::string bytes = read_text_file(kWalker / "networks.mimic");
  edit(bytes);
  write_file_atomic(dir / "networks.mimic", bytes);
  return dir;
}

NamedArray& array(std::vector<NamedArray>& arrays, const std::string& name) {
  for (NamedArray& a : arrays)
    if (a.name == name) return a;
  throw Error("test: no array " + name);
}

void remove_array(std::vector<NamedArray>& arrays, const std::string& name) {
  std::erase_if(arrays, [&](const NamedArray& a) { return a.name == name; });
}

struct MalformedModel {
  std::string what;
  std::function<std::filesystem::path()> make;
  std::string expected;        // in the message
  bool names_networks = true;  // the message names networks.mimic (else the directory or config)
};

TEST(RuntimeModel, EveryMalformedModelIsANamedErrorNeverACrash) {
  ASSERT_TRUE(std::filesystem::exists(kWalker / "networks.mimic"));
  const std::vector<MalformedModel> cases = {
      {"no directory", [] { return test::temp_dir("runtime_model_none") / "absent"; }, "no such model directory", false},
      {"no config", [] {
         const auto d = test::temp_dir("runtime_model_no_config");
         std::filesystem::copy_file(kWalker / "networks.mimic", d / "networks.mimic");
         return d;
       }, "config.yaml: missing", false},
      {"no networks", [] {
         const auto d = test::temp_dir("runtime_model_no_networks");
         std::filesystem::copy_file(kWalker / "config.yaml", d / "config.yaml");
         return d;
       }, "networks.mimic: missing; `mimic export RUN -o"},
      {"empty file", [] { return damaged_model("empty", [](std::string& b) { b.clear(); }); }, "not a mimic array file"},
      {"a LibTorch checkpoint instead", [] {
         return damaged_model("checkpoint", [](std::string& b) { b = read_text_file(kWalker / "checkpoint.pt", kMaxCheckpointBytes); });
       }, "not a mimic array file (it does not start with MIMICARR)"},
      {"cut inside the header", [] { return damaged_model("header", [](std::string& b) { b.resize(12); }); }, "file ends inside its 24-byte header"},
      {"cut inside the weights", [] { return damaged_model("cut", [](std::string& b) { b.resize(b.size() / 2); }); }, "(cut short)"},
      {"bytes appended", [] { return damaged_model("appended", [](std::string& b) { b += "junk"; }); }, "(bytes were added)"},
      {"a flipped bit in a weight", [] { return damaged_model("flipped", [](std::string& b) { b[b.size() - 100] ^= 0x04; }); },
       "does not match the one it was written with: the file is damaged"},
      {"a newer format version", [] { return damaged_model("version", [](std::string& b) { b[8] = 2; }); },
       "format version 2, where this build reads version 1 (written by a newer mimic"},
      {"another format", [] { return edited_model("format", [](auto& a) { array(a, "format").text = "something else"; array(a, "format").shape = {14}; }); },
       "format 'something else', expected 'mimic skill networks'"},
      {"a layer of the wrong shape", [] {
         return edited_model("shape", [](auto& a) {
           NamedArray& w = array(a, "policy.net.layers.1.weight");
           w.shape = {64, 63};
           w.f32.resize(64 * 63);
         });
       }, "array 'policy.net.layers.1.weight' has shape [64, 63], expected [64, 64]"},
      {"a NaN weight", [] { return edited_model("nan", [](auto& a) { array(a, "policy.net.layers.0.weight").f32[7] = std::nanf(""); }); },
       "array 'policy.net.layers.0.weight' holds a value that is not finite"},
      {"an infinite normaliser mean", [] {
         return edited_model("inf", [](auto& a) { array(a, "observation.mean").f64[0] = INFINITY; });
       }, "array 'observation.mean' holds a value that is not finite"},
      {"a missing bias", [] { return edited_model("bias", [](auto& a) { remove_array(a, "value.net.layers.2.bias"); }); },
       "no array 'value.net.layers.2.bias'"},
      {"no layers at all", [] {
         return edited_model("layers", [](auto& a) {
           std::erase_if(a, [](const NamedArray& x) { return x.name.rfind("policy.net.", 0) == 0; });
         });
       }, "no array 'policy.net.layers.0.weight': the network has no layer"},
      {"weights stored as float64", [] {
         return edited_model("kind", [](auto& a) {
           NamedArray& w = array(a, "policy.log_std");
           w = NamedArray::of_doubles(w.name, w.shape, std::vector<double>(w.f32.begin(), w.f32.end()));
         });
       }, "array 'policy.log_std' is float64, expected float32"},
      {"an unknown activation", [] {
         return edited_model("activation", [](auto& a) { array(a, "policy.activation") = NamedArray::of_text("policy.activation", "swish"); });
       }, "array 'policy.activation' is 'swish', expected relu or tanh"},
      {"a history of zero", [] { return edited_model("history", [](auto& a) { array(a, "observation.history").f64[0] = 0; }); },
       "array 'observation.history' is 0.000000, expected an integer in [1, 1024]"},
      {"a fractional action count", [] { return edited_model("actions", [](auto& a) { array(a, "action_size").f64[0] = 5.5; }); },
       "array 'action_size' is 5.500000, expected an integer"},
      {"more actions than the last layer gives", [] { return edited_model("more_actions", [](auto& a) { array(a, "action_size").f64[0] = 7; }); },
       "the policy's last layer gives 6 values for 7 actions"},
      {"a layout with a gap", [] {
         return edited_model("layout", [](auto& a) { array(a, "observation.layout") = NamedArray::of_text("observation.layout", "state 1 16\n"); });
       }, "part 'state' starts at 1, not 0"},
      {"a negative variance", [] { return edited_model("variance", [](auto& a) { array(a, "observation.variance").f64[3] = -1; }); },
       "array 'observation.variance' holds a negative value"},
      {"a value network with two outputs", [] {
         return edited_model("value_out", [](auto& a) {
           NamedArray& w = array(a, "value.net.layers.2.weight");
           w.shape[0] = 2;
           w.f32.resize(2 * 64, 0.5f);
           array(a, "value.net.layers.2.bias") = NamedArray::of_floats("value.net.layers.2.bias", {2}, {0, 0});
         });
       }, "the value network's last layer gives 2 values, not 1"},
      {"networks of another character", [] {
         return edited_model("bodies", [](auto& a) { array(a, "character.bodies") = NamedArray::of_text("character.bodies", "torso\nleg\n"); });
       }, "the networks were trained on a character of 2 bodies (torso ...)"},
      {"a config whose environment is another", [] {
         const auto d = edited_model("other_env", [](auto&) {});
         write_file_atomic(d / "config.yaml", "env: {name: reacher}\n");
         return d;
       }, "the networks take observations of 17 values and give 6 actions"},
      {"a config that is not YAML", [] {
         const auto d = edited_model("bad_yaml", [](auto&) {});
         write_file_atomic(d / "config.yaml", "env: {name: [\n");
         return d;
       }, "config.yaml:", false},
      {"a config without env", [] {
         const auto d = edited_model("no_env", [](auto&) {});
         write_file_atomic(d / "config.yaml", "seed: 1\n");
         return d;
       }, "config.yaml: no 'env' section", false},
  };
  ASSERT_GE(cases.size(), 20u);
  for (const MalformedModel& c : cases) {
    SCOPED_TRACE(c.what);
    const std::filesystem::path dir = c.make();
    const std::string message = error_of([&] { (void)Skill::load(dir); });
    EXPECT_TRUE(contains(message, c.expected)) << message;
    EXPECT_TRUE(contains(message, (c.names_networks ? dir / "networks.mimic" : dir).string())) << "the message names no file: " << message;
  }
}

TEST(RuntimeModel, TheCommittedWalkerLoadsAndWalksForward) {
  const auto skill = Skill::load(kWalker);
  EXPECT_EQ(skill->name(), "walker_ppo");
  EXPECT_EQ(skill->frame_size(), 17);
  EXPECT_EQ(skill->action_size(), 6);
  EXPECT_EQ(skill->policy_parameters(), (17 + 1) * 64 + (64 + 1) * 64 + (64 + 1) * 6 + 6);
  Controller c({skill}, 3);
  EXPECT_DOUBLE_EQ(c.control_dt(), 0.008) << "known before the first step (a window's or a video's frame rate)";
  const double x0 = c.root_position().x();
  for (int i = 0; i < 200; ++i)
    if (c.step().episode_over) break;
  EXPECT_GT(c.root_position().x() - x0, 0.5) << "the trained walker walks forward";
}

TEST(RuntimeModel, ASkillIsNamedByItsDirectoryOrByTheRunOfAModelDirectory) {
  EXPECT_EQ(Skill::default_name("models/humanoid_walk_iccgan"), "humanoid_walk_iccgan");
  EXPECT_EQ(Skill::default_name("models/humanoid_walk_iccgan/"), "humanoid_walk_iccgan");
  EXPECT_EQ(Skill::default_name("runs/my_walk/model"), "my_walk");  // what mimic imitate writes
  EXPECT_EQ(Skill::default_name("runs/my_walk/model/"), "my_walk");
  EXPECT_EQ(Skill::default_name("runs/my_walk/model/../model"), "my_walk");
  EXPECT_EQ(Skill::default_name("/model"), "model");  // no run above it
  EXPECT_EQ(Skill::default_name("runs/my_walk/models"), "models");
  // Skill::load names a skill so; a name given wins.
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "named_run" / "model";
  std::filesystem::remove_all(dir.parent_path());
  std::filesystem::create_directories(dir.parent_path());
  std::filesystem::copy(kWalker, dir, std::filesystem::copy_options::recursive);
  EXPECT_EQ(Skill::load(dir)->name(), "named_run");
  EXPECT_EQ(Skill::load(dir, "walker")->name(), "walker");
  std::filesystem::remove_all(dir.parent_path());
}

TEST(RuntimeModel, AControllerRefusesSkillsOfAnotherCharacterAndUnknownSwitches) {
  const auto walker = Skill::load(kWalker);
  const auto other = Skill::load(edited_model("twin", [](auto&) {}), "twin");
  Controller c({walker, other});
  EXPECT_EQ(c.skill(), "walker_ppo");
  EXPECT_TRUE(contains(error_of([&] { c.switch_to("run"); }), "no skill 'run' in this controller (it has walker_ppo, twin)"));
  EXPECT_TRUE(contains(error_of([&] { Controller twice({walker, walker}); }), "two skills are named 'walker_ppo'"));
  EXPECT_TRUE(contains(error_of([] { Controller none({}); }), "at least one skill"));
}

}  // namespace

namespace {

TEST(DenseKernel, ALayerIsPinnedByHandAndBothPathsAgreeOnEveryBlockShape) {
  // x = [[1, 2, 3], [-1, 0, 0.5]], W (input-major) = [[1, 0.5], [0, 0.5], [-1, 0.5]], b = [0.25, -1]:
  // row 1: 1 - 3 + 0.25 = -1.75, 0.5 + 1 + 1.5 - 1 = 2; row 2: -1 - 0.5 + 0.25 = -1.25, -0.5 + 0.25 - 1 = -1.25.
  const float x[] = {1, 2, 3, -1, 0, 0.5f}, w[] = {1, 0.5f, 0, 0.5f, -1, 0.5f}, b[] = {0.25f, -1};
  const float w_out_in[] = {1, 0, -1, 0.5f, 0.5f, 0.5f};
  float y[4], z[4], one[4];
  dense_forward(x, 2, 3, w, b, 2, y);
  dense_forward_portable(x, 2, 3, w, b, 2, z);
  dense_forward_one(x, 3, w_out_in, b, 2, one);
  dense_forward_one(x + 3, 3, w_out_in, b, 2, one + 2);
  const float expected[] = {-1.75f, 2.0f, -1.25f, -1.25f};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(y[i], expected[i]);
    EXPECT_EQ(z[i], expected[i]);
    EXPECT_EQ(one[i], expected[i]);
  }
  // Every remainder of the blocks (6 and 4 rows; 32, 16 and 8 outputs): batches 1-13, outputs 1-45.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  for (int n : {1, 3, 4, 5, 6, 9, 10, 11, 13})
    for (int in : {1, 7, 8, 9, 16, 19, 35})
      for (int out : {1, 7, 8, 9, 16, 23, 32, 45}) {
        std::vector<float> X(static_cast<std::size_t>(n * in)), W(static_cast<std::size_t>(out * in)), B(static_cast<std::size_t>(out));
        for (auto* v : {&X, &W, &B})
          for (float& f : *v) f = u(rng);
        std::vector<float> fast(static_cast<std::size_t>(n * out)), slow(fast.size()), single(fast.size()), single_slow(fast.size());
        dense_forward(X.data(), n, in, W.data(), B.data(), out, fast.data());
        dense_forward_portable(X.data(), n, in, W.data(), B.data(), out, slow.data());
        // The batch-1 kernels, row by row, on the output-major copy of W.
        std::vector<float> Wt(W.size());
        for (int k = 0; k < in; ++k)
          for (int j = 0; j < out; ++j) Wt[static_cast<std::size_t>(j * in + k)] = W[static_cast<std::size_t>(k * out + j)];
        for (int i = 0; i < n; ++i) {
          dense_forward_one(X.data() + i * in, in, Wt.data(), B.data(), out, single.data() + i * out);
          dense_forward_one_portable(X.data() + i * in, in, Wt.data(), B.data(), out, single_slow.data() + i * out);
        }
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < out; ++j) {
            double exact = static_cast<double>(B[static_cast<std::size_t>(j)]);
            for (int k = 0; k < in; ++k) exact += static_cast<double>(X[static_cast<std::size_t>(i * in + k)]) * static_cast<double>(W[static_cast<std::size_t>(k * out + j)]);
            const auto at = static_cast<std::size_t>(i * out + j);
            EXPECT_NEAR(static_cast<double>(fast[at]), exact, 1e-5) << n << " x " << in << " -> " << out << " at " << i << "," << j;
            EXPECT_NEAR(static_cast<double>(slow[at]), exact, 1e-5);
            EXPECT_NEAR(static_cast<double>(single[at]), exact, 1e-5);
            EXPECT_NEAR(static_cast<double>(single_slow[at]), exact, 1e-5);
          }
      }
}

}  // namespace

namespace {

// The committed walk and run as skills "walk" and "run" (the humanoid reads ../shared/data: a test
// checks for it first).
std::vector<std::shared_ptr<const Skill>> walk_and_run() {
  const std::filesystem::path models = std::filesystem::path(MIMIC_SOURCE_DIR) / "models";
  return {Skill::load(models / "humanoid_walk_iccgan", "walk"), Skill::load(models / "humanoid_run_iccgan_straight_loop", "run")};
}

TEST(RuntimeController, ASwitchHandsTheCharactersStateToTheOtherSkillWhichCarriesOn) {
  std::filesystem::path data;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", data);
  Controller c(walk_and_run(), 5);
  EXPECT_NEAR(c.control_dt(), 1.0 / 30.0, 1e-12);
  for (int i = 0; i < 45; ++i) ASSERT_FALSE(c.step().episode_over);
  const Eigen::Vector3d before = c.root_position();
  const long long steps = c.steps();
  c.switch_to("run");
  EXPECT_EQ(c.skill(), "run");
  // The run skill's world holds the walk's state; its own start rules apply (the run lifts a start
  // out of the floor by the depth a foot reaches into it, plus 1 mm: a few millimetres here).
  EXPECT_LT((c.root_position() - before).head<2>().norm(), 1e-9);
  EXPECT_LT(std::abs(c.root_position().z() - before.z()), 0.01);
  EXPECT_EQ(c.steps(), steps);
  // The run acts from there (a switch at any moment may fall: when to switch is seed 004's
  // score-based rule, the next step of the controller).
  int taken = 0;
  for (; taken < 60; ++taken)
    if (c.step().episode_over) break;
  EXPECT_GT(taken, 5);
  EXPECT_EQ(c.steps(), steps + taken + (taken < 60 ? 1 : 0));
  c.switch_to("walk");
  EXPECT_EQ(c.skill(), "walk");
}

TEST(RuntimeController, EnvironmentSettingsApplyAndProjectilesAreNotTakenForAnotherCharacter) {
  std::filesystem::path data;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", data);
  const std::filesystem::path walk = std::filesystem::path(MIMIC_SOURCE_DIR) / "models" / "humanoid_walk_iccgan";
  // Projectiles add free bodies to the world (before the character's in MuJoCo's body order).
  const auto skill = Skill::load(walk, "", {"env.projectiles={enabled: true, mass: 2}", "env.max_seconds=1"});
  Controller c({skill});
  StepInfo info;
  for (int i = 0; i < 40 && !info.episode_over; ++i) info = c.step();
  EXPECT_TRUE(info.episode_over) << "env.max_seconds=1 ends the episode within 40 steps";
  EXPECT_TRUE(contains(error_of([&] { (void)Skill::load(walk, "", {"ppo.clip=0.1"}); }), "env keys only"));
  EXPECT_TRUE(contains(error_of([&] { (void)Skill::load(walk, "", {"env.no_such_key=1"}); }), "no_such_key"));
}

// A skill starts from its own clips, but start clips given as settings are where its episodes
// start (how `mimic eval --set env.start_clips=...` measures starts from other motion): here the
// face-up get-up's, whose frames lie low (root 0.12-0.84 m), against the walk's upright 0.85 m.
TEST(RuntimeController, StartClipsGivenAsSettingsAreWhereTheEpisodesStart) {
  std::filesystem::path getup;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_getup_faceup.txt", getup);
  const std::filesystem::path walk = std::filesystem::path(MIMIC_SOURCE_DIR) / "models" / "humanoid_walk_iccgan";
  const auto lowest_start = [](const std::shared_ptr<const Skill>& skill) {
    Controller c({skill});
    double lowest = 1e9;
    for (int i = 0; i < 12; ++i) {
      c.reset();
      lowest = std::min(lowest, c.physics_data()->qpos[2]);
    }
    return lowest;
  };
  EXPECT_GT(lowest_start(Skill::load(walk)), 0.8);
  EXPECT_LT(lowest_start(Skill::load(walk, "", {"env.start_clips=[" + getup.string() + "]", "env.start_clip_share=1"})), 0.6);
  EXPECT_TRUE(contains(error_of([&] { (void)Skill::load(walk, "", {"env.start_clips=[/nonexistent/start.mclip]"}); }), "/nonexistent/start.mclip"));
}

// Seed 004 section 5.3's switch: a request is granted after the first step whose state the
// target's discriminators score >= tau, waits while they score below, waits out the delay after a
// take-over, and is dropped (and said so) when no step allows it within the time limit.
TEST(RuntimeController, ARequestedSkillTakesOverWhenItsDiscriminatorsScoreTheStateAboveTau) {
  std::filesystem::path data;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", data);
  const std::vector<std::shared_ptr<const Skill>> skills = walk_and_run();
  const auto& walk = skills[0];
  const auto& run = skills[1];
  // Two controllers on the same seed walk the same trajectory: the run's score of each step's
  // state is known beforehand.
  std::vector<double> run_scores;
  {
    Controller probe({walk, run}, 3);
    for (int i = 0; i < 30; ++i) {
      ASSERT_FALSE(probe.step().episode_over);
      run_scores.push_back(probe.score("run"));
    }
    EXPECT_EQ(probe.skill(), "walk");  // scoring a skill hands nothing over
    const double walk_score = probe.score("walk");
    EXPECT_GT(walk_score, 0.0) << "the walk's discriminator finds its own walking expert-like";
    EXPECT_GE(walk_score, -1.0);
    EXPECT_LE(walk_score, 1.0);
    EXPECT_THROW((void)probe.score("jump"), Error);
  }
  // The hand-made pair: tau just above the run's score at step 10 makes that step wait; just
  // below the first later step's that reaches it makes that one switch.
  const auto first_at_least = [&](double tau, std::size_t from) {
    for (std::size_t i = from; i < run_scores.size(); ++i)
      if (run_scores[i] >= tau) return static_cast<int>(i);
    return -1;
  };
  const double tau = run_scores[10] + 1e-6;
  const int expected = first_at_least(tau, 10);
  ASSERT_GT(expected, 10) << "the walk's states must come to score higher under the run's discriminators than at step 10";
  Controller c({walk, run}, 3);
  SwitchRule rule;
  rule.threshold = tau;
  rule.time_limit_seconds = 100.0;
  c.set_switch_rule(rule);
  for (int i = 0; i < 10; ++i) c.step();
  c.request("run");
  EXPECT_EQ(c.requested(), "run");
  int switched = -1;
  for (int i = 10; i < 30 && switched < 0; ++i) {
    const StepInfo info = c.step();
    EXPECT_NEAR(info.target_score, run_scores[static_cast<std::size_t>(i)], 1e-12);
    if (!info.switched_to.empty()) {
      EXPECT_EQ(info.switched_to, "run");
      switched = i;
    } else {
      EXPECT_LT(info.target_score, tau);
      EXPECT_EQ(c.skill(), "walk");
    }
  }
  EXPECT_EQ(switched, expected) << "the first step the run's discriminators score >= tau";
  EXPECT_EQ(c.skill(), "run");
  EXPECT_TRUE(c.requested().empty());
}

TEST(RuntimeController, TheDelayHoldsAndARequestNoStepAllowsIsDropped) {
  std::filesystem::path data;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", data);
  Controller c(walk_and_run(), 3);
  SwitchRule rule;
  rule.by = SwitchRule::By::Immediately;
  rule.delay_steps = 7;
  c.set_switch_rule(rule);
  c.request("run");
  StepInfo info = c.step();
  EXPECT_EQ(info.switched_to, "run");  // at once: after the first step
  // Back to the walk at once, but not before the run has had its 7 steps.
  c.request("walk");
  int waited = 0;
  for (info = c.step(); info.switched_to.empty(); info = c.step()) ++waited;
  EXPECT_EQ(waited, 6) << "granted after the 7th step since the take-over";
  EXPECT_EQ(c.skill(), "walk");
  // A score no state reaches: dropped after the time limit (15 steps at 30 Hz), and reported.
  rule.by = SwitchRule::By::Score;
  rule.threshold = 1.5;  // above the score's range
  rule.delay_steps = 0;
  rule.time_limit_seconds = 0.5;
  c.set_switch_rule(rule);
  c.request("run");
  int steps = 0;
  for (info = c.step(); info.dropped.empty(); info = c.step()) {
    ++steps;
    ASSERT_TRUE(info.switched_to.empty());
    ASSERT_LT(steps, 100);
  }
  EXPECT_EQ(steps + 1, 15);
  EXPECT_EQ(info.dropped, "run");
  EXPECT_EQ(c.skill(), "walk");
  EXPECT_TRUE(c.requested().empty());
  // Asking for the active skill cancels a request; bad rules and names are errors.
  c.request("run");
  c.request("walk");
  EXPECT_TRUE(c.requested().empty());
  rule.delay_steps = -1;
  EXPECT_THROW(c.set_switch_rule(rule), Error);
  EXPECT_TRUE(contains(error_of([&] { c.request("jump"); }), "no skill 'jump' in this controller (it has walk, run)"));
}

// The transition test's bookkeeping: every ordered pair, each rule; a tau no state reaches
// switches nothing; switching at once always switches, at the first step after the request.
TEST(RuntimeTransitions, EveryOrderedPairUnderEachRuleOnTheSameTrials) {
  std::filesystem::path data;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", data);
  const std::vector<std::shared_ptr<const Skill>> skills = walk_and_run();
  TransitionOptions o;
  o.trials = 2, o.thresholds = {1.01}, o.hold_seconds = 0.5, o.time_limit_seconds = 0.3, o.earliest_request = 0.2, o.latest_request = 0.5;
  std::vector<std::string> seen;
  const std::vector<TransitionCell> cells =
      measure_transitions(skills, o, [&](const TransitionCell& c) { seen.push_back(c.from + ">" + c.to + " " + c.rule); });
  EXPECT_EQ(seen, (std::vector<std::string>{"walk>run score", "walk>run value", "walk>run matching", "walk>run immediately", "run>walk score",
                                             "run>walk value", "run>walk matching", "run>walk immediately"}));
  for (const TransitionCell& c : cells) {
    EXPECT_EQ(c.trials, 2);
    if (c.rule == "score" || c.rule == "matching") {
      EXPECT_EQ(c.switched, 0) << c.from << " > " << c.to << ": tau 1.01 is above every " << c.rule << " figure";
      EXPECT_TRUE(std::isnan(c.mean_wait));
    } else if (c.rule == "value") {
      // 1.01 times the target's mean value over its own episode: a positive figure, whatever it grants.
      EXPECT_GT(c.value_threshold, 0.0);
      EXPECT_LE(c.succeeded + c.fell, c.switched);
    } else {
      EXPECT_EQ(c.switched, 2);
      EXPECT_NEAR(c.mean_wait, 1.0 / 30.0, 1e-9);
      EXPECT_LE(c.succeeded + c.fell, c.switched);
    }
  }
  EXPECT_THROW(measure_transitions({skills[0]}, o), Error);
  o.score_rule = o.value_baseline = o.matching_baseline = o.immediate_baseline = false;
  EXPECT_THROW(measure_transitions(skills, o), Error);
}

// The hand-over is faithful: the same walk handed its own state (pose, velocities, last poses) by
// a switch to a second copy walks on as the first would have, without going down.
TEST(RuntimeController, ASkillHandedItsOwnStateCarriesOn) {
  std::filesystem::path data;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", data);
  const std::filesystem::path walk = std::filesystem::path(MIMIC_SOURCE_DIR) / "models" / "humanoid_walk_iccgan";
  Controller c({Skill::load(walk, "walk"), Skill::load(walk, "walk_again")}, 11);
  for (int i = 0; i < 40; ++i) ASSERT_FALSE(c.step().fell);
  const Eigen::Vector3d before = c.root_position();
  c.switch_to("walk_again");
  double lowest = before.z();
  for (int i = 0; i < 60; ++i) {
    ASSERT_FALSE(c.step().fell) << "step " << i << " after the hand-over";
    lowest = std::min(lowest, c.root_position().z());
  }
  EXPECT_GT(lowest, 0.75);
  EXPECT_GT((c.root_position() - before).head<2>().norm(), 1.5) << "it walked on: 2 s at the walk's pace";
}

}  // namespace
