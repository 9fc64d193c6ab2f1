#ifndef cbc3d_FuzzBytes_h
#define cbc3d_FuzzBytes_h

#include <cstddef>
#include <cstdint>

// Reads a fuzzer's input a byte at a time; past the end every byte reads as 0, so any input,
// however short, decodes to something.
class FuzzBytes
{
public:
  FuzzBytes(const std::uint8_t* data, std::size_t size)
    : Data(data)
    , Size(size)
  {
  }
  std::uint8_t Next() { return this->Position < this->Size ? this->Data[this->Position++] : 0; }
  /// A value in [0, count) (count > 0).
  int Pick(int count) { return this->Next() % count; }
  bool AtEnd() const { return this->Position >= this->Size; }

private:
  const std::uint8_t* Data;
  std::size_t Size;
  std::size_t Position = 0;
};

#endif
