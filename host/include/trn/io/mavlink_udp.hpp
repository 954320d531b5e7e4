#pragma once
// Where MAVLink frames go: a UDP peer, named the way MAVLink tools name one. trnkit only sends, so
// the forms that send are accepted and those that listen are refused, saying which to use.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io::mavlink {

struct Endpoint {
    std::string host;  // a name or an address (IPv6 without its brackets)
    std::uint16_t port = 0;
};

// "udp:HOST:PORT", "udpout:HOST:PORT" (MAVProxy, pymavlink) and "udpout://HOST:PORT" (MAVSDK):
// send to HOST:PORT; an IPv6 HOST in brackets ([::1]). "udpin:", "udp://" (MAVSDK: listen), "tcp",
// serial devices are refused. Errors are trn::Error naming `option` and the text.
Endpoint parse_endpoint(const std::string& text, const std::string& option = "--mavlink");

// A UDP socket sending to one peer (resolved once, here). A datagram nobody receives is no error
// (telemetry to an autopilot not yet up); any other send failure is a trn::Error naming the peer.
class UdpSender {
public:
    explicit UdpSender(const Endpoint& peer, const std::string& option = "--mavlink");
    ~UdpSender();
    UdpSender(const UdpSender&) = delete;
    UdpSender& operator=(const UdpSender&) = delete;
    void send(std::span<const std::uint8_t> datagram);
    std::size_t sent() const { return sent_; }
    std::size_t refused() const { return refused_; }  // ICMP "port unreachable" seen at the next send

private:
    struct Socket;
    std::unique_ptr<Socket> socket_;
    std::string name_;
    std::size_t sent_ = 0, refused_ = 0;
};

}  // namespace trn::io::mavlink
TRN_API_END
