#include "scene/cornell_box.h"

namespace rcsplat {

Scene make_cornell_box() {
  Scene s;
  s.source = "built-in Cornell box";
  // Reflectances: the Cornell measured spectra reduced to linear sRGB (as in ../shared/scenes/cornell_box).
  enum : uint32_t { kWhite, kRed, kGreen, kLight };
  SceneMaterial white{"white", {0.738f, 0.736f, 0.737f, 1.0f}, -1, {0, 0, 0}, false};
  SceneMaterial red{"red", {0.472f, 0.047f, 0.049f, 1.0f}, -1, {0, 0, 0}, false};
  SceneMaterial green{"green", {0.088f, 0.398f, 0.084f, 1.0f}, -1, {0, 0, 0}, false};
  SceneMaterial light{"light", {0.78f, 0.78f, 0.78f, 1.0f}, -1, {17.2f, 11.5f, 3.06f}, false};
  s.materials = {white, red, green, light};

  using v = glm::vec3;
  // Floor, ceiling, back wall (white); left wall red (x = 556), right wall green (x = 0); normals face the inside.
  s.add_quad(v(552.8f, 0, 0), v(0, 0, 0), v(0, 0, 559.2f), v(549.6f, 0, 559.2f), kWhite);
  s.add_quad(v(556, 548.8f, 0), v(556, 548.8f, 559.2f), v(0, 548.8f, 559.2f), v(0, 548.8f, 0), kWhite);
  s.add_quad(v(549.6f, 0, 559.2f), v(0, 0, 559.2f), v(0, 548.8f, 559.2f), v(556, 548.8f, 559.2f), kWhite);
  s.add_quad(v(0, 0, 559.2f), v(0, 0, 0), v(0, 548.8f, 0), v(0, 548.8f, 559.2f), kGreen);
  s.add_quad(v(552.8f, 0, 0), v(549.6f, 0, 559.2f), v(556, 548.8f, 559.2f), v(556, 548.8f, 0), kRed);
  // The light, slightly below the ceiling so that it is not coplanar with it, facing down.
  s.add_quad(v(343, 548.7f, 227), v(343, 548.7f, 332), v(213, 548.7f, 332), v(213, 548.7f, 227), kLight);
  // Short block.
  s.add_quad(v(130, 165, 65), v(82, 165, 225), v(240, 165, 272), v(290, 165, 114), kWhite);
  s.add_quad(v(290, 0, 114), v(290, 165, 114), v(240, 165, 272), v(240, 0, 272), kWhite);
  s.add_quad(v(130, 0, 65), v(130, 165, 65), v(290, 165, 114), v(290, 0, 114), kWhite);
  s.add_quad(v(82, 0, 225), v(82, 165, 225), v(130, 165, 65), v(130, 0, 65), kWhite);
  s.add_quad(v(240, 0, 272), v(240, 165, 272), v(82, 165, 225), v(82, 0, 225), kWhite);
  // Tall block.
  s.add_quad(v(423, 330, 247), v(265, 330, 296), v(314, 330, 456), v(472, 330, 406), kWhite);
  s.add_quad(v(423, 0, 247), v(423, 330, 247), v(472, 330, 406), v(472, 0, 406), kWhite);
  s.add_quad(v(472, 0, 406), v(472, 330, 406), v(314, 330, 456), v(314, 0, 456), kWhite);
  s.add_quad(v(314, 0, 456), v(314, 330, 456), v(265, 330, 296), v(265, 0, 296), kWhite);
  s.add_quad(v(265, 0, 296), v(265, 330, 296), v(423, 330, 247), v(423, 0, 247), kWhite);

  SceneCamera cam;
  cam.eye = v(278, 273, -800);
  cam.target = v(278, 273, 0);
  cam.up = v(0, 1, 0);
  cam.yfov = 0.6860488f;  // 39.3 degrees
  cam.aspect = 1.0f;
  s.cameras.push_back(cam);
  return s;
}

}  // namespace rcsplat
