// Rendering: offscreen frames and videos of the expected length.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <random>
#include <fstream>
#include <set>
#include <string>

#include "core/error.hpp"
#include "env/reacher_arm.hpp"
#include "motion/builtin.hpp"
#include "render/clip_video.hpp"
#include "render/line_chart.hpp"
#include "render/offscreen.hpp"
#include "sim/world.hpp"
#include "test_data.hpp"

using namespace mimic;

namespace {

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string run(const std::string& cmd) {
  std::string out;
  if (std::FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[256];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    ::pclose(p);
  }
  return out;
}

// Skips the test when this machine has no headless GL (the message says what is missing).
#define MIMIC_RENDER_OR_SKIP(statement)                                         \
  try {                                                                         \
    statement;                                                                  \
  } catch (const Error& e) {                                                    \
    if (std::string(e.what()).find("no headless GL context") == std::string::npos) throw; \
    GTEST_SKIP() << e.what() << " (scripts/setup.sh installs Mesa's EGL)";      \
  }

}  // namespace

TEST(Render, OffscreenFrameShowsTheCharacter) {
  const Clip jack = builtin_jumping_jack();
  const CharacterModel ch = CharacterModel::from_skeleton(jack.skeleton, "builtin");
  World w(ch);
  w.set_state(jack.frames[0]);
  std::vector<std::uint8_t> rgb, empty_rgb;
  MIMIC_RENDER_OR_SKIP({
    OffscreenRenderer r(w.model(), 160, 120);
    r.render(w.data(), CameraSpec{}, rgb);
    // Same camera, character moved far away: the picture must change where the body was.
    Pose away = jack.frames[0];
    away.root_pos.x() += 50;
    w.set_state(away);
    r.render(w.data(), CameraSpec{}, empty_rgb);
  });
  ASSERT_EQ(rgb.size(), 160u * 120u * 3u);
  long differing = 0;
  for (std::size_t i = 0; i < rgb.size(); ++i) differing += rgb[i] != empty_rgb[i];
  EXPECT_GT(differing, 300);  // the body covers a visible patch of pixels
}

TEST(Render, AModelsOwnCameraFramesIt) {
  // The reacher's arm lies on a 0.8 m table that its model views from 0.8 m above. From the
  // humanoid's free camera (3.5 m away) the table is a speck; from its own camera it fills the picture.
  ReacherArmEnv env(ReacherConfig::two_link());
  std::mt19937_64 rng(1);
  env.reset(rng);
  std::vector<std::uint8_t> free_rgb, own_rgb, unused;
  CameraSpec own;
  own.model_camera = env.view_camera();
  EXPECT_EQ(own.model_camera, 0) << "the reacher is filmed by its camera from above";
  CameraSpec missing;
  missing.model_camera = 1;
  MIMIC_RENDER_OR_SKIP({
    OffscreenRenderer r(env.physics_model(), 160, 120);
    r.render(env.physics_data(), CameraSpec{}, free_rgb);
    r.render(env.physics_data(), own, own_rgb);
    EXPECT_THROW(r.render(env.physics_data(), missing, unused), Error) << "the reacher has one camera";
  });
  // The share of the picture that is the pale grey table (or the arm on it).
  auto table_share = [](const std::vector<std::uint8_t>& rgb) {
    long lit = 0;
    for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) lit += rgb[i] > 120 && rgb[i + 1] > 120 && rgb[i + 2] > 120;
    return static_cast<double>(lit) / static_cast<double>(rgb.size() / 3);
  };
  EXPECT_LT(table_share(free_rgb), 0.1);
  EXPECT_GT(table_share(own_rgb), 0.6);
}

TEST(Render, TwoSecondClipMakesAValidMp4OfSixtyFrames) {
  const Clip jack = builtin_jumping_jack();
  const CharacterModel ch = CharacterModel::from_skeleton(jack.skeleton, "builtin");
  const auto out = test::temp_dir("render") / "jack.mp4";
  ClipVideoOptions opts;
  opts.width = 160, opts.height = 120, opts.seconds = 2.0, opts.ghost = true;
  int frames = 0;
  MIMIC_RENDER_OR_SKIP(frames = render_clip_video(ch, jack, out, opts));
  EXPECT_EQ(frames, 60);
  ASSERT_TRUE(std::filesystem::exists(out));
  const std::string probe = run("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=codec_name,width,height,nb_read_frames -of csv=p=0 '" + out.string() + "'");
  EXPECT_EQ(probe, "h264,160,120,60\n");
  // Written to jack.mp4.partial<pid>.mp4 beside it and renamed: nothing but the video is left.
  for (const auto& f : std::filesystem::directory_iterator(out.parent_path())) EXPECT_EQ(f.path().filename(), "jack.mp4");
}

