// The video pipeline's steps that need no video: keypoint files (mimic's, OpenPose's, COCO's),
// the camera, keypoints synthesised from a clip, the pose parameterisation, the reconstruction and
// the errors it is measured with (docs/video.md).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/file_io.hpp"
#include "error_message.hpp"
#include "motion/builtin.hpp"
#include "motion/kinematics.hpp"
#include "test_data.hpp"
#include "video/camera.hpp"
#include "video/ground_plane.hpp"
#include "video/pose_error.hpp"
#include "video/pose_parameters.hpp"
#include "video/reconstruct.hpp"
#include "video/synthesize.hpp"

using namespace mimic;
using test::error_of;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A cycle and a half of the built-in jumping jack as one clip (40 frames at 30 Hz).
Clip jacks() {
  const Clip one = builtin_jumping_jack();
  Clip c = one;
  c.loop = LoopMode::None;
  c.frames.clear();
  for (int i = 0; i < 40; ++i) c.frames.push_back(one.sample(i / 30.0));
  return c;
}

SynthesisOptions clean() {
  SynthesisOptions o;
  o.pixel_noise = 0, o.world_noise = 0, o.dropout = 0, o.min_confidence = 1;
  return o;
}

TEST(VideoCamera, FocalLengthAndProjectionAreTheHandComputedOnes) {
  EXPECT_NEAR(focal_from_fov(90, 720), 360.0, 1e-9);  // half the height over tan(45 degrees)
  // At the origin, looking along +X: a point 4 m ahead, 1 m to the left (+Y) and 0.5 m up lands
  // left of and above the image centre by f/4 and f/8 pixels.
  const PinholeCamera c = PinholeCamera::looking_at(Vec3::Zero(), Vec3(1, 0, 0), 90, 1280, 720);
  const Vec2 px = c.project(Vec3(4, 1, 0.5));
  EXPECT_NEAR(px.x(), 640 - 90, 1e-9);
  EXPECT_NEAR(px.y(), 360 - 45, 1e-9);
  EXPECT_NEAR(c.to_camera(Vec3(4, 1, 0.5)).z(), 4.0, 1e-12);
}

TEST(VideoKeypoints, MimicsFileRoundTripsAndBadFilesAreNamed) {
  const SynthesisResult s = synthesize_keypoints(builtin_jumping_jack(), SynthesisOptions{});
  const KeypointTrack back = parse_keypoints(write_keypoints(s.track), "k.json");
  ASSERT_EQ(back.num_frames(), s.track.num_frames());
  EXPECT_EQ(back.names, s.track.names);
  EXPECT_EQ(back.width, 1280);
  EXPECT_NEAR(back.frames[5].pixel[3].x(), s.track.frames[5].pixel[3].x(), 1e-3);
  EXPECT_NEAR(back.frames[5].world[3].y(), s.track.frames[5].world[3].y(), 1e-6);
  for (std::size_t k = 0; k < back.names.size(); ++k) EXPECT_NEAR(back.frames[7].confidence[k], s.track.frames[7].confidence[k], 1e-6);
  KeypointTrack odd = s.track;  // a name with a line break, a tab, a quote and a backslash
  odd.names[0] = "a\nb\t\"c\\";
  EXPECT_EQ(parse_keypoints(write_keypoints(odd), "k.json").names[0], odd.names[0]);
  const std::string head = "{\"format\": \"mimic-keypoints\", \"version\": 1, \"fps\": 30, \"width\": 640, \"height\": 480, \"names\": [\"a\", \"b\"], ";
  EXPECT_TRUE(contains(error_of([&] { (void)parse_keypoints(head + "\"frames\": [{\"pixel\": [[1, 2]], \"confidence\": [1]}]}", "k.json"); }),
                       "k.json: frame 0 has 1 keypoints and 1 confidences where the file names 2"));
  EXPECT_TRUE(contains(error_of([&] { (void)parse_keypoints(head + "\"frames\": [{\"pixel\": [[1, 2], [3, 4]], \"confidence\": [1, 1.5]}]}", "k.json"); }),
                       "frame 0, 'b': confidence 1.5 outside [0, 1]"));
  EXPECT_TRUE(contains(error_of([&] { (void)parse_keypoints("{\"frames\": []}", "k.json"); }), "k.json: not a keypoint file"));
  EXPECT_TRUE(contains(error_of([&] { (void)parse_keypoints("{\"format\": \"mimic-keypoints\", \"version\": 2}", "k.json"); }), "version 2"));
  EXPECT_TRUE(contains(error_of([&] { (void)parse_keypoints(head + "\"frames\": [{\"pixel\": [[1, 2], [3]], \"confidence\": [1, 1]}]}", "k.json"); }),
                       "k.json:1"));  // the line of the short pair
}

