// The built-in default scene: the Cornell box (measured geometry, millimetres), lit by its ceiling light.
#pragma once
#include "scene/scene.h"

namespace rcsplat {
Scene make_cornell_box();
}
