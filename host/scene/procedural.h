// Generated scenes for tests and for benchmarks when the real scenes are absent.
#pragma once
#include <cstdint>

#include "scene/scene.h"

namespace rcsplat {

// A closed room holding `boxes` randomly placed, rotated boxes (12 triangles each), a camera inside and a point light.
Scene make_box_room(int boxes, uint32_t seed);

// A closed, watertight sphere of 20 * 4^subdivisions triangles with shared vertices, its radius displaced by a wave of
// relative amplitude bump; a smooth one (bump 0) gets radial vertex normals.
Scene make_icosphere(int subdivisions, float radius, float bump);
// make_icosphere with a wave of amplitude 0.08.
Scene make_bumpy_sphere(int subdivisions, float radius);

}  // namespace rcsplat
