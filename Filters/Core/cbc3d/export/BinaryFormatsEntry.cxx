// The entry point of libcbc3dBinaryFormats.so (BinaryFormats.h): its writers, for dlsym.
#include "cbc3d/export/BinaryFormats.h"
#include "cbc3d/export/ExodusWriter.h"
#include "cbc3d/export/Hdf5HeavyData.h"

extern "C" const cbc3d::BinaryFormatWriters* cbc3dBinaryFormatWriters()
{
  static const cbc3d::BinaryFormatWriters writers = { &cbc3d::WriteExodus,
    &cbc3d::MakeXdmfHeavyData };
  return &writers;
}
