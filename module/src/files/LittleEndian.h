// Values appended to a byte buffer in little-endian order (LAS and binary PLY), whatever this machine's (private to
// the file writers).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

namespace gls
{

template <typename T>
void appendLittleEndian(std::string& bytes, T v)
{
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  const std::uint16_t one = 1;
  if (*reinterpret_cast<const unsigned char*>(&one) != 1)
  {
    std::reverse(b, b + sizeof(T));
  }
  bytes.append(b, sizeof(T));
}

} // namespace gls
