// raylab-sandbox: the two steps of scripts/grade.sh that touch a hand-in before the
// worker's sandbox exists.
//
//   raylab-sandbox stage SRC DEST ID...   copy each module's file (and the headers beside
//                                         it) from the hand-in SRC to DEST/ID/
//   raylab-sandbox run [--ro PATH]... [--rw PATH]... -- COMMAND [ARGS...]
//                                         run COMMAND where it can open the given paths
//                                         only (Landlock), for a compile without
//                                         namespaces
//   raylab-sandbox check                  exit 0 when Landlock works on this kernel
//
// Staging never follows a link: every folder and file is opened relative to its parent
// with O_NOFOLLOW, and only regular files with one name (no hard link) and at most 1 MiB
// each, 8 MiB in all, are copied. A link, FIFO, device or socket is refused with a note
// naming it. Where the kernel has Landlock, staging also confines itself to SRC and DEST,
// so that even a slip here could not read another file. Its report, one line each on
// standard output (names escaped with printable()):
//   used TAB ID TAB PATH        the file graded for module ID
//   missing TAB ID TAB TEXT     module ID scores zero, and why
//   note TAB ID TAB TEXT        something the student should know (ID "-": the hand-in)
#include <dirent.h>
#include <fcntl.h>
#include <linux/landlock.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "raylab/input_file.h"

namespace {

constexpr size_t kMaxFile = size_t(1) << 20;    // one file of a hand-in
constexpr size_t kMaxHandIn = size_t(8) << 20;  // everything staged from one hand-in
constexpr int kMaxFolderDepth = 2;              // NN_name.cpp at most two folders deep
constexpr int kMaxScanDepth = 8;                // deeper files are named, not graded
constexpr size_t kMaxEntries = 20000;           // a hand-in with more is not scanned on

[[noreturn]] void fail(const std::string& message) {
    std::cerr << "raylab-sandbox: " << message << "\n";
    std::exit(2);
}

std::string shown(const std::string& path) {
    return raylab::printable(path, 160);
}

// ---- Landlock
// ---------------------------------------------------------------------------

int landlock_abi() {
#ifdef SYS_landlock_create_ruleset
    const long abi =
        syscall(SYS_landlock_create_ruleset, nullptr, 0, LANDLOCK_CREATE_RULESET_VERSION);
    return abi < 0 ? 0 : int(abi);
#else
    return 0;
#endif
}

// The rights and fields of later Landlock ABIs, which older kernel headers lack
constexpr std::uint64_t kTruncate = 1ull << 14;  // ABI 3
constexpr std::uint64_t kIoctlDev = 1ull << 15;  // ABI 5
constexpr std::uint64_t kScopeAbstractUnixSocket = 1ull << 0, kScopeSignal = 1ull << 1;
struct RulesetAttr {  // landlock_ruleset_attr of ABI 6
    std::uint64_t handled_access_fs = 0, handled_access_net = 0, scoped = 0;
};

// Every file-system right the kernel's Landlock knows
std::uint64_t handled_rights(int abi) {
    std::uint64_t r = (LANDLOCK_ACCESS_FS_MAKE_SYM << 1) - 1;  // ABI 1
    if (abi >= 2) r |= LANDLOCK_ACCESS_FS_REFER;
    if (abi >= 3) r |= kTruncate;
    if (abi >= 5) r |= kIoctlDev;
    return r;
}

constexpr std::uint64_t kFileRights =
    LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_WRITE_FILE |
    LANDLOCK_ACCESS_FS_READ_FILE | kTruncate | kIoctlDev;

// From here on this process and its children open only the paths given (read-only or
// read-write), whatever their permissions say; false when the kernel cannot
bool confine(const std::vector<std::string>& ro, const std::vector<std::string>& rw) {
#ifdef SYS_landlock_create_ruleset
    const int abi = landlock_abi();
    if (abi < 1) return false;
    const std::uint64_t handled = handled_rights(abi);
    RulesetAttr attr;
    attr.handled_access_fs = handled;
    // ABI 6: no signals to, and no abstract sockets of, processes outside
    if (abi >= 6) attr.scoped = kScopeAbstractUnixSocket | kScopeSignal;
    const size_t attr_size = abi >= 6 ? sizeof attr : sizeof attr.handled_access_fs;
    const int ruleset = int(syscall(SYS_landlock_create_ruleset, &attr, attr_size, 0));
    if (ruleset < 0) return false;
    const auto allow = [&](const std::string& path, std::uint64_t rights) {
        const int fd = open(path.c_str(), O_PATH | O_CLOEXEC);
        if (fd < 0) return;  // a path this machine does not have
        struct stat st {};
        fstat(fd, &st);
        if (!S_ISDIR(st.st_mode)) rights &= kFileRights;
        landlock_path_beneath_attr rule{};
        rule.allowed_access = rights & handled;
        rule.parent_fd = fd;
        if (syscall(SYS_landlock_add_rule, ruleset, LANDLOCK_RULE_PATH_BENEATH, &rule, 0))
            fail("Landlock refused a rule for " + shown(path) + ": " +
                 std::strerror(errno));
        close(fd);
    };
    const std::uint64_t read = LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_READ_FILE |
                               LANDLOCK_ACCESS_FS_READ_DIR;
    for (const std::string& p : ro)
        allow(p, read);
    for (const std::string& p : rw)
        allow(p, handled);
    if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) return false;
    const bool ok = syscall(SYS_landlock_restrict_self, ruleset, 0) == 0;
    close(ruleset);
    return ok;
#else
    (void)ro;
    (void)rw;
    return false;
#endif
}

