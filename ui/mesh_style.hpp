#pragma once
// Colours of the mesh view: one per node state of the last step (include/dampbound/physics/bounds.hpp NodeStatus),
// shared by the GL renderer, the legend and the tests. No GL.
#include <imgui.h>

#include <cstddef>

#include "dampbound/physics/bounds.hpp"

namespace dampbound::ui {

/// Colour of a node in `status` (IM_COL32 layout, opaque).
ImU32 status_color(NodeStatus status);

/// Legend text of a status, e.g. "within bounds".
const char* status_label(NodeStatus status);

/// Legend explanation, e.g. "effective gamma < lower bound or > upper bound".
const char* status_help(NodeStatus status);

/// SPEC 9: a node where critical damping cannot be guaranteed at this dt (gamma_lo_i >
/// gamma_safe_i) is drawn in this colour unless the paper's runtime check calls it
/// unstabilisable or it is fixed; its legend text and explanation.
ImU32 unguaranteed_color();
const char* unguaranteed_label();
const char* unguaranteed_help();

/// The node's colour: status_color, or unguaranteed_color as above.
ImU32 node_color(NodeStatus status, bool unguaranteed);

/// A node coloured by a value t in [0, 1] instead of its state (SPEC 11's added mass over the
/// largest): dark slate at 0, through violet, to a warm yellow at 1; 0 exactly (no mass added)
/// stays dim grey so that the scaled nodes stand out.
ImU32 shade_color(float t);

/// A mesh with more springs than this is big: while it plays, its image is made cheaper
/// (mesh_samples, springs_drawn), what a software rasteriser (llvmpipe) pays on every frame.
constexpr size_t kBigMeshSprings = 20000;

/// Samples per pixel of the mesh image. Springs closer than 5 px alias into moire, which 4x
/// multisampling smooths, at four times the fill rate: a big mesh (kBigMeshSprings) is drawn
/// with 1 sample while it plays (motion hides the moire) and 4 again when paused.
int mesh_samples(float spring_spacing_px, size_t springs, bool playing);

/// Opacity of the springs drawn `spring_spacing_px` apart (median projected length): 1 from
/// 5.5 px on, fading below, down to kFaintestSprings (lines closer than ~5 px alias into
/// moire; the fade keeps the nodes' colours readable through them).
constexpr float kFaintestSprings = 0.15f;
float spring_alpha(float spring_spacing_px);

/// Whether the springs are drawn. A big mesh (over kBigMeshSprings springs)
/// whose springs are at their faintest (spring_alpha) leaves them out while it plays: lines
/// that close cannot be told apart, and a software rasteriser pays for each one (about 20 ms
/// of a frame for the 119 201 springs of a 200 x 200 plane on llvmpipe, docs/performance.md).
/// Paused, or zoomed in, they are drawn again.
bool springs_drawn(bool shown, float spring_spacing_px, size_t springs, bool playing);

/// Colour of the springs and of the watched-node marker.
ImU32 spring_color();
ImU32 watched_color();

}  // namespace dampbound::ui
