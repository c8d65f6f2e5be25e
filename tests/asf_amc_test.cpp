// Acclaim ASF/AMC import: structure, hand-computed poses, unit/axis conversion, and malformed input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "malformed_cases.hpp"
#include "motion/asf_amc.hpp"
#include "motion/kinematics.hpp"
#include "test_data.hpp"

using namespace mimic;
using test::expect_parse_errors;
using test::MalformedCase;

namespace {

// A CMU-like skeleton: root, two legs (hip -> femur -> tibia -> foot). Source axes: Y up, Z
// forward, X left. The femurs and tibias have their Acclaim axis turned 20 degrees about z, the
// feet -90 about x then 20 about z. Line numbers matter to the malformed-input table below.
const std::string kAsf = R"(# test skeleton: root and two legs
:version 1.10
:name test
:units
  mass 1.0
  length 0.45
  angle deg
:documentation
  A root and two legs, CMU style.
:root
   order TX TY TZ RX RY RZ
   axis XYZ
   position 0 0 0
   orientation 0 0 0
:bonedata
  begin
     id 1
     name lhip
     direction 1 0 0
     length 2
     axis 0 0 0 XYZ
  end
  begin
     id 2
     name lfemur
     direction 0 -1 0
     length 9
     axis 0 0 20 XYZ
     dof rx ry rz
     limits (-160.0 , 20.0)
            (-70.0 , 70.0)
            (-60.0 , 70.0)
  end
  begin
     id 3
     name ltibia
     direction 0 -1 0
     length 9
     axis 0 0 20 XYZ
     dof rx
     limits (-10.0 , 170.0)
  end
  begin
     id 4
     name lfoot
     direction 0 0 1
     length 3
     axis -90 0 20 XYZ
     dof rx rz
     limits (-45.0 , 45.0)
            (-70.0 , 20.0)
  end
  begin
     id 5
     name rhip
     direction -1 0 0
     length 2
     axis 0 0 0 XYZ
  end
  begin
     id 6
     name rfemur
     direction 0 -1 0
     length 9
     axis 0 0 -20 XYZ
     dof rx ry rz
  end
  begin
     id 7
     name rtibia
     direction 0 -1 0
     length 9
     axis 0 0 -20 XYZ
     dof rx
  end
  begin
     id 8
     name rfoot
     direction 0 0 1
     length 3
     axis -90 0 -20 XYZ
     dof rx rz
  end
:hierarchy
  begin
    root lhip rhip
    lhip lfemur
    lfemur ltibia
    ltibia lfoot
    rhip rfemur
    rfemur rtibia
    rtibia rfoot
  end
)";

// Frame 1: rest. 2: left knee 90. 3: left foot rx 90, rz 90. 4: root moved and turned 90 about y.
const std::string kAmc = R"(#!OML:ASF test.asf
:FULLY-SPECIFIED
:DEGREES
1
root 0 0 0 0 0 0
lfemur 0 0 0
ltibia 0
lfoot 0 0
rfemur 0 0 0
rtibia 0
rfoot 0 0
2
root 0 0 0 0 0 0
lfemur 0 0 0
ltibia 90
lfoot 0 0
rfemur 0 0 0
rtibia 0
rfoot 0 0
3
root 0 0 0 0 0 0
lfemur 0 0 0
ltibia 0
lfoot 90 90
rfemur 0 0 0
rtibia 0
rfoot 0 0
4
root 10 20 30 0 90 0
lfemur 0 0 0
ltibia 0
rfoot 0 0
lfoot 0 0
rtibia 0
rfemur 0 0 0
)";

const double kScale = 0.0254 / 0.45;  // CMU: ":units length 0.45" -> metres per unit
const double kS20 = std::sin(deg_to_rad(20.0)), kC20 = std::cos(deg_to_rad(20.0));

// A point in source units and axes (Y up, Z forward, X left) in mimic's metres: X = z, Y = x, Z = y.
Vec3 src(double x, double y, double z) { return Vec3(z, x, y) * kScale; }

// Replaces the first occurrence of `from` (which must exist).
std::string edit(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in text";
  if (at == std::string::npos) return text;
  return text.substr(0, at) + to + text.substr(at + from.size());
}

std::string edit_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// The text before the first occurrence of `marker`, or before the end of `marker` if `keep`.
std::string cut_at(const std::string& text, const std::string& marker, bool keep = false) {
  const std::size_t at = text.find(marker);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << marker << "' not in text";
  return text.substr(0, at == std::string::npos ? text.size() : at + (keep ? marker.size() : 0));
}

// 1-based line of the first occurrence of `marker` (after the first occurrence of `after`).
int line_of(const std::string& text, const std::string& marker, const std::string& after = "") {
  const std::size_t from = after.empty() ? 0 : text.find(after);
  const std::size_t at = text.find(marker, from == std::string::npos ? 0 : from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << marker << "' not in text";
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(std::min(at, text.size())), '\n'));
}

