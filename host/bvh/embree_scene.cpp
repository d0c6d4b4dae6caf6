#include "bvh/embree_scene.h"

#include "bvh/embree_device.h"
#include "util/error.h"

namespace rcsplat {

EmbreeScene::EmbreeScene(const std::vector<glm::vec3>& positions) {
  scene_ = rtcNewScene(embree_device());
  check_embree("creating a scene");
  try {
    build(positions);
  } catch (...) {
    rtcReleaseScene(scene_);
    throw;
  }
}

void EmbreeScene::build(const std::vector<glm::vec3>& positions) {
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  size_t triangles = positions.size() / 3;
  RTCGeometry geom = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), std::max<size_t>(positions.size(), 3)));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), std::max<size_t>(triangles, 1)));
  check_embree("allocating the geometry buffers of " + std::to_string(triangles) + " triangles");
  if (!vertices || !indices) throw Error("Embree could not allocate the geometry buffers");
  for (size_t i = 0; i < positions.size(); ++i) {
    vertices[3 * i] = positions[i].x;
    vertices[3 * i + 1] = positions[i].y;
    vertices[3 * i + 2] = positions[i].z;
  }
  for (size_t i = 0; i < 3 * triangles; ++i) indices[i] = unsigned(i);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene_, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene_);
  check_embree("committing the scene of " + std::to_string(triangles) + " triangles");
}

EmbreeScene::~EmbreeScene() { rtcReleaseScene(scene_); }

EmbreeHit EmbreeScene::intersect(const glm::vec3& org, const glm::vec3& dir, float tmin, float tmax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = org.x, rh.ray.org_y = org.y, rh.ray.org_z = org.z;
  rh.ray.dir_x = dir.x, rh.ray.dir_y = dir.y, rh.ray.dir_z = dir.z;
  rh.ray.tnear = tmin;
  rh.ray.tfar = tmax;
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {tmax, 0.0f, 0.0f, -1};
  return {rh.ray.tfar, rh.hit.u, rh.hit.v, int(rh.hit.primID)};
}

bool EmbreeScene::occluded(const glm::vec3& org, const glm::vec3& dir, float tmin, float tmax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = org.x, ray.org_y = org.y, ray.org_z = org.z;
  ray.dir_x = dir.x, ray.dir_y = dir.y, ray.dir_z = dir.z;
  ray.tnear = tmin;
  ray.tfar = tmax;
  ray.mask = ~0u;
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar < 0.0f;  // Embree marks an occluded ray with tfar = -inf
}

}  // namespace rcsplat
