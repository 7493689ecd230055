// The trusted side of the grading worker: starts it in its sandbox, sends calls, answers
// its callbacks, and enforces a wall-clock limit per call (rpc.h has the wire).
//
// Environment of the trusted grader (set by raylab-grade, never seen by the worker):
//   RAYLAB_WORKER=FILE         the worker executable (default: the one CMake built for
//                              the implementation under test)
//   RAYLAB_WORKER_TIMEOUT=S    wall-clock limit per call and for start-up (default 10)
//   RAYLAB_WORKER_LOG=FILE     where the worker's own output goes (capped at 1 MiB)
//   RAYLAB_SANDBOX=auto|bwrap|none  bubblewrap when it can create namespaces (auto)
#pragma once

#include <sys/types.h>

#include <string>
#include <type_traits>

#include "rpc.h"

namespace raylab::grading {

/// The callbacks of the call under way.
struct Callbacks {
    const PixelRadiance* radiance = nullptr;
    const Occluder* occluder = nullptr;
};

/// How the worker of this run is protected, for the reports, e.g. "bubblewrap
/// (namespaces, read-only system, no network) + seccomp + rlimits". Valid once the
/// worker has started.
std::string sandbox_description();

/// Ends the worker and removes its private folder (before the trusted process exits).
void shutdown_worker();

/// Appends a line to the grade log (RAYLAB_GRADE_LOG), if there is one (main.cpp).
void log_line(const std::string& line);

/// Called when the worker crashed or ran out of time: kind "crash" or "timeout" and a
/// message. Writes the grade log's line and ends the trusted process (main.cpp).
[[noreturn]] void worker_lost(const std::string& kind, const std::string& message);

/// Sends call function with the encoded arguments, answers callbacks, returns the
/// result's payload; sets stubbed. Throws std::runtime_error with the message of an
/// exception the student's code threw.
rpc::Buffer exchange(rpc::Function function, std::uint32_t fault, const rpc::Buffer& args,
                     const Callbacks& callbacks, bool& stubbed);

// ---- Parameters, encoded -------------------------------------------------------------

template <class T>
struct Param {
    static void put(rpc::Buffer& b, const T& v, Callbacks&) { rpc::put_value(b, v); }
    static void read_out(rpc::Buffer&, const T&) {}
};
template <>
struct Param<PixelRadiance> {
    static void put(rpc::Buffer&, const PixelRadiance& v, Callbacks& c) {
        c.radiance = &v;
    }
    static void read_out(rpc::Buffer&, const PixelRadiance&) {}
};
template <>
struct Param<Occluder> {
    static void put(rpc::Buffer&, const Occluder& v, Callbacks& c) { c.occluder = &v; }
    static void read_out(rpc::Buffer&, const Occluder&) {}
};
template <>
struct Param<ImageView> {
    static void put(rpc::Buffer& b, const ImageView& v, Callbacks&) {
        b.put(v.width);
        b.put(v.height);
        b.put_raw(v.pixels, size_t(v.width) * size_t(v.height) * sizeof(Vec3));
    }
    static void read_out(rpc::Buffer& b, const ImageView& v) {
        b.get_raw(v.pixels, size_t(v.width) * size_t(v.height) * sizeof(Vec3));
    }
};

/// Calls function (signature fn, used for its type only: never called here) in the
/// worker. Returns the result and sets stubbed.
template <class R, class... A>
R remote(rpc::Function function, std::uint32_t fault, R (*)(A...), bool& stubbed,
         const std::decay_t<A>&... args) {
    rpc::Buffer b;
    Callbacks callbacks;
    (Param<std::decay_t<A>>::put(b, args, callbacks), ...);
    rpc::Buffer reply = exchange(function, fault, b, callbacks, stubbed);
    if constexpr (std::is_void_v<R>) {
        (Param<std::decay_t<A>>::read_out(reply, args), ...);
    } else {
        R result{};
        rpc::get_value(reply, result);
        (Param<std::decay_t<A>>::read_out(reply, args), ...);
        return result;
    }
}

}  // namespace raylab::grading
