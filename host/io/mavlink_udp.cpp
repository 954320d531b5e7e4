// MAVLink over UDP, send only (trn/io/mavlink_udp.hpp).
#include "trn/io/mavlink_udp.hpp"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>

#include "trn/error.hpp"

namespace trn::io::mavlink {
namespace {

const char* const kForms = "udp:HOST:PORT or udpout:HOST:PORT (send to HOST:PORT)";

[[noreturn]] void refuse(const std::string& option, const std::string& text, const std::string& why) {
    throw Error(option + " " + text + ": " + why);
}

}  // namespace

Endpoint parse_endpoint(const std::string& text, const std::string& option) {
    const std::string shown = text.substr(0, 80);
    std::string rest;
    for (const char* prefix : {"udpout://", "udp:", "udpout:"})
        if (text.rfind(prefix, 0) == 0 && (std::string(prefix) != "udp:" || text.rfind("udp://", 0) != 0)) {
            rest = text.substr(std::strlen(prefix));
            break;
        }
    if (rest.empty()) {
        if (text.rfind("udpin:", 0) == 0 || text.rfind("udpin://", 0) == 0)
            refuse(option, shown, std::string("trnkit only sends; udpin listens for a peer first. Use ") + kForms +
                                      ", the autopilot or MAVProxy listening there");
        if (text.rfind("udp://", 0) == 0)
            refuse(option, shown, std::string("udp:// listens (MAVSDK's form); trnkit only sends. Use ") + kForms);
        if (text.rfind("tcp", 0) == 0 || text.rfind("serial", 0) == 0 || text.rfind("/dev/", 0) == 0)
            refuse(option, shown, std::string("only UDP is supported; use ") + kForms);
        refuse(option, shown, std::string("expected ") + kForms);
    }
    Endpoint e;
    std::string port;
    if (!rest.empty() && rest[0] == '[') {  // [IPv6]:PORT
        const std::size_t close = rest.find("]:");
        if (close == std::string::npos) refuse(option, shown, "an IPv6 host is [ADDRESS]:PORT");
        e.host = rest.substr(1, close - 1), port = rest.substr(close + 2);
    } else {
        const std::size_t colon = rest.rfind(':');
        if (colon == std::string::npos) refuse(option, shown, std::string("no port; expected ") + kForms);
        e.host = rest.substr(0, colon), port = rest.substr(colon + 1);
        if (e.host.find(':') != std::string::npos) refuse(option, shown, "an IPv6 host goes in brackets: udp:[ADDRESS]:PORT");
    }
    if (e.host.empty()) refuse(option, shown, "no host; expected " + std::string(kForms) + " (127.0.0.1 for this machine)");
    unsigned value = 0;
    const auto [ptr, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
    if (port.empty() || ec != std::errc() || ptr != port.data() + port.size() || value < 1 || value > 65535)
        refuse(option, shown, "port '" + port.substr(0, 20) + "' is not a number in 1..65535");
    e.port = static_cast<std::uint16_t>(value);
    return e;
}

struct UdpSender::Socket {
    int fd = -1;
    sockaddr_storage peer{};
    socklen_t peer_len = 0;
};

UdpSender::UdpSender(const Endpoint& peer, const std::string& option) : socket_(std::make_unique<Socket>()) {
    name_ = (peer.host.find(':') != std::string::npos ? "[" + peer.host + "]" : peer.host) + ":" + std::to_string(peer.port);
    addrinfo hints{};
    // Numeric addresses only: a flight computer must not wait on (or leak queries to) a name server,
    // and a typo must not become a DNS lookup. "localhost" is this machine's IPv4 loopback.
    hints.ai_family = AF_UNSPEC, hints.ai_socktype = SOCK_DGRAM, hints.ai_flags = AI_NUMERICSERV | AI_NUMERICHOST;
    addrinfo* found = nullptr;
    const std::string host = peer.host == "localhost" ? "127.0.0.1" : peer.host;
    const int rc = getaddrinfo(host.c_str(), std::to_string(peer.port).c_str(), &hints, &found);
    if (rc != 0 || !found)
        throw Error(option + " udp:" + name_ + ": '" + peer.host + "' is not a numeric IP address (give the autopilot's address, e.g. " +
                    "127.0.0.1 or 192.168.1.10; host names are not resolved)");
    std::memcpy(&socket_->peer, found->ai_addr, found->ai_addrlen);
    socket_->peer_len = found->ai_addrlen;
    socket_->fd = ::socket(found->ai_family, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    const int err = errno;
    freeaddrinfo(found);
    if (socket_->fd < 0) throw Error(option + " udp:" + name_ + ": socket: " + std::strerror(err));
}

UdpSender::~UdpSender() {
    if (socket_ && socket_->fd >= 0) ::close(socket_->fd);
}

void UdpSender::send(std::span<const std::uint8_t> datagram) {
    for (int attempt = 0; attempt < 2; ++attempt) {
        const ssize_t n = ::sendto(socket_->fd, datagram.data(), datagram.size(), MSG_NOSIGNAL,
                                   reinterpret_cast<const sockaddr*>(&socket_->peer), socket_->peer_len);
        if (n == static_cast<ssize_t>(datagram.size())) {
            ++sent_;
            return;
        }
        // A previous datagram's ICMP "port unreachable" surfaces here once; this one may still go.
        if (n < 0 && errno == ECONNREFUSED) {
            ++refused_;
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        throw Error("mavlink: send to udp:" + name_ + ": " + (n < 0 ? std::strerror(errno) : "short datagram"));
    }
}

}  // namespace trn::io::mavlink
