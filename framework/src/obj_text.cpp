// OBJ and MTL line checks before tinyobjloader (obj_text.h).
//
// tinyobjloader reads numbers leniently (nan, junk and missing fields become 0), skips
// the first line after a byte order mark, reports a missing mtllib only as a warning,
// and has undefined behaviour on some lines raylab never uses (`vw 0 1e38 1`). So every
// line is checked here, and tinyobjloader gets a plain, already valid subset.
#include "obj_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "raylab/input_checks.h"
#include "raylab/input_file.h"

namespace raylab::obj {

namespace {

using Words = std::vector<std::string_view>;

std::string word_text(std::string_view w) {
    return "'" + printable(w, 40) + "'";
}

// Lines dropped because raylab does not use them: counted, one warning at the end
struct Ignored {
    size_t count = 0;
    size_t first_line = 0;
    std::string first_keyword;
    void add(size_t line, std::string_view keyword) {
        if (count++ == 0) {
            first_line = line;
            first_keyword = printable(keyword, 20);
        }
    }
    void report(const LoadProgress& progress, const std::string& source) const {
        if (count == 0) return;
        warn(progress, source + ": ignored " + std::to_string(count) +
                           " line(s) raylab does not use (first: line " +
                           std::to_string(first_line) + ", '" + first_keyword + "')");
    }
};

// The numbers after the keyword: between lo and hi of them, each strictly parsed
std::vector<float> numbers(const Words& words, size_t lo, size_t hi,
                           const char* const* names, const std::string& at) {
    const size_t n = words.size() - 1;
    if (n < lo || n > hi) {
        throw Error(at + "'" + std::string(words[0]) + "' needs " +
                    (lo == hi ? std::to_string(lo)
                              : std::to_string(lo) + " to " + std::to_string(hi)) +
                    " numbers, found " + std::to_string(n));
    }
    std::vector<float> xs(n);
    for (size_t k = 0; k < n; ++k) {
        if (!parse_real(words[k + 1], xs[k])) {
            throw Error(at + names[k] + ": " + word_text(words[k + 1]) +
                        " is not a finite number");
        }
    }
    return xs;
}

class ObjChecker {
  public:
    ObjChecker(const std::string& source,
               const std::function<std::string(const std::string&)>& read_mtl,
               const LoadProgress& progress)
        : source_(source), read_mtl_(read_mtl), progress_(progress) {}

    void line(std::string_view text, size_t number);
    CheckedObj finish() {
        ignored_.report(progress_, source_);
        if (vw_ > 0)
            warn(progress_, source_ + ": ignored " + std::to_string(vw_) +
                                " vertex weight (vw) line(s)");
        return std::move(out_);
    }

  private:
    void vertex(const Words& w, const std::string& at);
    void face(const Words& w, const std::string& at);
    void mtllib(const Words& w, const std::string& at);
    long long index(std::string_view word, long long count, const char* what,
                    const std::string& at, size_t corner);

