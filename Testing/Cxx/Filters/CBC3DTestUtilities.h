// Shared by the filter tests: a check that counts failures instead of stopping, and an
// observer that collects the messages of VTK error or warning events.
#ifndef CBC3DTestUtilities_h
#define CBC3DTestUtilities_h

#include <vtkCommand.h>

#include <iostream>
#include <string>

namespace cbc3dtest
{
inline int failures = 0;

/// Prints the outcome and returns the test's exit code.
inline int Finish()
{
  std::cout << (failures ? "FAILED" : "passed") << " with " << failures << " failed checks"
            << std::endl;
  return failures == 0 ? 0 : 1;
}

class MessageCatcher : public vtkCommand
{
public:
  static MessageCatcher* New() { return new MessageCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    this->Text += data ? static_cast<const char*>(data) : "";
  }
  std::string Text;
};
} // namespace cbc3dtest

#define CHECK(condition)                                                                         \
  do                                                                                             \
  {                                                                                              \
    if (!(condition))                                                                            \
    {                                                                                            \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #condition << std::endl;   \
      ++cbc3dtest::failures;                                                                     \
    }                                                                                            \
  } while (false)

#endif
