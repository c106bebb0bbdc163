// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320) for the .srm file's
// header and chunks; its low 16 bits serve as the short check of each
// coefficient segment (format/srm/README.md).
#pragma once

#include <cstddef>
#include <cstdint>

namespace srcodec {

uint32_t crc32(const uint8_t* data, size_t size, uint32_t crc = 0);
inline uint16_t crc16_of(const uint8_t* data, size_t size) { return static_cast<uint16_t>(crc32(data, size)); }

}  // namespace srcodec
