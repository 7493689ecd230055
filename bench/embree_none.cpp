// The Embree peer when the bench is built without Embree (bench/peer.h).
#include "peer.h"

namespace raylab::bench {

std::string peer_description() {
    return "Embree peer: not built (configure with -DRAYLAB_WITH_EMBREE=ON)";
}

bool peer_available() {
    return false;
}

std::unique_ptr<PeerScene> make_peer_scene(const std::vector<SceneTriangle>&, bool, int) {
    return nullptr;
}

}  // namespace raylab::bench