TEST(VideoKeypoints, OpenPoseFramesTakeTheSurestPersonAndNeedAnImageSize) {
  const auto dir = test::temp_dir("video_openpose");
  std::string faint, sure;
  for (int k = 0; k < 25; ++k) faint += (k ? ", " : "") + std::to_string(k) + ", 1, 0.1", sure += (k ? ", " : "") + std::to_string(k) + ", 2, 0.9";
  write_file_atomic(dir / "clip_000000000000_keypoints.json",
                    "{\"version\": 1.3, \"people\": [{\"pose_keypoints_2d\": [" + faint + "]}, {\"pose_keypoints_2d\": [" + sure + "]}]}");
  write_file_atomic(dir / "clip_000000000001_keypoints.json", "{\"version\": 1.3, \"people\": []}");
  EXPECT_TRUE(contains(error_of([&] { (void)load_keypoints(dir); }), "the image size is unknown"));
  const KeypointTrack t = load_keypoints(dir, KeypointReadOptions{640, 480, 25.0});
  ASSERT_EQ(t.num_frames(), 2);
  EXPECT_EQ(t.names.size(), 25u);
  EXPECT_EQ(t.names[8], "MidHip");
  EXPECT_EQ(t.frames[0].pixel[3], Vec2(3, 2));  // the second person, surer
  EXPECT_DOUBLE_EQ(t.frames[0].confidence[3], 0.9);
  EXPECT_EQ(t.frames[1].confidence, std::vector<double>(25, 0.0));  // nobody: nothing seen
  EXPECT_DOUBLE_EQ(t.fps, 25.0);
  write_file_atomic(dir / "clip_000000000002_keypoints.json", "{\"people\": [{\"pose_keypoints_2d\": [1, 2, 0.5]}]}");
  EXPECT_TRUE(contains(error_of([&] { (void)load_keypoints(dir, KeypointReadOptions{640, 480, 25.0}); }), "expected 75 numbers"));
}

TEST(VideoKeypoints, CocoResultsAreFramesInTheOrderOfTheirImages) {
  const auto dir = test::temp_dir("video_coco");
  std::string kp;
  for (int k = 0; k < 17; ++k) kp += (k ? ", " : "") + std::to_string(10 * k) + ", 5, 2";
  write_file_atomic(dir / "coco.json", "{\"images\": [{\"id\": 9, \"width\": 800, \"height\": 600}, {\"id\": 4}], "
                                       "\"annotations\": [{\"image_id\": 9, \"keypoints\": [" + kp + "]}]}");
  const KeypointTrack t = load_keypoints(dir / "coco.json");
  ASSERT_EQ(t.num_frames(), 2);
  EXPECT_EQ(t.height, 600);
  EXPECT_EQ(t.names[15], "left_ankle");
  EXPECT_EQ(t.frames[0].confidence, std::vector<double>(17, 0.0));  // image 4 comes first and has nobody
  EXPECT_EQ(t.frames[1].pixel[2], Vec2(20, 5));
  EXPECT_DOUBLE_EQ(t.frames[1].confidence[2], 1.0);  // COCO's visibility 2: seen
  write_file_atomic(dir / "bad.json", "{\"images\": [{\"id\": 1, \"width\": 8, \"height\": 6}], \"annotations\": [{\"image_id\": 2, \"keypoints\": [" + kp + "]}]}");
  EXPECT_TRUE(contains(error_of([&] { (void)load_keypoints(dir / "bad.json"); }), "image 2 is not among \"images\""));
  write_file_atomic(dir / "other.json", "{\"hello\": 1}");
  EXPECT_TRUE(contains(error_of([&] { (void)load_keypoints(dir / "other.json"); }), "not a keypoint file mimic reads"));
}

TEST(VideoPoseParameters, APoseRoundTripsThroughTheParameterVector) {
  const Clip c = builtin_jumping_jack();
  const Pose& pose = c.frames[9];
  const std::vector<double> p = pose_to_parameters(c.skeleton, pose);
  ASSERT_EQ(static_cast<int>(p.size()), c.skeleton.dof_count());
  const LinkFrames a = forward_kinematics(c.skeleton, pose), b = forward_kinematics(c.skeleton, parameters_to_pose(c.skeleton, p.data()));
  std::vector<Vec3> templated;
  std::vector<Quat> s1, s2;
  pose_positions(c.skeleton, parameter_offsets(c.skeleton), p.data(), templated, s1, s2);
  for (std::size_t j = 0; j < a.joint_pos.size(); ++j) {
    EXPECT_LT((a.joint_pos[j] - b.joint_pos[j]).norm(), 1e-9) << c.skeleton.joints[j].name;
    EXPECT_LT((a.joint_pos[j] - templated[j]).norm(), 1e-9) << c.skeleton.joints[j].name;
  }
}