TEST(Render, ClipThatDoesNotFitTheCharacterIsAnError) {
  const Clip jack = builtin_jumping_jack();
  Skeleton small = jack.skeleton;
  small.joints.resize(3);
  EXPECT_THROW(render_clip_video(CharacterModel::from_skeleton(small, "small"), jack, test::temp_dir("render_bad") / "x.mp4"), Error);
}

// A clip moving 3 m along x and 1 m along y: the fixed camera looks at the middle of its root's
// path, raised to 55% of the height, from where the path's diagonal and 0.5 m beyond each end fit
// the picture's width.
TEST(Render, TheFixedCameraFramesTheRootsWholePath) {
  Clip clip = builtin_jumping_jack();
  clip.loop = LoopMode::None;
  const Vec3 start = clip.frames.front().root_pos;
  const double n = static_cast<double>(clip.frames.size() - 1);
  for (std::size_t f = 0; f < clip.frames.size(); ++f) {
    const double u = static_cast<double>(f) / n;
    clip.frames[f].root_pos = Vec3(start.x() + 3.0 * u, start.y() + 1.0 * u, start.z());
  }
  CameraSpec base{Vec3(0, 0, 0.1), 0.0, 90.0, -12.0};
  const CameraSpec cam = fixed_clip_camera(clip, clip.duration(), 30.0, 1.6, 4.0 / 3.0, base);
  EXPECT_LT((cam.lookat - Vec3(start.x() + 1.5, start.y() + 0.5, 0.55 * 1.6 + 0.1)).norm(), 1e-9) << cam.lookat.transpose();
  const double half_width = std::atan(std::tan(22.5 * kPi / 180) * 4.0 / 3.0);  // 28.96 degrees
  EXPECT_NEAR(cam.distance, (std::sqrt(10.0) / 2 + 0.5) / std::tan(half_width), 1e-9);  // 3.77 m
  EXPECT_EQ(cam.azimuth, 90.0);
  // A clip that stays in place: the following camera's 2.2 heights.
  Clip still = clip;
  for (Pose& p : still.frames) p.root_pos = start;
  EXPECT_NEAR(fixed_clip_camera(still, still.duration(), 30.0, 1.6, 4.0 / 3.0, base).distance, 2.2 * 1.6, 1e-9);
}

// The camera follows the root smoothed (0.9 of where it looked, 0.1 of the root), but takes the
// root as it is at the first frame and after a restart (a new episode back at the start).
TEST(Render, CameraFollowSmoothsTheRootAndJumpsToItAfterARestart) {
  CameraFollow follow;
  EXPECT_EQ(follow.update(Vec3(5, 0, 1)), Vec3(5, 0, 1));
  const Vec3 second = follow.update(Vec3(6, 1, 1));
  EXPECT_LT((second - Vec3(5.1, 0.1, 1)).norm(), 1e-12) << second.transpose();
  follow.restart();
  EXPECT_EQ(follow.update(Vec3(0, 0, 1)), Vec3(0, 0, 1));
  EXPECT_LT((follow.update(Vec3(1, 0, 1)) - Vec3(0.1, 0, 1)).norm(), 1e-12);
}

TEST(LineChart, TicksAreRoundNumbersCoveringTheRange) {
  EXPECT_EQ(mimic::chart_ticks(0, 1000, 5), (std::vector<double>{0, 200, 400, 600, 800, 1000}));
  EXPECT_EQ(mimic::chart_ticks(2.6, 4685, 5), (std::vector<double>{1000, 2000, 3000, 4000}));
  // 0.55 / 5 = 0.11 per tick, rounded up to a step of 0.2.
  EXPECT_EQ(mimic::chart_ticks(-0.3, 0.25, 5), (std::vector<double>{-0.2, 0, 0.2}));
}

TEST(LineChart, DrawsEverySeriesWithGapsAtMissingValues) {
  mimic::LineChart c;
  c.title = "return <vs> samples";
  c.series = {{"a", {0, 1, 2, 3}, {1, 2, NAN, 4}}, {"b", {0, 1}, {0, 3}}};
  const std::string svg = mimic::line_chart_svg(c);
  EXPECT_EQ(occurrences(svg, "<polyline"), 3u);  // series a is split by its NaN
  EXPECT_NE(svg.find("return &lt;vs&gt; samples"), std::string::npos);
  EXPECT_NE(svg.find(">b</text>"), std::string::npos);
  c.series = {{"empty", {0}, {NAN}}};
  EXPECT_THROW(mimic::line_chart_svg(c), mimic::Error);
}

