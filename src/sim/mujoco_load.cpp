#include "sim/mujoco_load.hpp"

#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <vector>

#include "core/error.hpp"

namespace mimic {

namespace {
void print_warning(const char* msg) { std::fprintf(stderr, "MuJoCo warning: %s\n", msg); }
}  // namespace

mjModel* compile_mjcf(const std::string& mjcf, const std::string& what) {
  static std::once_flag handlers;
  std::call_once(handlers, [] { mju_user_warning = print_warning; });
  // MuJoCo 2.2 reads XML from files; a virtual file system keeps the text in memory. The VFS is
  // megabytes, so it lives on the heap rather than on a worker thread's stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "model.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(mjcf.size())) != 0)
    throw Error("MuJoCo cannot allocate a virtual file for " + what);
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], mjcf.data(), mjcf.size());
  char err[1000] = "";
  mjModel* m = mj_loadXML(name, vfs.get(), err, sizeof err);
  mj_deleteVFS(vfs.get());
  if (!m) throw Error("MuJoCo rejected the model of " + what + ": " + err);
  return m;
}

}  // namespace mimic

namespace mimic {

std::vector<std::string> character_body_names(const mjModel* m) {
  std::vector<std::string> names;
  if (!m || m->nbody < 2) return names;
  // The largest tree under the world (the first of equal ones): projectiles are bodies of their
  // own, added before or after the character.
  std::vector<int> size(static_cast<std::size_t>(m->nbody), 0);
  for (int b = 1; b < m->nbody; ++b) ++size[static_cast<std::size_t>(m->body_rootid[b])];
  int root = 1;
  for (int b = 1; b < m->nbody; ++b)
    if (size[static_cast<std::size_t>(b)] > size[static_cast<std::size_t>(root)]) root = b;
  for (int b = 1; b < m->nbody; ++b) {
    if (m->body_rootid[b] != root) continue;
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    names.emplace_back(name ? name : "?");
  }
  return names;
}

}  // namespace mimic
