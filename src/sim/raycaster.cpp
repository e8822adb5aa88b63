#include "litamin2/sim/raycaster.hpp"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "litamin2/sim/continuous_trajectory.hpp"
#include "litamin2/sim/random.hpp"

namespace litamin2::sim {
namespace {

void embree_error(void* /*user*/, RTCError code, const char* str) {
  // Must not throw through Embree's C frames; report instead.
  if (code != RTC_ERROR_NONE)
    std::fprintf(stderr, "Embree error %d: %s\n", static_cast<int>(code), str ? str : "");
}

struct Tile {
  RTCScene scene = nullptr;    // instancing mode: the tile's own scene
  RTCGeometry geom = nullptr;  // flat mode: the tile's triangle geometry
  std::vector<Material> materials;
  std::vector<float> reflectivity;
  unsigned instance = RTC_INVALID_GEOMETRY_ID;  // id in the top scene when active
  std::uint64_t last_used = 0;
};

/// A new Embree triangle geometry holding `mesh`, one time step per pose in `poses` (vertices
/// moved by the pose; none = one step with the vertices as they are). Committed; the caller
/// owns the reference.
RTCGeometry new_mesh_geometry(RTCDevice device, const TriangleMesh& mesh,
                              const std::vector<Eigen::Isometry3f>& poses = {}) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const unsigned steps = poses.empty() ? 1u : static_cast<unsigned>(poses.size());
  if (steps > 1) rtcSetGeometryTimeStepCount(g, steps);
  for (unsigned step = 0; step < steps; ++step) {
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, step,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          mesh.vertices.size()));
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      const Eigen::Vector3f w = poses.empty() ? mesh.vertices[i] : poses[step] * mesh.vertices[i];
      v[3 * i] = w.x();
      v[3 * i + 1] = w.y();
      v[3 * i + 2] = w.z();
    }
  }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) idx[3 * i + k] = mesh.triangles[i][k];
  }
  rtcCommitGeometry(g);
  return g;
}

}  // namespace

struct Raycaster::Impl {
  const World& world;
  RaycasterOptions opt;
  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  std::map<TileKey, Tile> tiles;
  std::vector<const Tile*> by_instance;  // instance geometry id -> tile
  std::uint64_t clock = 0;
  std::size_t active = 0, active_tris = 0;

  Impl(const World& w, const RaycasterOptions& o) : world(w), opt(o) {
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("Embree: cannot create device");
    rtcSetDeviceErrorFunction(device, embree_error, nullptr);
    top = rtcNewScene(device);
    rtcCommitScene(top);
  }

  ~Impl() {
    for (auto& [k, t] : tiles) {
      (void)k;
      release(t);
    }
    if (top) rtcReleaseScene(top);
    if (device) rtcReleaseDevice(device);
  }

  static void release(Tile& t) {
    if (t.scene) rtcReleaseScene(t.scene);
    if (t.geom) rtcReleaseGeometry(t.geom);
    t.scene = nullptr;
    t.geom = nullptr;
  }

  Tile make_tile(const TriangleMesh& mesh) {
    Tile t;
    if (opt.instancing) {
      t.scene = rtcNewScene(device);
      rtcSetSceneBuildQuality(t.scene, RTC_BUILD_QUALITY_MEDIUM);
    }
    if (!mesh.empty()) {
      RTCGeometry g = new_mesh_geometry(device, mesh);
      if (opt.instancing) {
        rtcAttachGeometryByID(t.scene, g, 0);
        rtcReleaseGeometry(g);
      } else {
        t.geom = g;  // keeps the reference
      }
    }
    if (t.scene) rtcCommitScene(t.scene);
    t.materials = mesh.materials;
    t.reflectivity = mesh.reflectivity;
    return t;
  }