void expect_vec(const Vec3& got, const Vec3& want, const std::string& what) {
  EXPECT_LT((got - want).norm(), 1e-9) << what << ": got " << got.transpose() << ", want " << want.transpose();
}

void expect_rot(const Quat& got, const Quat& want, const std::string& what) {
  EXPECT_LT(rotation_distance(got, want), 1e-9) << what;
}

struct Parsed {
  AsfSkeleton asf;
  Clip clip;
};

Parsed parse_both(const std::string& asf = kAsf, const std::string& amc = kAmc) {
  Parsed p{parse_asf(asf, "test.asf"), {}};
  p.clip = parse_amc(amc, "walk_01.amc", p.asf);
  return p;
}

LinkFrames fk(const Parsed& p, int frame) {
  return forward_kinematics(p.clip.skeleton, p.clip.frames[static_cast<std::size_t>(frame)]);
}

int joint(const Parsed& p, const char* name) {
  const int j = p.asf.skeleton.find(name);
  EXPECT_GE(j, 0) << name;
  return j;
}

Vec3 pos(const Parsed& p, const LinkFrames& f, const char* name) {
  return f.joint_pos[static_cast<std::size_t>(joint(p, name))];
}

Vec3 site(const Parsed& p, const LinkFrames& f, const char* name) {
  const int s = p.asf.skeleton.find_site(name);
  EXPECT_GE(s, 0) << name;
  return s < 0 ? Vec3::Zero() : f.site_pos[static_cast<std::size_t>(s)];
}

// Rest positions in source units: each bone starts at its parent's end (direction * length).
void expect_rest_positions(const Parsed& p, const LinkFrames& f) {
  for (double side : {1.0, -1.0}) {
    const std::string l = side > 0 ? "l" : "r";
    expect_vec(pos(p, f, (l + "hip").c_str()), src(0, 0, 0), l + "hip");
    expect_vec(pos(p, f, (l + "femur").c_str()), src(2 * side, 0, 0), l + "femur");
    expect_vec(pos(p, f, (l + "tibia").c_str()), src(2 * side, -9, 0), l + "tibia");
    expect_vec(pos(p, f, (l + "foot").c_str()), src(2 * side, -18, 0), l + "foot");
    expect_vec(site(p, f, (l + "foot_end").c_str()), src(2 * side, -18, 3), l + "foot_end");
  }
}

}  // namespace

TEST(AsfAmc, SkeletonStructureTypesAndUnits) {
  const AsfSkeleton a = parse_asf(kAsf, "test.asf");
  const Skeleton& sk = a.skeleton;
  EXPECT_NO_THROW(sk.validate());
  // Breadth-first from the root, children in hierarchy order: parents precede children.
  const std::vector<std::string> names = {"root", "lhip", "rhip", "lfemur", "rfemur", "ltibia", "rtibia", "lfoot", "rfoot"};
  ASSERT_EQ(sk.num_joints(), static_cast<int>(names.size()));
  for (std::size_t j = 0; j < names.size(); ++j) EXPECT_EQ(sk.joints[j].name, names[j]);
  EXPECT_EQ(sk.joints[static_cast<std::size_t>(sk.find("lfemur"))].parent, sk.find("lhip"));
  EXPECT_EQ(sk.joints[static_cast<std::size_t>(sk.find("lhip"))].parent, 0);
  EXPECT_EQ(sk.joints[0].type, JointType::Free);
  auto type = [&](const char* n) { return sk.joints[static_cast<std::size_t>(sk.find(n))].type; };
  EXPECT_EQ(type("lhip"), JointType::Fixed);        // no dof
  EXPECT_EQ(type("lfemur"), JointType::Spherical);  // dof rx ry rz
  EXPECT_EQ(type("ltibia"), JointType::Revolute);   // dof rx
  EXPECT_EQ(type("lfoot"), JointType::Spherical);   // dof rx rz
  // rx is about source x, which is mimic's Y (left).
  expect_vec(sk.joints[static_cast<std::size_t>(sk.find("ltibia"))].axis, Vec3::UnitY(), "knee axis");
  ASSERT_EQ(sk.sites.size(), 2u);
  EXPECT_EQ(sk.sites[0].name, "lfoot_end");
  EXPECT_EQ(sk.sites[1].name, "rfoot_end");

  EXPECT_NEAR(a.metres_per_unit, 0.0254 / 0.45, 1e-15);
  EXPECT_TRUE(a.degrees);
  EXPECT_EQ(a.source, "test.asf");
  ASSERT_EQ(a.dofs.size(), names.size());
  EXPECT_EQ(a.dofs[0], (std::vector<std::string>{"tx", "ty", "tz", "rx", "ry", "rz"}));
  EXPECT_EQ(a.dofs[static_cast<std::size_t>(sk.find("lfoot"))], (std::vector<std::string>{"rx", "rz"}));
  EXPECT_TRUE(a.dofs[static_cast<std::size_t>(sk.find("lhip"))].empty());
  // C of ltibia is 20 degrees about source z = mimic X.
  expect_rot(a.axis_rot[static_cast<std::size_t>(sk.find("ltibia"))], axis_rotation('x', deg_to_rad(20)), "C ltibia");
  // Y up, Z forward -> Z up, X forward: source z -> X, x -> Y, y -> Z.
  expect_vec(a.basis * Vec3::UnitZ(), Vec3::UnitX(), "basis z");
  expect_vec(a.basis * Vec3::UnitY(), Vec3::UnitZ(), "basis y");
}

