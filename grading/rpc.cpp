// The channel of the grading worker (rpc.h), shared by the worker and the trusted side.
#include "rpc.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

namespace raylab::rpc {

bool write_all(int fd, const void* data, size_t n) {
    const char* p = static_cast<const char*>(data);
    while (n > 0) {
        const ssize_t k = ::write(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return false;
        p += k;
        n -= size_t(k);
    }
    return true;
}

bool read_all(int fd, void* data, size_t n) {
    char* p = static_cast<char*>(data);
    while (n > 0) {
        const ssize_t k = ::read(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return false;
        p += k;
        n -= size_t(k);
    }
    return true;
}

bool send(int fd, Kind kind, std::uint32_t function, std::uint32_t flags,
          const Buffer& payload) {
    const Header h{kind, function, flags,
                   static_cast<std::uint32_t>(payload.bytes.size())};
    return write_all(fd, &h, sizeof h) &&
           write_all(fd, payload.bytes.data(), payload.bytes.size());
}

}  // namespace raylab::rpc
