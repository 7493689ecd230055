// The Intel Embree 3 peer (bench/peer.h): rtcIntersect1 and rtcOccluded1, one ray at a
// time, as raylab traces them. API: Embree 3 manual (rtcIntersect1(3), rtcOccluded1(3),
// rtcSetSceneFlags(3)); Debian's libembree-dev 3.13.5.
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <mutex>

#include "peer.h"
#include "raylab/error.h"

namespace raylab::bench {

namespace {

void report_error(void*, RTCError code, const char* message) {
    std::fprintf(stderr, "Embree error %d: %s\n", static_cast<int>(code), message);
}

// One device per thread count for the process; scenes keep their own reference to it
RTCDevice device(int threads) {
    static std::map<int, RTCDevice> devices;
    static std::mutex mutex;
    const std::lock_guard<std::mutex> lock(mutex);
    RTCDevice& d = devices[threads];
    if (!d) {
        const std::string config = "threads=" + std::to_string(threads);
        d = rtcNewDevice(config.c_str());
        if (!d) throw Error("Embree: rtcNewDevice(\"" + config + "\") failed");
        rtcSetDeviceErrorFunction(d, report_error, nullptr);
    }
    return d;
}

void set_ray(RTCRay& out, const Ray& r) {
    out.org_x = r.o.x;
    out.org_y = r.o.y;
    out.org_z = r.o.z;
    out.tnear = r.tmin;
    out.dir_x = r.w.x;
    out.dir_y = r.w.y;
    out.dir_z = r.w.z;
    out.time = 0.0f;
    out.tfar = r.tmax;
    out.mask = 0xFFFFFFFFu;  // Debian's Embree has ray masks on
    out.id = 0;
    out.flags = 0;
}

class EmbreeScene : public PeerScene {
  public:
    EmbreeScene(const std::vector<SceneTriangle>& triangles, bool robust, int threads) {
        RTCDevice dev = device(threads);
        const auto start = std::chrono::steady_clock::now();
        scene_ = rtcNewScene(dev);
        if (robust) rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        RTCGeometry geometry = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        const size_t n = triangles.size();
        auto* v = static_cast<float*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                    RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
        auto* index = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(unsigned), n));
        if (!v || !index) throw Error("Embree: could not allocate the triangle buffers");
        for (size_t k = 0; k < n; ++k) {
            const SceneTriangle& t = triangles[k];
            for (const Vec3* p : {&t.v0, &t.v1, &t.v2}) {
                *v++ = p->x;
                *v++ = p->y;
                *v++ = p->z;
            }
            for (unsigned c = 0; c < 3; ++c)
                index[3 * k + c] = static_cast<unsigned>(3 * k + c);
        }
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene_, geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(scene_);
        build_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                .count();
    }
    ~EmbreeScene() override { rtcReleaseScene(scene_); }
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    void closest_hit(const std::vector<Ray>& rays, std::vector<float>& t) const override {
        t.resize(rays.size());
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (size_t k = 0; k < rays.size(); ++k) {
            RTCRayHit rh;
            set_ray(rh.ray, rays[k]);
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene_, &context, &rh);
            t[k] = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : kInfinity;
        }
    }

    void closest_hit16(const std::vector<Ray>& rays,
                       std::vector<float>& t) const override {
        t.resize(rays.size());
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        alignas(64) RTCRayHit16 rh;
        alignas(64) int valid[16];
        for (size_t first = 0; first < rays.size(); first += 16) {
            const size_t n = std::min<size_t>(16, rays.size() - first);
            for (size_t k = 0; k < 16; ++k) {
                valid[k] = k < n ? -1 : 0;
                const Ray& r = rays[first + (k < n ? k : 0)];
                rh.ray.org_x[k] = r.o.x;
                rh.ray.org_y[k] = r.o.y;
                rh.ray.org_z[k] = r.o.z;
                rh.ray.tnear[k] = r.tmin;
                rh.ray.dir_x[k] = r.w.x;
                rh.ray.dir_y[k] = r.w.y;
                rh.ray.dir_z[k] = r.w.z;
                rh.ray.time[k] = 0.0f;
                rh.ray.tfar[k] = r.tmax;
                rh.ray.mask[k] = 0xFFFFFFFFu;
                rh.ray.id[k] = 0;
                rh.ray.flags[k] = 0;
                rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect16(valid, scene_, &context, &rh);
            for (size_t k = 0; k < n; ++k)
                t[first + k] = rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID
                                   ? rh.ray.tfar[k]
                                   : kInfinity;
        }
    }
    void any_hit(const std::vector<Ray>& rays, std::vector<char>& hit) const override {
        hit.resize(rays.size());
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (size_t k = 0; k < rays.size(); ++k) {
            RTCRay ray;
            set_ray(ray, rays[k]);
            rtcOccluded1(scene_, &context, &ray);
            hit[k] = ray.tfar < 0.0f;  // set to -inf on a hit
        }
    }

  private:
    RTCScene scene_ = nullptr;
};

}  // namespace

std::string peer_description() {
    return "Embree peer: Intel Embree " RTC_VERSION_STRING
           " (rtcIntersect1 / rtcOccluded1, one ray at a time, incoherent context)";
}

bool peer_available() {
    return true;
}

std::unique_ptr<PeerScene> make_peer_scene(const std::vector<SceneTriangle>& triangles,
                                           bool robust, int build_threads) {
    return std::make_unique<EmbreeScene>(triangles, robust, build_threads);
}

}  // namespace raylab::bench