TEST(AsfAmc, LimitsInRadiansAboutJointFrameAxes) {
  const AsfSkeleton a = parse_asf(kAsf, "test.asf");
  auto limits = [&](const char* n) { return a.skeleton.joints[static_cast<std::size_t>(a.skeleton.find(n))].limits; };
  using L = std::vector<std::pair<double, double>>;
  auto same = [](const L& got, const L& want) {
    if (got.size() != want.size()) return false;
    for (std::size_t k = 0; k < got.size(); ++k)
      if (std::abs(got[k].first - want[k].first) > 1e-12 || std::abs(got[k].second - want[k].second) > 1e-12) return false;
    return true;
  };
  auto rad = [](double lo, double hi) { return std::pair{deg_to_rad(lo), deg_to_rad(hi)}; };
  // Revolute: the one dof's limits. Spherical: about the joint frame's x, y, z = source z, x, y.
  EXPECT_TRUE(same(limits("ltibia"), L{rad(-10, 170)}));
  EXPECT_TRUE(same(limits("lfemur"), L{rad(-60, 70), rad(-160, 20), rad(-70, 70)}));
  EXPECT_TRUE(same(limits("lfoot"), L{rad(-70, 20), rad(-45, 45), {0.0, 0.0}}));  // no ry: stays at zero
  EXPECT_TRUE(limits("rfemur").empty());
  // Facing -Z: source x maps to mimic -Y, so rx limits flip sign; a revolute axis carries the sign.
  const AsfSkeleton b = parse_asf(kAsf, "test.asf", AxisConvention{"y", "-z", 0.0});
  const Joint& femur = b.skeleton.joints[static_cast<std::size_t>(b.skeleton.find("lfemur"))];
  EXPECT_TRUE(same(L{femur.limits.at(1)}, L{rad(-20, 160)}));
  const Joint& knee = b.skeleton.joints[static_cast<std::size_t>(b.skeleton.find("ltibia"))];
  expect_vec(knee.axis, -Vec3::UnitY(), "flipped knee axis");
  EXPECT_TRUE(same(knee.limits, L{rad(-10, 170)}));
  // Unbounded limits become half a turn.
  const AsfSkeleton c = parse_asf(edit(kAsf, "(-10.0 , 170.0)", "(-inf inf)"), "test.asf");
  EXPECT_TRUE(same(c.skeleton.joints[static_cast<std::size_t>(c.skeleton.find("ltibia"))].limits, L{{-kPi, kPi}}));
}

TEST(AsfAmc, RestPoseMatchesDirectionsTimesLengths) {
  const Parsed p = parse_both();
  const LinkFrames f = fk(p, 0);  // frame 1: all zero
  expect_vec(f.joint_pos[0], Vec3::Zero(), "root");
  expect_rest_positions(p, f);
  // At rest R_i = I, so each joint frame F_i = R_i * C_i is the bone's Acclaim axis C_i.
  for (std::size_t j = 0; j < f.joint_rot.size(); ++j) expect_rot(f.joint_rot[j], p.asf.axis_rot[j], p.asf.skeleton.joints[j].name);
  // The skeleton's rest_pose with the root at C_root is the same pose.
  Pose rest = rest_pose(p.asf.skeleton);
  rest.rot[0] = p.asf.axis_rot[0];
  const LinkFrames g = forward_kinematics(p.asf.skeleton, rest);
  for (std::size_t s = 0; s < g.site_pos.size(); ++s) expect_vec(g.site_pos[s], f.site_pos[s], "rest_pose site");
}

