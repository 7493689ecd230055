// Uses a helper header beside it; the driver gives every file of this hand-in CRLF ends.
#include "plane_helper.h"
static_assert(kPlaneHelper == 42, "the helper header beside the file is found");
// RAYLAB-HONEST-CODE 03_plane
