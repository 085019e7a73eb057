#pragma once
// The kitchen: 5 rigid parts, about 80k vertices — the room (floor sheet and
// counter block), a teapot (lathe body with lid and knob, spout, ring
// handle), a bowl, a cup with handle, and a chair. The teapot slides and turns
// on the counter and the cup circles, in a 4-second loop.
#include "tools/assets/model.h"

namespace rsl::assets {

inline constexpr float kKitchenLoopSeconds = 4.0f;
inline constexpr float kCounterTop = 0.9f;  // height of the counter's top face (m)

// Nodes: room (root; its part is the open floor sheet plus the counter),
// teapot, bowl, cup (children of room, on the counter top), chair (on the floor).
GeneratedModel make_kitchen();
// The kitchen's teapot on its own (teapot.obj: instanced.json, two-objs-animated.json).
TriangleMesh make_teapot();

}  // namespace rsl::assets