TEST(AsfAmc, KneeAt90DegreesMovesFootAsComputedByHand) {
  // Knee: C = Rz(20), M = Rx(90), R = C M C^-1 rotates about C x = (cos20, sin20, 0).
  // Tibia d = (0,-1,0): C^-1 d = (-sin20, -cos20, 0); Rx(90) (x,y,z) = (x,-z,y) gives
  // (-sin20, 0, -cos20); Rz(20) gives (-sin20 cos20, -sin^2 20, -cos20). Times length 9.
  // The foot (C_foot M C_foot^-1 = I) turns with the tibia: R (0,0,1) = Rz(20)(0,-1,0) = (sin20, -cos20, 0).
  const Parsed p = parse_both();
  const LinkFrames f = fk(p, 1);
  const Vec3 knee(2, -9, 0);
  const Vec3 ankle = knee + 9.0 * Vec3(-kS20 * kC20, -kS20 * kS20, -kC20);
  const Vec3 toe = ankle + 3.0 * Vec3(kS20, -kC20, 0);
  expect_vec(pos(p, f, "ltibia"), src(knee.x(), knee.y(), knee.z()), "knee");
  expect_vec(pos(p, f, "lfoot"), src(ankle.x(), ankle.y(), ankle.z()), "ankle");
  expect_vec(site(p, f, "lfoot_end"), src(toe.x(), toe.y(), toe.z()), "toe");
  // The shin points backwards (mimic -X) and the right leg has not moved.
  EXPECT_LT(pos(p, f, "lfoot").x(), -8.0 * kScale);
  expect_vec(site(p, f, "rfoot_end"), src(-2, -18, 3), "right toe");
  // The pose's joint rotation is M in mimic axes: 90 degrees about mimic Y.
  expect_rot(p.clip.frames[1].rot[static_cast<std::size_t>(joint(p, "ltibia"))], axis_rotation('y', kPi / 2), "q knee");
}

TEST(AsfAmc, FirstListedDofIsAppliedFirst) {
  // Foot: C = Rz(20) Rx(-90); dof rx rz with (90, 90) is M = Rz(90) Rx(90).
  // d = (0,0,1): C^-1 d = Rx(90) Rz(-20) d = (0,-1,0); Rx(90) -> (0,0,-1); Rz(90) -> (0,0,-1);
  // Rx(-90) -> (0,-1,0); Rz(20) -> (sin20, -cos20, 0). (Rx Rz instead would give (cos20, sin20, 0).)
  const Parsed p = parse_both();
  const LinkFrames f = fk(p, 2);
  const Vec3 toe = Vec3(2, -18, 0) + 3.0 * Vec3(kS20, -kC20, 0);
  expect_vec(pos(p, f, "lfoot"), src(2, -18, 0), "ankle");
  expect_vec(site(p, f, "lfoot_end"), src(toe.x(), toe.y(), toe.z()), "toe");
}

TEST(AsfAmc, RootPositionAndRotationGoToZUp) {
  // Root (10, 20, 30) units, Y up -> mimic (30, 10, 20) * 0.0254/0.45 m. Ry(90) about the
  // source's up axis is a 90 degree turn about mimic Z: the left hip (2,0,0) goes to (0,0,-2),
  // i.e. mimic (-2, 0, 0).
  const Parsed p = parse_both();
  const Pose& pose = p.clip.frames[3];
  expect_vec(pose.root_pos, src(10, 20, 30), "root position");
  EXPECT_NEAR(pose.root_pos.x(), 30 * 0.0254 / 0.45, 1e-12);
  expect_rot(pose.rot[0], axis_rotation('z', kPi / 2), "root rotation");
  const LinkFrames f = fk(p, 3);
  expect_vec(pos(p, f, "lfemur"), src(10, 20, 30) + src(0, 0, -2), "left femur");
  expect_vec(site(p, f, "rfoot_end"), src(10, 20, 30) + src(3, -18, 2), "right toe");
}

TEST(AsfAmc, RootRotationIsConjugatedByItsOrientation) {
  // orientation 0 0 90 (C = Rz(90)) and root rx 90 (M = Rx(90)): R = C M C^-1 is 90 degrees
  // about C x = (0,1,0), taking the left hip (2,0,0) to (0,0,-2) and the femur (0,-9,0) to itself.
  const std::string asf = edit(kAsf, "orientation 0 0 0", "orientation 0 0 90");
  const Parsed rest = parse_both(asf);
  expect_rest_positions(rest, fk(rest, 0));  // with M = I the orientation changes no position
  const Parsed p = parse_both(asf, edit(kAmc, "root 0 0 0 0 0 0\nlfemur", "root 0 0 0 90 0 0\nlfemur"));
  const LinkFrames f = fk(p, 0);
  expect_vec(pos(p, f, "lfemur"), src(0, 0, -2), "left femur");
  expect_vec(pos(p, f, "ltibia"), src(0, -9, -2), "left knee");
  // F_root = R_root * C_root = C_root * M_root.
  const Quat c = axis_rotation('x', kPi / 2), m = axis_rotation('y', kPi / 2);  // in mimic axes
  expect_rot(p.clip.frames[0].rot[0], c * m, "F_root");
}

