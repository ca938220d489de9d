// Manual camera control for a World (the `lantern play` fly camera), with no windowing here: the
// app translates its device input into a FlyCameraInput each frame and the world.fly_camera
// system (Simulate phase, after world.camera_path) moves the camera entity with it. Because the
// camera moves through the World, world.camera_history latches the previous camera as for any
// other motion: motion vectors stay right and no camera cut is requested (resume_camera_path
// teleports, so it requests one).
//
//   enable_fly_camera(world);                      // once, before the first step()
//   take_manual_control(world);                    // detaches the camera from its path
//   fly_camera_input(world) = {.move = {0, 0, 1}}; // forward at the current speed
//   world.step();
//   resume_camera_path(world);                     // back on the level's path (a cut)
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace lantern {

class World;

// One frame of input, in the camera's frame. Cleared by the app each frame (not by the system).
struct FlyCameraInput {
  glm::vec3 move{0.0f};  // -1..1 per axis: x right, y up (world up), z forward
  float yaw = 0.0f;      // radians to turn this frame, positive = to the left (counter-clockwise
                         // seen from above)
  float pitch = 0.0f;    // radians, positive = look up; the result is clamped to +-89 degrees
  float boost = 1.0f;    // speed multiplier (e.g. Shift)
  float dt = 0.0f;       // seconds this input covers; 0 = the frame's simulated dt
};

// The fly camera's state: a World resource created by enable_fly_camera.
struct FlyCamera {
  bool active = false;  // true while the camera is under manual control
  float speed = 2.0f;   // metres per second at boost 1
  float yaw = 0.0f;     // radians, 0 = looking down -Z
  float pitch = 0.0f;   // radians
  FlyCameraInput input;
};

// Adds the FlyCamera resource and the world.fly_camera system (call before the first step()).
void enable_fly_camera(World& world);
FlyCamera& fly_camera(World& world);

// Manual control from the camera's current pose on: the path stops driving it.
void take_manual_control(World& world);
// Back on the level's camera path at the current time: a teleport, so the next frame is a cut.
void resume_camera_path(World& world);

// yaw/pitch (radians) of a camera orientation, and back (no roll).
glm::vec2 yaw_pitch_of(const glm::quat& orientation);
glm::quat orientation_of(float yaw, float pitch);

inline FlyCameraInput& fly_camera_input(World& world) {
  return fly_camera(world).input;
}

}  // namespace lantern