TEST(VideoSynthesis, CleanKeypointsAreTheCamerasViewOfTheClip) {
  const Clip c = builtin_jumping_jack();
  const SynthesisResult s = synthesize_keypoints(c, clean());
  ASSERT_EQ(s.track.num_frames(), static_cast<int>(std::lround(c.duration() * 30)) + 1);  // at 30 fps, both ends
  const LinkFrames f = forward_kinematics(c.skeleton, c.sample(10 / 30.0));
  for (std::size_t k = 0; k < f.joint_pos.size(); ++k) {
    EXPECT_LT((s.track.frames[10].pixel[k] - s.camera.project(f.joint_pos[k])).norm(), 1e-9);
    EXPECT_LT((s.track.frames[10].world[k] - s.camera.world_from_camera.conjugate() * (f.joint_pos[k] - f.joint_pos[0])).norm(), 1e-9);
  }
  // 6 m away at 60 degrees from the clip's heading, 1.2 m up.
  EXPECT_NEAR(s.camera.position.z(), 1.2, 1e-12);
  SynthesisOptions near = clean();
  near.distance = 0.2;
  EXPECT_TRUE(contains(error_of([&] { (void)synthesize_keypoints(c, near); }), "within 1 m of the camera"));
}

TEST(VideoGround, APlaneUnderSpreadFeetALineOrNothing) {
  // Camera axes: x right, y down, z ahead. A floor 1.5 m below the camera, tilted so that the
  // camera looks 10 degrees down at it: its up is (0, -cos 10, -sin 10).
  const double a = deg_to_rad(10);
  const Vec3 up(0, -std::cos(a), -std::sin(a));
  const Vec3 along = Vec3(0, -std::sin(a), std::cos(a)), side(1, 0, 0);  // on the floor
  auto frame = [&](double u, double v) {  // a body's points, the lowest on the floor at (u, v)
    const Vec3 foot = -1.5 * Vec3(0, -1, 0) + 4 * Vec3::UnitZ() + u * side + v * along;
    return std::vector<Vec3>{foot, foot + 0.9 * up, foot + 1.6 * up};
  };
  std::vector<std::vector<Vec3>> spread, line, still;
  for (int i = 0; i < 20; ++i) {
    spread.push_back(frame(0.6 * std::cos(i), 0.6 * std::sin(1.7 * i)));
    line.push_back(frame(0.02 * (i % 2), 0.1 * i));
    still.push_back(frame(0.01 * (i % 2), 0));
  }
  const GroundFit s = fit_ground(spread);
  EXPECT_TRUE(s.fitted);
  EXPECT_LT((s.up - up).norm(), 1e-9);
  EXPECT_NEAR(s.pitch_deg, -10, 1e-6);
  EXPECT_LT((s.world_from_camera * up - Vec3::UnitZ()).norm(), 1e-9);
  // Along one line (here the view's direction on the floor) the tilt along it is seen: the same up,
  // to within the line's direction found among feet 2 cm apart sideways.
  const GroundFit l = fit_ground(line);
  EXPECT_TRUE(l.fitted);
  EXPECT_LT((l.up - up).norm(), 1e-3);
  // Standing still shows nothing: a level camera.
  const GroundFit n = fit_ground(still);
  EXPECT_FALSE(n.fitted);
  EXPECT_EQ(n.up, Vec3(0, -1, 0));
  EXPECT_DOUBLE_EQ(n.pitch_deg, 0);
}

TEST(VideoPoseErrors, AreZeroForTheTruthAndTheHandComputedValueForAnOffset) {
  const Clip truth = jacks();
  Clip turned = truth;  // the same motion seen from another heading: MPJPE aligns the yaw
  for (Pose& p : turned.frames) p.rot[0] = heading_rotation(1.0) * p.rot[0], p.root_pos = heading_rotation(1.0) * p.root_pos;
  const PoseErrors same = pose_errors(turned, truth);
  EXPECT_LT(same.mpjpe, 1e-9);
  EXPECT_LT(same.pa_mpjpe, 1e-9);
  EXPECT_NEAR(same.jitter, jitter(truth), 1e-9);
  // A still pose has no jitter; a pose whose root moves with constant acceleration a has a everywhere.
  Clip accel = truth;
  for (std::size_t i = 0; i < accel.frames.size(); ++i) {
    accel.frames[i] = truth.frames[0];
    accel.frames[i].root_pos.x() += 0.5 * 2.0 * std::pow(static_cast<double>(i) / truth.fps, 2);  // a = 2 m/s^2
  }
  EXPECT_NEAR(jitter(accel), 2.0, 1e-6);
}