  void prepare(const Eigen::Vector3d& position, double range) {
    ++clock;
    const auto needed = world.tiles_near(position.head<2>(), range + world.max_object_radius());
    // Build the missing tiles' meshes in parallel, then their Embree scenes.
    std::vector<TileKey> missing;
    for (const auto& k : needed) {
      if (!tiles.count(k)) missing.push_back(k);
    }
    std::vector<TriangleMesh> meshes(missing.size());
    auto build = [&](std::size_t i) { meshes[i] = world.build_tile(missing[i]); };
    if (opt.parallel) {
      tbb::parallel_for(std::size_t{0}, missing.size(), build);
    } else {
      for (std::size_t i = 0; i < missing.size(); ++i) build(i);
    }
    for (std::size_t i = 0; i < missing.size(); ++i) {
      tiles.emplace(missing[i], make_tile(meshes[i]));
      meshes[i] = TriangleMesh();
    }
    bool changed = false;
    std::vector<bool> keep_flags;
    // Mark needed tiles.
    std::map<TileKey, bool> need;
    for (const auto& k : needed) need[k] = true;
    for (auto& [k, t] : tiles) {
      const bool n = need.count(k) > 0;
      if (n) t.last_used = clock;
      if (n && t.instance == RTC_INVALID_GEOMETRY_ID && (t.scene || t.geom)) {
        if (opt.instancing) {
          RTCGeometry inst = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
          rtcSetGeometryInstancedScene(inst, t.scene);
          const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
          rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
          rtcCommitGeometry(inst);
          t.instance = rtcAttachGeometry(top, inst);
          rtcReleaseGeometry(inst);
        } else {
          t.instance = rtcAttachGeometry(top, t.geom);
        }
        if (by_instance.size() <= t.instance) by_instance.resize(t.instance + 1, nullptr);
        by_instance[t.instance] = &t;
        changed = true;
      } else if (!n && t.instance != RTC_INVALID_GEOMETRY_ID) {
        rtcDetachGeometry(top, t.instance);
        by_instance[t.instance] = nullptr;
        t.instance = RTC_INVALID_GEOMETRY_ID;
        changed = true;
      }
    }
    if (changed) rtcCommitScene(top);
    // Evict least recently used inactive tiles beyond the cache size.
    if (tiles.size() > opt.max_cached_tiles) {
      std::vector<std::pair<std::uint64_t, TileKey>> inactive;
      for (const auto& [k, t] : tiles) {
        if (t.instance == RTC_INVALID_GEOMETRY_ID) inactive.push_back({t.last_used, k});
      }
      std::sort(inactive.begin(), inactive.end());
      std::size_t excess = tiles.size() - opt.max_cached_tiles;
      for (std::size_t i = 0; i < inactive.size() && excess > 0; ++i, --excess) {
        auto it = tiles.find(inactive[i].second);
        release(it->second);
        tiles.erase(it);
      }
    }
    active = 0;
    active_tris = 0;
    for (const auto& [k, t] : tiles) {
      (void)k;
      if (t.instance != RTC_INVALID_GEOMETRY_ID) {
        ++active;
        active_tris += t.materials.size();
      }
    }
  }

  /// Casts one ray; fills hit and returns true on a hit.
  bool intersect(const Eigen::Vector3f& o, const Eigen::Vector3f& d, float tfar,
                 RTCIntersectContext* ctx, float& t, Eigen::Vector3f& n, const Tile*& tile,
                 unsigned& prim) const {
    RTCRayHit rh;
    rh.ray.org_x = o.x();
    rh.ray.org_y = o.y();
    rh.ray.org_z = o.z();
    rh.ray.dir_x = d.x();
    rh.ray.dir_y = d.y();
    rh.ray.dir_z = d.z();
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = tfar;
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(top, ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    t = rh.ray.tfar;
    n = Eigen::Vector3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    const float len = n.norm();
    n = len > 0 ? Eigen::Vector3f(n / len) : Eigen::Vector3f::UnitZ();
    if (n.dot(d) > 0) n = -n;
    const unsigned inst = opt.instancing ? rh.hit.instID[0] : rh.hit.geomID;
    tile = inst < by_instance.size() ? by_instance[inst] : nullptr;
    prim = rh.hit.primID;
    return tile != nullptr && prim < tile->materials.size();
  }
};

Raycaster::Raycaster(const World& world, const RaycasterOptions& options)
    : impl_(std::make_unique<Impl>(world, options)) {}

Raycaster::~Raycaster() = default;

void Raycaster::prepare(const Eigen::Vector3d& position, double range) {
  impl_->prepare(position, range);
}

std::optional<RayHit> Raycaster::cast(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction, double max_range) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  float t;
  Eigen::Vector3f n;
  const Tile* tile = nullptr;
  unsigned prim = 0;
  const Eigen::Vector3f d = direction.normalized().cast<float>();
  if (!impl_->intersect(origin.cast<float>(), d, static_cast<float>(max_range), &ctx, t, n, tile,
                        prim)) {
    return std::nullopt;
  }
  RayHit hit;
  hit.range = t;
  hit.normal = n.cast<double>();
  hit.material = tile->materials[prim];
  hit.reflectivity = tile->reflectivity[prim];
  return hit;
}

PointCloud Raycaster::scan(const Eigen::Isometry3d& sensor_pose, const LidarModel& model,
                           std::uint64_t scan_seed) {
  SweepRequest request;
  request.start = request.end = sensor_pose;
  return scan(request, model, SensorRig{}, scan_seed).cloud;
}