TEST(AsfAmc, FrameCountFpsAndName) {
  const Parsed p = parse_both();
  EXPECT_EQ(p.clip.num_frames(), 4);
  EXPECT_EQ(p.clip.fps, 120.0);
  EXPECT_EQ(p.clip.name, "walk_01");
  EXPECT_EQ(p.clip.loop, LoopMode::None);
  EXPECT_EQ(p.clip.skeleton.num_joints(), p.asf.skeleton.num_joints());
  EXPECT_NO_THROW(p.clip.validate());
  for (const Pose& pose : p.clip.frames)
    for (const Quat& q : pose.rot) EXPECT_GE(q.w(), 0.0);  // canonical sign
  const Clip slow = parse_amc(kAmc, "dir/slow.amc", p.asf, 60.0);
  EXPECT_EQ(slow.fps, 60.0);
  EXPECT_EQ(slow.name, "slow");
  EXPECT_NEAR(slow.duration(), 3.0 / 60.0, 1e-12);
}

TEST(AsfAmc, RadiansUnitsAndScaleOverride) {
  // ASF in radians: axis angles and (without :DEGREES) AMC values in radians give the same knee.
  std::string asf = edit(kAsf, "angle deg", "angle rad");
  asf = edit_all(asf, " 0 0 20 XYZ", " 0 0 0.3490658503988659 XYZ");
  asf = edit_all(asf, " 0 0 -20 XYZ", " 0 0 -0.3490658503988659 XYZ");
  asf = edit_all(asf, "-90 0 20 XYZ", "-1.5707963267948966 0 0.3490658503988659 XYZ");
  asf = edit_all(asf, "-90 0 -20 XYZ", "-1.5707963267948966 0 -0.3490658503988659 XYZ");
  const Parsed deg = parse_both();
  const Parsed rad = parse_both(asf, edit(edit(kAmc, ":DEGREES\n", ""), "ltibia 90", "ltibia 1.5707963267948966"));
  EXPECT_FALSE(rad.asf.degrees);
  for (int frame = 0; frame < 2; ++frame) {
    const LinkFrames a = fk(deg, frame), b = fk(rad, frame);
    for (std::size_t s = 0; s < a.site_pos.size(); ++s) expect_vec(b.site_pos[s], a.site_pos[s], "radian site");
  }
  // ":DEGREES" in the AMC overrides the ASF's unit; ":RADIANS" likewise.
  const Clip d = parse_amc(kAmc, "d.amc", rad.asf);
  expect_rot(d.frames[1].rot[static_cast<std::size_t>(joint(deg, "ltibia"))], axis_rotation('y', kPi / 2), "override");
  const Clip r = parse_amc(edit(edit(kAmc, ":DEGREES", ":RADIANS"), "ltibia 90", "ltibia 0.5"), "r.amc", deg.asf);
  expect_rot(r.frames[1].rot[static_cast<std::size_t>(joint(deg, "ltibia"))], axis_rotation('y', 0.5), "radians");
  // An explicit scale wins over ":units length".
  const AsfSkeleton cm = parse_asf(kAsf, "cm.asf", AxisConvention{"y", "z", 0.01});
  EXPECT_EQ(cm.metres_per_unit, 0.01);
  expect_vec(cm.skeleton.joints[static_cast<std::size_t>(cm.skeleton.find("lfemur"))].offset, Vec3(0, 0.02, 0), "cm offset");
  // A Z-up, X-forward source needs no rotation.
  const AsfSkeleton zup = parse_asf(kAsf, "z.asf", AxisConvention{"z", "x", 1.0});
  EXPECT_LT(rotation_distance(zup.basis, Quat::Identity()), 1e-12);
  expect_vec(zup.skeleton.joints[static_cast<std::size_t>(zup.skeleton.find("lfemur"))].offset, Vec3(2, 0, 0), "z-up offset");
}

TEST(AsfAmc, LoadsFilesAndGuessesTheAsf) {
  const auto dir = test::temp_dir("asf_amc");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  };
  const auto asf = write("07.asf", kAsf);
  const auto amc = write("07_01.amc", kAmc);
  EXPECT_EQ(guess_asf(amc), asf);
  const Clip c = load_amc(amc, load_asf(guess_asf(amc)));
  EXPECT_EQ(c.num_frames(), 4);
  EXPECT_EQ(c.name, "07_01");
  // No "07.asf" for this name, but the only .asf in the directory.
  EXPECT_EQ(guess_asf(dir / "walk.amc"), asf);
  write("other.asf", kAsf);
  EXPECT_TRUE(guess_asf(dir / "walk.amc").empty());  // two candidates: ambiguous
  EXPECT_EQ(guess_asf(amc), asf);
  EXPECT_TRUE(guess_asf(dir / "missing" / "01_01.amc").empty());
  try {
    load_amc(write("bad_01.amc", ":DEGREES\n1\nroot 0 0 0 0 0\n"), load_asf(asf));
    FAIL() << "no error";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.source(), (dir / "bad_01.amc").string());
    EXPECT_EQ(e.line(), 3);
  }
}

