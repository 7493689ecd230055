// viewer/actions.h: what the panel's buttons and the command-line flags do.
//
// No ImGui here: the panel (panel_*.cpp) calls these, and so do the scripted runs
// (--load-view, --save-image, --report ...). Every failure becomes a message in the
// panel and the log; the previous scene, view and image stay as they were.
#pragma once

#include <functional>
#include <string>

#include "raylab/options.h"
#include "report.h"
#include "viewer.h"

namespace raylab::viewer {

/// Fills v from the command line: scene, view, settings, modules, --load-view. Starts
/// the render worker and finds the graders. Throws raylab::Error for bad flags or files.
void init_viewer(Viewer& v, const Options& options, const ViewerOptions& viewer_options,
                 std::function<void()> wake);

/// Shows message in red in the panel and logs it (also on stderr).
void report_error(Viewer& v, const std::string& message);

/// Applies view when it is valid (marks the frame dirty and returns true); otherwise
/// keeps the current view and returns false with the reason in panel.view_error.
bool apply_view(Viewer& v, const View& view);

/// Built-in scenes load at once; an OBJ loads in the background (finish_loading picks
/// it up). A scene that fails to load leaves the current one running.
void start_loading_scene(Viewer& v, const std::string& source);
/// Takes a finished load. False when the command line's scene failed to load in a
/// scripted run (--frames): the viewer then exits with code 2.
bool finish_loading(Viewer& v);
/// "loading FILE: stage 45%" while a load runs, else empty.
std::string loading_text(const Viewer& v);
/// Asks the running load to stop (it throws LoadCancelled soon after).
void cancel_loading(Viewer& v);

/// Files. Each reports its own errors and returns false on failure.
bool load_view(Viewer& v, const std::string& path);
bool save_view(Viewer& v, const std::string& path);
bool save_image(Viewer& v, const std::string& path);
bool save_report(Viewer& v, const std::string& dir);

/// Starts the graders of all modules in child processes (panel "Run tests").
void run_tests(Viewer& v);
/// Logs the results once a grading run has finished.
void poll_grading(Viewer& v);
/// "01_pixel_loop  student  12/14 passed" lines, for the log and reports.
std::string grades_text(const Viewer& v);

/// Sends a job to the worker when the state is dirty (a preview while interacting).
void submit_if_dirty(Viewer& v);
/// Takes a finished frame from the worker; true when there was one.
bool take_result(Viewer& v);

/// After the swap that showed a new full frame: its latency (change to screen) and,
/// with --repeat N, the next of N renders of the same frame (then the medians' log line).
void frame_shown(Viewer& v);
/// True when --repeat's renders are all done (always without --repeat).
bool repeat_done(const Viewer& v);

/// Probes the pinned or hovered pixel when it or the frame changed.
void update_probes(Viewer& v);

/// The current frame as a report's input.
ReportInput report_input(const Viewer& v);

/// "eye x,y,z lookat x,y,z up x,y,z fov f": one line for logs and tests.
std::string view_line(const View& view);

/// Coarse-preview factor for a frame whose full render took full_ms: 1 when it is
/// already fast, else about sqrt(full_ms / 25), in 2..8.
int preview_factor(double full_ms);

/// The previews a full frame starts with when the last full frame took long (over
/// about 100 ms): preview_factor's, then 2 when that is 4 or more; none finer than a
/// preview of the same inputs the last job already made (a drag just ended).
std::vector<int> coarse_levels(const FrameState& f, const RenderJob& job);

}  // namespace raylab::viewer
