// raylab-grade: the score table, the per-module texts, JUnit XML and results.json, and
// the small helpers the driver's parts share.
#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "grade.h"

namespace raylab::grade {

// ---- Helpers
// -------------------------------------------------------------------------------

[[noreturn]] void die(const std::string& message) {
    std::cerr << "raylab-grade: " << message << "\n";
    std::exit(2);
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string item;
    std::istringstream in(s);
    while (std::getline(in, item, sep))
        out.push_back(item);
    return out;
}

std::string first_line(const std::string& s) {
    return s.substr(0, s.find('\n'));
}

std::string shorten(const std::string& s, size_t n) {
    return s.size() <= n ? s : s.substr(0, n - 3) + "...";
}

// mkdir -p
void make_dirs(const std::string& path) {
    size_t at = 0;
    do {
        at = path.find('/', at + 1);
        const std::string prefix = path.substr(0, at);
        if (mkdir(prefix.c_str(), 0755) != 0 && errno != EEXIST)
            die("cannot create " + prefix + ": " + std::strerror(errno));
    } while (at != std::string::npos);
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out) die("cannot write " + path);
}
// ---- Reports --------------------------------------------------------------------------

std::string fixed(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", x);
    return buf;
}

double rounded(double x) {
    return std::round(x * 100.0) / 100.0;
}

std::string indented(const std::string& s) {
    std::string out;
    for (const std::string& line : split(s, '\n'))
        out += "  " + line + "\n";
    return out;
}

std::string reason(const ModuleResult& m, double timeout) {
    if (m.status == "passed" && m.score == m.max_score) return "";
    if (m.status == "build error") {
        const std::string& f = m.first_failure;
        const auto has = [&](const char* what) {
            return f.find(what) != std::string::npos;
        };
        if (has("is missing")) return "missing";
        if (has("is refused")) return "refused";
        if (has("does not compile")) return "did not compile";
        if (has("does not link")) return "did not link";
        if (has("not allowed")) return "not allowed";
        return "did not build";
    }
    if (m.status == "not started") return "not started";
    if (m.status.rfind("crashed", 0) == 0) {
        const size_t open = m.status.find('(');
        return open == std::string::npos
                   ? "crashed"
                   : "crashed with signal " +
                         m.status.substr(open + 1, m.status.size() - open - 2);
    }
    if (m.status == "time limit") {
        char buf[64];
        std::snprintf(buf, sizeof buf, "no answer in %g s", timeout);
        return buf;
    }
    if (m.status == "error") return "grader error";
    for (const CaseResult& c : m.cases) {
        if (c.status == "pass") continue;
        const std::string& t = c.message;
        for (size_t at = t.find("nan"); at != std::string::npos;
             at = t.find("nan", at + 1)) {
            const bool word_start =
                at == 0 || !std::isalpha(static_cast<unsigned char>(t[at - 1]));
            const bool word_end = at + 3 >= t.size() ||
                                  !std::isalpha(static_cast<unsigned char>(t[at + 3]));
            if (word_start && word_end) return "NaN";
        }
        if (t.find("NaN") != std::string::npos) return "NaN";
    }
    return "wrong";
}

std::string pad(const std::string& s, size_t n) {
    return s.size() >= n ? s : s + std::string(n - s.size(), ' ');
}

std::string table(const std::vector<ModuleResult>& modules, const std::string& label) {
    std::ostringstream s;
    s << "raylab grade: " << label << "\n\n"
      << pad("module", 16) << pad("tests", 8) << pad("points", 14) << "first failure\n";
    double total = 0, max_total = 0;
    int passed = 0, cases = 0;
    for (const ModuleResult& m : modules) {
        const std::string tests =
            std::to_string(m.passed) + "/" + std::to_string(m.cases.size());
        s << pad(m.info->id, 16) << pad(tests, 8)
          << pad(fixed(m.score) + " / " + fixed(m.max_score), 14)
          << (m.reason.empty() ? "-"
                               : shorten("[" + m.reason + "] " + m.first_failure, 110))
          << "\n";
        total += m.score;
        max_total += m.max_score;
        passed += m.passed;
        cases += int(m.cases.size());
    }
    s << pad("total", 16) << pad(std::to_string(passed) + "/" + std::to_string(cases), 8)
      << fixed(total) << " / " << fixed(max_total) << "\n";
    return s.str();
}

