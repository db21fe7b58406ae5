// Camera moves of the viewer, as plain functions on cutaway::Camera so that the mouse, the
// keys and the script (`orbit 30 10`) share them and tests can check them without a window.
//
// Orbit turns the eye around the target; pan moves both in the view plane; zoom moves the
// eye towards the target (perspective) or shrinks the view's height (orthographic); fly
// moves both along the view's axes and look turns the target around the eye.
//
//   cutaway::view::orbit(camera, 30.0f, 10.0f);        // degrees: yaw about up, pitch
//   cutaway::view::frameBounds(camera, selectionBounds, aspect);
#pragma once

#include "cutaway/geometry/mesh.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway::view {

// The eye's elevation stays this far from the up axis, so that `up` never becomes parallel
// to the viewing direction (the scene format rejects such a camera).
constexpr float kMinPolarDegrees = 1.0f;

// Turns the eye about the target (degrees): a positive yaw carries it towards the view's right
// (about `up`), a positive pitch raises it (about the view's right axis).
void orbit(Camera& camera, float yawDegrees, float pitchDegrees);
// Turns the gaze about the eye (fly mode's mouse look): positive yaw looks right, positive
// pitch looks up.
void look(Camera& camera, float yawDegrees, float pitchDegrees);
// Moves eye and target in the view plane by (dx, dy) view heights at the target's distance
// (so a drag across the whole view moves the scene with the cursor).
void pan(Camera& camera, float dx, float dy);
// factor > 1 comes closer (perspective: distance / factor; orthographic: height / factor).
void zoom(Camera& camera, float factor);
// Moves eye and target by `move` in view axes (x right, y up, z forward), world units.
void fly(Camera& camera, const glm::vec3& move);
// Aims at the bounds' centre and backs off (or sets the height) so that their bounding
// sphere fills the view with a small margin, keeping the viewing direction.
void frameBounds(Camera& camera, const Bounds& bounds, float aspect);

}  // namespace cutaway::view