TEST(AsfAmc, DeepChainParsesWithoutRecursionAndBoneCountIsLimited) {
  auto chain = [](int n) {
    std::string t = ":root\n order TX TY TZ RX RY RZ\n axis XYZ\n:bonedata\n";
    for (int i = 1; i <= n; ++i)
      t += "begin\n name b" + std::to_string(i) + "\n direction 0 1 0\n length 1\n axis 0 0 0 XYZ\n dof rx\nend\n";
    t += ":hierarchy\nbegin\nroot b1\n";
    for (int i = 1; i < n; ++i) t += "b" + std::to_string(i) + " b" + std::to_string(i + 1) + "\n";
    return t + "end\n";
  };
  const AsfSkeleton a = parse_asf(chain(4096), "deep.asf", AxisConvention{"y", "z", 1.0});
  ASSERT_EQ(a.skeleton.num_joints(), 4097);
  EXPECT_EQ(a.skeleton.joints.back().parent, 4095);
  const LinkFrames f = forward_kinematics(a.skeleton, rest_pose(a.skeleton));
  expect_vec(f.site_pos.back(), Vec3(0, 0, 4096), "chain tip");
  EXPECT_THROW(parse_asf(chain(4097), "deep.asf"), ParseError);
}

TEST(AsfAmc, InconsistentSkeletonOrRateIsAnError) {
  EXPECT_THROW(parse_amc(kAmc, "x.amc", AsfSkeleton{}), ParseError);
  const AsfSkeleton a = parse_asf(kAsf, "test.asf");
  EXPECT_THROW(parse_amc(kAmc, "x.amc", a, 0.0), ParseError);
  EXPECT_THROW(parse_amc(kAmc, "x.amc", a, std::nan("")), ParseError);
}

