// Expected values from the reference or the golden data (grading.h).
#include "grading.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "raylab/error.h"

namespace raylab::grading {

namespace {

std::string format_floats(const Floats& f) {
    std::string s;
    for (size_t k = 0; k < f.size(); ++k) {
        if (k) s += ' ';
        s += format_float(f[k]);
    }
    return s;
}

Floats parse_floats(const std::string& s) {
    Floats f;
    std::istringstream in(s);
    std::string word;
    while (in >> word)
        f.push_back(std::strtof(word.c_str(), nullptr));
    return f;
}

// ---- Golden files ---------------------------------------------------------------------

struct GoldenEntry {
    std::string input, output;
};

std::mutex golden_mutex;
std::map<std::string, std::map<std::string, GoldenEntry>> golden_loaded;  // suite -> key
std::map<std::string, std::map<std::string, GoldenEntry>> golden_recorded;

std::string golden_path(const std::string& suite) {
    return golden_dir() + "/" + suite + ".txt";
}

const std::map<std::string, GoldenEntry>& golden_suite(const std::string& suite) {
    auto it = golden_loaded.find(suite);
    if (it != golden_loaded.end()) return it->second;
    std::map<std::string, GoldenEntry>& entries = golden_loaded[suite];
    std::ifstream in(golden_path(suite));
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        const size_t a = line.find('\t'), b = line.find('\t', a + 1);
        if (a == std::string::npos || b == std::string::npos) continue;
        entries[line.substr(0, a)] = {line.substr(a + 1, b - a - 1), line.substr(b + 1)};
    }
    return entries;
}

}  // namespace

// Writes what this run recorded (RAYLAB_GOLDEN_WRITE); called by finish()
bool write_golden() {
    if (golden_record_dir().empty()) return true;
    size_t cases = 0;
    for (const auto& [suite, entries] : golden_recorded) {
        const std::string path = golden_record_dir() + "/" + suite + ".txt";
        std::ofstream out(path);
        out << "# Golden data of the " << suite
            << " graders: the reference's answer to each\n"
            << "# case, for builds without solutions/. Written by raylab-grading-tests "
               "with\n"
            << "# RAYLAB_GOLDEN_WRITE (scripts/make-student-release.sh); do not edit.\n"
            << "# case<TAB>input<TAB>reference's answer\n";
        for (const auto& [key, entry] : entries)
            out << key << '\t' << entry.input << '\t' << entry.output << '\n';
        cases += entries.size();
        if (!out) {
            std::printf("[raylab] cannot write %s\n", path.c_str());
            return false;
        }
    }
    std::printf("[raylab] wrote golden data for %zu cases of %zu modules to %s\n", cases,
                golden_recorded.size(), golden_record_dir().c_str());
    return true;
}

// ---- Encoding -------------------------------------------------------------------------

void put(Floats& f, float x) {
    f.push_back(x);
}
void put(Floats& f, int x) {
    f.push_back(static_cast<float>(x));
}
void put(Floats& f, bool x) {
    f.push_back(x ? 1.0f : 0.0f);
}
void put(Floats& f, const Vec2& v) {
    f.insert(f.end(), {v.x, v.y});
}
void put(Floats& f, const Vec3& v) {
    f.insert(f.end(), {v.x, v.y, v.z});
}
void put(Floats& f, const Ray& r) {
    put(f, r.o);
    put(f, r.w);
    f.insert(f.end(), {r.tmin, r.tmax});
}
void put(Floats& f, const std::optional<Hit>& hit) {
    put(f, hit.has_value());
    if (!hit) return;
    put(f, hit->t);
    put(f, hit->position);
    put(f, hit->n);
    put(f, hit->uv);
}
void put(Floats& f, const CameraFrame& frame) {
    put(f, frame.x);
    put(f, frame.y);
    put(f, frame.n);
}
void put(Floats& f, const LightSample& s) {
    put(f, s.wi);
    put(f, s.r);
    put(f, s.Li);
}

float FloatReader::next() {
    if (at_ >= f_.size()) {
        FAIL("golden data: a case has fewer numbers than its type needs");
    }
    return f_[at_++];
}
void FloatReader::get(Vec2& v) {
    v.x = next();
    v.y = next();
}
void FloatReader::get(Vec3& v) {
    v.x = next();
    v.y = next();
    v.z = next();
}
void FloatReader::get(Ray& r) {
    get(r.o);
    get(r.w);
    r.tmin = next();
    r.tmax = next();
}
void FloatReader::get(std::optional<Hit>& hit) {
    bool present = false;
    get(present);
    if (!present) {
        hit.reset();
        return;
    }
    Hit h;
    h.t = next();
    get(h.position);
    get(h.n);
    get(h.uv);
    hit = h;
}
void FloatReader::get(CameraFrame& frame) {
    get(frame.x);
    get(frame.y);
    get(frame.n);
}
void FloatReader::get(LightSample& s) {
    get(s.wi);
    s.r = next();
    get(s.Li);
}

// A hidden case compares with the reference itself; golden data would put its inputs in
// the release
static void refuse_private(const std::string& what) {
    if (current_case().rfind("[private]", 0) == 0)
        FAIL("the hidden case \"" << current_case() << "\" asked for golden data ("
                                  << what
                                  << "), which a release would ship: compare with "
                                     "reference_modules() directly");
}

Floats expected_floats(const std::string& key, const Floats& input,
                       const std::function<Floats()>& compute) {
    refuse_private(key);
    const std::string suite = key.substr(0, key.find('/'));
    const std::string in = format_floats(input);
    if (!using_golden()) {
        Floats out = compute();
        if (!golden_record_dir().empty()) {
            const std::lock_guard<std::mutex> lock(golden_mutex);
            golden_recorded[suite][key] = {in, format_floats(out)};
        }
        return out;
    }
    std::string stored_in, stored_out;
    bool found = false;
    {
        const std::lock_guard<std::mutex> lock(golden_mutex);
        const auto& entries = golden_suite(suite);
        const auto it = entries.find(key);
        if (it != entries.end()) {
            found = true;
            stored_in = it->second.input;
            stored_out = it->second.output;
        }
    }
    if (!found) {
        FAIL(
            "no golden data for case '"
            << key << "' in " << golden_path(suite)
            << ": the golden data does not belong to these tests (regenerate it with the "
               "reference: scripts/make-student-release.sh)");
    }
    if (stored_in != in) {
        FAIL("the golden data of case '" << key << "' was made for the input "
                                         << stored_in << ", but this test generated "
                                         << in);
    }
    return parse_floats(stored_out);
}

Image expected_image(const std::string& suite, const std::string& stem,
                     const std::function<Image()>& compute) {
    const std::string name = suite + "-" + stem + ".pfm";
    refuse_private(name);
    if (!using_golden()) {
        Image image = compute();
        if (!golden_record_dir().empty())
            write_pfm(golden_record_dir() + "/" + name, image);
        return image;
    }
    try {
        return read_pfm(golden_dir() + "/" + name);
    } catch (const Error& e) {
        FAIL("golden image missing: " << e.what());
    }
    return Image();
}

std::string save_image(const std::string& name, const Image& image) {
    if (images_dir().empty()) return "";
    // The PNG for looking at it (any image viewer opens it), the PFM for its exact values
    const std::string stem = images_dir() + "/" + name;
    try {
        write_pfm(stem + ".pfm", image);
        write_png(stem + ".png", image);
    } catch (const Error&) {
        return "";
    }
    return stem + ".png (and .pfm)";
}

}  // namespace raylab::grading
