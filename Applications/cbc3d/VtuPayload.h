#ifndef cbc3d_VtuPayload_h
#define cbc3d_VtuPayload_h

#include <cstddef>
#include <string>
#include <vector>

/// The raw bytes of one array as VTK's XML writer takes them (native little-endian words).
struct VtuBytes
{
  const unsigned char* Data = nullptr;
  std::size_t Size = 0;
};

/// Joins texts[0], payload 0, texts[1], payload 1, ..., texts.back() (texts has one more entry
/// than payloads) into one string, each payload in vtkXMLWriter's inline binary form: zlib at
/// level 5 in 32 KiB blocks, base64 of the UInt32 header, then base64 of the joined blocks.
/// Blocks are compressed and encoded on `threads` OpenMP threads; zlib compresses each block on
/// its own, so the bytes do not depend on the thread count.
std::string JoinVtuPayloads(
  const std::vector<std::string>& texts, const std::vector<VtuBytes>& payloads, int threads);

#endif
