// viewer/report.h: "Save report": everything needed to reproduce what the student sees,
// in one folder for a bug report.
#pragma once

#include <string>
#include <vector>

#include "raylab/image.h"
#include "raylab/modules.h"
#include "raylab/renderer.h"
#include "raylab/scene.h"

namespace raylab::viewer {

/// The frame a report describes.
struct ReportInput {
    std::string scene_source;  ///< "cornell", "dtu" or the OBJ path
    View view;
    std::vector<PointLight> lights;
    float ambient = 0.0f;
    RenderSettings settings;
    float exposure = 0.0f;
    ModuleSelection modules;
    FrameStats stats;              ///< of the last full frame
    const Image* image = nullptr;  ///< the last full image; null: none yet
    std::string grades;            ///< the module list's test results, one line each
    std::string log;               ///< the viewer's log
};

/// The raylab-render command line that renders the same frame into output.
std::string render_command(const ReportInput& input, const std::string& output);

/// "raylab-report-YYYYmmdd-HHMMSS" for the local time now.
std::string default_report_dir();

/// Writes dir/view.txt (a view file), dir/settings.txt (scene, settings, modules, frame
/// statistics, grades and the raylab-render command), dir/image.png and dir/log.txt.
/// Creates dir. Throws raylab::Error naming the file that failed.
void write_report(const std::string& dir, const ReportInput& input);

}  // namespace raylab::viewer
