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

namespace {

// One packet of N rays through rtcIntersectN (RayHitN: RTCRayHit8 or RTCRayHit16).
template <int N, typename RayHitN, typename IntersectN>
void trace_packet(RTCScene scene, IntersectN intersect, int count, const glm::vec3* org, const glm::vec3* dir,
                  const float* tmin, const float* tmax, EmbreeHit* out) {
  alignas(64) int valid[N];
  alignas(64) RayHitN rh;
  for (int i = 0; i < N; ++i) {
    const bool live = i < count;
    valid[i] = live ? -1 : 0;
    const int k = live ? i : 0;
    rh.ray.org_x[i] = org[k].x, rh.ray.org_y[i] = org[k].y, rh.ray.org_z[i] = org[k].z;
    rh.ray.dir_x[i] = dir[k].x, rh.ray.dir_y[i] = dir[k].y, rh.ray.dir_z[i] = dir[k].z;
    rh.ray.tnear[i] = tmin[k];
    rh.ray.tfar[i] = tmax[k];
    rh.ray.mask[i] = ~0u;
    rh.ray.time[i] = 0.0f;
    rh.ray.flags[i] = 0;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  intersect(valid, scene, &context, &rh);
  for (int i = 0; i < count; ++i)
    out[i] = rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID
                 ? EmbreeHit{tmax[i], 0.0f, 0.0f, -1}
                 : EmbreeHit{rh.ray.tfar[i], rh.hit.u[i], rh.hit.v[i], int(rh.hit.primID[i])};
}

}  // namespace

void EmbreeScene::intersect_packet(int width, int count, const glm::vec3* org, const glm::vec3* dir,
                                   const float* tmin, const float* tmax, EmbreeHit* out) const {
  if (width == 16 && count <= 16)
    trace_packet<16, RTCRayHit16>(scene_, rtcIntersect16, count, org, dir, tmin, tmax, out);
  else if (width == 8 && count <= 8)
    trace_packet<8, RTCRayHit8>(scene_, rtcIntersect8, count, org, dir, tmin, tmax, out);
  else
    throw Error("Embree packets hold 8 or 16 rays, not " + std::to_string(count) + " of " + std::to_string(width));
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