namespace {

// Each table is parsed as one kind of file: ASF as "bad.asf", AMC as "bad.amc" (with kAsf's skeleton).
std::vector<MalformedCase> bad_asf_cases() {
  const std::string& A = kAsf;
  auto la = [&](const std::string& m, const std::string& after = "") { return line_of(A, m, after); };
  const std::string no_root = edit(A, ":root\n   order TX TY TZ RX RY RZ\n   axis XYZ\n   position 0 0 0\n   orientation 0 0 0\n", "");
  const std::string cyclic = edit(edit(A, "root lhip rhip", "root rhip"), "ltibia lfoot\n", "ltibia lfoot\n    lfoot lhip\n");
  return {
      {"asf empty", "", 0, "empty file"},
      {"asf only comments", "# nothing here\n\n", 0, "empty file"},
      {"asf missing bonedata", cut_at(A, ":bonedata"), 0, "missing ':bonedata' section"},
      {"asf missing root", no_root, 0, "missing ':root' section"},
      {"asf missing hierarchy", cut_at(A, ":hierarchy"), 0, "missing ':hierarchy' section"},
      {"asf hierarchy first", ":hierarchy\n" + A, 1, ":hierarchy must come after :bonedata"},
      {"asf duplicate section", A + ":units\n  length 1\n", la("  end\n", ":hierarchy") + 1, "duplicate ':units' section"},
      {"asf unknown section", edit(A, ":documentation", ":docs"), la(":documentation"), "unknown section ':docs'"},
      {"asf stray token", edit(A, ":version", "version"), la(":version"), "expected a section keyword"},
      {"asf bad number", edit(A, "length 9\n", "length 9x\n"), la("length 9"), "bone 'lfemur' length must be a finite number, found '9x'"},
      {"asf nan", edit(A, "direction 0 -1 0", "direction 0 nan 0"), la("direction 0 -1 0"), "direction must be a finite number, found 'nan'"},
      {"asf inf", edit(A, "direction 1 0 0", "direction inf 0 0"), la("direction 1 0 0"), "found 'inf'"},
      {"asf missing coordinate", edit(A, "direction 0 0 1", "direction 0 0"), la("direction 0 0 1"), "missing bone 'lfoot' direction"},
      {"asf zero direction", edit(A, "direction 0 0 1", "direction 0 0 0"), la("direction 0 0 1"), "bone 'lfoot': direction must be a non-zero vector"},
      {"asf negative length", edit(A, "length 3", "length -3"), la("length 3"), "bone 'lfoot': length must not be negative"},
      {"asf missing length", edit(A, "     length 3\n", ""), la("id 4") - 1, "bone 'lfoot' has no 'length'"},
      {"asf missing direction", edit(A, "     direction 1 0 0\n", ""), la("begin"), "bone 'lhip' has no 'direction'"},
      {"asf missing name", edit(A, "     name lhip\n", ""), la("begin"), "bone has no 'name'"},
      {"asf duplicate bone", edit(A, "name rhip", "name lhip"), la("id 5") - 1, "duplicate bone name 'lhip'"},
      {"asf bone named root", edit(A, "name lhip", "name root"), la("name lhip"), "'root' cannot be a bone name"},
      {"asf numeric bone name", edit(A, "name lhip", "name 12"), la("name lhip"), "'12' cannot be a bone name"},
      {"asf unknown field", edit(A, "id 1", "idx 1"), la("id 1"), "bone at line 16: unknown field 'idx'"},
      {"asf extra token", edit(A, "length 2\n", "length 2 3\n"), la("length 2"), "unexpected '3' after bone 'lhip' length"},
      {"asf unknown dof", edit(A, "dof rx\n", "dof rq\n"), la("dof rx\n"), "bone 'ltibia': unknown dof 'rq'"},
      {"asf translational dof", edit(A, "dof rx\n", "dof tx\n"), la("dof rx\n"), "translational dof 'tx' is not supported"},
      {"asf length dof", edit(A, "dof rx rz", "dof rx l"), la("dof rx rz"), "translational dof 'l' is not supported"},
      {"asf duplicate dof", edit(A, "dof rx rz", "dof rx rx"), la("dof rx rz"), "dof 'rx' is listed twice"},
      {"asf empty dof", edit(A, "dof rx\n     limits (-10.0 , 170.0)\n", "dof\n"), la("dof rx\n"), "'dof' lists no channels"},
      {"asf fewer limits", edit(A, "            (-70.0 , 20.0)\n", ""), la("limits (-45.0"), "'limits' needs one '(lo hi)' pair per dof (2), found 1"},
      {"asf more limits", edit(A, "(-10.0 , 170.0)\n", "(-10.0 , 170.0)\n (0 1)\n"), la("(-10.0 , 170.0)"), "found more"},
      {"asf bad limit", edit(A, "(-10.0 , 170.0)", "(-10.0 , abc)"), la("(-10.0 , 170.0)"), "limit pair must be '(lo hi)' with finite numbers"},
      {"asf limit no paren", edit(A, "(-10.0 , 170.0)", "(-10.0 , 170.0"), la("(-10.0 , 170.0)"), "has no ')'"},
      {"asf limit three numbers", edit(A, "(-10.0 , 170.0)", "(-10.0 , 170.0 5)"), la("(-10.0 , 170.0)"), "more than two numbers"},
      {"asf limit reversed", edit(A, "(-10.0 , 170.0)", "(170.0 , -10.0)"), la("(-10.0 , 170.0)"), "limit low is greater than high"},
      {"asf limits before dof", edit(A, "     dof rx\n     limits (-10.0 , 170.0)\n", "     limits (-10.0 , 170.0)\n     dof rx\n"),
       la("dof rx\n"), "'limits' before 'dof'"},
      {"asf bad axis letters", edit(A, "axis 0 0 20 XYZ", "axis 0 0 20 XYW"), la("axis 0 0 20 XYZ"), "axis order 'xyw' must be a permutation of XYZ"},
      {"asf repeated axis letters", edit(A, "axis 0 0 20 XYZ", "axis 0 0 20 XXZ"), la("axis 0 0 20 XYZ"), "must be a permutation of XYZ"},
      {"asf missing axis order", edit(A, "axis 0 0 20 XYZ", "axis 0 0 20"), la("axis 0 0 20 XYZ"), "missing bone 'lfemur' axis order"},
      {"asf root axis", edit(A, "axis XYZ\n", "axis XY\n"), la("axis XYZ\n"), "root: axis order 'xy'"},
      {"asf root order", edit(A, "RX RY RZ", "RX RY RW"), la("RX RY RZ"), "root: unknown channel 'rw'"},
      {"asf root no order", edit(A, "   order TX TY TZ RX RY RZ\n", ""), la(":root"), ":root has no 'order' line"},
      {"asf units angle", edit(A, "angle deg", "angle grad"), la("angle deg"), ":units angle must be 'deg' or 'rad'"},
      {"asf units length", edit(A, "length 0.45", "length 0"), la("length 0.45"), ":units length must be positive"},
      {"asf missing end", edit(A, "  end\n", ""), la("begin"), "bone 'lhip': 'begin' has no matching 'end'"},
      {"asf missing begin", edit(A, "  begin\n", ""), la("begin"), "expected 'begin' of a bone in :bonedata, found 'id'"},
      {"asf truncated", cut_at(A, "     length 9\n", true), la("id 2") - 1, "bone 'lfemur': 'begin' has no matching 'end'"},
      {"asf hierarchy no end", A.substr(0, A.size() - 6), la("begin", ":hierarchy"), ":hierarchy 'begin' has no matching 'end'"},
      {"asf hierarchy no begin", edit(A, "  begin\n    root", "    root"), la("root lhip") - 1, "expected 'begin', found 'root'"},
      {"asf unknown bone in hierarchy", edit(A, "lfemur ltibia", "lfemur lshin"), la("lfemur ltibia"), "unknown bone 'lshin' in :hierarchy"},
      {"asf root as child", edit(A, "lfemur ltibia", "lfemur root"), la("lfemur ltibia"), "'root' cannot be a child"},
      {"asf two parents", edit(A, "rhip rfemur", "rhip rfemur ltibia"), la("rhip rfemur"), "bone 'ltibia' has two parents in :hierarchy (first given at line " + std::to_string(la("lfemur ltibia")) + ")"},
      {"asf cycle", cyclic, line_of(cyclic, "lfoot lhip"), "bone 'lhip' is not connected to the root: its parents form a cycle"},
      {"asf self parent", edit(edit(A, "root lhip rhip", "root rhip"), "lhip lfemur", "lhip lhip lfemur"), la("lhip lfemur"), "parents form a cycle"},
      {"asf unreachable", edit(A, "    ltibia lfoot\n", ""), la("id 4") - 1, "bone 'lfoot' is not connected to the root in :hierarchy"},
  };
}

std::vector<MalformedCase> bad_amc_cases() {
  const std::string& M = kAmc;
  auto lm = [&](const std::string& m, const std::string& after = "") { return line_of(M, m, after); };
  return {
      {"amc empty", "", 0, "no frames"},
      {"amc header only", ":FULLY-SPECIFIED\n:DEGREES\n", 0, "no frames"},
      {"amc unknown keyword", edit(M, ":DEGREES", ":GRADIANS"), lm(":DEGREES"), "unknown AMC keyword ':GRADIANS'"},
      {"amc missing frame number", edit(M, ":DEGREES\n1\n", ":DEGREES\n"), lm("1\n"), "expected frame number 1, found 'root'"},
      {"amc frame zero", edit(M, ":DEGREES\n1\n", ":DEGREES\n0\n"), lm("1\n"), "frame number 0 where 1 was expected"},
      {"amc non-consecutive", edit(M, "\n3\n", "\n5\n"), lm("\n3\n") + 1, "frame number 5 where 3 was expected"},
      {"amc frame number junk", edit(M, "\n2\n", "\n2 x\n"), lm("\n2\n") + 1, "unexpected 'x' after frame number 2"},
      {"amc too few values", edit(M, "ltibia 90", "ltibia"), lm("ltibia 90"), "frame 2: bone 'ltibia' has 0 values, expected 1"},
      {"amc too many values", edit(M, "ltibia 90", "ltibia 90 0"), lm("ltibia 90"), "frame 2: bone 'ltibia' has more than 1 values"},
      {"amc values split over lines", edit(M, "root 10 20 30 0 90 0", "root 10 20 30\n0 90 0"), lm("root 10 20"), "frame 4: bone 'root' has 3 values, expected 6"},
      {"amc value for fixed bone", edit(M, "lfemur 0 0 0\n", "lhip 5\nlfemur 0 0 0\n"), lm("lfemur 0 0 0"), "frame 1: bone 'lhip' has more than 0 values"},
      {"amc unknown bone", edit(M, "ltibia 90", "lshin 90"), lm("ltibia 90"), "frame 2: unknown bone 'lshin'"},
      {"amc duplicate bone", edit(M, "ltibia 90\n", "ltibia 90\nltibia 80\n"), lm("ltibia 90") + 1, "frame 2: bone 'ltibia' appears twice"},
      {"amc missing bone", edit(M, "ltibia 90\n", ""), lm("\n2\n") + 1, "frame 2: bone 'ltibia' is missing"},
      {"amc nan", edit(M, "ltibia 90", "ltibia nan"), lm("ltibia 90"), "frame 2: bone 'ltibia': value 'nan' is not a finite number"},
      {"amc inf", edit(M, "ltibia 90", "ltibia -inf"), lm("ltibia 90"), "value '-inf' is not a finite number"},
      {"amc overflow", edit(M, "ltibia 90", "ltibia 1e999"), lm("ltibia 90"), "value '1e999' is not a finite number"},
      {"amc truncated frame", cut_at(M, "ltibia 90\n", true), lm("\n2\n") + 1, "frame 2: bone 'rfemur' is missing"},
      {"amc truncated line", cut_at(M, "root 10 20 30 0 90", true), lm("root 10 20"), "frame 4: bone 'root' has 5 values, expected 6"},
  };
}

}  // namespace

TEST(AsfAmc, MalformedInputsRaiseParseErrorsWithPlaceAndReason) {
  const AsfSkeleton asf = parse_asf(kAsf, "test.asf");
  const std::vector<MalformedCase> asf_cases = bad_asf_cases();
  const std::vector<MalformedCase> amc_cases = bad_amc_cases();
  EXPECT_GE(asf_cases.size() + amc_cases.size(), 30u);
  expect_parse_errors(asf_cases, kAsf, "bad.asf", [](const std::string& text) { parse_asf(text, "bad.asf"); });
  expect_parse_errors(amc_cases, kAmc, "bad.amc",
                      [&asf](const std::string& text) { parse_amc(text, "bad.amc", asf); });
}
