// SHA-256 (FIPS 180-4) and base64 (RFC 4648), for the hashes of the
// dashboard's inline import map in its Content-Security-Policy.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace rrlab::server {

std::array<std::uint8_t, 32> sha256(std::string_view data);
std::string base64(const std::uint8_t* data, std::size_t size);

}  // namespace rrlab::server
