// viewer/app.h: the viewer's window and main loop.
#pragma once

#include "raylab/options.h"
#include "viewer_options.h"

namespace raylab::viewer {

/// Opens the window and runs until it is closed (or --frames are done). Returns the
/// exit code: 0, 1 when a scripted step failed, 2 when no window can be opened. Throws
/// raylab::Error for bad flags or files given on the command line.
int run_viewer(const Options& options, const ViewerOptions& viewer_options);

}  // namespace raylab::viewer
