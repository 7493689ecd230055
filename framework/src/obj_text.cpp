// OBJ and MTL line checks before tinyobjloader (obj_text.h).
//
// tinyobjloader reads numbers leniently (nan, junk and missing fields become 0), skips
// the first line after a byte order mark, reads a `usemtl` name to the first space but a
// `newmtl` name to the end of the line, and has undefined behaviour on some lines raylab
// never uses (`vw 0 1e38 1`). So every line is checked here, materials are read here, and
// tinyobjloader gets a plain, already valid subset with material slots for names.
#include "obj_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <utility>
#include <vector>

#include "raylab/input_checks.h"
#include "raylab/input_file.h"

namespace raylab::obj {

namespace {

using Words = std::vector<std::string_view>;

std::string word_text(std::string_view w) {
    return "'" + printable(w, 40) + "'";
}

// A material without a name (`newmtl` or `usemtl` alone) gets this one
constexpr const char* kUnnamed = "unnamed";

// Distinct usemtl names, and materials over all MTL files: far above real models, low
// enough that a file of nothing but names cannot fill the memory with maps of them
constexpr size_t kMaxMaterials = size_t(1) << 16;

// A material name: the rest of the line after the keyword, less spaces and tabs at
// either end, so names with spaces (`newmtl Hard Shiny Plastic`) stay whole. A `#` is
// part of the name: exporters write names such as "Material #25", and cutting them there
// would merge materials silently, where a name that does not match is a warning.
std::string_view rest_of_line(std::string_view line, std::string_view keyword) {
    std::string_view rest = line.substr(keyword.data() + keyword.size() - line.data());
    const size_t first = rest.find_first_not_of(" \t");
    if (first == std::string_view::npos) return {};
    rest = rest.substr(first);
    return rest.substr(0, rest.find_last_not_of(" \t") + 1);
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

// MTL materials without a `Kd` line: one warning each for the first few, then one for
// the rest, so a file of bare `newmtl` lines cannot flood the terminal
struct NoDiffuse {
    static constexpr size_t kNamed = 8;
    size_t count = 0;
    size_t first_summed_line = 0;
    void add(const LoadProgress& progress, const std::string& source, size_t line,
             const std::string& name) {
        if (++count > kNamed) {
            if (count == kNamed + 1) first_summed_line = line;
            return;
        }
        warn(progress, where(source, line) + "material " + word_text(name) +
                           " has no Kd: it gets the default diffuse colour (" + grey() +
                           ")");
    }
    void report(const LoadProgress& progress, const std::string& source) const {
        if (count <= kNamed) return;
        warn(progress, where(source, first_summed_line) + "and " +
                           std::to_string(count - kNamed) +
                           " more material(s) without Kd: they get the default "
                           "diffuse colour (" +
                           grey() + ") too");
    }
    static std::string grey() {
        char c[16];
        std::snprintf(c, sizeof c, "%g", kDefaultDiffuse);
        return std::string(c) + " " + c + " " + c;
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
        const Decimal read = parse_decimal(words[k + 1], xs[k]);
        if (read != Decimal::ok) {
            throw Error(at + names[k] + ": " + word_text(words[k + 1]) +
                        " is not a finite number" +
                        (read == Decimal::out_of_range
                             ? " (beyond +-3.4e38, a float's range)"
                             : ""));
        }
    }
    return xs;
}

class ObjChecker {
  public:
    ObjChecker(const std::string& source,
               const std::function<std::string(const std::string&)>& read_mtl,
               const LoadProgress& progress)
        : source_(source), read_mtl_(read_mtl), progress_(progress) {
        // tinyobjloader learns the slot names here, before any usemtl
        out_.obj.append("mtllib ").append(kMaterialSlots).append("\n");
    }

    void line(std::string_view text, size_t number);
    CheckedObj finish();

  private:
    void vertex(const Words& w, const std::string& at);
    void face(const Words& w, const std::string& at);
    void mtllib(const Words& w, const std::string& at);
    void usemtl(std::string_view name, size_t number);
    long long index(std::string_view word, long long count, const char* what,
                    const std::string& at, size_t corner);

    const std::string& source_;
    const std::function<std::string(const std::string&)>& read_mtl_;
    const LoadProgress& progress_;
    CheckedObj out_;
    long long v_ = 0, vt_ = 0, vn_ = 0;
    size_t vw_ = 0;
    Ignored ignored_;
    std::map<std::string, int> material_index_;  // name -> first material of that name
    std::map<std::string, size_t> slot_;         // usemtl name -> slot
    std::vector<std::pair<std::string, size_t>> slot_use_;  // slot -> name, first line
    size_t unnamed_uses_ = 0, first_unnamed_use_ = 0;
    bool library_missing_ = false;
    std::set<std::string> libraries_;  // mtllib names read (or tried) so far
};

CheckedObj ObjChecker::finish() {
    ignored_.report(progress_, source_);
    if (vw_ > 0)
        warn(progress_, source_ + ": ignored " + std::to_string(vw_) +
                            " vertex weight (vw) line(s)");
    const bool unnamed_exists = material_index_.count(kUnnamed) > 0;
    if (unnamed_uses_ > 0) {
        warn(
            progress_,
            where(source_, first_unnamed_use_) + "'usemtl' without a name" +
                (unnamed_uses_ > 1
                     ? " (and " + std::to_string(unnamed_uses_ - 1) + " more such lines)"
                     : std::string()) +
                (unnamed_exists ? std::string(": read as the material '") + kUnnamed + "'"
                                : std::string("; its faces get the default material")));
    }
    // Names are resolved at the end, so an mtllib after its usemtl lines still counts
    size_t unknown = 0, first_unknown = 0;
    for (size_t slot = 0; slot < slot_use_.size(); ++slot) {
        const auto it = material_index_.find(slot_use_[slot].first);
        out_.slot_material.push_back(it == material_index_.end() ? -1 : it->second);
        const bool told = unnamed_uses_ > 0 && slot_use_[slot].first == kUnnamed;
        if (it == material_index_.end() && !told && unknown++ == 0) first_unknown = slot;
    }
    // A missing library has had its warning: the names it would have held are not listed
    if (unknown > 0 && !library_missing_) {
        const auto& [name, line] = slot_use_[first_unknown];
        warn(progress_, where(source_, line) + "usemtl " + word_text(name) +
                            ": no material of that name" +
                            (unknown > 1 ? " (nor of " + std::to_string(unknown - 1) +
                                               " other name(s) used)"
                                         : std::string()) +
                            "; its faces get the default material");
    }
    return std::move(out_);
}

void ObjChecker::usemtl(std::string_view name, size_t number) {
    if (name.empty()) {
        if (unnamed_uses_++ == 0) first_unnamed_use_ = number;
        name = kUnnamed;
    }
    const auto [it, added] = slot_.emplace(std::string(name), slot_.size());
    if (added) {
        if (slot_.size() > kMaxMaterials)
            throw Error(where(source_, number) + "usemtl: more than " +
                        std::to_string(kMaxMaterials) + " material names");
        slot_use_.emplace_back(it->first, number);
    }
    out_.obj.append("usemtl ").append(std::to_string(it->second)).append("\n");
}

void ObjChecker::line(std::string_view text, size_t number) {
    const std::string_view whole = text;
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
    } else if (key == "usemtl") {
        usemtl(rest_of_line(whole, key), number);
    } else if (key == "o" || key == "g") {
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
        if (!libraries_.insert(name).second) continue;
        std::string text;
        try {
            text = read_mtl_(name);
        } catch (const Error& e) {
            // Models often travel without their MTL file: the geometry still loads
            warn(progress_, at + "mtllib: " + e.what() +
                                "; faces using its materials get the default material");
            library_missing_ = true;
            continue;
        }
        std::vector<Material> materials = check_mtl(text, printable(name), progress_);
        if (out_.materials.size() + materials.size() > kMaxMaterials)
            throw Error(at + "mtllib: more than " + std::to_string(kMaxMaterials) +
                        " materials");
        for (Material& m : materials) {
            // The first material of a name wins, as in tinyobjloader
            material_index_.emplace(m.name, static_cast<int>(out_.materials.size()));
            out_.materials.push_back(std::move(m));
        }
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

std::vector<Material> check_mtl(const std::string& text, const std::string& source,
                                const LoadProgress& progress) {
    static const char* const rgb[] = {"red", "green", "blue"};
    static const char* const one[] = {"value"};
    std::vector<Material> out;
    Ignored ignored;
    NoDiffuse no_diffuse;
    // The open material's newmtl line, and whether it has had a Kd line: tinyobjloader's
    // diffuse is 0 without one, and textured exports often give only `map_Kd`
    size_t newmtl_line = 0;
    bool has_kd = true;
    const auto close_material = [&] {
        if (has_kd) return;
        out.back().rho = Vec3(kDefaultDiffuse);
        no_diffuse.add(progress, source, newmtl_line, out.back().name);
    };
    const std::vector<std::string_view> lines = split_lines(text, kMaxLine, source);
    for (size_t k = 0; k < lines.size(); ++k) {
        const std::string_view whole = lines[k];
        std::string_view line = whole;
        if (const size_t hash = line.find('#'); hash != std::string_view::npos)
            line = line.substr(0, hash);
        const Words w = split_words(line);
        if (w.empty()) continue;
        const std::string at = where(source, k + 1);
        const std::string_view key = w[0];
        if (key == "newmtl") {
            std::string name(rest_of_line(whole, key));
            if (name.empty()) {
                warn(progress, at + "'newmtl' without a name: the material is called '" +
                                   kUnnamed + "'");
                name = kUnnamed;
            }
            close_material();
            out.push_back(Material{std::move(name), Vec3(0.0f), Vec3(0.0f)});
            newmtl_line = k + 1;
            has_kd = false;
        } else if (out.empty()) {
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
            // raylab shades with the diffuse colour and the emission only
            if (key == "Kd") {
                out.back().rho = Vec3(x[0], x[1], x[2]);
                has_kd = true;
            }
            if (key == "Ke") out.back().Le = Vec3(x[0], x[1], x[2]);
        } else if (key == "Ns" || key == "Ni" || key == "d" || key == "Tr") {
            numbers(w, 1, 1, one, at);
        } else {
            ignored.add(k + 1, key);
        }
    }
    close_material();
    no_diffuse.report(progress, source);
    ignored.report(progress, source);
    return out;
}

}  // namespace raylab::obj