namespace {

/// The moving actors near one sweep as an Embree scene with one triangle geometry per actor
/// (two time steps, sweep start and end, when the sweep has motion). Released on destruction.
struct DynamicScene {
  RTCScene scene = nullptr;
  /// Mesh of each geometry id (materials and reflectivities).
  std::vector<const TriangleMesh*> meshes;

  DynamicScene(RTCDevice device, const Traffic& traffic, const Eigen::Vector3d& position,
               double radius, double t0, double t1, bool motion) {
    const auto actors = traffic.near(position, radius, t0);
    if (actors.empty()) return;
    scene = rtcNewScene(device);
    for (std::size_t actor : actors) {
      const TriangleMesh& mesh = traffic.mesh(actor);
      if (mesh.empty()) continue;
      std::vector<Eigen::Isometry3f> poses{traffic.pose(actor, t0).cast<float>()};
      if (motion) poses.push_back(traffic.pose(actor, t1).cast<float>());
      RTCGeometry g = new_mesh_geometry(device, mesh, poses);
      const unsigned id = rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
      if (meshes.size() <= id) meshes.resize(id + 1, nullptr);
      meshes[id] = &mesh;
    }
    rtcCommitScene(scene);
  }
  ~DynamicScene() {
    if (scene) rtcReleaseScene(scene);
  }
  DynamicScene(const DynamicScene&) = delete;
  DynamicScene& operator=(const DynamicScene&) = delete;
};

/// Rank of each beam's elevation from the lowest (the driver's ring number).
std::vector<std::uint16_t> ring_numbers(const std::vector<double>& elevations_deg) {
  std::vector<std::uint16_t> rings(elevations_deg.size(), 0);
  for (std::size_t b = 0; b < elevations_deg.size(); ++b) {
    for (std::size_t o = 0; o < elevations_deg.size(); ++o) {
      if (elevations_deg[o] < elevations_deg[b] ||
          (elevations_deg[o] == elevations_deg[b] && o > b)) {
        ++rings[b];
      }
    }
  }
  return rings;
}

}  // namespace