TEST(VideoReconstruction, CleanKeypointsFromALevelCameraGiveBackTheClip) {
  // A level camera (at the pelvis's mean height): the jumping jack's feet spread only sideways,
  // which cannot show a tilt along the view, and the reconstruction keeps the camera level then.
  const Clip truth = jacks();
  SynthesisOptions level = clean();
  level.height = 0;
  for (const Pose& p : truth.frames) level.height += p.root_pos.z() / truth.num_frames();
  const SynthesisResult s = synthesize_keypoints(truth, level);
  const Reconstruction r = reconstruct_motion(s.track, truth.skeleton, {});
  EXPECT_EQ(r.reconstructed.num_frames(), truth.num_frames());
  EXPECT_TRUE(r.report.unfit.empty());
  const PoseErrors e = pose_errors(r.reconstructed, truth);
  EXPECT_LT(e.mpjpe, 0.01);
  EXPECT_LT(e.pa_mpjpe, 0.01);
}

TEST(VideoReconstruction, BeatsTheRawEstimateOnNoisyKeypoints) {
  const Clip truth = jacks();
  const SynthesisResult s = synthesize_keypoints(truth, SynthesisOptions{});  // the documented noise levels
  const Reconstruction r = reconstruct_motion(s.track, truth.skeleton, {});
  const PoseErrors raw = pose_errors(r.raw, truth), rec = pose_errors(r.reconstructed, truth);
  EXPECT_LT(rec.mpjpe, raw.mpjpe);
  EXPECT_LT(rec.pa_mpjpe, raw.pa_mpjpe);
  EXPECT_LT(rec.jitter, raw.jitter);
  EXPECT_LT(r.report.reconstructed.lsm, r.report.raw.lsm);
}

TEST(VideoReconstruction, UnfitFramesAreBridgedOrCutAndReported) {
  const Clip truth = jacks();
  SynthesisResult s = synthesize_keypoints(truth, clean());
  for (int t : {0, 1, 20, 21, 22}) s.track.frames[static_cast<std::size_t>(t)] = KeypointFrame{};  // nobody seen
  const Reconstruction r = reconstruct_motion(s.track, truth.skeleton, {});
  EXPECT_EQ(r.report.unfit, (std::vector<int>{0, 1, 20, 21, 22}));
  EXPECT_EQ(r.report.cut, (std::vector<int>{0, 1}));
  EXPECT_EQ(r.report.bridged, (std::vector<int>{20, 21, 22}));
  EXPECT_EQ(r.report.first_frame, 2);
  EXPECT_EQ(r.reconstructed.num_frames(), truth.num_frames() - 2);
  // A gap longer than max_bridge (5): the side with more frames is kept, frames 2-16 are cut.
  for (int t = 17; t < 23; ++t) s.track.frames[static_cast<std::size_t>(t)] = KeypointFrame{};
  const Reconstruction cut = reconstruct_motion(s.track, truth.skeleton, {});
  EXPECT_EQ(cut.report.first_frame, 23);
  EXPECT_EQ(cut.reconstructed.num_frames(), 17);
  EXPECT_EQ(cut.report.cut.size(), 2u + 15u + 6u);
}

TEST(VideoReconstruction, BadInputIsRefusedByName) {
  const Clip truth = jacks();
  SynthesisResult s = synthesize_keypoints(truth, clean());
  s.track.source = "k.json";
  KeypointTrack short_track = s.track;
  short_track.frames.resize(6);
  EXPECT_TRUE(contains(error_of([&] { (void)reconstruct_motion(short_track, truth.skeleton, {}); }), "k.json: the longest stretch of frames that can be fitted has 6 frames"));
  KeypointTrack flat = s.track;
  for (KeypointFrame& f : flat.frames) f.world.clear();
  EXPECT_TRUE(contains(error_of([&] { (void)reconstruct_motion(flat, truth.skeleton, {}); }), "no frame has 3D keypoints"));
  KeypointTrack strangers = s.track;
  for (std::string& n : strangers.names) n = "x_" + n;
  EXPECT_TRUE(contains(error_of([&] { (void)reconstruct_motion(strangers, truth.skeleton, {}); }), "only 0 of its keypoints name joints"));
  EXPECT_TRUE(contains(error_of([&] { (void)reconstruct_motion(s.track, truth.skeleton, KeypointMap{{{"nose", "head"}}, "m.yaml"}); }),
                       "m.yaml: keypoint 'nose' is not among k.json's keypoints"));
}

}  // namespace
