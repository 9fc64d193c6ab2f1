#include "VtuPayload.h"

#include "cbc3d/base/Parallel.h"

#include <vtkBase64Utilities.h>

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace
{
// vtkXMLWriter's defaults: 32 KiB blocks, vtkZLibDataCompressor at the XML writer's level 5.
constexpr std::size_t BlockSize = 32768;
constexpr int CompressionLevel = 5;
// Base64 input per parallel chunk: a multiple of 3 bytes, so chunks encode without padding.
constexpr std::size_t EncodeChunk = 3 * 16384;

std::size_t EncodedSize(std::size_t bytes)
{
  return (bytes + 2) / 3 * 4;
}

// VTK's base64, as vtkBase64OutputStream writes it ('=' padding, no end mark).
void EncodeBase64(const unsigned char* in, std::size_t size, char* out)
{
  vtkBase64Utilities::Encode(in, static_cast<unsigned long>(size), reinterpret_cast<unsigned char*>(out), 0);
}

// One 32 KiB block of one payload, and where its compressed bytes go.
struct Block
{
  std::size_t Payload;
  const unsigned char* Data;
  std::size_t Size;
  std::vector<unsigned char> Compressed;
};

std::vector<Block> SplitBlocks(const std::vector<VtuBytes>& payloads)
{
  std::vector<Block> blocks;
  for (std::size_t p = 0; p < payloads.size(); ++p)
    for (std::size_t at = 0; at < payloads[p].Size; at += BlockSize)
      blocks.push_back({ p, payloads[p].Data + at, std::min(BlockSize, payloads[p].Size - at), {} });
  return blocks;
}

// Compressed in a scratch buffer of the worst case, then kept at its own size: the blocks
// together stay the size of the compressed data, not of the raw data.
void CompressBlock(Block& block, std::vector<unsigned char>& scratch)
{
  uLongf size = compressBound(static_cast<uLong>(block.Size));
  scratch.resize(size);
  if (compress2(scratch.data(), &size, block.Data, static_cast<uLong>(block.Size), CompressionLevel) != Z_OK)
    throw std::runtime_error("zlib cannot compress a block");
  block.Compressed.assign(scratch.begin(), scratch.begin() + size);
}

// The UInt32 header: block count, block size, last block's size (0 when the data fill whole
// blocks, as vtkXMLWriter writes it), then each block's compressed size.
std::vector<unsigned char> Header(
  const VtuBytes& payload, const std::vector<Block>& blocks, std::size_t first, std::size_t count)
{
  std::vector<std::uint32_t> words = { static_cast<std::uint32_t>(count),
    static_cast<std::uint32_t>(BlockSize), static_cast<std::uint32_t>(payload.Size % BlockSize) };
  for (std::size_t b = first; b < first + count; ++b)
    words.push_back(static_cast<std::uint32_t>(blocks[b].Compressed.size()));
  std::vector<unsigned char> bytes(words.size() * 4);
  std::memcpy(bytes.data(), words.data(), bytes.size()); // little-endian, as the file says
  return bytes;
}

// A payload's compressed blocks joined (base64 runs across block boundaries), its encoded
// header, and where in the output its data's base64 starts.
struct Encoded
{
  std::string Header;
  std::vector<unsigned char> Data;
  std::size_t Position = 0;
};

// Each block is freed once joined, so that the compressed data are held once, not twice.
std::vector<Encoded> JoinBlocks(const std::vector<VtuBytes>& payloads, std::vector<Block>& blocks)
{
  std::vector<Encoded> encoded(payloads.size());
  std::size_t b = 0;
  for (std::size_t p = 0; p < payloads.size(); ++p)
  {
    const std::size_t first = b;
    std::size_t size = 0;
    for (; b < blocks.size() && blocks[b].Payload == p; ++b)
      size += blocks[b].Compressed.size();
    const std::vector<unsigned char> header = Header(payloads[p], blocks, first, b - first);
    encoded[p].Header.resize(EncodedSize(header.size()));
    EncodeBase64(header.data(), header.size(), &encoded[p].Header[0]);
    encoded[p].Data.reserve(size);
    for (std::size_t i = first; i < b; ++i)
    {
      encoded[p].Data.insert(encoded[p].Data.end(), blocks[i].Compressed.begin(), blocks[i].Compressed.end());
      std::vector<unsigned char>().swap(blocks[i].Compressed);
    }
  }
  return encoded;
}

// Lays out texts and headers, and leaves room for each payload's base64 data.
std::string Layout(const std::vector<std::string>& texts, std::vector<Encoded>& encoded)
{
  std::size_t total = texts.back().size();
  for (std::size_t p = 0; p < encoded.size(); ++p)
    total += texts[p].size() + encoded[p].Header.size() + EncodedSize(encoded[p].Data.size());
  std::string out;
  out.reserve(total);
  for (std::size_t p = 0; p < encoded.size(); ++p)
  {
    out += texts[p];
    out += encoded[p].Header;
    encoded[p].Position = out.size();
    out.append(EncodedSize(encoded[p].Data.size()), '\0');
  }
  out += texts.back();
  return out;
}

struct Chunk
{
  const Encoded* Payload;
  std::size_t Offset;
};

void EncodeData(const std::vector<Encoded>& encoded, std::string& out, int threads)
{
  std::vector<Chunk> chunks;
  for (const Encoded& e : encoded)
    for (std::size_t at = 0; at < e.Data.size(); at += EncodeChunk)
      chunks.push_back({ &e, at });
  char* base = &out[0];
#pragma omp parallel for schedule(dynamic) num_threads(threads)
  for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(chunks.size()); ++c)
  {
    const Chunk& chunk = chunks[c];
    const std::size_t size = std::min(EncodeChunk, chunk.Payload->Data.size() - chunk.Offset);
    EncodeBase64(chunk.Payload->Data.data() + chunk.Offset, size,
      base + chunk.Payload->Position + chunk.Offset / 3 * 4);
  }
}
} // namespace

std::string JoinVtuPayloads(
  const std::vector<std::string>& texts, const std::vector<VtuBytes>& payloads, int threads)
{
  threads = cbc3d::ThreadCount(threads);
  std::vector<Block> blocks = SplitBlocks(payloads);
  cbc3d::RegionErrors errors;
#pragma omp parallel num_threads(threads)
  {
    std::vector<unsigned char> scratch;
#pragma omp for schedule(dynamic)
    for (std::ptrdiff_t b = 0; b < static_cast<std::ptrdiff_t>(blocks.size()); ++b)
      errors.Run([&] { CompressBlock(blocks[b], scratch); });
  }
  errors.Rethrow();
  std::vector<Encoded> encoded = JoinBlocks(payloads, blocks);
  blocks.clear();
  std::string out = Layout(texts, encoded);
  EncodeData(encoded, out, threads);
  return out;
}