TEST(LineChart, TwelveSeriesAreDrawnInTwelveDifferentStyles) {
  mimic::LineChart c;
  for (int k = 0; k < 12; ++k) c.series.push_back({"s" + std::to_string(k), {0, 1}, {0, double(k)}});
  const std::string svg = mimic::line_chart_svg(c);
  std::set<std::string> styles;  // a polyline's attributes before its points
  for (std::size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1))
    styles.insert(svg.substr(at, svg.find("points=", at) - at));
  EXPECT_EQ(styles.size(), 12u);
  // Series 10 and 11 reuse the first two colours, dashed, and so do their legend lines.
  for (const char* colour : {"#1f77b4", "#d62728"}) {
    EXPECT_EQ(occurrences(svg, fmt::format("stroke='{}' stroke-width='1.6' stroke-dasharray", colour)), 1u) << colour;
    EXPECT_EQ(occurrences(svg, fmt::format("stroke='{}' stroke-width='3' stroke-dasharray", colour)), 1u) << colour;
  }
}

TEST(LineChart, ShadesABandUnderTheLinesAndFitsTheAxesToIt) {
  mimic::LineChart c;
  c.series = {{"a", {0, 1}, {1, 2}, {0, 1}, {2, 4}}};
  const std::string svg = mimic::line_chart_svg(c);
  // Plot box: x 70..550, y 40..370 for values 0..4 (the band's range, not only the line's 1..2):
  // the high edge left to right, then the low edge back.
  EXPECT_NE(svg.find("points='70.0,205.0 550.0,40.0 550.0,287.5 70.0,370.0 '"), std::string::npos) << svg;
  EXPECT_LT(svg.find("<polygon"), svg.find("<polyline"));  // no band hides a line
  // A point without a band splits it, as a missing value splits a line.
  c.series = {{"a", {0, 1, 2, 3}, {1, 2, 2, 1}, {0, NAN, 0, 0}, {2, 3, 3, 2}}};
  EXPECT_EQ(occurrences(mimic::line_chart_svg(c), "<polygon"), 2u);
  c.series = {{"a", {0, 1}, {1, 2}, {0}, {2}}};
  EXPECT_THROW(mimic::line_chart_svg(c), mimic::Error);
}

TEST(LineChart, LongLegendNamesWidenThePictureNotCutOff) {
  mimic::LineChart c;
  c.series = {{"a", {0, 1}, {0, 1}}};
  EXPECT_NE(mimic::line_chart_svg(c).find("width='720'"), std::string::npos);
  c.series[0].name = std::string(40, 'x');  // 30 + 7 * 40 = 310 px of legend instead of 150
  EXPECT_NE(mimic::line_chart_svg(c).find("width='880'"), std::string::npos);
}

TEST(LineChart, AMoreThanPlotHighLegendMakesThePictureTaller) {
  auto chart = [](int n) {
    mimic::LineChart c;
    for (int k = 0; k < n; ++k) c.series.push_back({"s" + std::to_string(k), {0, 1}, {0, 1}});
    return mimic::line_chart_svg(c);
  };
  EXPECT_NE(chart(17).find("height='420'"), std::string::npos);  // 40 + 20 + 18 * 17 + 50 = 416: the set height
  EXPECT_NE(chart(18).find("height='434'"), std::string::npos);  // 40 + 20 + 18 * 18 + 50
  // 30 names: 650 px; the last name at y = 40 + 10 + 18 * 29 + 4 = 576, the x label at the foot.
  const std::string svg = chart(30);
  EXPECT_NE(svg.find("height='650'"), std::string::npos);
  EXPECT_NE(svg.find("y='576.0'>s29</text>"), std::string::npos);
  EXPECT_NE(svg.find("y='640.0' text-anchor='middle'>"), std::string::npos);
}

TEST(LineChart, WritesPngOfTheChartsSizeAndLeavesNoPartialFiles) {
  mimic::LineChart c;
  c.series = {{"a", {0, 1, 2}, {0, 1, 4}}};
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("mimic_chart_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  mimic::write_line_chart(dir / "curve.png", c);
  std::ifstream in(dir / "curve.png", std::ios::binary);
  std::string head(24, '\0');
  in.read(head.data(), 24);
  ASSERT_EQ(head.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR's big-endian width and height (bytes 16-23): the SVG's 720 x 420.
  const auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned char>(head[at]) << 24) | (static_cast<unsigned char>(head[at + 1]) << 16) |
           (static_cast<unsigned char>(head[at + 2]) << 8) | static_cast<unsigned char>(head[at + 3]);
  };
  EXPECT_EQ(be32(16), 720);
  EXPECT_EQ(be32(20), 420);
  mimic::write_line_chart(dir / "curve.svg", c);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 2);
  EXPECT_THROW(mimic::write_line_chart(dir / "curve.jpg", c), mimic::Error);
  std::filesystem::remove_all(dir);
}