// The text a student reads for one module: status, then every failed case with its
// message
std::string module_output(const ModuleResult& m, size_t max_cases) {
    std::ostringstream s;
    s << m.info->id << " (" << m.info->title << "): " << m.passed << "/" << m.cases.size()
      << " tests passed, " << fixed(m.score) << " of " << fixed(m.max_score)
      << " points [" << (m.reason.empty() ? m.status : m.reason) << "]\n";
    int hidden = 0, hidden_passed = 0;
    for (const CaseResult& c : m.cases) {
        if (c.name.rfind(kPrivate, 0) != 0) continue;
        ++hidden;
        hidden_passed += c.status == "pass";
    }
    if (hidden > 0)
        s << "public tests: " << m.passed - hidden_passed << "/"
          << m.cases.size() - hidden << " passed; private tests: " << hidden_passed << "/"
          << hidden << " passed\n";
    if (!m.source.empty()) s << "graded file: " << m.source << "\n";
    for (const std::string& note : m.notes)
        s << "note: " << note << "\n";
    if (!m.sandbox.empty()) s << "student code ran in: " << m.sandbox << "\n";
    if (!m.build_error.empty()) {
        s << "\n" << indented(shorten(m.build_error, 4000));
        return s.str();
    }
    if (m.status == "time limit" || m.status.rfind("crashed", 0) == 0)
        s << indented(m.first_failure);
    if (m.status == "not started") {
        s << "Every test stopped at a function that still calls RAYLAB_STUB.\n";
        return s.str();
    }
    size_t shown = 0;
    for (const CaseResult& c : m.cases) {
        if (c.status == "pass" || c.status == "not run") continue;
        if (shown++ == max_cases) {
            s << "(more failures in logs/" << m.info->id << ".log)\n";
            break;
        }
        s << "\nFAILED: " << c.name << "\n" << indented(shorten(c.message, 1500));
    }
    return s.str();
}

std::string clean_text(const std::string& s) {
    std::string out;
    size_t k = 0;
    const auto byte = [&](size_t at) { return static_cast<unsigned char>(s[at]); };
    while (k < s.size()) {
        const unsigned char c = byte(k);
        if (c == 0x1b) {  // a terminal escape: ESC [ parameters final-byte, or ESC x
            ++k;
            if (k < s.size() && s[k] == '[') {
                ++k;
                while (k < s.size() && !(byte(k) >= 0x40 && byte(k) <= 0x7e))
                    ++k;
            }
            if (k < s.size()) ++k;
            continue;
        }
        if (c < 0x80) {
            if ((c >= 0x20 && c != 0x7f) || c == '\n' || c == '\t') out += char(c);
            ++k;
            continue;
        }
        // A UTF-8 sequence: lead byte, then 1-3 continuation bytes, no overlong forms
        const int n = c >= 0xf0 && c <= 0xf4  ? 3
                      : c >= 0xe0             ? 2
                      : c >= 0xc2 && c < 0xe0 ? 1
                                              : -1;
        bool ok = n > 0 && k + size_t(n) < s.size();
        for (int j = 1; ok && j <= n; ++j)
            ok = k + j < s.size() && (byte(k + j) & 0xc0) == 0x80;
        if (ok && n == 2 && c == 0xe0) ok = byte(k + 1) >= 0xa0;
        if (ok && n == 2 && c == 0xed) ok = byte(k + 1) < 0xa0;  // no surrogates
        if (ok && n == 3 && c == 0xf0) ok = byte(k + 1) >= 0x90;
        if (ok && n == 3 && c == 0xf4) ok = byte(k + 1) < 0x90;
        if (!ok) {
            out += "\xef\xbf\xbd";  // U+FFFD
            ++k;
            continue;
        }
        // The C1 controls (U+009B is a terminal's CSI), the line and paragraph separators
        // and the bidirectional controls can move the cursor or reorder what a reader
        // sees: they are written out as a backslash, u and {hex}
        char32_t cp = c & (n == 1 ? 0x1f : n == 2 ? 0x0f : 0x07);
        for (int j = 1; j <= n; ++j)
            cp = (cp << 6) | (byte(k + j) & 0x3f);
        if ((cp >= 0x80 && cp <= 0x9f) || cp == 0x2028 || cp == 0x2029 || cp == 0x200e ||
            cp == 0x200f || (cp >= 0x202a && cp <= 0x202e) ||
            (cp >= 0x2066 && cp <= 0x2069) || cp == 0xfeff) {
            char hex[16];
            std::snprintf(hex, sizeof hex, "\\u{%x}", unsigned(cp));
            out += hex;
        } else {
            out.append(s, k, size_t(n) + 1);
        }
        k += size_t(n) + 1;
    }
    return out;
}