SimulatedScan Raycaster::scan(const SweepRequest& request, const LidarModel& model,
                              const SensorRig& rig, std::uint64_t scan_seed) {
  rig.validate();
  const bool motion = rig.sweep.motion;
  const bool tilted = !rig.mount.is_identity();
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.linear() = rig.mount.rotation();
  if (motion) {
    const Eigen::Vector3d a = request.start.translation(), b = request.end.translation();
    impl_->prepare(0.5 * (a + b), model.max_range + 0.5 * (b - a).norm());
  } else {
    impl_->prepare(request.start.translation(), model.max_range);
  }
  const int beams = static_cast<int>(model.beams());
  const int steps = model.azimuth_steps;
  std::vector<float> cos_el(beams), sin_el(beams), cos_az(steps), sin_az(steps);
  for (int b = 0; b < beams; ++b) {
    const double e = model.elevations_deg[b] * M_PI / 180.0;
    cos_el[b] = static_cast<float>(std::cos(e));
    sin_el[b] = static_cast<float>(std::sin(e));
  }
  for (int a = 0; a < steps; ++a) {
    const double az = rig.sweep.column_azimuth(a, steps);
    cos_az[a] = static_cast<float>(std::cos(az));
    sin_az[a] = static_cast<float>(std::sin(az));
  }
  // Sensor pose of each column (one for all without motion): world rotation and origin. A
  // point stays in the sensor frame of its own firing, as LiDAR drivers publish them (not
  // motion-compensated), so a sweep with motion is distorted until it is deskewed with the
  // points' times.
  const Eigen::Isometry3d reference = tilted ? request.start * mount : request.start;
  const std::size_t n_poses = motion ? static_cast<std::size_t>(steps) : 1;
  std::vector<Eigen::Matrix3f> col_R(n_poses);
  std::vector<Eigen::Vector3f> col_origin(n_poses);
  for (std::size_t a = 0; a < n_poses; ++a) {
    Eigen::Isometry3d sensor = reference;
    if (motion) {
      const Eigen::Isometry3d vehicle =
          interpolate_pose(request.start, request.end, static_cast<double>(a) / steps);
      sensor = tilted ? vehicle * mount : vehicle;
    }
    col_R[a] = sensor.linear().cast<float>();
    col_origin[a] = sensor.translation().cast<float>();
  }
  const Eigen::Matrix3f mount_f = mount.linear().cast<float>();
  // Slots [beam][azimuth]: x, y, z, intensity; NaN x = no return.
  std::vector<Eigen::Vector4f> slots(static_cast<std::size_t>(beams) * steps);
  const double ref2 = model.reference_range * model.reference_range;
  const Impl& impl = *impl_;
  const WorldOptions& wopt = impl.world.options();
  // Moving actors, cast at each column's time within the sweep.
  std::unique_ptr<DynamicScene> dynamic;
  if (request.traffic && request.traffic->size() > 0) {
    dynamic = std::make_unique<DynamicScene>(impl.device, *request.traffic, reference.translation(),
                                             model.max_range + 10.0, request.start_time,
                                             request.start_time + rig.sweep.duration, motion);
    if (!dynamic->scene) dynamic.reset();
  }
  // Rays blocked by the ego vehicle (slab test in the vehicle frame; the origin is outside).
  const Eigen::Vector3f ego_lo = model.ego_box_min.cast<float>(),
                        ego_hi = model.ego_box_max.cast<float>();
  const bool has_ego = (ego_lo.array() < ego_hi.array()).all();
  auto hits_ego = [&](const Eigen::Vector3f& d) {
    float t0 = 0.0f, t1 = std::numeric_limits<float>::infinity();
    for (int i = 0; i < 3; ++i) {
      if (std::abs(d[i]) < 1e-9f) {
        if (0.0f < ego_lo[i] || 0.0f > ego_hi[i]) return false;
        continue;
      }
      float ta = ego_lo[i] / d[i], tb = ego_hi[i] / d[i];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    return t0 <= t1;
  };
  const float max_range = static_cast<float>(model.max_range);
  // Turns one hit at distance t into a point (or no return) in slot k, in the sensor frame of
  // the hit's column (`ds` the ray there); `n` is the surface normal and `d` the ray direction in
  // one frame, for the incidence angle.
  auto shade = [&](std::size_t k, const Eigen::Vector3f& ds, const Eigen::Vector3f& d, float t,
                   Eigen::Vector3f n, Material material, float reflectivity) {
    Eigen::Vector4f& out = slots[k];
    const float len = n.norm();
    n = len > 0 ? Eigen::Vector3f(n / len) : Eigen::Vector3f::UnitZ();
    Rng rng(hash_combine(scan_seed, k));
    const MaterialProperties mp = material_properties(material);
    const double refl = reflectivity;
    const double cos_inc = std::abs(n.dot(d));
    // Echo power relative to the detection threshold; soft threshold around 1.
    const double power = refl * std::sqrt(cos_inc) * ref2 / (double(t) * t);
    const double p_detect = std::clamp((power - 0.5) / 1.5, 0.0, 1.0);
    if (rng.uniform() >= p_detect) return;
    if (rng.uniform() < model.dropout + mp.dropout) return;
    double range = t + model.range_noise_sigma * rng.normal();
    if (material == Material::kGrass && wopt.grass_height > 0) {
      // Grass: the footprint covers many blades; the return comes from near their tops.
      range -=
          wopt.grass_height * (1.0 - 0.1 * rng.uniform()) / std::max(std::abs(double(d.z())), 0.05);
    } else if (material == Material::kFoliage && wopt.foliage_penetration > 0) {
      // Porous foliage: the beam travels into the crown before enough of it is reflected.
      range += std::min(1.0, -wopt.foliage_penetration * std::log(1.0 - rng.uniform()));
    }
    if (range < model.min_range || range > model.max_range) return;
    const double intensity =
        std::clamp(refl * (0.35 + 0.65 * cos_inc) + 0.02 * rng.normal(), 0.0, 1.0);
    out << ds * static_cast<float>(range), static_cast<float>(intensity);
  };
  auto cast_block = [&](const tbb::blocked_range<int>& r) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(32) RTCRayHit8 rh;
    alignas(32) int valid[8];
    for (int b = 0; b < beams; ++b) {
      for (int a0 = r.begin(); a0 < r.end(); a0 += 8) {
        const int na = std::min(8, r.end() - a0);
        Eigen::Vector3f ds[8], dv[8], dw[8];
        std::optional<BodyHit> body[8];
        for (int i = 0; i < 8; ++i) {
          const int a = a0 + (i < na ? i : 0);
          const std::size_t pose = motion ? static_cast<std::size_t>(a) : 0;
          ds[i] = Eigen::Vector3f(cos_el[b] * cos_az[a], cos_el[b] * sin_az[a], sin_el[b]);
          dv[i] = tilted ? Eigen::Vector3f(mount_f * ds[i]) : ds[i];
          valid[i] = i < na && !(has_ego && hits_ego(dv[i])) ? -1 : 0;
          body[i] = valid[i] && !rig.body.empty()
                        ? rig.body.intersect(dv[i].cast<double>().normalized())
                        : std::nullopt;
          dw[i] = col_R[pose] * ds[i];
          rh.ray.org_x[i] = col_origin[pose].x();
          rh.ray.org_y[i] = col_origin[pose].y();
          rh.ray.org_z[i] = col_origin[pose].z();
          rh.ray.dir_x[i] = dw[i].x();
          rh.ray.dir_y[i] = dw[i].y();
          rh.ray.dir_z[i] = dw[i].z();
          rh.ray.tnear[i] = 0.0f;
          rh.ray.tfar[i] =
              body[i] ? std::min(max_range, static_cast<float>(body[i]->range)) : max_range;
          rh.ray.time[i] = motion ? static_cast<float>(a) / static_cast<float>(steps) : 0.0f;
          rh.ray.mask[i] = 0xffffffffu;
          rh.ray.id[i] = 0;
          rh.ray.flags[i] = 0;
          rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect8(valid, impl.top, &ctx, &rh);
        // Static hits, kept before the moving actors are cast up to them.
        unsigned geom[8], prim[8], inst[8];
        float tfar[8];
        Eigen::Vector3f ng[8];
        for (int i = 0; i < 8; ++i) {
          geom[i] = rh.hit.geomID[i];
          prim[i] = rh.hit.primID[i];
          inst[i] = rh.hit.instID[0][i];
          tfar[i] = rh.ray.tfar[i];
          ng[i] = Eigen::Vector3f(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]);
        }
        if (dynamic) {
          for (int i = 0; i < 8; ++i) rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect8(valid, dynamic->scene, &ctx, &rh);
        }
        for (int i = 0; i < na; ++i) {
          const int a = a0 + i;
          const std::size_t k = static_cast<std::size_t>(b) * steps + a;
          slots[k].x() = std::numeric_limits<float>::quiet_NaN();
          if (!valid[i]) continue;
          if (dynamic && rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID) {
            const unsigned id = rh.hit.geomID[i], p = rh.hit.primID[i];
            const TriangleMesh* mesh = id < dynamic->meshes.size() ? dynamic->meshes[id] : nullptr;
            if (!mesh || p >= mesh->materials.size()) continue;
            shade(k, ds[i], dw[i], rh.ray.tfar[i],
                  Eigen::Vector3f(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]),
                  mesh->materials[p], mesh->reflectivity[p]);
          } else if (geom[i] != RTC_INVALID_GEOMETRY_ID) {
            const unsigned id = impl.opt.instancing ? inst[i] : geom[i];
            const Tile* tile = id < impl.by_instance.size() ? impl.by_instance[id] : nullptr;
            if (!tile || prim[i] >= tile->materials.size()) continue;
            shade(k, ds[i], dw[i], tfar[i], ng[i], tile->materials[prim[i]],
                  tile->reflectivity[prim[i]]);
          } else if (body[i]) {
            shade(k, ds[i], dv[i], static_cast<float>(body[i]->range),
                  body[i]->normal.cast<float>(), Material::kCarPaint, body[i]->reflectivity);
          }
        }
      }
    }
  };
  if (impl_->opt.parallel) {
    tbb::parallel_for(tbb::blocked_range<int>(0, steps, 64), cast_block);
  } else {
    cast_block(tbb::blocked_range<int>(0, steps));
  }
  SimulatedScan out;
  out.cloud.points.reserve(slots.size());
  out.cloud.intensities.reserve(slots.size());
  const auto rings = ring_numbers(model.elevations_deg);
  auto emit = [&](int b, int a) {
    const Eigen::Vector4f& s = slots[static_cast<std::size_t>(b) * steps + a];
    if (std::isnan(s.x())) return;
    out.cloud.points.push_back(s.head<3>());
    out.cloud.intensities.push_back(s.w());
    out.times.push_back(static_cast<float>(rig.sweep.column_time(a, steps)));
    out.rings.push_back(rings[b]);
  };
  if (motion || !rig.sweep.is_default_layout()) {
    for (int a = 0; a < steps; ++a) {
      for (int b = 0; b < beams; ++b) emit(b, a);
    }
  } else {
    for (int b = 0; b < beams; ++b) {
      for (int a = 0; a < steps; ++a) emit(b, a);
    }
  }
  return out;
}

std::size_t Raycaster::cached_tiles() const {
  return impl_->tiles.size();
}
std::size_t Raycaster::active_tiles() const {
  return impl_->active;
}
std::size_t Raycaster::active_triangles() const {
  return impl_->active_tris;
}

}  // namespace litamin2::sim
