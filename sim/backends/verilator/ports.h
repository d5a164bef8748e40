// The Verilated model's ports as the harness sees them: a name, a width, a
// direction and the address of the model's member (vc_ports.h lists them).
#ifndef VC_PORTS_ACCESS_H
#define VC_PORTS_ACCESS_H

#include <cstdint>

namespace {

struct Port {
    const char* name;
    int width;
    int direction;  // 0 input, 1 output
    void* address;
};

uint64_t mask(int width) { return width >= 64 ? ~0ULL : (1ULL << width) - 1; }

uint64_t read_port(const Port& port) {
    if (port.width <= 8) return *static_cast<uint8_t*>(port.address);
    if (port.width <= 16) return *static_cast<uint16_t*>(port.address);
    if (port.width <= 32) return *static_cast<uint32_t*>(port.address);
    return *static_cast<uint64_t*>(port.address);
}

void write_port(const Port& port, uint64_t value) {
    value &= mask(port.width);
    if (port.width <= 8) *static_cast<uint8_t*>(port.address) = static_cast<uint8_t>(value);
    else if (port.width <= 16) *static_cast<uint16_t*>(port.address) = static_cast<uint16_t>(value);
    else if (port.width <= 32) *static_cast<uint32_t*>(port.address) = static_cast<uint32_t>(value);
    else *static_cast<uint64_t*>(port.address) = value;
}

}  // namespace

#endif  // VC_PORTS_ACCESS_H