std::string xml_escape(const std::string& raw) {
    std::string out;
    for (const char c : clean_text(raw)) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string junit(const std::vector<ModuleResult>& modules) {
    std::ostringstream s;
    int tests = 0, failures = 0, errors = 0;
    std::ostringstream suites;
    for (const ModuleResult& m : modules) {
        int f = 0, e = 0;
        std::ostringstream cases;
        for (const CaseResult& c : m.cases) {
            cases << "    <testcase classname=\"" << m.info->id << "\" name=\""
                  << xml_escape(c.name) << "\"";
            if (c.status == "pass") {
                cases << "/>\n";
                continue;
            }
            const bool error = c.status == "crash" || c.status == "not run";
            (error ? e : f)++;
            const char* tag = error ? "error" : "failure";
            const std::string message = c.message.empty() ? m.first_failure : c.message;
            cases << ">\n      <" << tag << " message=\""
                  << xml_escape(first_line(message)) << "\">" << xml_escape(message)
                  << "</" << tag << ">\n    </testcase>\n";
        }
        suites << "  <testsuite name=\"" << m.info->id << "\" tests=\"" << m.cases.size()
               << "\" failures=\"" << f << "\" errors=\"" << e << "\" time=\""
               << m.seconds << "\">\n"
               << cases.str() << "  </testsuite>\n";
        tests += int(m.cases.size());
        failures += f;
        errors += e;
    }
    s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"raylab-grade\" "
         "tests=\""
      << tests << "\" failures=\"" << failures << "\" errors=\"" << errors << "\">\n"
      << suites.str() << "</testsuites>\n";
    return s.str();
}

std::string cases_json(const std::vector<ModuleResult>& modules) {
    nlohmann::json out = nlohmann::json::array();
    for (const ModuleResult& m : modules) {
        nlohmann::json cases = nlohmann::json::array();
        for (const CaseResult& c : m.cases)
            cases.push_back({{"name", clean_text(c.name)},
                             {"status", c.status},
                             {"message", clean_text(c.message)}});
        out.push_back({{"id", m.info->id},
                       {"status", m.status},
                       {"passed", m.passed},
                       {"score", m.score},
                       {"max_score", m.max_score},
                       {"reason", m.reason},
                       {"first_failure", clean_text(m.first_failure)},
                       {"build_error", clean_text(m.build_error)},
                       {"cases", cases}});
    }
    return out.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::vector<ModuleResult> read_cases_json(const std::string& text) {
    std::vector<ModuleResult> modules;
    const nlohmann::json list = nlohmann::json::parse(text, nullptr, false);
    if (!list.is_array()) return modules;
    try {
        for (const nlohmann::json& m : list) {
            if (!m.is_object()) continue;
            const std::string id = m.value("id", "");
            const ModuleInfo* info = nullptr;
            for (const ModuleInfo& i : module_infos())
                if (id == i.id) info = &i;
            if (!info) continue;
            ModuleResult r;
            r.info = info;
            r.status = m.value("status", "error");
            r.passed = m.value("passed", 0);
            r.score = m.value("score", 0.0);
            r.max_score = m.value("max_score", 0.0);
            r.reason = m.value("reason", "");
            r.first_failure = m.value("first_failure", "");
            r.build_error = m.value("build_error", "");
            for (const nlohmann::json& c : m.value("cases", nlohmann::json::array()))
                r.cases.push_back(
                    {c.value("name", ""), c.value("status", ""), c.value("message", "")});
            modules.push_back(std::move(r));
        }
    } catch (const nlohmann::json::exception&) {  // a field of the wrong type
        modules.clear();
    }
    return modules;
}

// Which part of the module's points came from the public and the private tests
nlohmann::json part_points(const ModuleResult& m) {
    int hidden = 0, hidden_passed = 0;
    for (const CaseResult& c : m.cases) {
        if (c.name.rfind(kPrivate, 0) != 0) continue;
        ++hidden;
        hidden_passed += c.status == "pass";
    }
    const double per_case = m.passed > 0 ? m.score / m.passed : 0.0;
    return {{"public_points", per_case * (m.passed - hidden_passed)},
            {"private_points", per_case * hidden_passed},
            {"public_cases", int(m.cases.size()) - hidden},
            {"private_cases", hidden}};
}

std::string results_json(const std::vector<ModuleResult>& modules,
                         const std::string& summary,
                         const std::vector<std::string>& hand_in_notes) {
    // Gradescope's format: https://gradescope-autograders.readthedocs.io/en/latest/specs/
    double total = 0;
    nlohmann::json tests = nlohmann::json::array();
    for (const ModuleResult& m : modules) {
        total += m.score;
        nlohmann::json extra = part_points(m);
        extra["reason"] = m.reason;
        extra["notes"] = nlohmann::json::array();
        for (const std::string& note : m.notes)
            extra["notes"].push_back(clean_text(note));
        tests.push_back({
            {"name", std::string(m.info->id) + ": " + m.info->title},
            {"number", m.info->id},
            {"score", m.score},
            {"max_score", m.max_score},
            {"status", m.status == "passed" ? "passed" : "failed"},
            {"visibility", "visible"},
            {"output", clean_text(module_output(m))},
            {"extra_data", extra},
        });
    }
    nlohmann::json notes = nlohmann::json::array();
    for (const std::string& note : hand_in_notes)
        notes.push_back(clean_text(note));
    const nlohmann::json results = {
        {"score", rounded(total)}, {"output", clean_text(summary)},
        {"visibility", "visible"}, {"stdout_visibility", "hidden"},
        {"tests", tests},          {"extra_data", {{"notes", notes}}},
    };
    // clean_text made every string valid UTF-8; replace guards against a slip anyway
    return results.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace raylab::grade
