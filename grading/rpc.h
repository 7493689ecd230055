// The wire between the trusted grader and the grading worker (worker_main.cpp), shared by
// both sides.
//
// The trusted side (grading.cpp, worker_client.cpp) sends one call at a time: a Header
// and the encoded arguments. The worker answers with a result, an exception message, or a
// callback request (the PixelRadiance of render_tile, the Occluder of in_shadow) that the
// trusted side answers before the worker goes on. Every value crosses as the bytes of a
// trivially copyable type, so the contract types can gain fields without touching this
// file; the functions themselves come from the registry (raylab/modules.def).
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "raylab/contract.h"

namespace raylab::rpc {

/// One value per contract function, in registry order.
enum class Function : std::uint32_t {
#define RAYLAB_FUNCTION(m, f) f,
#include "raylab/modules.def"
    count
};

/// The function's name, for messages.
inline const char* function_name(std::uint32_t f) {
    static const char* const names[] = {
#define RAYLAB_FUNCTION(m, f) #f,
#include "raylab/modules.def"
    };
    return f < std::uint32_t(Function::count) ? names[f] : "an unknown function";
}

enum class Kind : std::uint32_t {
    hello = 1,  ///< worker -> trusted: main() started (static initializers are done)
    call,       ///< trusted -> worker: function, fault, arguments
    result,     ///< worker -> trusted: return value and out-parameters; flags: stub bit
    exception,  ///< worker -> trusted: what() of an exception the student's code threw
    radiance,   ///< worker -> trusted: PixelRadiance(uv); answered with reply
    occluded,   ///< worker -> trusted: Occluder::occluded(ray); answered with reply
    reply,      ///< trusted -> worker: the callback's answer
};

/// Faults the grader's own tests inject into the worker (RAYLAB_GRADE_FAULT).
enum Fault : std::uint32_t { kNoFault = 0, kSegv, kHang, kThrow };

struct Header {
    Kind kind;
    std::uint32_t function;
    std::uint32_t flags;
    std::uint32_t size;  ///< bytes of payload that follow
};
static_assert(std::is_trivially_copyable_v<Header>);

/// The largest payload either side accepts (an image of 4096 x 4096 pixels).
inline constexpr std::uint32_t kMaxPayload = 4096u * 4096u * sizeof(Vec3) + 64;

/// A message's payload: values appended with put() and read back with get().
class Buffer {
  public:
    std::vector<char> bytes;

    template <class T>
    void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>, "only plain bytes cross the wire");
        put_raw(&value, sizeof(T));
    }
    void put_raw(const void* data, size_t n) {
        if (n == 0) return;
        const size_t at = bytes.size();
        bytes.resize(at + n);
        std::memcpy(bytes.data() + at, data, n);
    }
    template <class T>
    T get() {
        static_assert(std::is_trivially_copyable_v<T>, "only plain bytes cross the wire");
        T value;
        get_raw(&value, sizeof(T));
        return value;
    }
    void get_raw(void* data, size_t n) {
        if (n > bytes.size() - at_) throw std::runtime_error("rpc: message too short");
        std::memcpy(data, bytes.data() + at_, n);
        at_ += n;
    }

  private:
    size_t at_ = 0;
};

// ---- Values ---------------------------------------------------------------------------
// put_value/get_value for the types of contract_functions.inc. A bool and an optional
// cross as a byte and a value, never as the bytes of a bool (which could hold 2).

template <class T>
void put_value(Buffer& b, const T& v) {
    b.put(v);
}
template <class T>
void get_value(Buffer& b, T& v) {
    v = b.get<T>();
}
inline void put_value(Buffer& b, const bool& v) {
    b.put<std::uint8_t>(v ? 1 : 0);
}
inline void get_value(Buffer& b, bool& v) {
    v = b.get<std::uint8_t>() != 0;
}
template <class T>
void put_value(Buffer& b, const std::optional<T>& v) {
    put_value(b, v.has_value());
    if (v) put_value(b, *v);
}
template <class T>
void get_value(Buffer& b, std::optional<T>& v) {
    bool has = false;
    get_value(b, has);
    v.reset();
    if (has) {
        T value;
        get_value(b, value);
        v = value;
    }
}
template <class T>
void put_value(Buffer& b, const std::vector<T>& v) {
    b.put<std::uint32_t>(static_cast<std::uint32_t>(v.size()));
    for (const T& x : v)
        put_value(b, x);
}
template <class T>
void get_value(Buffer& b, std::vector<T>& v) {
    const auto n = b.get<std::uint32_t>();
    if (n > kMaxPayload / sizeof(T)) throw std::runtime_error("rpc: vector too long");
    v.resize(n);
    for (T& x : v)
        get_value(b, x);
}

// ---- Channel --------------------------------------------------------------------------

/// Writes all of data to fd; false when the other side is gone.
bool write_all(int fd, const void* data, size_t n);
/// Reads exactly n bytes from fd; false at end of file or error.
bool read_all(int fd, void* data, size_t n);

/// Sends one message.
bool send(int fd, Kind kind, std::uint32_t function, std::uint32_t flags,
          const Buffer& payload);

}  // namespace raylab::rpc
