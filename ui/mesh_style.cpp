#include "ui/mesh_style.hpp"

#include <algorithm>

namespace dampbound::ui {

ImU32 status_color(NodeStatus status) {
  switch (status) {
    case NodeStatus::within:
      return IM_COL32(120, 200, 140, 255);  // soft green
    case NodeStatus::clamped:
      return IM_COL32(250, 190, 40, 255);  // amber
    case NodeStatus::violating:
      return IM_COL32(235, 60, 50, 255);  // red
    case NodeStatus::unstabilisable:
      return IM_COL32(230, 60, 230, 255);  // magenta
    case NodeStatus::fixed:
      return IM_COL32(110, 150, 255, 255);  // blue
  }
  return IM_COL32(200, 200, 200, 255);
}

ImU32 shade_color(float t) {
  if (!(t > 0)) return IM_COL32(90, 95, 105, 255);
  t = std::min(t, 1.0f);
  // Two straight pieces: (80, 60, 160) -> (220, 70, 160) -> (255, 220, 60).
  const auto mix = [](float a, float b, float u) { return static_cast<int>(a + (b - a) * u + 0.5f); };
  if (t < 0.5f) {
    const float u = 2 * t;
    return IM_COL32(mix(80, 220, u), mix(60, 70, u), 160, 255);
  }
  const float u = 2 * t - 1;
  return IM_COL32(mix(220, 255, u), mix(70, 220, u), mix(160, 60, u), 255);
}

const char* status_label(NodeStatus status) {
  switch (status) {
    case NodeStatus::within:
      return "within bounds";
    case NodeStatus::clamped:
      return "clamped by the policy";
    case NodeStatus::violating:
      return "violating";
    case NodeStatus::unstabilisable:
      return "unstabilisable";
    case NodeStatus::fixed:
      return "fixed";
  }
  return "?";
}

const char* status_help(NodeStatus status) {
  switch (status) {
    case NodeStatus::within:
      return "effective gamma in [lower (eq. 5), upper (eq. 6)], as the user set it";
    case NodeStatus::clamped:
      return "the policy changed gamma; the result is within the bounds";
    case NodeStatus::violating:
      return "effective gamma outside [lower, upper]";
    case NodeStatus::unstabilisable:
      return "lower > upper: no damping satisfies both bounds (paper sec. 5)";
    case NodeStatus::fixed:
      return "a fixed node: never moves, not judged";
  }
  return "";
}

ImU32 spring_color() {
  return IM_COL32(160, 175, 205, 190);
}
ImU32 watched_color() {
  return IM_COL32(255, 255, 255, 255);
}

ImU32 unguaranteed_color() { return IM_COL32(0, 215, 215, 255); }  // cyan

const char* unguaranteed_label() { return "not guaranteed"; }

const char* unguaranteed_help() {
  return "gamma_lo > gamma_safe: critical damping cannot be guaranteed stable at this dt "
         "(safe bound); a smaller dt would";
}

ImU32 node_color(NodeStatus status, bool unguaranteed) {
  // Under the safe policy an infeasible node is damped at gamma_safe < gamma_lo, which the
  // paper's bounds call violating: SPEC 9's colour says why. The paper's own alarm
  // (unstabilisable) and fixed nodes keep theirs.
  const bool shown = status == NodeStatus::within || status == NodeStatus::clamped ||
                     status == NodeStatus::violating;
  return unguaranteed && shown ? unguaranteed_color() : status_color(status);
}

float spring_alpha(float spring_spacing_px) {
  return std::clamp((spring_spacing_px - 1.5f) / 4.0f, kFaintestSprings, 1.0f);
}

bool springs_drawn(bool shown, float spring_spacing_px, size_t springs, bool playing) {
  if (!shown) return false;
  const bool faintest = !(spring_alpha(spring_spacing_px) > kFaintestSprings);
  return !(playing && springs > kBigMeshSprings && faintest);
}

int mesh_samples(float spring_spacing_px, size_t springs, bool playing) {
  if (!(spring_spacing_px < 5.0f)) return 1;
  return playing && springs > kBigMeshSprings ? 1 : 4;
}

}  // namespace dampbound::ui
