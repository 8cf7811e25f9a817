// Scene: recentres a Mesh in double precision and builds an Embree BVH.
//
// Every Scene shares one Embree device (a device owns the thread pool and
// memory accounting; one per scene would start a pool per scene).  Embree
// reports failures through the device's error callback, whose message is
// kept and put into the exception the failing call throws.
#include "embree_ray.hpp"
#include "scene_access.hpp"

#include <attenuvis/visgraph/limits.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>

namespace attenuvis::visgraph {

namespace {

// Embree's last error message (its callback may run on a worker thread).
std::mutex embree_message_mutex;
std::string embree_message;

void remember_embree_error(void* /*user*/, RTCError code, const char* text) {
  const std::lock_guard<std::mutex> lock(embree_message_mutex);
  embree_message = "Embree error " + std::to_string(static_cast<int>(code)) + (text ? std::string(": ") + text : "");
}

std::string last_embree_message() {
  const std::lock_guard<std::mutex> lock(embree_message_mutex);
  return embree_message.empty() ? std::string("no message from Embree") : embree_message;
}

std::string embree_error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unknown error";
  }
}

// The process's Embree device, made on first use; each Scene holds a
// reference, so the device outlives every scene whatever the order of
// static destruction.
std::shared_ptr<RTCDeviceTy> shared_device() {
  static const std::shared_ptr<RTCDeviceTy> device = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d)
      throw std::runtime_error("scene: Embree device could not be created (" +
                               embree_error_name(rtcGetDeviceError(nullptr)) + ")");
    rtcSetDeviceErrorFunction(d, remember_embree_error, nullptr);
    return std::shared_ptr<RTCDeviceTy>(d, rtcReleaseDevice);
  }();
  return device;
}

}  // namespace

struct Scene::Impl {
  std::shared_ptr<RTCDeviceTy> device;
  RTCScene scene = nullptr;
  std::size_t triangles = 0;
  BoundingBox bounds;
  Eigen::Vector3d origin{0, 0, 0};
  std::vector<GroupInfo> groups, classes;
  std::vector<std::uint32_t> triangle_group, triangle_class;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
  }
};

Scene::Scene(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
  if (mesh.triangles.empty() || mesh.vertices.empty())
    throw std::invalid_argument("scene is empty: the mesh has no triangles");
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite())
      throw std::invalid_argument("scene: vertex " + std::to_string(v + 1) + " is not finite");
    else
      for (int c = 0; c < 3; ++c) check_coordinate(mesh.vertices[v][c], "scene: vertex " + std::to_string(v + 1));
  BoundingBox box{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
                  Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::uint32_t index : mesh.triangles[t]) {
      if (index >= mesh.vertices.size())
        throw std::invalid_argument("scene: triangle " + std::to_string(t + 1) + " refers to missing vertex " +
                                    std::to_string(index + 1));
      box.min = box.min.cwiseMin(mesh.vertices[index]);
      box.max = box.max.cwiseMax(mesh.vertices[index]);
    }
  impl_->bounds = box;
  impl_->origin = box.centre();
  impl_->triangles = mesh.triangles.size();
  impl_->triangle_group = mesh.triangle_group;
  impl_->triangle_group.resize(mesh.triangles.size(), 0);
  impl_->groups.resize(std::max<std::size_t>(mesh.groups.size(), 1));
  for (std::size_t g = 0; g < mesh.groups.size(); ++g) impl_->groups[g].name = mesh.groups[g];
  for (std::uint32_t& g : impl_->triangle_group) {
    if (g >= impl_->groups.size()) g = 0;
    ++impl_->groups[g].triangles;
  }
  if (mesh.triangle_class.size() == mesh.triangles.size() && !mesh.classes.empty()) {
    impl_->triangle_class = mesh.triangle_class;
    impl_->classes.resize(mesh.classes.size());
    for (std::size_t c = 0; c < mesh.classes.size(); ++c) impl_->classes[c].name = mesh.classes[c];
    for (std::uint32_t& c : impl_->triangle_class) {
      if (c >= impl_->classes.size())
        throw std::invalid_argument("scene: a triangle's class index is out of range");
      ++impl_->classes[c].triangles;
    }
  }

  impl_->device = shared_device();
  RTCDevice device = impl_->device.get();
  rtcGetDeviceError(device);  // clears an error left on this thread by an earlier failure
  impl_->scene = rtcNewScene(device);
  if (!impl_->scene) throw std::runtime_error("scene: Embree could not create a scene: " + last_embree_message());
  // ROBUST: a segment grazing the shared edge of two wall triangles must not
  // slip through the crack (it would add a false line of sight).
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (!geometry) throw std::runtime_error("scene: Embree could not create the geometry: " + last_embree_message());
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.vertices.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
  if (!vertices || !indices) {
    rtcReleaseGeometry(geometry);
    throw std::runtime_error("scene: Embree could not allocate the geometry buffers (" +
                             std::to_string(mesh.triangles.size()) + " triangles): " + last_embree_message());
  }
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Eigen::Vector3d local = mesh.vertices[v] - impl_->origin;  // subtract in double, round once
    for (int c = 0; c < 3; ++c) vertices[3 * v + c] = static_cast<float>(local[c]);
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) indices[3 * t + c] = mesh.triangles[t][c];
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl_->scene);
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE)
    throw std::runtime_error("scene: Embree failed to build the BVH (" + embree_error_name(error) +
                             "): " + last_embree_message());
}

