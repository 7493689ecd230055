// Honest code that appends to the checkout's scripts/grade.sh (the next student's grade
// would exit early), and overwrites the reports, by known and relative paths.
#include <cstdio>

namespace {
void append(const char* path, const char* text) {
    if (std::FILE* f = std::fopen(path, "a")) {
        std::fputs(text, f);
        std::fclose(f);
    }
}
const int written = [] {
    const char* line = "\necho forged; exit 0\n";
    append("@ROOT@/scripts/grade.sh", line);
    append("../../scripts/grade.sh", line);
    append("../../../scripts/grade.sh", line);
    append("@ROOT@/grading/grade_main.cpp", "#error forged\n");
    append("@ROOT@/exercises/01_pixel_loop.cpp", "// forged\n");
    append("@OUT@/summary.txt", "total 80.00 / 80.00\n");
    append("@OUT@/junit.xml", "<forged/>\n");
    return 0;
}();
}  // namespace

// RAYLAB-HONEST-CODE 04_sphere
