#include "env/env.hpp"

namespace mimic {

const char* to_string(Termination t) {
  switch (t) {
    case Termination::None: return "none";
    case Termination::Fall: return "fall";
    case Termination::TimeLimit: return "time_limit";
    case Termination::ClipEnd: return "clip_end";
    case Termination::Drift: return "drift";
  }
  return "?";
}

}  // namespace mimic
