// The message log (viewer/log.h).
#include "log.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <string_view>

#include "raylab/input_file.h"

namespace raylab::viewer {

namespace {

// Control bytes of a file name or a flag (ESC, BEL) never reach the terminal or the
// panel; line breaks stay
std::string safe_text(const std::string& text) {
    std::string out;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t end = std::min(text.find('\n', start), text.size());
        if (start > 0) out += '\n';
        out += printable(std::string_view(text).substr(start, end - start),
                         4 * text.size() + 1);
        start = end + 1;
    }
    return out;
}

}  // namespace

void Log::add(const std::string& raw) {
    const std::string line = safe_text(raw);
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char stamp[16];
    std::strftime(stamp, sizeof stamp, "[%H:%M:%S] ", &local);
    lines_.push_back(stamp + line);
    if (lines_.size() > kMaxLines) lines_.pop_front();
    if (echo) {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
    }
}

std::string Log::text() const {
    std::string text;
    for (const std::string& line : lines_)
        text += line + "\n";
    return text;
}

}  // namespace raylab::viewer
