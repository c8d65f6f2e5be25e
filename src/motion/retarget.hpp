#pragma once
// Retargeting a clip onto another skeleton by a joint-name map (a small YAML file, see
// docs/retargeting.md). Each mapped target joint takes the source joint's rotation relative to
// its rest pose, after aligning the two rest poses bone by bone (a T-pose source drives an
// arms-down target correctly). Where the source's rest pose faces another way than the target's
// (an axis convention the import was not told), the target's rest is first turned by that quarter
// or half turn about the vertical, so that the character faces where the source does. Root
// translation is scaled. Then, where the map lists them,
// inverse kinematics puts end effectors where the scaled source has them and holds the contact
// joints (feet) still on the ground while the source's are in stance (motion/effector_ik.hpp).
// Last, one vertical shift per clip puts the lowest contact point on the ground.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "motion/clip.hpp"

namespace mimic {

struct RetargetSite {
  std::string name, joint;
  Vec3 offset = Vec3::Zero();  // in the target joint's frame, metres
};

struct RetargetMap {
  // Target joint <- source joint: the first of the names the source skeleton has. A source joint
  // named "prefix:Name" (Mixamo's "mixamorig:Hips") answers to "Name" as well.
  std::vector<std::pair<std::string, std::vector<std::string>>> joints;
  double scale = 0.0;                     // target/source length ratio; 0 = from the rest poses
  std::vector<RetargetSite> sites;        // extra target sites (e.g. soles) kept in the output
  std::vector<std::string> end_effectors; // target joints whose error is reported
  std::vector<std::string> ik;            // target joints put where the scaled source has them
  std::vector<std::string> contacts;      // of those, the ones held still through the source's stance
  bool ground_fix = true;
  std::string source;                     // where the map came from, for errors
};

RetargetMap parse_retarget_map(std::string_view text, const std::string& source);
RetargetMap load_retarget_map(const std::filesystem::path& path);

// The source joint a map's names give: the first name the skeleton has as a joint, or as the part
// after the last ':' of one joint's name; -1 if none.
int find_source_joint(const Skeleton& source, const std::vector<std::string>& names);

// Whether the map applies: every target joint (and every site's joint) is in the target, every
// source name list finds a joint of the source.
bool map_fits(const RetargetMap& map, const Skeleton& source, const Skeleton& target);

struct EffectorError {
  std::string name;
  double mean = 0.0, max = 0.0;  // metres, root-relative, target vs scaled source
  double world_mean = 0.0;       // metres, in the world (before the ground shift), target vs scaled source
  double world_mean_before_ik = 0.0;  // the same from the rotation transfer alone
};

// A contact joint through the source's stance frames: how far it slides (mean horizontal speed).
struct ContactReport {
  std::string name;
  int stance_frames = 0;
  double sliding = 0.0, sliding_before_ik = 0.0;  // m/s
};

struct RetargetReport {
  double scale = 1.0;
  double ground_shift = 0.0;  // metres added to the root height
  std::vector<EffectorError> effectors;
  std::vector<ContactReport> contacts;
  int frames_below_floor = 0;  // frames whose lowest joint or site is under the floor (ground_fix: none)
  int source_turn = 0;         // degrees about the vertical from the target's rest facing to the source's (0, 90, 180, -90)
};

// Throws Error naming the map file when a mapped joint is missing on either side.
Clip retarget(const Clip& source, const Skeleton& target, const RetargetMap& map, RetargetReport* report = nullptr);

}  // namespace mimic
