#pragma once
// A skinned tube that bends: a capsule standing on y = 0 along +Y, its
// skeleton a chain of joints up its axis, each joint after the first bending
// it about Z in a loop. The project's own skinned asset (docs/design/SKINNING.md):
// the tests bend a two-joint tube to 90°, the demo scene (assets/scenes/tube.json)
// a three-joint one that also turns about its base.
#include "tools/assets/model.h"

namespace rsl::assets {

struct TubeOptions {
    std::string name = "tube";
    float radius = 0.1f;
    float length = 1.2f;     // base to tip (y = 0 to y = length at rest)
    int joints = 2;          // joint k sits at y = k · length / joints
    float spacing = 0.02f;   // vertex spacing of the capsule
    float blend = 0.08f;     // weights ramp (smoothstep) over ±blend about each joint but the first
    float bend_degrees = 90;  // the whole tube's bend at half the period, shared by the joints after the first
    float period = 2;        // seconds; at t = 0 (and every period) the tube stands straight
    float turn_degrees = 0;  // the base turns about +Y by turn_degrees · sin(2π t / period)
    Vec3 position{0};        // the root joint's position (the mesh and its bind matrices do not depend on it)
};

// The tube: one root joint node (named "<name>_joint0", parent of the chain
// "<name>_joint1" …) and one GeneratedSkin named `name`.
GeneratedModel make_bending_tube(const TubeOptions& options = {});
// Adds a tube to a model (several tubes of one shape share their segments' fields).
void add_bending_tube(GeneratedModel& model, const TubeOptions& options);

// The demo's tube (assets/generated/tube.glb): three joints, a 100° bend, its
// base turning ±40°.
TubeOptions demo_tube_options();

}  // namespace rsl::assets