    const std::string& source_;
    const std::function<std::string(const std::string&)>& read_mtl_;
    const LoadProgress& progress_;
    CheckedObj out_;
    long long v_ = 0, vt_ = 0, vn_ = 0;
    size_t vw_ = 0;
    Ignored ignored_;
};

void ObjChecker::line(std::string_view text, size_t number) {
    if (const size_t hash = text.find('#'); hash != std::string_view::npos)
        text = text.substr(0, hash);
    const Words w = split_words(text);
    if (w.empty()) return;
    const std::string at = where(source_, number);
    const std::string_view key = w[0];
    if (key == "v" || key == "vn" || key == "vt") {
        vertex(w, at);
    } else if (key == "f") {
        face(w, at);
    } else if (key == "mtllib") {
        mtllib(w, at);
    } else if (key == "usemtl" || key == "o" || key == "g") {
        if (key == "usemtl" && w.size() != 2)
            throw Error(at + "'usemtl' needs one material name");
        std::string& o = out_.obj;
        o.append(key).append(" ").append(w.size() > 1 ? w[1] : "unnamed").append("\n");
    } else if (key == "s") {
        out_.obj.append("s ").append(w.size() > 1 ? w[1] : "off").append("\n");
    } else if (key == "vw") {
        ++vw_;  // skin weights: tinyobjloader 2.0.0rc10 has undefined behaviour on them
    } else {
        ignored_.add(number, key);
    }
}

void ObjChecker::vertex(const Words& w, const std::string& at) {
    static const char* const v_names[] = {"x",     "y",    "z", "w or red",
                                          "green", "blue", "w"};
    static const char* const vn_names[] = {"normal x", "normal y", "normal z"};
    static const char* const vt_names[] = {"u", "v", "w"};
    std::string& o = out_.obj;
    if (w[0] == "v") {
        const std::vector<float> x = numbers(w, 3, 7, v_names, at);
        if (x.size() == 5) throw Error(at + "'v' needs 3, 4, 6 or 7 numbers, found 5");
        for (int k = 0; k < 3; ++k) {
            if (std::fabs(x[k]) > kMaxCoordinate)
                throw Error(at + v_names[k] + ": " + word_text(w[k + 1]) +
                            " is too large (coordinates within +-1e6)");
        }
        o.append("v ").append(w[1]).append(" ").append(w[2]).append(" ").append(w[3]);
        ++v_;
    } else if (w[0] == "vn") {
        numbers(w, 3, 3, vn_names, at);
        o.append("vn ").append(w[1]).append(" ").append(w[2]).append(" ").append(w[3]);
        ++vn_;
    } else {
        numbers(w, 1, 3, vt_names, at);
        o.append("vt ").append(w[1]).append(" ").append(w.size() > 2 ? w[2] : "0");
        ++vt_;
    }
    o.append("\n");
}

long long ObjChecker::index(std::string_view word, long long count, const char* what,
                            const std::string& at, size_t corner) {
    long long i = 0;
    const std::string field = at + "face corner " + std::to_string(corner) + ": ";
    if (!parse_whole(word, -(1LL << 62), 1LL << 62, i))
        throw Error(field + word_text(word) + " is not a " + what + " index");
    if (i == 0) throw Error(field + what + " index 0 (OBJ indices start at 1)");
    const long long absolute = i > 0 ? i : count + 1 + i;
    if (absolute < 1 || absolute > count) {
        throw Error(field + what + " " + std::to_string(i) + " does not exist (" +
                    std::to_string(count) + " defined so far)");
    }
    return absolute;
}

void ObjChecker::face(const Words& w, const std::string& at) {
    const size_t n = w.size() - 1;
    if (n < 3) throw Error(at + "a face needs 3 corners, found " + std::to_string(n));
    std::vector<std::string> corners(n);
    for (size_t k = 0; k < n; ++k) {
        const std::string_view c = w[k + 1];
        const size_t s1 = c.find('/');
        const size_t s2 = s1 == std::string_view::npos ? s1 : c.find('/', s1 + 1);
        if (s2 != std::string_view::npos && c.find('/', s2 + 1) != std::string_view::npos)
            throw Error(at + "face corner " + std::to_string(k + 1) + ": " +
                        word_text(c) + " is not v, v/t, v//n or v/t/n");
        std::string& out = corners[k];
        out = std::to_string(index(c.substr(0, s1), v_, "vertex", at, k + 1));
        if (s1 == std::string_view::npos) continue;
        const std::string_view t =
            c.substr(s1 + 1, s2 == std::string_view::npos ? s2 : s2 - s1 - 1);
        if (t.empty() && s2 == std::string_view::npos)  // "1/": tinyobjloader misreads it
            throw Error(at + "face corner " + std::to_string(k + 1) + ": " +
                        word_text(c) + " is not v, v/t, v//n or v/t/n");
        out += "/";
        if (!t.empty())
            out += std::to_string(index(t, vt_, "texture coordinate", at, k + 1));
        if (s2 == std::string_view::npos) continue;
        out += "/" + std::to_string(index(c.substr(s2 + 1), vn_, "normal", at, k + 1));
    }
    std::string& o = out_.obj;
    if (n <= kMaxEarClipCorners) {
        o += "f";
        for (const std::string& c : corners)
            o.append(" ").append(c);
        o += "\n";
        return;
    }
    for (size_t k = 1; k + 1 < n; ++k)  // a fan: exact for convex polygons
        o.append("f ")
            .append(corners[0])
            .append(" ")
            .append(corners[k])
            .append(" ")
            .append(corners[k + 1])
            .append("\n");
}

void ObjChecker::mtllib(const Words& w, const std::string& at) {
    if (w.size() < 2) throw Error(at + "'mtllib' needs a file name");
    for (size_t k = 1; k < w.size(); ++k) {
        const std::string name(w[k]);
        if (out_.mtl.count(name)) continue;
        std::string text;
        try {
            text = read_mtl_(name);
        } catch (const Error& e) {
            throw Error(at + "mtllib: " + e.what());
        }
        out_.mtl[name] = check_mtl(text, printable(name), progress_);
        out_.obj.append("mtllib ").append(name).append("\n");
    }
}

}  // namespace

void warn(const LoadProgress& progress, const std::string& message) {
    if (progress.warn) {
        progress.warn(message);
    } else {
        std::fprintf(stderr, "raylab: warning: %s\n", message.c_str());
    }
}

CheckedObj check_obj(const std::string& text, const std::string& source,
                     const std::function<std::string(const std::string&)>& read_mtl,
                     const LoadProgress& progress) {
    const std::vector<std::string_view> lines = split_lines(text, kMaxObjLine, source);
    ObjChecker checker(source, read_mtl, progress);
    for (size_t k = 0; k < lines.size(); ++k) {
        if ((k & 0xffff) == 0) {
            if (progress.cancel && progress.cancel->load()) throw LoadCancelled();
            if (progress.report)
                progress.report("reading", static_cast<float>(k) / lines.size());
        }
        checker.line(lines[k], k + 1);
    }
    return checker.finish();
}

std::string check_mtl(const std::string& text, const std::string& source,
                      const LoadProgress& progress) {
    static const char* const rgb[] = {"red", "green", "blue"};
    static const char* const one[] = {"value"};
    std::string out;
    Ignored ignored;
    bool in_material = false;
    const std::vector<std::string_view> lines = split_lines(text, kMaxLine, source);
    for (size_t k = 0; k < lines.size(); ++k) {
        std::string_view line = lines[k];
        if (const size_t hash = line.find('#'); hash != std::string_view::npos)
            line = line.substr(0, hash);
        const Words w = split_words(line);
        if (w.empty()) continue;
        const std::string at = where(source, k + 1);
        const std::string_view key = w[0];
        if (key == "newmtl") {
            if (w.size() != 2) throw Error(at + "'newmtl' needs one material name");
            out.append("newmtl ").append(w[1]).append("\n");
            in_material = true;
        } else if (!in_material) {
            throw Error(at + "not an MTL file: " + word_text(key) +
                        " comes before any 'newmtl'");
        } else if (key == "Kd" || key == "Ka" || key == "Ks" || key == "Ke") {
            std::vector<float> x = numbers(w, 1, 3, rgb, at);
            if (x.size() == 2)
                throw Error(at + "'" + std::string(key) + "' needs 1 or 3 numbers");
            if (x.size() == 1) x = {x[0], x[0], x[0]};
            for (int c = 0; c < 3; ++c) {
                if (x[c] < 0.0f || x[c] > kMaxIntensity)
                    throw Error(at + rgb[c] + ": " +
                                word_text(w[std::min<size_t>(c + 1, w.size() - 1)]) +
                                " is outside [0, 1e6]");
            }
            char buffer[128];
            std::snprintf(buffer, sizeof buffer, "%s %.9g %.9g %.9g\n",
                          std::string(key).c_str(), double(x[0]), double(x[1]),
                          double(x[2]));
            out += buffer;
        } else if (key == "Ns" || key == "Ni" || key == "d" || key == "Tr") {
            numbers(w, 1, 1, one, at);
            out.append(key).append(" ").append(w[1]).append("\n");
        } else {
            ignored.add(k + 1, key);
        }
    }
    ignored.report(progress, source);
    return out;
}

}  // namespace raylab::obj