Scene::~Scene() = default;

std::size_t Scene::triangle_count() const { return impl_->triangles; }
const BoundingBox& Scene::bounds() const { return impl_->bounds; }
const Eigen::Vector3d& Scene::origin() const { return impl_->origin; }
const std::vector<GroupInfo>& Scene::groups() const { return impl_->groups; }
std::uint32_t Scene::triangle_group(std::size_t triangle) const { return impl_->triangle_group.at(triangle); }
const std::vector<GroupInfo>& Scene::classes() const { return impl_->classes; }
std::uint32_t Scene::triangle_class(std::size_t triangle) const {
  return impl_->triangle_class.empty() ? kNoClass : impl_->triangle_class.at(triangle);
}
RTCScene detail::SceneAccess::embree(const Scene& scene) { return scene.impl_->scene; }

Scene::Hit Scene::intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_near, double t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = detail::embree_ray(o.data(), d.data(), t_near, t_far);
  rtcIntersect1(impl_->scene, &context, &rh);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.found = true;
  hit.t = rh.ray.tfar;
  hit.normal = Eigen::Vector3d(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  const double n = hit.normal.norm();
  if (n > 0) hit.normal /= n;
  hit.triangle = rh.hit.primID;
  return hit;
}

bool Scene::occluded(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double end_gap) const {
  const Eigen::Vector3d d = b - a;
  const double length = d.norm();
  if (!(length > 2 * end_gap)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = static_cast<float>(a.x());
  ray.org_y = static_cast<float>(a.y());
  ray.org_z = static_cast<float>(a.z());
  ray.dir_x = static_cast<float>(d.x());
  ray.dir_y = static_cast<float>(d.y());
  ray.dir_z = static_cast<float>(d.z());
  ray.tnear = static_cast<float>(end_gap / length);
  ray.tfar = static_cast<float>(1.0 - end_gap / length);
  ray.mask = 0xFFFFFFFFu;
  rtcOccluded1(impl_->scene, &context, &ray);
  return ray.tfar < 0;  // Embree sets tfar = -inf when something is hit
}

std::string describe(const Scene& scene) {
  std::ostringstream out;
  const BoundingBox& b = scene.bounds();
  out.precision(10);
  out << scene.triangle_count() << " triangles; bounding box [" << b.min.x() << ", " << b.max.x() << "] x ["
      << b.min.y() << ", " << b.max.y() << "] x [" << b.min.z() << ", " << b.max.z() << "] m; ";
  // A city model may hold thousands of groups: a count and the first few.
  const auto names = [](const std::vector<GroupInfo>& list) {
    std::vector<std::string> out;
    for (const GroupInfo& g : list) out.push_back((g.name.empty() ? "(default)" : g.name) + " (" + std::to_string(g.triangles) + ")");
    return out;
  };
  out << scene.groups().size() << " groups: " << preview_names(names(scene.groups()));
  if (!scene.classes().empty()) out << "; " << scene.classes().size() << " classes: " << preview_names(names(scene.classes()), 12);
  return out.str();
}

}  // namespace attenuvis::visgraph
