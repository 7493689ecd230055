// bench/peer.h: the Intel Embree peer, behind an interface so that the bench builds
// without Embree (embree_none.cpp) and with it (embree_peer.cpp,
// -DRAYLAB_WITH_EMBREE=ON).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "raylab/scene.h"

namespace raylab::bench {

/// A triangle scene held by the peer library.
class PeerScene {
  public:
    virtual ~PeerScene() = default;
    /// t of every ray's closest hit in [tmin, tmax], kInfinity on a miss.
    virtual void closest_hit(const std::vector<Ray>& rays,
                             std::vector<float>& t) const = 0;
    /// The same as closest_hit, each 16 consecutive rays as one packet (rtcIntersect16,
    /// coherent context): Embree's own fastest way for a block of camera rays.
    virtual void closest_hit16(const std::vector<Ray>& rays,
                               std::vector<float>& t) const = 0;
    /// Whether anything lies on every ray in [tmin, tmax].
    virtual void any_hit(const std::vector<Ray>& rays, std::vector<char>& hit) const = 0;
    double build_seconds = 0.0;  ///< rtcNewScene to rtcCommitScene, device excluded
};

/// "Embree 3.13.5 (...)" or the line that says how to build the peer.
std::string peer_description();

/// True when this build has the Embree peer.
bool peer_available();

/// The scene's triangles in Embree (one RTC_GEOMETRY_TYPE_TRIANGLE geometry, default
/// build quality; robust: RTC_SCENE_FLAG_ROBUST). build_threads: the device's
/// "threads=N". nullptr without Embree.
std::unique_ptr<PeerScene> make_peer_scene(const std::vector<SceneTriangle>& triangles,
                                           bool robust, int build_threads);

}  // namespace raylab::bench