// ---- Staging
// ----------------------------------------------------------------------------

struct Entry {
    std::string path;  // relative to the hand-in
    std::string name;
    int folders = 0;  // how many folders deep
    mode_t type = 0;
    off_t size = 0;
    nlink_t links = 1;
};

const char* type_name(mode_t type) {
    switch (type) {
        case S_IFLNK:
            return "a symbolic link";
        case S_IFIFO:
            return "a FIFO";
        case S_IFCHR:
            return "a character device";
        case S_IFBLK:
            return "a block device";
        case S_IFSOCK:
            return "a socket";
        default:
            return "not a regular file";
    }
}

std::vector<Entry> entries;
bool too_many = false;

void scan(int dir, const std::string& prefix, int folders) {
    const int fd = dup(dir);
    DIR* d = fd >= 0 ? fdopendir(fd) : nullptr;
    if (!d) return;
    std::vector<std::string> names;
    while (const dirent* e = readdir(d)) {
        const std::string name = e->d_name;
        // Dot files (.git, .DS_Store) and macOS's zip metadata are not part of a hand-in
        if (name.empty() || name[0] == '.' || name == "__MACOSX") continue;
        names.push_back(name);
    }
    closedir(d);
    std::sort(names.begin(), names.end());
    for (const std::string& name : names) {
        if (entries.size() >= kMaxEntries) {
            too_many = true;
            return;
        }
        struct stat st {};
        if (fstatat(dir, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) continue;
        Entry e{prefix + name, name,       folders, mode_t(st.st_mode & S_IFMT),
                st.st_size,    st.st_nlink};
        entries.push_back(e);
        if (e.type == S_IFDIR && folders < kMaxScanDepth) {
            const int sub = openat(dir, name.c_str(),
                                   O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
            if (sub >= 0) {
                scan(sub, e.path + "/", folders + 1);
                close(sub);
            }
        }
    }
}

// Opens the regular file at the relative path without following a link anywhere on the
// way; -1 when it is not one
int open_regular(int root, const std::string& rel) {
    int dir = dup(root);
    size_t at = 0;
    for (;;) {
        const size_t slash = rel.find('/', at);
        const std::string part = rel.substr(at, slash - at);
        const int flags = slash == std::string::npos
                              ? O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC
                              : O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC;
        const int next = openat(dir, part.c_str(), flags);
        close(dir);
        if (next < 0) return -1;
        if (slash == std::string::npos) {
            struct stat st {};
            if (fstat(next, &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink != 1) {
                close(next);
                return -1;
            }
            return next;
        }
        dir = next;
        at = slash + 1;
    }
}

std::string lower(std::string s) {
    for (char& c : s)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// A name a student may have meant as want: another case, a copy's suffix ("(1)", " copy",
// "-2"), or .cc/.cxx/.txt for .cpp (every module's name ends in a letter)
bool near_miss(const std::string& name, const std::string& want) {
    const std::string n = lower(name), w = lower(want);
    if (n == w) return name != want;
    const size_t dot = n.find('.');
    std::string base = n.substr(0, dot);
    const std::string ext = dot == std::string::npos ? "" : n.substr(dot);
    if (ext != ".cpp" && ext != ".cc" && ext != ".cxx" && ext != ".c" && ext != ".txt" &&
        ext != ".cpp.txt")
        return false;
    for (bool again = true; again;) {
        again = false;
        if (base.size() > 5 && base.compare(base.size() - 5, 5, " copy") == 0) {
            base.resize(base.size() - 5);
            again = true;
        }
        while (!base.empty() && std::strchr(" ()-_0123456789", base.back())) {
            base.pop_back();
            again = true;
        }
    }
    return base == w.substr(0, w.size() - 4);
}

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() &&
           s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Copies rel (a regular file) to dest with CR LF as LF; false (and a note) when it cannot
size_t staged_bytes = 0;

std::string copy_file(int root, const std::string& rel, const std::string& dest) {
    const int fd = open_regular(root, rel);
    if (fd < 0) return "it is not a regular file with one name";
    std::string data;
    char buf[65536];
    for (;;) {
        const ssize_t n = read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        data.append(buf, size_t(n));
        if (data.size() > kMaxFile) break;
    }
    close(fd);
    if (data.size() > kMaxFile) return "it is larger than 1 MiB";
    if (staged_bytes + data.size() > kMaxHandIn)
        return "the hand-in's files add up to more than 8 MiB";
    staged_bytes += data.size();
    std::string out;
    out.reserve(data.size());
    for (size_t k = 0; k < data.size(); ++k)
        if (!(data[k] == '\r' && k + 1 < data.size() && data[k + 1] == '\n'))
            out += data[k];
    FILE* f = std::fopen(dest.c_str(), "wbx");
    if (!f) fail("cannot write " + dest + ": " + std::strerror(errno));
    const bool ok = std::fwrite(out.data(), 1, out.size(), f) == out.size();
    if (std::fclose(f) != 0 || !ok) fail("cannot write " + dest);
    return "";
}

std::string folder_of(const std::string& rel) {
    const size_t slash = rel.rfind('/');
    return slash == std::string::npos ? "" : rel.substr(0, slash + 1);
}

int stage(const std::string& src, const std::string& dest,
          const std::vector<std::string>& ids) {
    const int root = open(src.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (root < 0)
        fail("cannot open the hand-in " + shown(src) + ": " + std::strerror(errno));
    if (landlock_abi() >= 1 && !confine({src}, {dest}))
        fail("Landlock is here but could not confine the staging step");
    scan(root, "", 0);
    const auto say = [](const char* kind, const std::string& id,
                        const std::string& text) {
        std::cout << kind << '\t' << id << '\t' << text << '\n';
    };
    if (too_many)
        say("note", "-",
            "the hand-in has more than " + std::to_string(kMaxEntries) +
                " files and folders: only the first were looked at");
    const auto is_module = [&](const std::string& name) {
        return std::find(ids.begin(), ids.end(), name.substr(0, name.size() - 4)) !=
                   ids.end() &&
               ends_with(name, ".cpp");
    };
    // Anything that is not a regular file or folder is refused, whatever its name
    for (const Entry& e : entries) {
        if (e.type == S_IFDIR) continue;
        if (e.type != S_IFREG)
            say("note", "-",
                "refused " + shown(e.path) + ": " + type_name(e.type) +
                    " (a hand-in holds regular files only)");
        else if (e.links != 1)
            say("note", "-",
                "refused " + shown(e.path) +
                    ": a hard link (a hand-in holds regular files "
                    "only)");
        else if (ends_with(e.name, ".cpp") && !is_module(e.name) &&
                 e.folders <= kMaxFolderDepth)
            say("note", "-",
                "not compiled: " + shown(e.path) +
                    " (each module is one NN_name.cpp file; put helpers in a header "
                    "beside it)");
    }
    for (const std::string& id : ids) {
        const std::string want = id + ".cpp";
        std::vector<const Entry*> found, deeper, misses, refused;
        for (const Entry& e : entries) {
            if (e.type == S_IFDIR) continue;
            if (e.name == want) {
                if (e.type != S_IFREG || e.links != 1)
                    refused.push_back(&e);
                else
                    (e.folders <= kMaxFolderDepth ? found : deeper).push_back(&e);
            } else if (e.type == S_IFREG && near_miss(e.name, want)) {
                misses.push_back(&e);
            }
        }
        std::stable_sort(found.begin(), found.end(), [](const Entry* a, const Entry* b) {
            return a->folders != b->folders ? a->folders < b->folders : a->path < b->path;
        });
        if (found.empty()) {
            std::string why = want + " is missing from the hand-in";
            if (!refused.empty())
                why = want + " is refused: " + shown(refused[0]->path) + " is " +
                      (refused[0]->type == S_IFREG ? std::string("a hard link")
                                                   : type_name(refused[0]->type)) +
                      ", not a regular file";
            else if (!deeper.empty())
                why = want + " is missing from the hand-in: " + shown(deeper[0]->path) +
                      " is more than two folders deep, and is not graded (move it up)";
            else if (!misses.empty())
                why = want + " is missing from the hand-in: " + shown(misses[0]->path) +
                      " is not graded (rename it to " + want + ")";
            say("missing", id, why);
            continue;
        }
        const Entry& used = *found[0];
        for (size_t k = 1; k < found.size(); ++k)
            say("note", id,
                "ignored " + shown(found[k]->path) + " (graded " + shown(used.path) +
                    ", the one nearest the top)");
        for (const Entry* e : deeper)
            say("note", id,
                "ignored " + shown(e->path) + " (more than two folders deep)");
        const std::string dir = dest + "/" + id;
        if (mkdir(dir.c_str(), 0755) != 0) fail("cannot create " + dir);
        if (const std::string why = copy_file(root, used.path, dir + "/" + want);
            !why.empty()) {
            say("missing", id, want + " is refused: " + shown(used.path) + ": " + why);
            continue;
        }
        say("used", id, shown(used.path));
        // The headers beside it
        const std::string folder = folder_of(used.path);
        for (const Entry& e : entries) {
            if (e.type != S_IFREG || e.links != 1 || folder_of(e.path) != folder ||
                !(ends_with(e.name, ".h") || ends_with(e.name, ".hpp")))
                continue;
            if (const std::string why = copy_file(root, e.path, dir + "/" + e.name);
                !why.empty())
                say("note", id, "refused " + shown(e.path) + ": " + why);
        }
    }
    close(root);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::vector<std::string> a(argv + 1, argv + argc);
    if (a.empty()) fail("usage: raylab-sandbox stage|run|check ...");
    if (a[0] == "check") return landlock_abi() >= 1 ? 0 : 1;
    if (a[0] == "stage") {
        if (a.size() < 4) fail("usage: raylab-sandbox stage SRC DEST ID...");
        return stage(a[1], a[2], std::vector<std::string>(a.begin() + 3, a.end()));
    }
    if (a[0] == "run") {
        std::vector<std::string> ro, rw;
        size_t k = 1;
        for (; k < a.size() && a[k] != "--"; ++k) {
            if (k + 1 >= a.size()) fail(a[k] + " needs a path");
            if (a[k] == "--ro")
                ro.push_back(a[++k]);
            else if (a[k] == "--rw")
                rw.push_back(a[++k]);
            else
                fail("unknown option " + shown(a[k]));
        }
        if (k + 1 >= a.size()) fail("run needs -- COMMAND");
        if (!confine(ro, rw)) fail("Landlock is not available on this kernel");
        std::vector<char*> args;
        for (size_t j = k + 1; j < a.size(); ++j)
            args.push_back(argv[j + 1]);
        args.push_back(nullptr);
        execvp(args[0], args.data());
        fail("cannot run " + shown(a[k + 1]) + ": " + std::strerror(errno));
    }
    fail("unknown command " + shown(a[0]));
}
